"""Do the bands of `sensitive` map points hold the value a further refinement gives?

A map point whose F̄max does not settle within the accuracy control's two refinement
levels is stored ``sensitive`` with a band [fmax_low, fmax_high]
(:func:`impactmaps.maps.family.accuracy.controlled_point`). This study finds N random sensitive
points per structure (log-uniform in ζ ∈ [1, 1e3], λ ∈ [1e-3, 0.05], where they lie),
computes at each the three levels (base, 2×/½, 4×/¼), the five perturbed runs (cut-off
±1 %, step −1 %, ζ ±1 %) made from the base settings *and* from the finest level, and the
reference: a third refinement (8× cut-off and mode floor, ⅛ step). It then counts at how
many points each candidate band holds the reference:

* ``levels``: every level and the finest ± its last change, no perturbed runs;
* ``perturbed at base`` / ``perturbed at finest``: the same plus the perturbed runs;
* ``perturbed at base, widened by the tolerance``: the finest ± max(last change, 1e-3)
  — the band :func:`~impactmaps.maps.family.accuracy.controlled_point` stores.

Writes ``validation/sensitive_bands.csv`` (one row per point) and prints a Markdown table.

    python validation/sensitive_bands.py [--points 70] [--seed 1]
    python validation/sensitive_bands.py --smoke    # 1 point per structure
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.maps.family.accuracy import AccuracyControl, perturbed_runs, settled
from impactmaps.maps.compute.linear_points import LINEAR
from impactmaps.maps.compute.points import basis_table, map_plan, table_runner
from impactmaps.maps.family.structures import MAX_MODES
from impactmaps.solvers.mode_budget import frequency_cap
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.solvers.modal import ModalSettings

from _script_options import parse

HERE = Path(__file__).resolve().parent
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
CONTROL = AccuracyControl()


def sensitive_points(name: str, count: int, seed: int) -> list[dict]:
    """``count`` random sensitive points of ``name`` with their levels, perturbed runs and reference."""
    structure = structure_from_name(name)
    target, cap = structure.build(), frequency_cap(structure.build(), MAX_MODES)
    base = ModalSettings()
    table = basis_table(structure, base.min_modes)
    levels = [base]
    for _ in range(3):
        levels.append(levels[-1].refined())
    rng = np.random.default_rng(seed)
    rows = []
    while len(rows) < count:
        zeta, lam = 10 ** rng.uniform(0, 3), 10 ** rng.uniform(-3, np.log10(0.05))
        impact = LINEAR.realise(target, (zeta, lam))
        plan = map_plan(target, impact.law, impact.mass, impact.omega, base.cutoff_ratio * impact.omega, cap, zeta)
        if plan is None or plan.method != "modal+residual":
            continue
        run = table_runner(LINEAR, target, table, cap, (zeta, lam), impact, [])
        runs = [run(levels[0], 1.0), run(levels[1], 1.0)]
        if settled(runs[1], runs[0], CONTROL):
            continue
        runs.append(run(levels[2], 1.0))
        if settled(runs[2], runs[1], CONTROL):
            continue
        rows.append({"structure": name, "zeta": zeta, "lambda": lam,
                     **{f"level{k}": r.fmax_normalised for k, r in enumerate(runs)},
                     "impacts_finest": runs[2].impacts,
                     "reference": run(levels[3], 1.0).fmax_normalised,
                     **{f"{name}_perturbed{k}": r.fmax_normalised for name, level in (("base", 0), ("finest", 2))
                        for k, r in enumerate(perturbed_runs(run, levels[level], CONTROL.perturbation))}})
    return rows


def band_holds(frame: pd.DataFrame, perturbed: str | None, floor: float) -> pd.Series:
    """Whether each point's band, built with the ``perturbed`` runs ("base", "finest" or None), holds its reference."""
    levels = frame[["level0", "level1", "level2"]].to_numpy()
    widening = np.maximum(np.abs(levels[:, 2] - levels[:, 1]), floor)
    seen = [levels, (levels[:, 2] - widening)[:, None], (levels[:, 2] + widening)[:, None]]
    if perturbed is not None:
        seen.append(frame[[f"{perturbed}_perturbed{k}" for k in range(5)]].to_numpy())
    seen = np.hstack(seen)
    reference = frame["reference"].to_numpy()
    return pd.Series((seen.min(axis=1) <= reference) & (reference <= seen.max(axis=1)), index=frame.index)


BANDS = {
    "levels": (None, 0.0),
    "perturbed at finest (before 2026-11-24)": ("finest", 0.0),
    "perturbed at base": ("base", 0.0),
    "perturbed at base, widened by the tolerance (stored)": ("base", CONTROL.tolerance),
}


def main(argv=None) -> None:
    def options(parser):
        parser.add_argument("--points", type=int, default=70, help="sensitive points per structure")
        parser.add_argument("--seed", type=int, default=1)

    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=options)
    count = 1 if args.smoke else args.points
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        frame = pd.DataFrame([row for k, name in enumerate(STRUCTURES)
                              for row in sensitive_points(name, count, args.seed + k)])
    frame.to_csv(args.out_dir / "sensitive_bands.csv", index=False, float_format="%.9g")
    print("| band | " + " | ".join(STRUCTURES) + " |\n|---|" + "---|" * len(STRUCTURES))
    for label, (perturbed, floor) in BANDS.items():
        holds = band_holds(frame, perturbed, floor)
        cells = [f"{int(holds[frame.structure == name].sum())}/{int((frame.structure == name).sum())}"
                 for name in STRUCTURES]
        print(f"| {label} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
