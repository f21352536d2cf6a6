"""Peak force against the patch cut-off on plates with free, clamped and mixed edges.

The modal solver integrates the modes up to ``patch_cutoff_ratio · ω`` (ω = sqrt(K/m), the
contact frequency) under the contact patch and adds the rest as a static residual. On a
plate struck by a heavy impactor the contact force carries frequencies well above ω: the
contact spring K against the plate's local impedance ``c = 8 sqrt(ρh D*)`` has the corner
frequency ``K/c = 2 ζ_p ω`` (ζ_p the plate loss factor), and a cut-off below it leaves
force content to modes that the static residual cannot carry
(docs/plates_any_edges.rst, "The patch cut-off of heavy impactors").

This script measures, for a 150 × 100 mm plate struck at its centre by a 12.7 mm steel
ball on 0.3 kg at 2 m/s (and the heavier/lighter impactors of the ζ_p scan), the peak force
at cut-offs 20, 40, 80, 160 ω and under the default settings (the cut-off rule of
:func:`impactmaps.solvers.modal_settings.patch_cutoff_ratio_for`), on CFCF, CFFF, SCSF,
CCCC and SSSS edges; isotropic 6061-T6 at a/h = 100, 75 and 10 and a [0/90]4s
AS4/3501-6 laminate at a/h = 75 and 10. Writes ``validation/patch_cutoff_edges.csv`` and
prints the table of docs/plates_any_edges.rst.

With ``--scan``: the impactor mass scan on the SSSS plate (Navier, nothing capped), 10 … 160 ω
against 320 ω, under the patch and, for the Kirchhoff twin, the point load
(``validation/patch_cutoff_scan.csv``).

    python validation/patch_cutoff_edges.py              # full (≈ 30–60 min on a loaded 2-core machine)
    python validation/patch_cutoff_edges.py --scan       # the mass scan (≈ 1 min)
    python validation/patch_cutoff_edges.py --smoke      # one SSSS plate, two cut-offs
"""

from __future__ import annotations

import os
import time
import warnings
from dataclasses import replace
from pathlib import Path

import pandas as pd

from impactmaps.cases import parse_case
from impactmaps.contact.contact_scale import reference_contact_stiffness
from impactmaps.solvers.modal import simulate

from _script_options import parse

HERE = Path(__file__).resolve().parent
CUTOFFS = (20, 40, 80, 160)

_ISOTROPIC = 'thickness = {h}\nmaterial = "aluminium-6061-t6"'
_LAMINATE = ('layup = {{ ply = "as4-3501-6", angles_deg = [0, 90, 0, 90, 0, 90, 0, 90], symmetric = true, '
             'ply_thickness = {ply} }}')
#: (label, the [target] lines of its material): a/h counted on the 150 mm side.
PLATES = (("6061-T6, a/h = 100", _ISOTROPIC.format(h=0.0015)),
          ("6061-T6, a/h = 75", _ISOTROPIC.format(h=0.002)),
          ("6061-T6, a/h = 10", _ISOTROPIC.format(h=0.015)),
          ("[0/90]4s, a/h = 75", _LAMINATE.format(ply=0.000125)),
          ("[0/90]4s, a/h = 10", _LAMINATE.format(ply=0.0009375)))
EDGES = ("CFCF", "CFFF", "SCSF", "CCCC", "SSSS")


def case_text(edges: str, material_lines: str, mass: float = 0.3) -> str:
    """The case file of one plate of the study."""
    return f"""name = "patch cut-off, {edges}"
[impactor]
radius = 0.00635
mass = {mass}
material = "structural-steel"
velocity = 2.0
[target]
type = "plate"
length_x = 0.15
length_y = 0.10
theory = "mindlin"
edges = "{edges}"
{material_lines}
[contact]
law = "hertz"
"""


def _peak(case, settings, corner_cutoff=True):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=settings, record=False,
                          corner_cutoff=corner_cutoff)
    capped = any("needs more than" in str(w.message) for w in caught)
    return result, capped


