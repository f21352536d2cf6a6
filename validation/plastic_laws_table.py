"""Table: each plastic contact law against the axisymmetric FE reference (half-space impact).

For every reference run of ``validation/fe/results/axisym_runs.csv`` with a rigid sphere and
a flat of ν = 0.3 (the runs of ``plastic_laws_figure.py``: small strain to δ_m = 0.012 R,
NLGEOM to 0.05 R), the impact whose kinetic energy equals the FE cycle's absorbed work,
V/V_y = sqrt(W_abs/((2/5) F_y δ_y)), is run with each registered plastic law through
:func:`impactmaps.closed_forms.halfspace.halfspace_impact` (the issue-28 example: a 12.7 mm
steel ball on aluminium, Y = 275 MPa; the normalised answers depend on V/V_y alone, as
``tests/contact/test_contact_epp.py`` shows for epp), and its peak force, restitution and permanent
indentation are compared with the FE's F_m, sqrt(W_rec/W_abs) and dent. Thornton's 1997
model (closed form, ``plastic_laws_figure.thornton``) is the implementation cross-check.

Writes ``validation/plastic_laws_error.csv`` (one row per law and FE point) and the per-law
ranges the package ships (``impactmaps/contact/data/fe_agreement.csv``, printed by
``impactmaps laws``), and prints the ranges, the table of ``docs/epp_calibration.rst``.

    python validation/plastic_laws_table.py     (--smoke: the table into a temporary directory)
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _script_options import parse  # noqa: E402
from plastic_laws_figure import LAWS, fe_points, law_curves, thornton  # noqa: E402

OUT = HERE / "plastic_laws_error.csv"
#: The per-law ranges the package ships (``impactmaps.contact.plastic.fe_agreement``).
PACKAGE_SUMMARY = HERE.parent / "impactmaps" / "contact" / "data" / "fe_agreement.csv"
QUANTITIES = ("peak_force", "restitution", "permanent_indentation")


def error_table() -> pd.DataFrame:
    """One row per (law, FE point): V/V_y and the law's relative errors against the FE."""
    ratios, e_fe, force_fe, dent_fe = (np.asarray(a, float) for a in fe_points())
    curves = law_curves(ratios)
    curves["thornton"] = np.column_stack(thornton(ratios))
    rows = []
    for law in (*LAWS, "thornton"):
        e, force, dent = curves[law].T
        for k, ratio in enumerate(ratios):
            rows.append({"law": law, "velocity_over_yield_velocity": ratio,
                         "peak_force_error": force[k] / force_fe[k] - 1.0,
                         "restitution_error": e[k] / e_fe[k] - 1.0,
                         "permanent_indentation_error": dent[k] / dent_fe[k] - 1.0})
    return pd.DataFrame(rows).sort_values(["law", "velocity_over_yield_velocity"])


def ranges(table: pd.DataFrame) -> pd.DataFrame:
    """Smallest and largest error of each law and quantity, over V/V_y ≥ 2 (below, the FE
    dent is a fraction of a yield indentation and its relative error is not meaningful)."""
    sel = table[table["velocity_over_yield_velocity"] >= 2.0]
    columns = [f"{quantity}_error" for quantity in QUANTITIES]
    return sel.groupby("law")[columns].agg(["min", "max"])


def package_summary(table: pd.DataFrame) -> pd.DataFrame:
    """The rows of ``impactmaps/contact/data/fe_agreement.csv``: law, quantity, lowest, highest."""
    spans = ranges(table)
    return pd.DataFrame([{"law": law, "quantity": quantity, "lowest": spans.loc[law, (f"{quantity}_error", "min")],
                          "highest": spans.loc[law, (f"{quantity}_error", "max")]}
                         for law in spans.index if law != "thornton" for quantity in QUANTITIES])


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE)
    table = error_table()
    out, summary = OUT, PACKAGE_SUMMARY
    if args.smoke or args.out_dir.resolve() != HERE:
        out, summary = args.out_dir / OUT.name, args.out_dir / PACKAGE_SUMMARY.name
    table.to_csv(out, index=False, float_format="%.6g")
    package_summary(table).to_csv(summary, index=False, float_format="%.4f")
    with pd.option_context("display.float_format", "{:+.3f}".format, "display.width", 160):
        print(ranges(table))
    print(out)


if __name__ == "__main__":
    main()
