"""What a lookup costs, per law: vectorised, one point at a time, per physical case, first call.

For each shipped map family (linear and Hertz on the SS Euler beam and the SSSS Kirchhoff
plate; Yigit–Christoforou, Stronge and epp on the plate) in one process: ``lookup`` (or
``lookup(β, ζ, λ, law=…)``) of N fresh random points at once (per point), of fresh points one at
a time and of one point repeated; ``lookup(case=…)`` of fresh physical cases one at a time
and of one case again; and, in a fresh process each, the first lookup (imports, the map
and its refinement read). With ``--base PATH`` the same measurements run with the code at
PATH (a checkout of another commit, first on ``PYTHONPATH``) and with this checkout,
alternately, twice each, in one session; the table gives both (the faster of the two
runs) and their ratio. Only public functions present in both are called.

    python benchmarks/studies/bench_lookup.py                                   # this checkout, printed
    python benchmarks/studies/bench_lookup.py --base /tmp/base --out benchmarks/studies/RESULTS_lookup.md
    python benchmarks/studies/bench_lookup.py --quick                           # a few points each (smoke)
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import pathlib
import subprocess
import sys
import time
import warnings
import zlib

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
#: (row, law, structure, theory): the families measured.
ROWS = [("linear beam", "linear", "beam", "euler"), ("linear plate", "linear", "plate", "kirchhoff"),
        ("Hertz beam", "hertz", "beam", "euler"), ("Hertz plate", "hertz", "plate", "kirchhoff"),
        ("YC plate", "yc", "plate", "kirchhoff"), ("Stronge plate", "stronge", "plate", "kirchhoff"),
        ("epp plate", "epp", "plate", "kirchhoff")]
#: The numbers drawn (log-uniform), inside every measured map and next to no unresolved point.
RANGES = {"zeta": (0.01, 50.0), "lambda_": (0.002, 10.0)}
FIRST = ("import time, warnings; warnings.simplefilter('ignore'); t = time.perf_counter(); {imports}; {call}; "
         "print(time.perf_counter() - t)")


def _draw(rng, count: int, dataset=None) -> dict:
    numbers = {axis: np.exp(rng.uniform(np.log(low), np.log(high), count)) for axis, (low, high) in RANGES.items()}
    if dataset is not None:  # a plastic map: its own (β, ζ, λ) ranges, kept off the edges
        numbers = {axis: np.exp(rng.uniform(*np.log(np.quantile(dataset[axis].values, [0.1, 0.9])), count))
                   for axis in ("beta", "zeta", "lambda_")}
    return numbers


def _reader(law: str, structure: str, theory: str):
    """``(read(numbers), dataset)``: a vectorised read of the family's shipped map."""
    if law in ("linear", "hertz"):
        from impactmaps import lookup

        return (lambda n: lookup(n["zeta"], n["lambda_"], kind=structure, theory=theory, law=law)), None
    from impactmaps.maps.files.shipped import load_shipped_map
    from impactmaps import lookup

    return ((lambda n: lookup(n["beta"], n["zeta"], n["lambda_"], kind=structure, theory=theory,
                                      law=law)), load_shipped_map(structure, theory, law))