def row(label: str, edges: str, material_lines: str, mass: float = 0.3, cutoffs=CUTOFFS) -> dict:
    """Peak forces [N] of one plate at each cut-off and under the defaults."""
    case = parse_case(case_text(edges, material_lines, mass))
    stiffness = reference_contact_stiffness(case.law, case.impactor_mass, case.velocity)
    out = {"plate": label, "edges": edges, "mass_kg": mass,
           "zeta_p": float(case.target.loss_factor(case.impactor_mass, stiffness))}
    start = time.time()
    default, capped = _peak(case, case.settings)
    out |= {"default_N": default.peak_force, "default_modes": default.n_modes, "default_capped": capped,
            "default_ratio": default.settings["patch_cutoff_ratio"], "impacts": len(default.contact_intervals)}
    for ratio in cutoffs:
        result, capped = _peak(case, replace(case.settings, patch_cutoff_ratio=float(ratio)), corner_cutoff=False)
        out |= {f"F{ratio}_N": result.peak_force, f"modes{ratio}": result.n_modes, f"capped{ratio}": capped}
    out["seconds"], out["load"] = time.time() - start, os.getloadavg()[0]
    return out


def table(frame: pd.DataFrame, cutoffs=CUTOFFS) -> str:
    """The rows as text: each peak force's deviation from the finest cut-off [%]."""
    finest = frame[f"F{cutoffs[-1]}_N"]
    lines = [f"{'plate':20s} {'edges':5s} {'ζ_p':>6s} " + " ".join(f"{f'{c} ω':>8s}" for c in cutoffs)
             + f" {'default':>17s} {'reference [N]':>13s}"]
    for index, item in frame.iterrows():
        cells = [f"{(item[f'F{c}_N'] / finest[index] - 1) * 100:+7.2f}%" + ("*" if item[f"capped{c}"] else " ")
                 for c in cutoffs]
        default = f"{(item['default_N'] / finest[index] - 1) * 100:+.2f}% ({item['default_ratio']:.0f} ω)"
        lines.append(f"{item['plate']:20s} {item['edges']:5s} {item['zeta_p']:6.2f} " + "".join(cells)
                     + f" {default:>17s} {finest[index]:13.2f}")
    return "\n".join(lines)


SCAN_MASSES = (0.0084, 0.03, 0.1, 0.3, 1.0, 3.0)
SCAN_CUTOFFS = (10, 20, 40, 80, 160, 320)


def scan(masses=SCAN_MASSES, cutoffs=SCAN_CUTOFFS) -> pd.DataFrame:
    """Peak force [N] against the cut-off on the SSSS 150 × 100 × 2 mm plate: Mindlin under the
    patch (``patch_cutoff_ratio``) and Kirchhoff under the point load (``cutoff_ratio``)."""
    rows = []
    for theory, key in (("mindlin", "patch_cutoff_ratio"), ("kirchhoff", "cutoff_ratio")):
        for mass in masses:
            case = parse_case(case_text("SSSS", PLATES[1][1], mass).replace('"mindlin"', f'"{theory}"'))
            stiffness = reference_contact_stiffness(case.law, case.impactor_mass, case.velocity)
            item = {"theory": theory, "mass_kg": mass,
                    "zeta_p": float(case.target.loss_factor(case.impactor_mass, stiffness))}
            for ratio in cutoffs:
                result, _ = _peak(case, replace(case.settings, **{key: float(ratio)}), corner_cutoff=False)
                item[f"F{ratio}_N"] = result.peak_force
            rows.append(item)
            print(" ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}" for k, v in item.items()), flush=True)
    return pd.DataFrame(rows)


def _options(parser) -> None:
    parser.add_argument("--scan", action="store_true", help="the impactor mass scan on the SSSS plate")
    parser.add_argument("--edges", nargs="*", default=EDGES, help="edge sets to run (default: all)")
    parser.add_argument("--plates", nargs="*", type=int, default=None, help="indices into PLATES (default: all)")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=_options)
    if args.scan:
        frame = scan((0.0084, 0.3), (10, 20)) if args.smoke else scan()
        frame.to_csv(Path(args.out_dir) / "patch_cutoff_scan.csv", index=False, float_format="%.8g")
        return
    if args.smoke:
        rows, cutoffs = [row(PLATES[1][0], "SSSS", PLATES[1][1], cutoffs=(20, 40))], (20, 40)
    else:
        cutoffs = CUTOFFS
        chosen = [PLATES[i] for i in args.plates] if args.plates is not None else PLATES
        rows = []
        for label, lines in chosen:
            for edges in args.edges:
                rows.append(row(label, edges, lines))
                print(table(pd.DataFrame(rows[-1:]), cutoffs).splitlines()[-1], flush=True)
    frame = pd.DataFrame(rows)
    frame.to_csv(Path(args.out_dir) / "patch_cutoff_edges.csv", index=False, float_format="%.8g")
    text = table(frame, cutoffs)
    (Path(args.out_dir) / "patch_cutoff_edges.txt").write_text(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
