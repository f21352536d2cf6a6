"""Chart throughput: converged (ζ, λ) points per second of the default chart.

Workload: ``impactmaps.plotting.chart.make_chart`` with its defaults (SS Euler beam and SS
square Kirchhoff plate struck at the centre, 8 λ from 0.05 to 20, DEFAULT_ZETA_COUNT (200) log-spaced ζ from
0.005 to 100, default ``ModalSettings``, a local process pool over all cores), written
into a temporary directory; and, separately, the ``sweep`` of the same grid alone (no
files except its NetCDF, no figures). Both compute every point: the shipped result of the
default chart's sweep (:mod:`impactmaps.maps.files.shipped`, what ``impactmaps chart``
draws from) is switched off in the child process.

Each workload runs in a fresh Python process, as the command line would. Reported:

* wall time of the call (``make_chart`` or ``sweep``) inside that process;
* CPU time of the call: ``time.process_time`` of the process plus the CPU of its pool
  workers (``resource.getrusage(RUSAGE_CHILDREN)`` after the workers are reaped) — the
  machine may be shared, and CPU time is what does not inflate with other users' load;
* the whole process (interpreter start, imports, the call, exit): wall and CPU as the
  benchmark driver sees them (``RUSAGE_CHILDREN`` of this process);
* points computed, converged points (finite F̄max, time limit not hit), points/s.

Targets of the issue: ≥ 200 points/s and the chart in < 60 s on the 2-core machine.

If a structure of the default chart cannot be built (e.g. ``impactmaps.targets.beams.beam``
missing) the chart is run with the structures that can, and the table says so.

Run: ``python benchmarks/bench_chart.py``.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]

TARGET_POINTS_PER_SECOND = 200.0
TARGET_CHART_SECONDS = 60.0


# -- helpers shared with bench_memory ------------------------------------------------------
def children_cpu() -> float:
    """User + system CPU [s] of all reaped child processes of this process."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def reap_pool_workers(timeout: float = 30.0) -> None:
    """Wait until multiprocessing workers have exited and are reaped (so that their CPU
    and memory show in ``RUSAGE_CHILDREN``); ``sweep`` shuts its pool down without waiting."""
    import multiprocessing

    deadline = time.monotonic() + timeout
    while multiprocessing.active_children() and time.monotonic() < deadline:
        time.sleep(0.02)


def buildable_structures(structures):
    """(structures that build, notes about those that do not)."""
    usable, notes = [], []
    for structure in structures:
        try:
            structure.build()
        except ImportError as error:
            notes.append(f"{structure.name} left out: {error}")
        else:
            usable.append(structure)
    return usable, notes


def run_child(arguments, sampler=None) -> dict:
    """Run ``python <this file's sibling> --child ...`` and return its JSON report plus the
    whole-process wall and CPU time seen from here."""
    env = dict(os.environ)
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(name, "1")
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    cpu_before = children_cpu()
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, *arguments], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, cwd=str(ROOT), env=env)
    samples = sampler(process.pid) if sampler else None
    stdout, stderr = process.communicate()
    if samples is not None:
        samples.stop()
    wall = time.perf_counter() - start
    cpu = children_cpu() - cpu_before
    if process.returncode != 0:
        return {"error": stderr.strip().splitlines()[-1] if stderr.strip() else f"exit {process.returncode}",
                "process_wall_s": wall, "process_cpu_s": cpu}
    report = json.loads(stdout.strip().splitlines()[-1])
    report.update(process_wall_s=wall, process_cpu_s=cpu)
    if samples is not None:
        report.update(samples.report())
    return report


def count_points(dataset) -> tuple[int, int]:
    """(points computed, converged points: finite F̄max and time limit not hit)."""
    import numpy as np

    done = dataset["done"].values.astype(bool)
    finite = np.isfinite(dataset["fmax_normalised"].values)
    limited = dataset["time_limit_reached"].values == 1
    return int(done.sum()), int((done & finite & ~limited).sum())


