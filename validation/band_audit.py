"""Band audit: does a map point's ``fmax_error``, and a lookup's band, cover the error?

For each family of the shipped linear maps (SS Euler and Timoshenko beams, SSSS Kirchhoff and
Mindlin plates) the script draws ``--points`` log-uniform random (ζ, λ) inside the shipped map's
range (``--seed``, recorded in the output), solves each as a map point
(:func:`impactmaps.maps.family.accuracy.controlled_point`: base run, refinements until the change is
within 1e-3) and, at the ``converged`` and ``refined`` modal points, runs a reference
``--levels`` refinement levels above the base (cut-off and mode floor ×2ᵏ, step /2ᵏ; default 4:
two to three levels above the retained run). It counts where |F̄max − reference| is within

* the change alone (``fmax_error`` before issue 40: "before"),
* the stated ``fmax_error`` (:func:`~impactmaps.maps.family.accuracy.stated_error`: the change, at
  least 2e-4, 1e-3 with re-impacts; "after"),

and where the shipped map's lookup at the same point (interpolation + its points' stated
errors; a lookup refused or ``sensitive`` is not counted) is within its band of the reference.

Writes ``band_audit.csv`` (one row per point) and ``band_audit.md`` (the tables docs/accuracy.rst
and docs/validation.rst quote) into ``--out-dir`` (default ``validation/``).

    nice -n 10 python validation/band_audit.py [--points 60] [--seed 40] [--levels 4]
    python validation/band_audit.py --smoke    # 1 point per family, reference 2 levels up
"""

from __future__ import annotations

import os
import time
import warnings
from pathlib import Path

if __name__ == "__main__":  # one BLAS thread, set before NumPy loads
    from _script_options import one_blas_thread

    one_blas_thread()

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from impactmaps.maps.compute.linear_points import LINEAR  # noqa: E402
from impactmaps.maps.compute.points import basis_table, table_runner  # noqa: E402
from impactmaps.maps.family.accuracy import (  # noqa: E402
    ERROR_FLOOR,
    REIMPACT_ERROR_FLOOR,
    STATUSES,
    AccuracyControl,
    controlled_point,
    stated_error,
)
from impactmaps.maps.family.structures import MAX_MODES, structure_from_name  # noqa: E402
from impactmaps import lookup  # noqa: E402
from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map
from impactmaps.solvers.modal import ModalSettings  # noqa: E402
from impactmaps.solvers.mode_budget import frequency_cap  # noqa: E402

from _script_options import parse  # noqa: E402

HERE = Path(__file__).resolve().parent
#: Status codes of the points whose error the audit measures.
SETTLED = (STATUSES.index("converged"), STATUSES.index("refined"))


def audit_family(kind: str, theory: str, points: int, seed: int, levels: int) -> pd.DataFrame:
    """``points`` random points of one shipped map's family, each with its error and the lookup's."""
    name = SHIPPED_MAPS[(kind, theory)]
    structure = structure_from_name(name)
    target = structure.build()
    cap = frequency_cap(target, MAX_MODES)
    dataset = load_shipped_map(kind, theory)
    rng = np.random.default_rng(seed)
    zetas = np.exp(rng.uniform(*np.log([dataset["zeta"].min().item(), dataset["zeta"].max().item()]), points))
    lambdas = np.exp(rng.uniform(*np.log([dataset["lambda_"].min().item(), dataset["lambda_"].max().item()]), points))
    base = ModalSettings()
    reference_settings = base
    for _ in range(levels):
        reference_settings = reference_settings.refined()
    table = basis_table(structure, base.min_modes)
    rows = []
    for zeta, lam in zip(zetas, lambdas):
        point = (float(zeta), float(lam))
        realised = LINEAR.realise(target, point)
        plan = LINEAR.plan(target, realised, point, cap, base)
        row = {"family": name, "seed": seed, "zeta": zeta, "lambda": lam}
        try:
            found = lookup(zeta, lam, kind=kind, theory=theory)
            row |= {"lookup": found.fmax_normalised, "lookup_band": found.fmax_error, "lookup_status": found.status}
        except ValueError:  # next to an unresolved map point: refused
            row |= {"lookup": np.nan, "lookup_band": np.nan, "lookup_status": "refused"}
        if plan.method is None or plan.asymptote is not None:
            rows.append(row | {"status": "unresolved" if plan.method is None else "asymptotic"})
            continue
        run = table_runner(LINEAR, target, table, cap, point, realised, [])
        answer = controlled_point(run, base, AccuracyControl())
        row |= {"status": STATUSES[answer["status"]], "impacts": answer["impacts"], "fmax": answer["fmax_normalised"],
                "change": answer["fmax_error"],
                "fmax_error": stated_error(answer["fmax_error"], answer["status"], answer["impacts"])}
        if answer["status"] in SETTLED:
            reference = run(reference_settings, 1.0)
            row |= {"reference": reference.fmax_normalised, "reference_impacts": reference.impacts}
        rows.append(row)
    return pd.DataFrame(rows)


