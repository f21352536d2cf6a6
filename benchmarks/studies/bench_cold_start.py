"""Cold start: what the first run after installation costs, and where the compile time goes.

Each measurement runs in a fresh interpreter with ``NUMBA_CACHE_DIR`` pointing at an empty
temporary directory (numba then compiles everything, as after a fresh install):

1. ``import impactmaps.solvers.modal`` (compiles nothing since the integrator is compiled on
   its first call, :mod:`impactmaps._compile.lazy_kernel`), then the first integration
   (``integrate_impact.compile()``) with numba's compile events recorded: the largest
   inclusive compile times per function (nested functions are counted in their callers
   too);
2. ``impactmaps chart --quiet --out DIR`` on an empty cache (the README's first command
   after ``pip install .``: drawn from the shipped result of its sweep,
   :mod:`impactmaps.maps.files.shipped`), then again on the now warm cache;
3. ``impactmaps chart --zeta-count 100 --quiet`` on an empty cache and again warm: a chart
   no result is shipped for, swept on all cores (compiles the integrator, then computes);
4. the first integrating commands, ``impactmaps simulate`` of the example cases
   ``aluminium_beam_linear.toml`` (linear law) and ``steel_plate_hertz.toml`` (Hertz), on
   an empty cache and again warm; then, on another empty cache, ``impactmaps warm-up``
   (what the installation runs, :mod:`impactmaps.solvers.warm_up`) followed by the same
   command (a checkout without ``warm-up`` shows nan);
5. commands that solve nothing: ``impactmaps --help``, ``materials``, ``laws`` and a
   ``lookup`` on a shipped map (median of three runs; imports only).

Each command's CPU time (``getrusage`` of the ended children: the command and the
processes it started) is given beside its wall time.
Reported with the load average (other jobs on the machine make every number larger: run
it for two checkouts in the same minutes and compare ratios, ``--root``).

Run: ``python benchmarks/studies/bench_cold_start.py [--skip-chart] [--root CHECKOUT] [--print-only]``;
writes ``benchmarks/studies/RESULTS_cold_start.md`` unless ``--print-only``. The commands run with
the background warm-up off, except with ``--background``: then only the scenarios of
:func:`background_rows` run, appended to the results.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

_PROFILE = r"""
import collections, json, time
from numba.core import event
recorder = event.RecordingListener()
event.register("numba:compile", recorder)
start = time.perf_counter()
import impactmaps.solvers.modal  # noqa: F401
elapsed = time.perf_counter() - start
from impactmaps.solvers.integrator.exact_step import integrate_impact
start = time.perf_counter()
integrate_impact.compile()
first_call = time.perf_counter() - start
totals, starts = collections.Counter(), {}
for stamp, ev in recorder.buffer:
    dispatcher = ev.data["dispatcher"]
    key = (id(dispatcher), str(ev.data.get("args")))
    name = dispatcher.py_func.__module__ + "." + dispatcher.py_func.__qualname__
    if ev.is_start:
        starts[key] = stamp
    else:
        totals[name] += stamp - starts.pop(key)
print(json.dumps({"import_s": elapsed, "compile_s": first_call, "top": totals.most_common(12)}))
"""


#: The commands that solve nothing, timed (median of three runs each).
LIGHT_COMMANDS = (("--help",), ("materials",), ("laws",),
                  ("lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1.198", "--lambda", "0.425"))

#: The checkout measured (``--root``; default this one).
CODE = ROOT


def _environment(cache: str, background: bool = False) -> dict:
    """The commands' environment: numba's cache at ``cache``, the background warm-up off
    unless ``background`` (the measurements above it are of the commands alone)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, OMP_NUM_THREADS="1",
               PYTHONPATH=str(CODE) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("IMPACTMAPS_NO_BACKGROUND_WARMUP", None)
    if not background:
        env["IMPACTMAPS_NO_BACKGROUND_WARMUP"] = "1"
    return env


#: CPU time [s] of each command :func:`run_command` ran, in order (user + system of the child).
CPU_TIMES: list[float] = []


def _children_cpu() -> float:
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_command(argv, cache: str, cwd: str) -> float:
    """Wall time [s] of ``impactmaps ARGV`` with numba's cache at ``cache``; its CPU time
    (children's ``getrusage``: the command and any process it started) is appended to
    :data:`CPU_TIMES` — on a shared machine the CPU time is the steadier figure."""
    cpu, start = _children_cpu(), time.perf_counter()
    subprocess.run([sys.executable, "-m", "impactmaps.cli", *argv], env=_environment(cache), check=True,
                   capture_output=True, cwd=cwd)
    wall = time.perf_counter() - start
    CPU_TIMES.append(_children_cpu() - cpu)
    return wall


