"""`lookup --case` against `simulate` on random physical cases, per contact law and family.

For each contact law (linear, Hertz, Yigit–Christoforou, ``epp``) and each family of targets, N
random physical cases are drawn — random size and metal of the target, the impact's
numbers drawn log-uniform over (and a little beyond) the maps' range and realised as an
impactor mass, speed and contact stiffness (plastic law: a steel ball of random radius
and speed, its numbers where physics puts them) — and each is answered by
:func:`impactmaps.lookup` (``case=``) and by :func:`impactmaps.cases.run_case`
(the modal simulation the lookup stands in for). Families:

* ``shipped``: SS Euler beams and SSSS square Kirchhoff plates struck at the centre — the
  shipped maps describe them;
* ``clamped beam``, ``off-centre beam`` (x0/L ∈ [0.2, 0.45]), ``oblong plate`` (b/a ∈
  [1.2, 2]), ``thick Mindlin plate`` (a/h ∈ [6, 9.5], below the shipped families): no
  shipped map describes them; lookup builds a map tile on demand where it can
  (:mod:`impactmaps.cases.on_demand`; a plastic tile over (β, ζ, λ) for a plastic law) or
  refuses (a linear law on a Mindlin plate is a point load, which has no converged value;
  a plastic law on a Mindlin plate has the sphere radius as a fourth number: refused).

A lookup is *right* when |peak force − simulate| ≤ its band + 1e-3 of the force scale
(the direct run's own tolerance). Prints a Markdown table per (law, family): cases,
answered, refused (and the first refusal reason), median and largest error, median band,
answers inside their band; writes ``validation/case_lookup_error.csv`` (with ``--laws``,
only those laws' rows of an existing file are replaced).

    python validation/case_lookup_error.py [--cases 20] [--seed 1] [--laws LAW …]
    python validation/case_lookup_error.py --smoke    # 1 case: linear and Hertz, shipped and clamped beam
"""

from __future__ import annotations

import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.cases import parse_case, run_case
from impactmaps.dimensionless import realise
from impactmaps.closed_forms.hertz_similarity import realise_hertz
from impactmaps import lookup

from _script_options import parse

HERE = Path(__file__).resolve().parent
LAWS = ("linear", "hertz", "yigit-christoforou", "epp")
FAMILIES = ("shipped", "clamped beam", "off-centre beam", "oblong plate", "thick Mindlin plate")
SPHERE = 'radius = 0.005\nmaterial = "structural-steel"'


def _target_table(rng, family: str) -> str:
    """The [target] table of a random target of ``family``."""
    metal = rng.choice(["structural-steel", "aluminium-6061-t6"])
    beam = family in ("clamped beam", "off-centre beam") or (family == "shipped" and rng.uniform() < 0.5)
    if beam:
        length, width, height = rng.uniform(0.2, 1.0), rng.uniform(0.01, 0.05), rng.uniform(0.005, 0.03)
        table = (f'type = "beam"\nlength = {length!r}\nwidth = {width!r}\nheight = {height!r}\n'
                 f'material = "{metal}"\ntheory = "euler"\n')
        if family == "clamped beam":
            table += 'supports = "cc"\n'
        elif family == "off-centre beam":
            table += f'supports = "ss"\nimpact_position = {rng.uniform(0.2, 0.45) * length!r}\n'
        return table
    side = rng.uniform(0.1, 0.6)
    aspect = rng.uniform(1.2, 2.0) if family == "oblong plate" else 1.0
    if family == "thick Mindlin plate":
        return (f'type = "plate"\nlength_x = {side!r}\nlength_y = {side!r}\n'
                f'thickness = {side / rng.uniform(6.0, 9.5)!r}\nmaterial = "{metal}"\ntheory = "mindlin"\n')
    return (f'type = "plate"\nlength_x = {side!r}\nlength_y = {side * aspect!r}\n'
            f'thickness = {rng.uniform(0.001, 0.01)!r}\nmaterial = "{metal}"\ntheory = "kirchhoff"\n')


