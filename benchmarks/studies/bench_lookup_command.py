"""The ``impactmaps lookup`` command's cost in a fresh interpreter, beside another checkout's.

A lookup on a shipped map only interpolates it, so its cost is the interpreter's start and
the imports (issue 30: a non-solving command in ≤ 0.5 s). Each command runs ``REPEATS`` times
in a fresh ``python -m impactmaps.cli`` (background warm-up off), alternating between this
checkout and ``--base`` so both see the same load; reported: the best wall time and the best
CPU time (``getrusage`` of the ended child), with the load average before and after.

Run: ``python benchmarks/studies/bench_lookup_command.py --base CHECKOUT [--repeats 5] [--append]``;
``--append`` adds the table to ``benchmarks/studies/RESULTS_cold_start.md``.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import resource
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

#: The lookups timed: linear, Hertz and an elastic-plastic map, human and JSON output.
COMMANDS = {
    "lookup linear": ("lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1.198", "--lambda", "0.425"),
    "lookup hertz --json": ("lookup", "--kind", "beam", "--theory", "euler", "--law", "hertz", "--zeta", "0.3",
                            "--lambda", "2", "--json"),
    "lookup yc": ("lookup", "--kind", "plate", "--theory", "kirchhoff", "--law", "yc", "--beta", "3", "--zeta",
                  "0.5", "--lambda", "1"),
    "--help": ("--help",),
}


def run_once(root: pathlib.Path, argv) -> tuple[float, float]:
    """(wall, CPU) seconds of ``impactmaps ARGV`` from ``root`` in a fresh interpreter."""
    env = dict(os.environ, PYTHONPATH=str(root), IMPACTMAPS_NO_BACKGROUND_WARMUP="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "impactmaps.cli", *argv], cwd=root, env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed in {root}: {done.stderr}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=pathlib.Path, required=True, help="the checkout to compare with")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--append", action="store_true", help="append to benchmarks/studies/RESULTS_cold_start.md")
    args = parser.parse_args()
    load_before = os.getloadavg()
    rows = []
    for label, argv in COMMANDS.items():
        runs = {"this": [], "base": []}
        for _ in range(args.repeats):
            for key, root in (("this", ROOT), ("base", args.base.resolve())):
                runs[key].append(run_once(root, argv))
        best = {key: (min(w for w, _ in values), min(c for _, c in values)) for key, values in runs.items()}
        rows.append(f"| `{label}` | **{best['this'][0]:.2f}** | {best['this'][1]:.2f} | {best['base'][0]:.2f} | "
                    f"{best['base'][1]:.2f} | {best['base'][0] / best['this'][0]:.1f} |")
    load_after = os.getloadavg()
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    text = "\n".join([
        f"\n## The lookup command, fresh interpreter ({stamp})\n",
        f"`python benchmarks/studies/bench_lookup_command.py --base {args.base} --repeats {args.repeats}`; best of "
        f"{args.repeats} alternating runs, background warm-up off; load average (1, 5, 15 min) "
        f"{load_before[0]:.1f}/{load_before[1]:.1f}/{load_before[2]:.1f} before, "
        f"{load_after[0]:.1f}/{load_after[1]:.1f}/{load_after[2]:.1f} after (2 shared cores).\n",
        "| command | wall [s] | CPU [s] | base wall [s] | base CPU [s] | base/this wall |",
        "|---|---|---|---|---|---|",
        *rows, ""])
    print(text)
    if args.append:
        with open(ROOT / "benchmarks" / "studies" / "RESULTS_cold_start.md", "a", encoding="utf-8") as out:
            out.write(text)


if __name__ == "__main__":
    main()