# -- the child processes ---------------------------------------------------------------------
def _child(kind: str, out_dir: str) -> dict:
    import numpy as np
    import xarray as xr

    from impactmaps.plotting.chart import CHART_STRUCTURES, DEFAULT_CHART_LAMBDAS, DEFAULT_ZETA_COUNT, make_chart
    from impactmaps.maps.compute.sweep import log_grid, sweep

    import impactmaps.maps.compute.sweep as sweep_module

    # the computation is measured, not the shipped result of the default chart's sweep
    sweep_module.load_shipped_result = lambda digest, description=None: None
    structures, notes = buildable_structures(CHART_STRUCTURES)
    wall, cpu, children = time.perf_counter(), time.process_time(), children_cpu()
    if kind == "chart":
        paths = make_chart(out_dir, structures=structures, progress=False)
        reap_pool_workers()
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        children = children_cpu() - children
        with xr.open_dataset(paths["netcdf"]) as dataset:
            computed, converged = count_points(dataset.load())
            max_modes = int(dataset["n_modes"].values.max())
    else:
        dataset = sweep(structures, log_grid(0.005, 100.0, DEFAULT_ZETA_COUNT), np.asarray(DEFAULT_CHART_LAMBDAS),
                        path=pathlib.Path(out_dir) / "sweep.nc", progress=False)
        reap_pool_workers()
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        children = children_cpu() - children
        computed, converged = count_points(dataset)
        max_modes = int(dataset["n_modes"].values.max())
    return {"kind": kind, "structures": [s.name for s in structures], "notes": notes,
            "wall_s": wall, "cpu_s": cpu + children, "cpu_parent_s": cpu, "cpu_workers_s": children,
            "points": computed, "converged": converged, "max_modes": max_modes,
            "workers": os.cpu_count()}


# -- where the time goes ------------------------------------------------------------------------
def profile_points(top: int = 10) -> dict:
    """Solve every default-chart point one by one in this process (after a warm-up) and
    return the CPU time per point: total, median, and the most expensive points."""
    import numpy as np

    from impactmaps.plotting.chart import CHART_STRUCTURES, DEFAULT_CHART_LAMBDAS, DEFAULT_ZETA_COUNT
    from impactmaps.maps.compute.sweep import log_grid
    from impactmaps.maps.compute.linear_points import solve_points
    from impactmaps.solvers.modal_settings import ModalSettings

    settings = ModalSettings()
    structures, notes = buildable_structures(CHART_STRUCTURES)
    records = []
    for structure in structures:
        solve_points(structure, [(1.0, 1.0)], settings)  # warm-up: compile/cache load, target build
        for lam in DEFAULT_CHART_LAMBDAS:
            for zeta in log_grid(0.005, 100.0, DEFAULT_ZETA_COUNT):
                start = time.process_time()
                row = solve_points(structure, [(float(zeta), float(lam))], settings)[0]
                records.append((time.process_time() - start, structure.name, float(zeta), float(lam),
                                int(row["n_modes"])))
    seconds = np.array([r[0] for r in records])
    order = np.argsort(seconds)[::-1]
    return {"points": len(records), "total_s": float(seconds.sum()), "median_ms": float(1e3 * np.median(seconds)),
            "top_share": float(seconds[order[:top]].sum() / seconds.sum()),
            "top": [records[k] for k in order[:top]], "notes": notes}


def profile_markdown(profile: dict) -> str:
    """The per-point profile as Markdown."""
    lines = [
        f"{profile['points']} chart points solved one by one in one process (no pool, no files): "
        f"{profile['total_s']:.1f} CPU-s in all, {profile['points'] / profile['total_s']:.0f} points per "
        f"CPU-second, median {profile['median_ms']:.1f} ms per point; the {len(profile['top'])} most "
        f"expensive points take {100 * profile['top_share']:.0f} % of the time:",
        "",
        "| structure | ζ | λ | modes | CPU [ms] |",
        "|---|---|---|---|---|",
    ]
    lines += [f"| {name} | {zeta:.3g} | {lam:g} | {modes} | {1e3 * cpu:.0f} |"
              for cpu, name, zeta, lam, modes in profile["top"]]
    lines += [f"- {note}" for note in profile["notes"]]
    return "\n".join(lines)