def time_command(*argv: str, cold: bool = True) -> tuple[float, float]:
    """(cold, warm) wall time [s] of ``impactmaps ARGV`` on a fresh numba cache; warm is
    NaN unless ``cold`` (then the first run is the only one, on a fresh cache too)."""
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        times = [run_command(argv, cache, out) for _ in range(2 if cold else 1)]
    return times[0], (times[1] if cold else float("nan"))


def time_after_warm_up(*argv: str) -> tuple[float, float]:
    """(``impactmaps warm-up`` on an empty cache, then ``impactmaps ARGV``) wall times [s];
    (nan, nan) for a checkout without the warm-up command."""
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        try:
            warm = run_command(["warm-up"], cache, out)
        except subprocess.CalledProcessError:
            CPU_TIMES.extend((float("nan"), float("nan")))
            return float("nan"), float("nan")
        return warm, run_command(argv, cache, out)


def time_light(*argv: str, repeats: int = 3) -> float:
    """Median wall time [s] of ``impactmaps ARGV`` (a command that solves nothing)."""
    runs = [time_command(*argv, cold=False)[0] for _ in range(repeats)]
    return statistics.median(runs)


def profile_import() -> dict:
    """Cold import of the modal solver with numba's compile events (fresh cache)."""
    import json

    with tempfile.TemporaryDirectory() as cache:
        done = subprocess.run([sys.executable, "-c", _PROFILE], capture_output=True, text=True,
                              env=_environment(cache), check=True, cwd=cache)  # not this checkout's cwd
    return json.loads(done.stdout.strip().splitlines()[-1])


def time_chart(*options: str) -> tuple[float, float]:
    """(cold, warm) wall time [s] of ``impactmaps chart OPTIONS`` on a fresh numba cache."""
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        times = []
        for run in ("cold", "warm"):
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "impactmaps.cli", "chart", *options, "--quiet", "--out",
                            str(pathlib.Path(out) / run)], env=_environment(cache), check=True,
                           capture_output=True, cwd=out)
            times.append(time.perf_counter() - start)
    return times[0], times[1]


def _background_done(cache: str) -> None:
    """End the background warm-up a scenario started in ``cache`` (its session: the process
    and its workers), so that the next scenario starts on an idle machine."""
    import json
    import signal

    for lock in pathlib.Path(cache).glob("impactmaps-warm-up/*.lock"):
        try:
            pid = int(json.loads(lock.read_text() or "{}")["pid"])
            os.killpg(os.getpgid(pid), signal.SIGTERM)  # its session's process group: it and its workers
        except (OSError, ValueError, KeyError):
            continue
        time.sleep(1.0)


def _timed(command: list[str], env: dict, cwd: str) -> float:
    """Wall time [s] of ``command``; its CPU time appended to :data:`CPU_TIMES` (a background
    warm-up it starts is not its child for long: it detaches at once)."""
    cpu, start = _children_cpu(), time.perf_counter()
    subprocess.run(command, env=env, check=True, capture_output=True, cwd=cwd)
    wall = time.perf_counter() - start
    CPU_TIMES.append(_children_cpu() - cpu)
    return wall


def _warm_up_finished(cache: str, limit_s: float = 900.0) -> float:
    """Seconds until the background warm-up in ``cache`` has written its marker (at most ``limit_s``)."""
    start = time.perf_counter()
    while time.perf_counter() - start < limit_s and not list(pathlib.Path(cache).glob("impactmaps-warm-up/*.marker")):
        time.sleep(0.5)
    return time.perf_counter() - start


