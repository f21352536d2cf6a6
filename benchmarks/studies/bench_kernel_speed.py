"""Warm speed of the modal kernel on a few runs, for two checkouts side by side.

Each checkout (``--root``, repeatable; default this one) runs in its own interpreter with
its own package first on the path: one warm-up call per case (compile or cache load),
then the CPU time (``time.process_time``) of ``--repeats`` calls of ``simulate``; the
median per case is printed with the load average. The cases: Hertz and linear (exact
contact phase) impacts on the shipped SS Euler beam and SS Kirchhoff plate, a light and
a heavy impactor, with and without the history. Run the checkouts in the same minutes
(the machine is shared) and compare ratios.

Run: ``python benchmarks/studies/bench_kernel_speed.py --root /tmp/base --root . [--repeats 7] [--out FILE]``.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

_SCRIPT = r"""
import json, statistics, sys, time, warnings
warnings.simplefilter("ignore")
from impactmaps.contact import contact_law
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.solvers.modal import simulate
repeats = int(sys.argv[1])
out = {}
for structure in ("beam-ss-euler", "plate-ssss-kirchhoff"):
    target = structure_from_name(structure).build()
    for law_name, law in (("hertz", contact_law("hertz", stiffness=1e10)), ("linear", contact_law("linear", stiffness=1e7))):
        for mass in (1e-3, 1.0):
            for record in (False, True):
                run = lambda: simulate(target, law, mass, 1.0, record=record)
                result = run()  # warm-up
                times = []
                for _ in range(repeats):
                    start = time.process_time()
                    run()
                    times.append(time.process_time() - start)
                out[f"{structure} {law_name} m={mass:g} record={record}"] = [statistics.median(times), result.details.steps]
print(json.dumps(out))
"""


def measure(root: pathlib.Path, repeats: int) -> dict:
    """{case: [median CPU seconds, steps]} of the checkout at ``root``."""
    env = dict(os.environ, PYTHONPATH=str(root))
    done = subprocess.run([sys.executable, "-c", _SCRIPT, str(repeats)], cwd=root, env=env, capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path, action="append", help="a checkout (repeatable)")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--out", type=pathlib.Path, help="also write the table here (Markdown)")
    args = parser.parse_args(argv)
    roots = [root.resolve() for root in (args.root or [ROOT])]
    results = [measure(root, args.repeats) for root in roots]
    head = "| case | steps | " + " | ".join(f"`{root}` CPU [ms]" for root in roots) + " |"
    lines = ["# Warm CPU per modal run, checkouts side by side", "",
             f"`python benchmarks/studies/bench_kernel_speed.py` ({', '.join(root.name for root in roots)}); "
             f"load average {os.getloadavg()[0]:.1f}; median of {args.repeats} runs", "", head,
             "|" + "---|" * (2 + len(roots))]
    for case in results[0]:
        cells = " | ".join(f"{result[case][0] * 1e3:.2f}" for result in results)
        lines.append(f"| {case} | {results[0][case][1]} | {cells} |")
    text = "\n".join(lines)
    print(text)
    if args.out:
        args.out.write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