# -- the benchmark ---------------------------------------------------------------------------
def run() -> list[dict]:
    """Run the chart and the sweep alone, each in a fresh process; return the reports."""
    reports = []
    for kind in ("chart", "sweep"):
        with tempfile.TemporaryDirectory(prefix=f"impactmaps-bench-{kind}-") as out_dir:
            report = run_child([str(pathlib.Path(__file__).resolve()), "--child", kind, "--out", out_dir])
            report.setdefault("kind", kind)
            reports.append(report)
    return reports


def markdown(reports: list[dict]) -> str:
    """The reports as a Markdown table with the verdict against the targets."""
    from impactmaps.plotting.chart import DEFAULT_ZETA_COUNT

    lines = [
        f"Default chart grid (8 λ × {DEFAULT_ZETA_COUNT} ζ per structure), default `ModalSettings`, process pool over "
        f"all cores. CPU = call's own process + its pool workers. Targets: ≥ {TARGET_POINTS_PER_SECOND:g} "
        f"points/s, chart < {TARGET_CHART_SECONDS:g} s.",
        "",
        "| workload | structures | points (converged) | max modes | call wall [s] | call CPU [s] "
        "(parent + workers) | points/s wall | points/s per CPU-second × cores | whole process wall / CPU [s] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    notes = []
    for r in reports:
        if "error" in r:
            lines.append(f"| {r['kind']} | — | failed: {r['error']} | | | | | | "
                         f"{r['process_wall_s']:.1f} / {r['process_cpu_s']:.1f} |")
            continue
        cores = r["workers"] or 1
        rate_wall = r["converged"] / r["wall_s"]
        rate_cpu = r["converged"] / r["cpu_s"] * cores
        lines.append(
            f"| {'make_chart' if r['kind'] == 'chart' else 'sweep alone'} | {', '.join(r['structures'])} | "
            f"{r['points']} ({r['converged']}) | {r['max_modes']} | {r['wall_s']:.1f} | "
            f"{r['cpu_s']:.1f} ({r['cpu_parent_s']:.1f} + {r['cpu_workers_s']:.1f}) | {rate_wall:.0f} | "
            f"{rate_cpu:.0f} | {r['process_wall_s']:.1f} / {r['process_cpu_s']:.1f} |"
        )
        notes += r.get("notes", [])
    lines += ["", "'points/s per CPU-second × cores' = converged points / call CPU × cores: the rate an "
              "unloaded machine with this many cores would reach if the work parallelised perfectly."]
    chart = next((r for r in reports if r.get("kind") == "chart" and "error" not in r), None)
    if chart:
        met_time = chart["wall_s"] < TARGET_CHART_SECONDS
        met_rate = chart["converged"] / chart["wall_s"] >= TARGET_POINTS_PER_SECOND
        lines.append(f"Chart wall {chart['wall_s']:.1f} s ({'met' if met_time else '**missed**'}); "
                     f"{chart['converged'] / chart['wall_s']:.0f} points/s wall "
                     f"({'met' if met_rate else '**missed**'}).")
    lines += [f"- {note}" for note in dict.fromkeys(notes)]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--child", choices=("chart", "sweep"))
    parser.add_argument("--out")
    parser.add_argument("--profile", action="store_true", help="also profile the points one by one")
    args = parser.parse_args()
    if args.child:
        print(json.dumps(_child(args.child, args.out)))
        return
    print(markdown(run()))
    if args.profile:
        print()
        print(profile_markdown(profile_points()))


if __name__ == "__main__":
    main()
