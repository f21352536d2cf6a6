"""Peak force against basis size for a thick and a thin clamped Mindlin plate (issue 39).

The largest basis per direction (``plate_any_edges.MAX_UNKNOWNS``) is set to each value in turn
and the impact is run; where the run's cut-off lies above what the basis resolves, the modes up
to its resolved frequency are integrated with the residual compliance for the rest (the run says
``modal+residual-capped``). Prints a Markdown table for docs/plates_any_edges.rst.

Run:  PYTHONPATH=. python benchmarks/convergence_plates_any_edges.py
"""

from __future__ import annotations

import warnings

from impactmaps.cases import parse_case, run_case
from impactmaps.solvers import mode_budget
from impactmaps.targets.plates import plate as plate_module
from impactmaps.targets.plates import plate_any_edges, plate_general

CASE = """
[impactor]
radius = 0.010
mass = {mass}
material = "structural-steel"
velocity = 2.0
[target]
type = "plate"
length_x = {a}
length_y = {a}
thickness = {h}
material = "aluminium-6061-t6"
theory = "mindlin"
edges = "CCCC"
[contact]
law = "hertz"
[solver]
check_convergence = false
"""

PLATES = (("thick, a/h = 10: 100 × 100 × 10 mm, 2 kg", 0.1, 0.01, 2.0),
          ("thin, a/h = 100: 300 × 300 × 3 mm, 0.2 kg", 0.3, 0.003, 0.2))
SIZES = (16, 24, 32, 40, 48, 56, 64)


def _clear():
    for function in (plate_general.solve_general_plate, plate_general._stiffness_factor,
                     plate_any_edges.patch_static_compliance, plate_module._plate_modes, mode_budget.frequency_cap):
        function.cache_clear()


def main() -> None:
    original = plate_any_edges.MAX_UNKNOWNS
    print("| plate | largest basis (functions per direction, centre class) | resolved [rad/s] | modes | "
          "peak force [N] | first contact [ms] | impacts | method |")
    print("|---|---|---|---|---|---|---|---|")
    try:
        for label, a, h, mass in PLATES:
            for n in SIZES:
                plate_any_edges.MAX_UNKNOWNS = 3 * n * n // 4  # one class of four: n per direction
                _clear()
                limit = plate_module.Plate.resolution_limit(result_target(a, h))
                try:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        result, summary = run_case(parse_case(CASE.format(a=a, h=h, mass=mass)))
                except ValueError:
                    print(f"| {label} | {n} | {limit:.4g} | - | refused: the basis resolves less than 8 ω | "
                          "- | - | - |", flush=True)
                    continue
                print(f"| {label} | {n} | {limit:.4g} | {summary['n_modes']} | {result.peak_force:.2f} | "
                      f"{1e3 * summary['first_contact_duration_s']:.4f} | {summary['impacts']} | {result.method} |", flush=True)
    finally:
        plate_any_edges.MAX_UNKNOWNS = original


def result_target(a, h):
    from impactmaps.materials import material

    return plate_module.Plate.isotropic(a, a, h, material("aluminium-6061-t6"), theory="mindlin", edges="CCCC")


if __name__ == "__main__":
    main()