def random_case(rng, law: str, family: str):
    """A random physical case of ``law`` on a target of ``family`` (see the module docstring)."""
    table = _target_table(rng, family)
    if law in ("yigit-christoforou", "epp"):
        radius, velocity = 10 ** rng.uniform(np.log10(0.002), np.log10(0.03)), 10 ** rng.uniform(-1.0, 1.0)
        return parse_case(f'[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
                          f'[target]\n{table}[contact]\nlaw = "{law}"\n')
    zeta, lam = 10 ** rng.uniform(-2.0, 1.7), 10 ** rng.uniform(-1.2, 1.2)
    if law == "linear":
        target = parse_case(f'[impactor]\n{SPHERE}\nmass = 1.0\nvelocity = 1.0\n[target]\n{table}'
                            '[contact]\nlaw = "linear"\nstiffness = 1e7\n').target
        impactor = realise(target, zeta, lam)
        return parse_case(f'[impactor]\n{SPHERE}\nmass = {float(impactor.impactor_mass)!r}\n'
                          f'velocity = {rng.uniform(0.1, 3.0)!r}\n[target]\n{table}[contact]\nlaw = "linear"\n'
                          f'stiffness = {float(impactor.contact_stiffness)!r}\n')
    text = f'[impactor]\n{SPHERE}\nmass = 1.0\nvelocity = 1.0\n[target]\n{table}[contact]\nlaw = "hertz"\n'
    case = parse_case(text)
    impact = realise_hertz(case.target, zeta, lam, case.law)
    return parse_case(text.replace("mass = 1.0", f"mass = {impact.mass!r}")
                      .replace("velocity = 1.0", f"velocity = {impact.velocity!r}"))


def measure(law: str, family: str, count: int, rng, cache_dir: Path) -> list[dict]:
    """``count`` random cases of (law, family): the lookup, its band and simulate's peak force."""
    rows = []
    for _ in range(count):
        case = random_case(rng, law, family)
        row = {"law": law, "family": family}
        start = time.perf_counter()
        try:
            found = lookup(case=case, cache_dir=cache_dir)
        except ValueError as error:
            rows.append(row | {"answered": False, "reason": str(error).split(";")[0][:120]})
            continue
        row |= {"answered": True, "lookup_seconds": time.perf_counter() - start, "map": found["map"],
                "status": found["status"], "lookup_N": found["peak_force_N"], "band_N": found["peak_force_error_N"],
                "scale_N": found["peak_force_N"] / found["fmax_normalised"]}
        _, summary = run_case(case)
        row["simulate_N"] = summary["peak_force_N"]
        rows.append(row)
    return rows


def summary_table(frame: pd.DataFrame) -> str:
    """The Markdown table of the module docstring."""
    lines = ["| law | family | cases | answered | refused (first reason) | median error | largest error "
             "| median band | inside band |", "|---|---|---|---|---|---|---|---|---|"]
    for (law, family), group in frame.groupby(["law", "family"], sort=False):
        answered = group[group.answered]
        refused = group[~group.answered]
        reason = f" ({refused.reason.iloc[0]})" if len(refused) else ""
        if len(answered):
            error = (answered.lookup_N - answered.simulate_N).abs() / answered.simulate_N
            band = answered.band_N / answered.lookup_N
            inside = (answered.lookup_N - answered.simulate_N).abs() <= answered.band_N + 1e-3 * answered.scale_N
            cells = f"{100 * error.median():.2f} % | {100 * error.max():.2f} % | {100 * band.median():.2f} % " \
                    f"| {int(inside.sum())}/{len(answered)}"
        else:
            cells = "– | – | – | –"
        lines.append(f"| {law} | {family} | {len(group)} | {len(answered)} | {len(refused)}{reason} | {cells} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    def options(parser):
        parser.add_argument("--cases", type=int, default=20, help="cases per law and family")
        parser.add_argument("--seed", type=int, default=1)
        parser.add_argument("--laws", nargs="*", choices=LAWS, default=None,
                            help="only these laws (their rows replace those of an existing CSV)")

    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=options)
    count = 1 if args.smoke else args.cases
    laws, families = (LAWS[:2], FAMILIES[:2]) if args.smoke else (tuple(args.laws or LAWS), FAMILIES)
    rng = np.random.default_rng(args.seed)
    with tempfile.TemporaryDirectory(prefix="impactmaps-tiles-") as cache, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings of the extreme draws
        frame = pd.DataFrame([row for law in laws for family in families
                              for row in measure(law, family, count, rng, Path(cache))])
    path = args.out_dir / "case_lookup_error.csv"
    if args.laws and path.exists():  # the other laws' rows kept, in the order of LAWS
        kept = pd.read_csv(path)
        frame = pd.concat([kept[~kept.law.isin(laws)], frame], ignore_index=True)
        frame = frame.sort_values("law", key=lambda column: column.map(LAWS.index), kind="stable")
    frame.to_csv(path, index=False, float_format="%.9g")
    print(summary_table(frame))


if __name__ == "__main__":
    main()