def _case(rng, law: str, structure: str):
    """A physical case of the family with fresh numbers inside its map."""
    from impactmaps.cases import parse_case
    from impactmaps.dimensionless import realise
    from impactmaps.closed_forms.hertz_similarity import realise_hertz
    from impactmaps.materials import material
    from impactmaps.targets import Beam, Plate

    steel = material("structural-steel")
    if structure == "beam":
        target = Beam.rectangular(0.5, 0.02, 0.02, steel, theory="euler")
        table = 'type = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.02\ntheory = "euler"'
    else:
        target = Plate.isotropic(0.3, 0.3, 0.004, steel)
        table = 'type = "plate"\nlength_x = 0.3\nlength_y = 0.3\nthickness = 0.004\ntheory = "kirchhoff"'
    table += '\nmaterial = "structural-steel"'
    numbers = _draw(rng, 1)
    zeta, lam = float(numbers["zeta"][0]), float(numbers["lambda_"][0])
    if law == "linear":
        impactor = realise(target, zeta, lam)
        return parse_case(f'[impactor]\nradius = 0.005\nmaterial = "structural-steel"\n'
                          f'mass = {float(impactor.impactor_mass)!r}\nvelocity = 1.0\n[target]\n{table}\n'
                          f'[contact]\nlaw = "linear"\nstiffness = {float(impactor.contact_stiffness)!r}\n')
    if law == "hertz":
        text = ('[impactor]\nradius = 0.005\nmaterial = "structural-steel"\nmass = 1.0\nvelocity = 1.0\n'
                f'[target]\n{table}\n[contact]\nlaw = "hertz"\n')
        impact = realise_hertz(target, zeta, lam, parse_case(text).law)
        return parse_case(text.replace("mass = 1.0", f"mass = {impact.mass!r}")
                          .replace("velocity = 1.0", f"velocity = {impact.velocity!r}"))
    name = {"yc": "yigit-christoforou"}.get(law, law)
    radius, velocity = 10 ** rng.uniform(np.log10(0.003), np.log10(0.02)), 10 ** rng.uniform(-0.5, 0.5)
    return parse_case(f'[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
                      f'[target]\n{table}\n[contact]\nlaw = "{name}"\n')


_CPU = {}


def _time(call, repeat: int = 1) -> float:
    """Wall seconds per call (the process CPU seconds per call: ``_CPU["last"]``)."""
    start, cpu = time.perf_counter(), time.process_time()
    for _ in range(repeat):
        call()
    _CPU["last"] = (time.process_time() - cpu) / repeat
    return (time.perf_counter() - start) / repeat


def measure(points: int, singles: int, cases: int) -> dict:
    """The figures of this process's code (module docstring): row → name → seconds."""
    from impactmaps import lookup

    warnings.simplefilter("ignore")
    out = {}
    for row, law, structure, theory in ROWS:
        rng = np.random.default_rng(zlib.crc32(row.encode()))
        read, dataset = _reader(law, structure, theory)
        read(_draw(rng, 1, dataset))  # the map read and prepared: not what is measured here
        numbers = _draw(rng, points, dataset)
        cpu = {}
        vector = _time(lambda: read(numbers)) / points
        cpu["vector"] = _CPU["last"] / points
        fresh = _draw(rng, singles, dataset)
        single_fresh = _time(lambda: [read({k: v[i] for k, v in fresh.items()}) for i in range(singles)]) / singles
        cpu["single_fresh"] = _CPU["last"] / singles
        one = {k: v[0] for k, v in fresh.items()}
        single_again = _time(lambda: read(one), 200)
        cpu["single_again"] = _CPU["last"]
        drawn, answered = [], 0
        while law not in ("linear", "hertz") and len(drawn) < cases and answered < 50 * cases:
            answered += 1
            case = _case(rng, law, structure)
            try:
                lookup(case=case, build=False)  # a case outside the map (plastic numbers fall where they fall)
            except ValueError:
                continue
            drawn.append(case)
        fresh_cases = [_case(rng, law, structure) for _ in range(cases)] if law in ("linear", "hertz") else drawn
        case_fresh = _time(lambda: [lookup(case=case, build=False) for case in fresh_cases]) / len(fresh_cases)
        cpu["case_fresh"] = _CPU["last"] / len(fresh_cases)
        case_again = _time(lambda: lookup(case=fresh_cases[0], build=False), 50)
        cpu["case_again"] = _CPU["last"]
        out[row] = {"vector": vector, "single_fresh": single_fresh, "single_again": single_again,
                    "case_fresh": case_fresh, "case_again": case_again, "points": points, "singles": singles,
                    "cases": len(fresh_cases)} | {f"cpu_{key}": value for key, value in cpu.items()}
        print(f"# {row}: {out[row]}", file=sys.stderr)
    return out


