"""The first integrating command on an empty numba cache, with the compile helper and without.

:mod:`impactmaps._compile.compile_helper` has a helper process compile part of the
integrator on the second core during the first cold run. Each measurement runs
``impactmaps --no-background-warm-up simulate CASE`` in a fresh interpreter on an empty
``NUMBA_CACHE_DIR``, for the example cases ``steel_plate_hertz.toml`` and
``aluminium_beam_linear.toml``, in rounds alternating three configurations:

* ``base``: another checkout (``--base``, e.g. a worktree of ``main``);
* ``helper``: this checkout;
* ``off``: this checkout with ``IMPACTMAPS_NO_BACKGROUND_WARMUP=1`` (no helper).

Wall time and CPU time (``getrusage`` of the ended children: the command and its helper)
with the load average. Then: one traced run (``IMPACTMAPS_COMPILE_HELPER_TRACE``: when each
process finished its share of the callees and when the helper finished the integrator,
seconds from the helper's launch); two commands started at once on one empty cache (their
peak forces against a run without the helper); the command again on the warm cache (median
of three, helper on and off: the helper's check is then a no-op).

Run: ``python benchmarks/studies/bench_compile_helper.py --base /tmp/base [--rounds 3] [--print-only]``;
appends to ``benchmarks/studies/RESULTS_cold_start.md`` unless ``--print-only``. Measure on an
otherwise idle machine: the helper needs the second core.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASES = ("steel_plate_hertz.toml", "aluminium_beam_linear.toml")
SWITCH = "IMPACTMAPS_NO_BACKGROUND_WARMUP"


def _children_cpu() -> float:
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _environment(code: pathlib.Path, cache: str, helper: bool, trace: str | None = None) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, OMP_NUM_THREADS="1",
               PYTHONPATH=str(code) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop(SWITCH, None)
    env.pop("IMPACTMAPS_COMPILE_HELPER_TRACE", None)
    if not helper:
        env[SWITCH] = "1"
    if trace:
        env["IMPACTMAPS_COMPILE_HELPER_TRACE"] = trace
    return env


def _command(case: str, out: str) -> list[str]:
    return [sys.executable, "-m", "impactmaps.cli", "--no-background-warm-up", "simulate",
            str(ROOT / "examples" / case), "--out", out]


def run(code: pathlib.Path, case: str, helper: bool, cache: str | None = None, trace: str | None = None):
    """(wall [s], CPU [s], peak force [N]) of one ``simulate CASE`` with the code of
    ``code``, on ``cache`` (default a new empty one)."""
    with tempfile.TemporaryDirectory() as fresh, tempfile.TemporaryDirectory() as out:
        cpu, start = _children_cpu(), time.perf_counter()
        subprocess.run(_command(case, out), env=_environment(code, cache or fresh, helper, trace), check=True,
                       capture_output=True, cwd=out)
        wall = time.perf_counter() - start
        summary = json.loads((pathlib.Path(out) / "summary.json").read_text())
    return wall, _children_cpu() - cpu, summary.get("peak_force_N", summary.get("peak_force"))


def rounds_rows(base: pathlib.Path, rounds: int, extra=(), cases=CASES) -> list[str]:
    configs = (("base", base, True), ("helper", ROOT, True), ("off", ROOT, False),
               *((name, pathlib.Path(path).resolve(), True) for name, path in extra))
    rows = ["| round | case | configuration | wall [s] | CPU [s] | peak force [N] | load |", "|---|---|---|---|---|---|---|"]
    walls: dict = {}
    for number in range(rounds):
        order = configs[number % len(configs):] + configs[:number % len(configs)]  # alternate who goes first
        for case in cases:
            for name, code, helper in order:
                wall, cpu, peak = run(code, case, helper)
                walls.setdefault((case, name), []).append((wall, cpu))
                rows.append(f"| {number + 1} | `{case}` | {name} | **{wall:.1f}** | {cpu:.1f} | {peak} | "
                            f"{os.getloadavg()[0]:.1f} |")
                print(rows[-1], flush=True)
    rows += ["", "| case | configuration | median wall [s] | median CPU [s] |", "|---|---|---|---|"]
    for (case, name), values in walls.items():
        rows.append(f"| `{case}` | {name} | **{statistics.median(v[0] for v in values):.1f}** | "
                    f"{statistics.median(v[1] for v in values):.1f} |")
    return rows


def traced_rows(case: str = CASES[0]) -> list[str]:
    with tempfile.TemporaryDirectory() as folder:
        trace = str(pathlib.Path(folder) / "trace")
        wall, cpu, _ = run(ROOT, case, True, trace=trace)
        lines = pathlib.Path(trace).read_text().split("\n")
    events = [line.split() for line in lines if line]
    start = float(events[0][2])
    timeline = ", ".join(f"{event} {float(stamp) - start:.1f} s" for _pid, event, stamp in events)
    return [f"Traced run of `{case}` ({wall:.1f} s wall, {cpu:.1f} CPU-s), seconds from the helper's launch: "
            f"{timeline}."]


def concurrent_rows(case: str = CASES[0]) -> list[str]:
    reference = run(ROOT, case, False)[2]
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as a, \
            tempfile.TemporaryDirectory() as b:
        start = time.perf_counter()
        processes = [subprocess.Popen(_command(case, out), env=_environment(ROOT, cache, True), cwd=out,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for out in (a, b)]
        codes = [process.wait() for process in processes]
        wall = time.perf_counter() - start
        peaks = [json.loads((pathlib.Path(out) / "summary.json").read_text()).get("peak_force_N") for out in (a, b)]
    same = all(peak == reference for peak in peaks)
    return [f"Two `{case}` commands started at once on one empty cache: exit statuses {codes}, both done in "
            f"{wall:.1f} s, peak forces {peaks} ({'identical to' if same else 'DIFFERENT from'} a run without "
            f"the helper, {reference})."]


def warm_rows(case: str = CASES[0]) -> list[str]:
    with tempfile.TemporaryDirectory() as cache:
        run(ROOT, case, False, cache)
        figures = {helper: statistics.median(run(ROOT, case, helper, cache)[0] for _ in range(3))
                   for helper in (True, False)}
    return [f"`{case}` on the warm cache (median of 3): helper on {figures[True]:.2f} s, off {figures[False]:.2f} s."]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=pathlib.Path, required=True, help="the checkout to compare with")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--extra", nargs="*", default=[], metavar="NAME=PATH",
                        help="more configurations: the helper of another checkout (e.g. another split)")
    parser.add_argument("--only-rounds", action="store_true", help="no traced, concurrent and warm runs")
    parser.add_argument("--hertz-only", action="store_true", help="only steel_plate_hertz.toml in the rounds")
    parser.add_argument("--print-only", action="store_true", help="print, do not append to RESULTS_cold_start.md")
    args = parser.parse_args(argv)
    load = os.getloadavg()
    lines = ["", "## The compile helper: the first integrating command on 2 cores", "",
             f"`python benchmarks/studies/bench_compile_helper.py {' '.join(sys.argv[1:] if argv is None else argv)}`, run "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load average "
             f"{load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} on {os.cpu_count()} cores at the start; "
             "`impactmaps --no-background-warm-up simulate CASE`, each on an empty numba cache.", ""]
    extra = [tuple(item.split("=", 1)) for item in args.extra]
    lines += rounds_rows(args.base.resolve(), args.rounds, extra, CASES[:1] if args.hertz_only else CASES)
    for part in () if args.only_rounds else (traced_rows, concurrent_rows, warm_rows):
        lines += ["", *part()]
        print(lines[-1], flush=True)
    lines += ["", f"Load average at the end: {os.getloadavg()[0]:.1f}."]
    text = "\n".join(lines) + "\n"
    if not args.print_only:
        with open(ROOT / "benchmarks" / "studies" / "RESULTS_cold_start.md", "a") as results:
            results.write(text)
    print(text)


if __name__ == "__main__":
    main()
