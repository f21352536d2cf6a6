"""Peak force against the mode cut-off: point load against the Hertz contact patch.

A point load on a Mindlin plate has a logarithmically divergent deflection, so its modal
peak force never converges in the cut-off; the Hertz pressure over the contact disc of
the peak indentation (``ModalSettings(contact_patch="hertz-peak")``, the default
``"auto"`` on Mindlin SSSS plates) does. This script measures both for

* the README example: 12.7 mm steel ball at 3 m/s on the centre of a simply supported
  300 × 300 × 4 mm aluminium 6061-T6 Mindlin plate (span/thickness 75);
* the same on a thick plate, 300 × 300 × 30 mm (span/thickness 10);
* the Timoshenko beam of validation/fe level 3 (steel, 500 × 20 × 20 mm, simply
  supported, struck at mid-span by a solid 10 mm-radius steel sphere at 1 m/s), point
  load only (the default there): its point-load deflection is finite and it converges;

at cut-offs 10, 20, 40, 80, 160 ω (ω the contact frequency), and, when the committed FE
results are present, the Mindlin plate of validation/fe level 3 (steel 200 × 200 ×
10 mm, 4 sphere masses) against the 3D spring-coupled FE model: point load at 40 and
160 ω, patch at 40 ω; and the effect of the patch radius (fixed at 0.5, 1, 2 × the
converged peak-indentation radius); and the static compliance under the FE plate's
patch, 3D (minus its half-space local part) against Kirchhoff and Mindlin. Writes the
tables into ``validation/patch_convergence.csv`` (column ``table``: ``cutoff``,
``radius``, ``fe_plate``, ``fe_static``) and prints them as the Markdown tables of ``docs/contact_patch.rst``.

    python validation/patch_convergence.py              # full (≈ 1–2 min)
    python validation/patch_convergence.py --smoke      # README plate, 10 and 20 ω
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import pandas as pd

from impactmaps.contact import Sphere, law_for_sphere
from impactmaps.materials import material
from impactmaps.solvers.modal import ModalSettings, reference_contact_stiffness, simulate
from impactmaps.targets.beams.beam import Beam
from impactmaps.targets.patch import mean_square_transform, uniform_transform
from impactmaps.targets.plates.plate import Plate
from impactmaps.targets.plates.plate_static import navier_patch_residual

from _script_options import parse

HERE = Path(__file__).resolve().parent
CUTOFFS = (10, 20, 40, 80, 160)
LOADS = ("point", "hertz-peak")
FE_PLATE = HERE / "fe" / "results" / "level3_plate.json"


def cases(smoke: bool):
    """(name, target, law, mass [kg], velocity [m/s], loads) of the study."""
    aluminium, steel = material("aluminium-6061-t6"), material("structural-steel")
    ball = Sphere(0.0127 / 2, steel)
    ball_on_aluminium = law_for_sphere("hertz", ball, aluminium)
    found = [("README plate (a/h = 75)", Plate.isotropic(0.3, 0.3, 0.004, aluminium, theory="mindlin"),
              ball_on_aluminium, ball.mass, 3.0, LOADS)]
    if smoke:
        return found
    sphere = Sphere(0.01, steel)
    found += [("thick plate (a/h = 10)", Plate.isotropic(0.3, 0.3, 0.03, aluminium, theory="mindlin"),
               ball_on_aluminium, ball.mass, 3.0, LOADS),
              ("Timoshenko beam (L/h = 25)", Beam.rectangular(0.5, 0.02, 0.02, steel, theory="timoshenko"),
               law_for_sphere("hertz", sphere, steel), sphere.mass, 1.0, ("point",))]
    return found


def run(target, law, mass, velocity, cutoff, load, record=False):
    """One modal run; (result, number of warnings). Warnings (the point-loaded Mindlin
    plate's thickness-shear notice at high cut-offs) are counted, not shown."""
    settings = ModalSettings(cutoff_ratio=cutoff, patch_cutoff_ratio=cutoff, contact_patch=load)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate(target, law, mass, velocity, settings=settings, record=record)
    return result, len(caught)


def convergence_table(smoke: bool) -> pd.DataFrame:
    """Peak force of every case, load and cut-off."""
    rows = []
    for name, target, law, mass, velocity, loads in cases(smoke):
        for load in loads:
            for cutoff in (CUTOFFS[:2] if smoke else CUTOFFS):
                result, warned = run(target, law, mass, velocity, cutoff, load)
                rows.append({"case": name, "load": load, "cutoff_ratio": cutoff,
                             "peak_force_N": result.peak_force, "modes": result.n_modes,
                             "steps": result.details.steps,
                             "contact_radius_m": result.settings.get("contact_radius_m", 0.0),
                             "warnings": warned})
    return pd.DataFrame(rows)


def fe_plate_table() -> pd.DataFrame:
    """First-contact peak of the level-3 FE plate: FE, point load at 40 and 320 ω, patch."""
    if not FE_PLATE.exists():
        return pd.DataFrame()
    steel = material("structural-steel")
    plate = Plate.isotropic(0.2, 0.2, 0.01, steel, theory="mindlin")
    rows = []
    for case in json.loads(FE_PLATE.read_text())["cases"]:
        sphere = Sphere(0.01, steel, mass=case["mass_kg"])
        law = law_for_sphere("hertz", sphere, steel)
        row = {"mass_factor": case["mass_factor"], "fe_peak_N": case["fe"]["reference"]["first_peak_N"]}
        for label, cutoff, load in (("point_40", 40, "point"), ("point_160", 160, "point"),
                                    ("patch_40", 40, "hertz-peak")):
            result, _ = run(plate, law, case["mass_kg"], 1.0, cutoff, load, record=True)
            if result.history is None:  # beyond the mode budget: an asymptote, no history
                row[label] = float("nan")
                continue
            start, end = result.contact_intervals[0]
            history = result.history
            first = history[(history["time_s"] >= start) & (history["time_s"] <= end)]
            row[label] = float(first["force_N"].max())
        rows.append(row)
    return pd.DataFrame(rows)


def fe_static_table() -> pd.DataFrame:
    """Static compliance under the FE plate's uniform 0.7 mm patch [m/N]: the 3D solid
    (level 3, fine mesh) minus its half-space local part 16(1 − ν²)/(3π² a E) — the
    structural compliance the FE spring model puts in series with the Hertz law — against
    the Kirchhoff and Mindlin plates under the same patch (``navier_patch_residual``)."""
    if not FE_PLATE.exists():
        return pd.DataFrame()
    results = json.loads(FE_PLATE.read_text())
    modes = results["modes"][results["reference"]]
    radius, fe = modes["patch_radius_m"], modes["static_compliance_m_per_N"]
    youngs, poisson = modes["material"]["E_Pa"], modes["material"]["nu"]
    plate = Plate.isotropic(0.2, 0.2, 0.01, material("structural-steel"), theory="mindlin")
    bending = (plate.D11, plate.D22, plate.D12, plate.D66)
    shear = (plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)

    def patch(stiffnesses):
        return navier_patch_residual(0.2, 0.2, stiffnesses, (0.1, 0.1), radius, uniform_transform,
                                     mean_square=lambda x: mean_square_transform(x, "uniform"))

    local = 16 * (1 - poisson**2) / (3 * math.pi**2 * radius * youngs)
    structural = fe - local
    rows = [("3D solid (FE), whole patch compliance", fe), ("half-space local part", local),
            ("3D structural = FE − local", structural), ("Kirchhoff plate", patch(bending)),
            ("Mindlin plate", patch(bending + shear))]
    return pd.DataFrame([{"quantity": name, "compliance_m_per_N": value,
                          "relative_to_3d_structural": value / structural - 1.0} for name, value in rows])


def radius_table(smoke: bool) -> pd.DataFrame:
    """Peak force and first-contact duration with the patch radius fixed at 0.5, 1 and 2 ×
    the converged peak-indentation radius (40 ω): the effect of the choice of radius."""
    rows = []
    for name, target, law, mass, velocity, loads in cases(smoke):
        if "hertz-peak" not in loads:
            continue
        converged, _ = run(target, law, mass, velocity, 40, "hertz-peak")
        radius = converged.settings["contact_radius_m"]
        omega = (reference_contact_stiffness(law, mass, velocity) / mass) ** 0.5
        for factor in (0.5, 1.0, 2.0):
            basis = target.modes(40 * omega, min_modes=4, contact_radius=factor * radius)
            result, _ = run(basis, law, mass, velocity, 40, "point")
            start, end = result.contact_intervals[0]
            rows.append({"case": name, "radius_factor": factor, "contact_radius_m": factor * radius,
                         "peak_force_N": result.peak_force, "first_contact_s": end - start})
    return pd.DataFrame(rows)


def markdown(table: pd.DataFrame) -> str:
    """Peak force per cut-off (rows) and case/load (columns), and the step from each row."""
    columns = [(c, load) for c in dict.fromkeys(table["case"]) for load in LOADS
               if ((table["case"] == c) & (table["load"] == load)).any()]
    lines = ["| cut-off | " + " | ".join(f"{c}, {'patch' if load != 'point' else 'point'} [N]"
                                         for c, load in columns) + " |",
             "|---" * (len(columns) + 1) + "|"]
    for cutoff in dict.fromkeys(table["cutoff_ratio"]):
        cells = []
        for c, load in columns:
            row = table[(table["case"] == c) & (table["load"] == load) & (table["cutoff_ratio"] == cutoff)]
            if row.empty:
                cells.append("")
                continue
            previous = table[(table["case"] == c) & (table["load"] == load)
                             & (table["cutoff_ratio"] == cutoff / 2)]
            change = "" if previous.empty else (
                f" ({row['peak_force_N'].iloc[0] / previous['peak_force_N'].iloc[0] - 1:+.1e})")
            cells.append(f"{row['peak_force_N'].iloc[0]:.3f}{change}")
        lines.append(f"| {cutoff:g} ω | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def fe_markdown(fe: pd.DataFrame) -> str:
    """The FE plate comparison as a Markdown table (toolkit − FE in %)."""
    lines = ["| sphere mass | FE peak [N] | point 40 ω | point 160 ω | patch (converged) |",
             "|---|---|---|---|---|"]
    for _, row in fe.iterrows():
        cells = [f"{row[k]:.1f} ({100 * (row[k] / row['fe_peak_N'] - 1):+.2f} %)"
                 for k in ("point_40", "point_160", "patch_40")]
        lines.append(f"| {row['mass_factor']:g} × | {row['fe_peak_N']:.1f} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE)
    table = convergence_table(args.smoke)
    print(markdown(table))
    at_default = table[table["cutoff_ratio"] == 40]
    if not at_default.empty:
        print()
        print("modes / steps at 40 ω: " + "; ".join(
            f"{r.case}, {r.load}: {r.modes} / {r.steps}" for r in at_default.itertuples()))
    radii = radius_table(args.smoke)
    print()
    print("| case | patch radius | peak force [N] | first contact [µs] |")
    print("|---|---|---|---|")
    for r in radii.itertuples():
        print(f"| {r.case} | {r.radius_factor:g} × a_peak = {r.contact_radius_m * 1e3:.3f} mm | "
              f"{r.peak_force_N:.2f} | {r.first_contact_s * 1e6:.2f} |")
    fe = pd.DataFrame() if args.smoke else fe_plate_table()
    if not fe.empty:
        print()
        print(fe_markdown(fe))
    static = fe_static_table()
    if not static.empty:
        print()
        print("| static compliance under the FE plate's uniform 0.7 mm patch | [m/N] | vs 3D structural |")
        print("|---|---|---|")
        for r in static.itertuples():
            print(f"| {r.quantity} | {r.compliance_m_per_N:.4e} | {100 * r.relative_to_3d_structural:+.2f} % |")
    frames = [frame.assign(table=name) for name, frame in
              (("cutoff", table), ("radius", radii), ("fe_plate", fe), ("fe_static", static)) if not frame.empty]
    pd.concat(frames, ignore_index=True).to_csv(args.out_dir / "patch_convergence.csv", index=False)


if __name__ == "__main__":
    main()