def first_lookup(law: str, structure: str, theory: str, env: dict) -> float:
    """Seconds of the first lookup in a fresh process (imports, map and refinement read)."""
    if law in ("linear", "hertz"):
        imports = "from impactmaps import lookup"
        call = f"lookup(1.0, 0.1, kind={structure!r}, theory={theory!r}, law={law!r})"
    else:
        imports = "from impactmaps import lookup"
        call = f"lookup(1.0, 1.0, 1.0, kind={structure!r}, theory={theory!r}, law={law!r})"
    script = FIRST.format(imports=imports, call=call)
    result = subprocess.run([sys.executable, "-c", script], check=False, capture_output=True, text=True, env=env,
                            cwd="/")
    return float(result.stdout) if result.returncode == 0 else float("nan")


def _run(code: pathlib.Path, args, points: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(code), OMP_NUM_THREADS="1")
    command = [sys.executable, str(HERE / "bench_lookup.py"), "--measure", "--points", str(points),
               "--singles", str(args.singles), "--cases", str(args.cases)]
    result = subprocess.run(command, check=True, capture_output=True, text=True, env=env, cwd="/")
    figures = json.loads(result.stdout)
    for row, law, structure, theory in ROWS:
        figures[row]["first"] = first_lookup(law, structure, theory, env)
    return figures


COLUMNS = [("vector", 1e6, "µs/point", "`lookup`, fresh points at once (this: {points}; base: --base-points)"),
           ("single_fresh", 1e3, "ms", "one fresh point at a time ({singles})"),
           ("single_again", 1e3, "ms", "one point repeated"),
           ("case_fresh", 1e3, "ms", "`lookup_case`, fresh case ({cases})"),
           ("case_again", 1e3, "ms", "`lookup_case`, the same case again"),
           ("first", 1.0, "s", "first lookup, fresh process")]


def table(runs: dict, labels: list[str]) -> str:
    """Markdown: per family and measurement, each code's faster run and the ratio base/this
    (wall time, then the process's CPU time of the same calls)."""
    lines = []
    columns = COLUMNS + [(f"cpu_{key}", factor, unit, f"CPU time: {text}") for key, factor, unit, text in COLUMNS
                         if key != "first"]
    for key, factor, unit, text in columns:
        example = runs[labels[-1]][0][ROWS[0][0]]
        lines += [f"**{text.format(**example)}** [{unit}]", "",
                  "| family | " + " | ".join(labels) + (" | ratio |" if len(labels) == 2 else " |"),
                  "|---|" + "---|" * (len(labels) + (len(labels) == 2))]
        for row, *_ in ROWS:
            best = [min(run[row][key] for run in runs[label]) * factor for label in labels]
            ratio = f" {best[0] / best[1]:.3g}× |" if len(labels) == 2 and best[1] > 0 else ""
            lines.append(f"| {row} | " + " | ".join(f"{value:.3g}" for value in best) + " |" + ratio)
        lines.append("")
    return "\n".join(lines)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=pathlib.Path, help="checkout of the code to compare with")
    parser.add_argument("--out", type=pathlib.Path, help="write the Markdown table here")
    parser.add_argument("--points", type=int, default=1000)
    parser.add_argument("--base-points", type=int, default=100,
                        help="points at once with the base code (its Hertz lookups integrate per point)")
    parser.add_argument("--singles", type=int, default=50)
    parser.add_argument("--cases", type=int, default=50)
    parser.add_argument("--quick", action="store_true", help="a few points each: a smoke run")
    parser.add_argument("--measure", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.quick:
        args.points, args.base_points, args.singles, args.cases = 20, 5, 3, 2
    if args.measure:
        print(json.dumps(measure(args.points, args.singles, args.cases)))
        return
    codes = {"base": args.base, "this": HERE.parents[1]} if args.base else {"this": HERE.parents[1]}
    runs = {label: [] for label in codes}
    for _ in range(1 if args.quick else 2):
        for label, code in codes.items():
            runs[label].append(_run(code, args, args.base_points if label == "base" else args.points))
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    text = table(runs, list(codes))
    header = (f"Measured {datetime.datetime.now().astimezone().isoformat(timespec='seconds')}, "
              f"{os.cpu_count()} cores, load average {load} at the end; "
              + (f"base: {args.base}, " if args.base else "") + f"this: {HERE.parents[1]}.\n\n")
    print(header + text)
    if args.out:
        args.out.write_text(header + text)


if __name__ == "__main__":
    main()