def summary(frame: pd.DataFrame, seed: int, levels: int, seconds: float) -> str:
    """The Markdown tables of ``band_audit.md``."""
    settled = frame[frame["reference"].notna()]
    error = (settled["fmax"] - settled["reference"]).abs()
    lines = [
        "# Band audit: `fmax_error` and lookup bands against finer references",
        "",
        f"`nice -n 10 python validation/band_audit.py --points {int(frame.groupby('family').size().max())} "
        f"--seed {seed} --levels {levels}` ({time.strftime('%Y-%m-%d', time.gmtime())}, "
        f"{seconds / 60:.1f} CPU-min, load {os.getloadavg()[0]:.1f}). Random log-uniform (ζ, λ) in each shipped "
        f"map's range; references {levels} refinement levels above the base run. Floors of the stated "
        f"error: `ERROR_FLOOR` = {ERROR_FLOOR:g} (one impact), `REIMPACT_ERROR_FLOOR` = {REIMPACT_ERROR_FLOOR:g} "
        "(re-impacts).",
        "",
        "## `fmax_error` of converged and refined points",
        "",
        "| family | points drawn | converged/refined | within the change alone (before) "
        "| within `fmax_error` (after) | largest error | largest error / `fmax_error` |",
        "|---|---|---|---|---|---|---|",
    ]
    total = [0, 0, 0]
    for name, part in frame.groupby("family", sort=False):
        chosen = settled.family == name
        e, change, stated = error[chosen], settled["change"][chosen], settled["fmax_error"][chosen]
        before, after = int((e <= change).sum()), int((e <= stated).sum())
        total = [total[0] + len(e), total[1] + before, total[2] + after]
        lines.append(f"| {name} | {len(part)} | {len(e)} | {before} ({100 * before / max(len(e), 1):.0f} %) "
                     f"| {after} ({100 * after / max(len(e), 1):.1f} %) | {e.max() if len(e) else 0:.1e} "
                     f"| {(e / stated).max() if len(e) else 0:.2f} |")
    lines.append(f"| all | {len(frame)} | {total[0]} | {total[1]} ({100 * total[1] / max(total[0], 1):.0f} %) "
                 f"| {total[2]} ({100 * total[2] / max(total[0], 1):.1f} %) | {error.max() if len(error) else 0:.1e} "
                 f"| {(error / settled['fmax_error']).max() if len(error) else 0:.2f} |")
    looked = settled[settled["lookup_status"].isin(["converged", "refined", "interpolated"])]
    miss = (looked["lookup"] - looked["reference"]).abs()
    lines += ["", "## Lookup bands (interpolation + the points' `fmax_error`) at the same points", "",
              "| family | lookups (converged, refined, interpolated) | within the band | largest error "
              "| largest error / band | refused or sensitive |", "|---|---|---|---|---|---|"]
    for name, part in frame.groupby("family", sort=False):
        chosen = looked.family == name
        m, band = miss[chosen], looked["lookup_band"][chosen]
        inside = int((m <= band).sum())
        other = int((~part["lookup_status"].isin(["converged", "refined", "interpolated"])).sum())
        lines.append(f"| {name} | {len(m)} | {inside} ({100 * inside / max(len(m), 1):.1f} %) "
                     f"| {m.max() if len(m) else 0:.1e} | {(m / band).max() if len(m) else 0:.2f} | {other} |")
    inside = int((miss <= looked["lookup_band"]).sum())
    lines.append(f"| all | {len(miss)} | {inside} ({100 * inside / max(len(miss), 1):.1f} %) "
                 f"| {miss.max() if len(miss) else 0:.1e} | {(miss / looked['lookup_band']).max() if len(miss) else 0:.2f} "
                 f"| {int((~frame['lookup_status'].isin(['converged', 'refined', 'interpolated'])).sum())} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> None:
    def options(parser):
        parser.add_argument("--points", type=int, default=60, help="random points per family (default 60)")
        parser.add_argument("--seed", type=int, default=40, help="random seed (family k uses seed + k)")
        parser.add_argument("--levels", type=int, default=4, help="reference levels above the base (default 4)")

    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=options)
    points, levels = (1, 2) if args.smoke else (args.points, args.levels)
    start = time.process_time()
    frames = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k, (kind, theory) in enumerate(SHIPPED_MAPS):
            frames.append(audit_family(kind, theory, points, args.seed + k, levels))
            print(f"{SHIPPED_MAPS[(kind, theory)]}: {time.process_time() - start:.0f} CPU-s", flush=True)
    frame = pd.concat(frames, ignore_index=True)
    frame.to_csv(args.out_dir / "band_audit.csv", index=False, float_format="%.9g")
    text = summary(frame, args.seed, levels, time.process_time() - start)
    (args.out_dir / "band_audit.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