def background_rows(pauses=(0.0, 20.0)) -> list[str]:
    """The background warm-up (:mod:`impactmaps._compile.background_warm_up`), each on an
    empty cache: the default chart with it and without it (its cost to the foreground);
    ``chart`` then, after a pause, ``simulate examples/steel_plate_hertz.toml`` (the wait a
    user sees), also once the warm-up has finished; ``simulate`` as the very first command,
    with and without it."""
    case = str(ROOT / "examples" / "steel_plate_hertz.toml")
    cli = [sys.executable, "-m", "impactmaps.cli"]
    rows = ["| scenario (empty numba cache) | foreground wall [s] | its CPU [s] | load |", "|---|---|---|---|"]

    def row(text, seconds):
        rows.append(f"| {text} | **{seconds:.1f}** | {CPU_TIMES[-1]:.1f} | {os.getloadavg()[0]:.1f} |")
        print(rows[-1], flush=True)

    for background in (False, True):
        with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
            wall = _timed([*cli, "chart", "--quiet", "--out", out], _environment(cache, background), out)
            _background_done(cache)
        row(f"`impactmaps chart`, background warm-up {'on' if background else 'off'}", wall)
    for pause in (*pauses, None):
        with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
            env = _environment(cache, True)
            chart = _timed([*cli, "chart", "--quiet", "--out", out], env, out)
            if pause is None:
                waited = _warm_up_finished(cache)
                text = f"the warm-up's end ({waited:.0f} s after the chart)"
            else:
                time.sleep(pause)
                text = f"{pause:.0f} s"
            wall = _timed([*cli, "simulate", case, "--out", "s"], env, out)
            _background_done(cache)
        row(f"`chart` ({chart:.1f} s), then after {text} `simulate steel_plate_hertz.toml`", wall)
    for background in (False, True):
        with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
            wall = _timed([*cli, "simulate", case, "--out", "s"], _environment(cache, background), out)
            _background_done(cache)
        row(f"`simulate steel_plate_hertz.toml` first, background warm-up {'on' if background else 'off'}", wall)
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-chart", action="store_true", help="no chart timings")
    parser.add_argument("--root", type=pathlib.Path, default=ROOT, help="the checkout to measure (default this one)")
    parser.add_argument("--print-only", action="store_true", help="print, do not write RESULTS_cold_start.md")
    parser.add_argument("--background", action="store_true",
                        help="only the background warm-up's scenarios (background_rows), appended to the results")
    args = parser.parse_args(argv)
    global CODE
    CODE = args.root.resolve()
    load = os.getloadavg()[0]
    if args.background:
        lines = ["", "## Background warm-up", "", f"`python benchmarks/studies/bench_cold_start.py --background` (code of "
                 f"{CODE.name}), run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load average "
                 f"{load:.1f} on {os.cpu_count()} cores", "", *background_rows()]
        text = "\n".join(lines) + "\n"
        if not args.print_only:
            with open(ROOT / "benchmarks" / "studies" / "RESULTS_cold_start.md", "a") as results:
                results.write(text)
        print(text)
        return
    profile = profile_import()
    lines = [
        "# Cold start",
        "",
        f"`python benchmarks/studies/bench_cold_start.py` (code of {CODE.name})",
        f"run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load average {load:.1f} "
        f"on {os.cpu_count()} cores",
        "",
        f"Cold `import impactmaps.solvers.modal` (empty numba cache): **{profile['import_s']:.1f} s** "
        "(the integrator is compiled on its first call, not at import). "
        f"Compiling both variants of the integrator (with and without the exact contact phase): "
        f"**{profile['compile_s']:.1f} s**. "
        "Largest compile times (inclusive: a function's callees count in it too):",
        "",
        "| function | compile [s] |",
        "|---|---|",
    ]
    lines += [f"| `{name}` | {seconds:.2f} |" for name, seconds in profile["top"]]
    if not args.skip_chart:
        cold, warm = time_chart()
        lines += ["", f"`impactmaps chart` (the default chart, drawn from its shipped sweep result): first run "
                  f"(empty cache) **{cold:.1f} s**, second run {warm:.1f} s."]
        cold, warm = time_chart("--zeta-count", "100")
        lines += ["", f"`impactmaps chart --zeta-count 100` (no shipped result: compiles, then sweeps 1 600 "
                  f"points): first run **{cold:.1f} s**, second run {warm:.1f} s."]
    examples = ROOT / "examples"
    lines += ["", "| first integrating command | empty cache: wall [s] (CPU [s]) | warm [s] (CPU) | "
              "`warm-up` on an empty cache [s] (CPU) | then the command [s] (CPU) | load |", "|---|---|---|---|---|---|"]
    for case in ("aluminium_beam_linear.toml", "steel_plate_hertz.toml"):
        cold, warm = time_command("simulate", str(examples / case), "--out", "out")
        warm_up, after = time_after_warm_up("simulate", str(examples / case), "--out", "out")
        cpu = CPU_TIMES[-4:]
        lines.append(f"| `impactmaps simulate examples/{case}` | **{cold:.1f}** ({cpu[0]:.1f}) | {warm:.1f} "
                     f"({cpu[1]:.1f}) | {warm_up:.1f} ({cpu[2]:.1f}) | **{after:.1f}** ({cpu[3]:.1f}) | "
                     f"{os.getloadavg()[0]:.1f} |")
    lines += ["", "| command that solves nothing | wall [s] (median of 3) | CPU [s] (median of 3) | load |",
              "|---|---|---|---|"]
    for command in LIGHT_COMMANDS:
        wall = time_light(*command)
        lines.append(f"| `impactmaps {' '.join(command)}` | **{wall:.2f}** | {statistics.median(CPU_TIMES[-3:]):.2f} | "
                     f"{os.getloadavg()[0]:.1f} |")
    text = "\n".join(lines) + "\n"
    if not args.print_only:
        (ROOT / "benchmarks" / "studies" / "RESULTS_cold_start.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
