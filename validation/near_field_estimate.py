"""The near field a laminate lacks, estimated, and what the near field does on isotropic plates.

Isotropic Mindlin plates under the contact patch carry a 3D-consistent near field
(:mod:`impactmaps.targets.plates.near_field`); laminates do not.
:func:`~impactmaps.targets.plates.near_field.near_field_estimate` estimates the compliance it
would remove (the isotropic kernel on the laminate's own half-wave pairs), and a run warns when
that exceeds :data:`~impactmaps.validity.NEAR_FIELD_SHARE_LIMIT` of the contact's secant
compliance at the peak force. This script measures

* on isotropic SSSS plates: the peak force with the near field and without it (the same plate
  with D22 raised by 1e-7, which is then not isotropic and has none), and the estimate's share
  (exact there: the plate's own ν) — the calibration of the warning's "up to 0.7 times";
* on [0/90]4s AS4/3501-6 SSSS plates (a/h 75 and 10) and ``examples/composite_plate_sun_chen.toml``:
  the estimated share (ν = 0.2, 0.3, 0.4).

Writes ``validation/near_field_estimate.csv`` and prints the tables of docs/contact_patch.rst.

    python validation/near_field_estimate.py            # full (≈ 2–5 min)
    python validation/near_field_estimate.py --smoke    # one isotropic plate
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import pandas as pd

from impactmaps.cases import load_case, parse_case
from impactmaps.contact import Sphere, law_for_sphere
from impactmaps.materials import material
from impactmaps.solvers.modal import simulate
from impactmaps.targets.plates import near_field
from impactmaps.targets.plates.plate import Plate

from _script_options import parse
from patch_cutoff_edges import PLATES, case_text

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def isotropic_cases(smoke: bool):
    """(label, plate, sphere radius [m], mass [kg] or None (the solid sphere), speed [m/s], material)."""
    al, steel = material("aluminium-6061-t6"), material("structural-steel")
    found = [("README plate 300 × 300 × 4 mm 6061-T6, 3 m/s", Plate.isotropic(0.3, 0.3, 0.004, al, theory="mindlin"),
              0.00635, None, 3.0, al)]
    if smoke:
        return found
    fe = Plate.isotropic(0.2, 0.2, 0.01, steel, theory="mindlin")
    return found + [
        ("steel_plate_hertz 250 × 250 × 4 mm steel, 2 m/s", Plate.isotropic(0.25, 0.25, 0.004, steel, theory="mindlin"),
         0.005, None, 2.0, steel),
        ("200 × 200 × 10 mm steel, 1 kg, 1 m/s", fe, 0.01, 1.0, 1.0, steel),
        ("200 × 200 × 10 mm steel, 10 kg, 1 m/s", fe, 0.01, 10.0, 1.0, steel),
        ("300 × 300 × 30 mm 6061-T6, 3 m/s", Plate.isotropic(0.3, 0.3, 0.03, al, theory="mindlin"), 0.00635, None, 3.0, al),
        ("150 × 100 × 6 mm 6061-T6, 0.05 kg, 3 m/s", Plate.isotropic(0.15, 0.10, 0.006, al, theory="mindlin"),
         0.00635, 0.05, 3.0, al),
        ("150 × 100 × 15 mm 6061-T6, 0.3 kg, 2 m/s", Plate.isotropic(0.15, 0.10, 0.015, al, theory="mindlin"),
         0.00635, 0.3, 2.0, al),
        ("150 × 100 × 2 mm 6061-T6, 0.3 kg, 2 m/s", Plate.isotropic(0.15, 0.10, 0.002, al, theory="mindlin"),
         0.00635, 0.3, 2.0, al),
    ]


def _share(plate, result, poisson_ratio):
    radius = result.settings["contact_radius_m"]
    return near_field.near_field_estimate(plate, radius, poisson_ratio) * result.peak_force / result.max_indentation


def isotropic_row(label, plate, radius, mass, velocity, target_material) -> dict:
    law = law_for_sphere("hertz", Sphere(radius, material("structural-steel")), target_material)
    mass = mass or float(Sphere(radius, material("structural-steel")).mass)
    with_field = simulate(plate, law, mass, velocity, record=False)
    without = simulate(replace(plate, D22=plate.D22 * (1.0 + 1e-7)), law, mass, velocity, record=False)
    share = _share(plate, without, target_material.poisson_ratio)
    change = with_field.peak_force / without.peak_force - 1.0
    return {"table": "isotropic", "case": label, "peak_with_N": with_field.peak_force,
            "peak_without_N": without.peak_force, "share": share, "peak_change": change, "ratio": change / share}


def laminate_rows() -> list[dict]:
    cases = [(f"{label}, {mass} kg, 2 m/s", parse_case(case_text("SSSS", lines, mass)))
             for label, lines in PLATES[3:] for mass in (0.3, 0.01)]
    cases.append(("composite_plate_sun_chen.toml", load_case(ROOT / "examples" / "composite_plate_sun_chen.toml")))
    rows = []
    for label, case in cases:
        result = simulate(case.target, case.law, case.impactor_mass, case.velocity, record=False)
        rows.append({"table": "laminate", "case": label, "peak_without_N": result.peak_force,
                     **{f"share_nu{nu}": _share(case.target, result, nu) for nu in (0.2, 0.3, 0.4)}})
    return rows


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE)
    warnings.simplefilter("ignore")
    rows = [isotropic_row(*case) for case in isotropic_cases(args.smoke)]
    for row in rows:
        print(f"{row['case']:48s} with {row['peak_with_N']:9.2f} N  without {row['peak_without_N']:9.2f} N  "
              f"change {row['peak_change']:+.2%}  share {row['share']:.3f}  change/share {row['ratio']:.2f}")
    if not args.smoke:
        laminates = laminate_rows()
        for row in laminates:
            print(f"{row['case']:48s} peak {row['peak_without_N']:9.2f} N  share (ν 0.2/0.3/0.4) "
                  f"{row['share_nu0.2']:.3f} / {row['share_nu0.3']:.3f} / {row['share_nu0.4']:.3f}")
        rows += laminates
    pd.DataFrame(rows).to_csv(Path(args.out_dir) / "near_field_estimate.csv", index=False, float_format="%.8g")


if __name__ == "__main__":
    main()
