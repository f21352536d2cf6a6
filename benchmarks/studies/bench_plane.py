"""The whole (ζ, λ) plane: cost, statuses and accuracy of every map point (issue 12).

Workload: a 200 × 50 log grid (ζ × λ over [1e-3, 1e3]²) for ``beam-ss-euler`` and
``plate-ssss-kirchhoff``, each point solved as a sweep solves it
(:func:`impactmaps.maps.compute.linear_points.solve_points`: default ``ModalSettings``, per-point error
control), one point per task on a pool of worker processes (all cores), one BLAS thread
each. One point per task keeps the per-point wall times and guards; it costs the executor
~0.5–2 ms a task (from the walls of the two runs below; a cheap beam point takes 0.6 ms),
so the grid is then run again as a user runs it, through
:func:`impactmaps.maps.compute.sweep.sweep` (chunks of 40 points), timed on its own and checked bit
for bit against the per-point results.

Guards (the corners of the plane are known to blow up; that is the rest of issue 12):

* a point whose finest refinement level would integrate more than ``--max-modes`` modes
  (counted in the sweep's basis table at 4× the cut-off: the two refinement levels of the
  default ``AccuracyControl``) is not run: "skipped (modes)";
* a point still running after ``--point-cap`` seconds is killed with its worker: "timed
  out";
* after ``--budget`` seconds no new point starts: "not run (budget)".

Reported (``benchmarks/studies/RESULTS_plane.md``): wall time of each structure and in total,
per-point wall percentiles and the slowest point, CPU time (the points': each worker's
``time.process_time`` over its task; the pool's: ``getrusage`` of this process and its
ended workers), the share of points per status, and,
at ``--reference N`` random finished points, |F̄max − reference| where the reference is
one run at 8× the cut-off, 8× the mode floor and 1/8 of the step
(``ModalSettings().refined()`` three times), max over non-sensitive points. (Before
2026-11-24 the reference kept the mode floor of 4, so at heavy-impactor points, whose
modes are set by the floor, it was coarser than the map's own finest level.)

Run: ``python benchmarks/studies/bench_plane.py [--quick] [--reference N]``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import multiprocessing
import os
import pathlib
import subprocess
import sys
import time
import warnings

# One BLAS thread per process. OpenBLAS reads these once, when NumPy loads it: so here, before
# the import, and the forked workers inherit it (set in a worker, as before 2026-11-24, they did
# nothing). Measured: the wall of the pool is the same, a worker's spare BLAS thread only burns CPU.
if __name__ == "__main__":
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
#: ``--root DIR`` (a checkout of another commit, e.g. the base of a change): its impactmaps is
#: imported instead of this checkout's; read here, before any import of the package.
PACKAGE_ROOT = pathlib.Path(sys.argv[sys.argv.index("--root") + 1]).resolve() if (
    __name__ == "__main__" and "--root" in sys.argv[:-1]) else ROOT
sys.path.insert(0, str(PACKAGE_ROOT))  # this checkout's impactmaps (or --root's), not an installed one
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
REFERENCE_LEVELS = 3  # the reference: three refinements of the default settings (8× cut-off and floor, 1/8 step)
#: Refinement levels of the default AccuracyControl multiply the cut-off by 2 each.
FINEST_CUTOFF_FACTOR = 4


# -- worker side ---------------------------------------------------------------------------
def _solve(task) -> dict:
    """One point: ``("map", structure, ζ, λ)`` as a sweep solves it, or ``("reference", …)``:
    one run at 8× the cut-off and mode floor, 1/8 of the step."""
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.compute.points import basis_table, table_runner
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.linear_points import solve_points
    from impactmaps.solvers.modal_settings import ModalSettings

    kind, name, zeta, lambda_ = task
    structure = structure_from_name(name)
    settings = ModalSettings()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if kind == "map":
            return solve_points(structure, [(zeta, lambda_)], settings)[0]
        fine = settings
        for _ in range(REFERENCE_LEVELS):  # cut-off and mode floor ×2, step /2, each time
            fine = fine.refined()
        target = structure.build()
        run = table_runner(LINEAR, target, basis_table(structure, fine.min_modes), frequency_cap(structure.build(), MAX_MODES),
                           (zeta, lambda_), LINEAR.realise(target, (zeta, lambda_)), [])
        result = run(fine, 1.0)
        return {"fmax_normalised": result.fmax_normalised, "n_modes": result.n_modes}


def _worker(conn) -> None:
    """Run the tasks the driver sends on this worker's own pipe (``None`` ends it); report
    ``start``, then ``done`` or ``fail``, on the same pipe."""
    while True:
        item = conn.recv()
        if item is None:
            return
        index, task = item
        conn.send(("start", index, time.time()))
        start, cpu = time.perf_counter(), time.process_time()
        try:
            row = _solve(task)
            conn.send(("done", index, row, time.perf_counter() - start, time.process_time() - cpu))
        except Exception as error:  # reported as a failed point, the run goes on
            conn.send(("fail", index, f"{type(error).__name__}: {error}", time.perf_counter() - start,
                       time.process_time() - cpu))


# -- driver side ---------------------------------------------------------------------------
def run_tasks(tasks, workers: int, point_cap: float, budget: float) -> list[dict]:
    """Run every task on ``workers`` processes; a task over ``point_cap`` s is killed with
    its worker (which is replaced); after ``budget`` s no task starts. One outcome per task:
    ``{"state": "done"|"timeout"|"fail"|"budget", "row", "seconds", "cpu", "error"}``: ``seconds``
    the task's wall time, ``cpu`` the worker process's CPU time during it (``time.process_time``
    in the worker). Each worker has a pipe of its own: a worker killed mid-task (or mid-message)
    takes its pipe with it and leaves no lock of a shared queue held for the others."""
    from multiprocessing.connection import wait

    context = multiprocessing.get_context("fork")
    outcomes = [{"state": "budget"} for _ in tasks]
    workers_by_conn, running = {}, {}
    next_task = 0
    started = time.time()

    def dispatch(conn) -> None:
        nonlocal next_task
        if next_task < len(tasks) and time.time() - started <= budget:
            conn.send((next_task, tasks[next_task]))
            next_task += 1
        else:
            conn.send(None)
            workers_by_conn.pop(conn)[0].join(timeout=5)
            conn.close()

    def spawn() -> None:
        ours, theirs = context.Pipe()
        process = context.Process(target=_worker, args=(theirs,), daemon=True)
        process.start()
        theirs.close()
        workers_by_conn[ours] = (process,)
        dispatch(ours)

    for _ in range(min(workers, len(tasks))):
        spawn()
    while workers_by_conn:
        for conn in wait(list(workers_by_conn), timeout=0.2):
            try:
                message = conn.recv()
            except EOFError:  # the worker died: its task failed, a new worker takes the next one
                process = workers_by_conn.pop(conn)[0]
                process.join(timeout=5)
                if conn in running:
                    index, since = running.pop(conn)
                    outcomes[index] = {"state": "fail", "error": f"worker died (exit {process.exitcode})",
                                       "seconds": time.time() - since}
                conn.close()
                spawn()
                continue
            kind, index = message[:2]
            if kind == "start":
                running[conn] = (index, message[2])
                continue
            running.pop(conn, None)
            if kind == "done":
                outcomes[index] = {"state": "done", "row": message[2], "seconds": message[3], "cpu": message[4]}
            else:
                outcomes[index] = {"state": "fail", "error": message[2], "seconds": message[3], "cpu": message[4]}
            dispatch(conn)
        now = time.time()
        for conn, (index, since) in list(running.items()):
            if now - since > point_cap:
                process = workers_by_conn.pop(conn)[0]
                process.kill()
                process.join(timeout=5)  # reaped: its CPU time counts in RUSAGE_CHILDREN
                running.pop(conn)
                conn.close()
                outcomes[index] = {"state": "timeout", "seconds": now - since}
                spawn()
    return outcomes


def finest_mode_counts(name: str, zetas, lambdas) -> np.ndarray:
    """Modes the finest refinement level of each point would integrate (sweep's table)."""
    from impactmaps.dimensionless import realise
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.points import basis_table
    from impactmaps.maps.family.structures import MAX_MODES
    from impactmaps.solvers.mode_budget import frequency_cap
    from impactmaps.solvers.modal_settings import ModalSettings

    structure = structure_from_name(name)
    settings = ModalSettings()
    zz, ll = np.meshgrid(zetas, lambdas, indexing="ij")
    omegas = np.atleast_1d(realise(structure.build(), zz.ravel(), ll.ravel()).contact_frequency)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        table = basis_table(structure, FINEST_CUTOFF_FACTOR * settings.min_modes)
    cutoffs = np.minimum(FINEST_CUTOFF_FACTOR * settings.cutoff_ratio * omegas, frequency_cap(structure.build(), MAX_MODES))
    counts = np.searchsorted(np.sort(table.basis.frequencies), cutoffs, side="right")
    return np.maximum(counts, FINEST_CUTOFF_FACTOR * settings.min_modes).reshape(zz.shape)


def _grid(quick: bool):
    """The (ζ, λ) grid: 200 × 50 log-spaced over [1e-3, 1e3]² (20 × 10 with ``--quick``)."""
    n_zeta, n_lambda = (20, 10) if quick else (200, 50)
    return np.geomspace(1e-3, 1e3, n_zeta), np.geomspace(1e-3, 1e3, n_lambda)


def cpu_seconds() -> float:
    """CPU time [s] of this process and of its children that have ended (user + system)."""
    import resource

    return sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
               for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


def percentile_row(seconds) -> str:
    p = np.percentile(seconds, [50, 90, 99, 100]) * 1e3
    return " / ".join(f"{v:.1f}" for v in p)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarse 20 × 10 grid")
    parser.add_argument("--reference", type=int, default=200, help="random points checked (default 200)")
    parser.add_argument("--max-modes", type=int, default=20_000, help="skip points needing more modes")
    parser.add_argument("--point-cap", type=float, default=10.0, help="per-point wall cap [s]")
    parser.add_argument("--budget", type=float, default=330.0, help="wall budget of each structure's points [s]")
    parser.add_argument("--reference-budget", type=float, default=150.0, help="wall budget of the references [s]")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--seed", type=int, default=12)
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "studies" / "RESULTS_plane.md"))
    parser.add_argument("--baseline", help="another checkout (e.g. the base commit's worktree): its sweeps are "
                        "timed side by side with this one's, alternating")
    parser.add_argument("--repeats", type=int, default=3, help="side-by-side rounds with --baseline (default 3)")
    parser.add_argument("--root", help="import impactmaps from this checkout (read before the import)")
    parser.add_argument("--time-sweeps", metavar="NPZ", help=argparse.SUPPRESS)  # a side-by-side round's child
    args = parser.parse_args(argv)
    if args.reference < 0:
        raise ValueError(f"--reference = {args.reference} is invalid: valid range is [0, inf)")
    if args.repeats < 1:
        raise ValueError(f"--repeats = {args.repeats} is invalid: valid range is [1, inf)")
    if args.time_sweeps:
        zetas, lambdas = _grid(args.quick)
        print(json.dumps(time_sweeps(zetas, lambdas, args.workers, args.time_sweeps)))
        return
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.compute.points import METHODS

    zetas, lambdas = _grid(args.quick)
    n_zeta, n_lambda = zetas.size, lambdas.size
    lines = [f"# The whole (ζ, λ) plane: {n_zeta} × {n_lambda} log grid over [1e-3, 1e3]²",
             "", f"`python benchmarks/studies/bench_plane.py {' '.join(sys.argv[1:] if argv is None else argv)}`"
             .replace(" `", "`"),
             f"run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {args.workers} workers, "
             f"guards: > {args.max_modes} modes skipped, {args.point_cap:g} s per point, "
             f"{args.budget:g} s budget per structure; load average at the start {os.getloadavg()[0]:.1f} "
             "(the machine may be shared: compare walls within one run)", ""]
    from impactmaps.solvers.warm_up import warm_up

    warmed = warm_up()  # compiled once before the pool: a cold compile in every worker would hit the point cap
    lines += [f"Kernels compiled or loaded first (`impactmaps warm-up`): {warmed['total_s']:.1f} s, "
              f"{warmed['compiled_variants']} integrator variants compiled.", ""]
    finished = []  # (name, ζ, λ, row)
    total_wall = 0.0
    lines += ["| structure | wall [s] | done | skipped (modes) | timed out | failed | not run (budget) "
              "| per point p50 / p90 / p99 / max [ms] | slowest point | CPU [s] of the points done | CPU [s] of the "
              "pool |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    status_lines = []
    for name in STRUCTURES:
        counts = finest_mode_counts(name, zetas, lambdas)
        tasks, skipped = [], []
        for i, zeta in enumerate(zetas):
            for j, lam in enumerate(lambdas):
                if counts[i, j] > args.max_modes:
                    skipped.append((zeta, lam, counts[i, j]))
                else:
                    tasks.append(("map", name, float(zeta), float(lam)))
        # random order: if the budget stops the run, the points done are a fair sample
        order = np.random.default_rng(args.seed).permutation(len(tasks))
        tasks = [tasks[k] for k in order]
        start, cpu = time.perf_counter(), cpu_seconds()
        outcomes = run_tasks(tasks, args.workers, args.point_cap, args.budget)
        wall, pool_cpu = time.perf_counter() - start, cpu_seconds() - cpu
        total_wall += wall
        done = [(t, o) for t, o in zip(tasks, outcomes) if o["state"] == "done"]
        timed = [(t, o) for t, o in zip(tasks, outcomes) if o["state"] == "timeout"]
        failed = [(t, o) for t, o in zip(tasks, outcomes) if o["state"] == "fail"]
        budget = sum(o["state"] == "budget" for o in outcomes)
        seconds = np.array([o["seconds"] for _, o in done]) if done else np.array([np.nan])
        point_cpu = sum(o["cpu"] for _, o in done)
        slow_t, slow_o = max(done, key=lambda item: item[1]["seconds"]) if done else ((None,) * 4, {})
        slowest = (f"ζ = {slow_t[2]:.3g}, λ = {slow_t[3]:.3g}: {slow_o['seconds']:.2f} s, "
                   f"{slow_o['row']['n_modes']} modes" if done else "–")
        lines.append(f"| {name} | {wall:.1f} | {len(done)} | {len(skipped)} | {len(timed)} | {len(failed)} | "
                     f"{budget} | {percentile_row(seconds)} | {slowest} | {point_cpu:.1f} | {pool_cpu:.1f} |")
        for t, o in done:
            finished.append((name, t[2], t[3], o["row"] | {"seconds": o["seconds"]}))
        total = counts.size
        shares = {s: sum(STATUSES[o["row"]["status"]] == s for _, o in done) for s in STATUSES}
        methods = {m: sum(METHODS[o["row"]["method"]] == m for _, o in done) for m in METHODS}
        status_lines.append(
            f"| {name} | " + " | ".join(f"{100 * shares[s] / total:.1f} %" for s in STATUSES)
            + f" | {100 * (len(skipped) + len(timed) + len(failed) + budget) / total:.1f} % | "
            + ", ".join(f"{m}: {c}" for m, c in methods.items() if c) + " |")
        if skipped:
            fewest = min(c for _, _, c in skipped)
            zeta_max = max(z for z, _, _ in skipped)
            status_lines.append(f"| ↳ {name} skipped | {len(skipped)} points need > {args.max_modes} modes at the "
                                f"finest level (fewest {fewest}); all at ζ ≤ {zeta_max:.3g} | | | | | |")
        for t, o in timed:
            status_lines.append(f"| ↳ {name} timed out | ζ = {t[2]:.3g}, λ = {t[3]:.3g} (> {args.point_cap:g} s, "
                                f"{counts[list(zetas).index(t[2]), list(lambdas).index(t[3])]} modes) | | | | | |")
        for t, o in failed[:5]:
            status_lines.append(f"| ↳ {name} failed | ζ = {t[2]:.3g}, λ = {t[3]:.3g}: {o['error'][:120]} | | | | | |")
    lines += ["", f"Total wall: **{total_wall:.1f} s** (issue 12 goal: ≤ 20 s for both together).", "",
              "Share of all grid points per status:", "",
              "| structure | " + " | ".join(STATUSES) + " | not computed | methods of the computed points |",
              "|---|" + "---|" * (len(STATUSES) + 2)] + status_lines
    lines += cost_section(finished, STATUSES)
    lines += sweep_section(finished, zetas, lambdas, args.workers)
    if args.baseline:
        lines += side_by_side_section(args)
    lines += reference_section(finished, args, STATUSES)
    text = "\n".join(lines) + "\n"
    pathlib.Path(args.out).write_text(text)
    print(text)


#: Classes of the retained run's modes and of the impacts, for :func:`cost_section`.
MODE_CLASSES = ((1, 16), (17, 64), (65, 400), (401, 1000), (1001, 10**9))
IMPACT_CLASSES = ((1, 1), (2, 4), (5, 19), (20, 10**9))


def cost_section(finished, statuses) -> list[str]:
    """Where the points' time goes: the share of the summed per-point wall by status, by the
    retained run's modes (``n_modes``; above 400 the contact phase is sampled, below it may be
    exact) and by the number of impacts."""
    lines = ["", "## Where the time goes (per-point tasks above)", "",
             "Share of each structure's summed per-point wall (and of its points) by class:", "",
             "| structure | by status | by modes of the retained run | by impacts |", "|---|---|---|---|"]

    def shares(rows, key, classes, label):
        total = sum(r["seconds"] for r in rows) or 1.0
        parts = []
        for cls in classes:
            chosen = [r for r in rows if key(r, cls)]
            if chosen:
                parts.append(f"{label(cls)}: {100 * sum(r['seconds'] for r in chosen) / total:.0f} % "
                             f"({100 * len(chosen) / len(rows):.0f} %)")
        return "; ".join(parts)

    for name in STRUCTURES:
        rows = [row for structure, _, _, row in finished if structure == name]
        if not rows:
            continue
        by_status = shares(rows, lambda r, c: statuses[r["status"]] == c, statuses, str)
        by_modes = shares(rows, lambda r, c: c[0] <= r["n_modes"] <= c[1], MODE_CLASSES,
                          lambda c: f"{c[0]}–{c[1]}" if c[1] < 10**9 else f"> {c[0] - 1}")
        by_impacts = shares(rows, lambda r, c: r["n_modes"] > 0 and c[0] <= r["impacts"] <= c[1], IMPACT_CLASSES,
                            lambda c: (f"{c[0]}" if c[0] == c[1] else f"{c[0]}–{c[1]}") if c[1] < 10**9 else f"≥ {c[0]}")
        lines.append(f"| {name} | {by_status} | {by_modes} | {by_impacts} |")
    return lines


def timed_sweeps(zetas, lambdas, workers: int):
    """The grid through :func:`impactmaps.maps.compute.sweep.sweep` as a user runs it (chunks of points
    per task, no per-point guards, never read from a shipped result): each structure alone,
    then both in one call (one pool). Returns ({"beam-ss-euler": s, …, "both": s} walls [s],
    the datasets by the same keys)."""
    from impactmaps.maps.compute import sweep as sweep_module
    from impactmaps.maps.family.structures import structure_from_name

    sweep_module.load_shipped_result = lambda digest, description=None: None  # compute, never read
    walls, datasets = {}, {}
    for key, names in [*((name, [name]) for name in STRUCTURES), ("both", list(STRUCTURES))]:
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            datasets[key] = sweep_module.sweep([structure_from_name(name) for name in names], zetas, lambdas,
                                               progress=False, max_workers=workers)
        walls[key] = time.perf_counter() - start
    return walls, datasets


def time_sweeps(zetas, lambdas, workers: int, save: str) -> dict:
    """A side-by-side round's child: :func:`timed_sweeps`, F̄max and status of the one-call sweep
    saved to ``save`` (.npz); returns the walls and whether the one-structure sweeps gave the
    same bits."""
    walls, datasets = timed_sweeps(zetas, lambdas, workers)
    both = datasets["both"]
    same = all(np.array_equal(datasets[name][var].sel(structure=name).values,
                              both[var].sel(structure=name).values, equal_nan=(var == "fmax_normalised"))
               for name in STRUCTURES for var in ("fmax_normalised", "status"))
    np.savez(save, fmax=both["fmax_normalised"].values, status=both["status"].values)
    return {"walls": walls, "same": bool(same)}


def sweep_section(finished, zetas, lambdas, workers: int) -> list[str]:
    """The same grid through :func:`impactmaps.maps.compute.sweep.sweep` (what a user runs: chunks of
    points per task, no per-point guards), its wall time, and whether every value equals the
    per-point tasks' bit for bit (a point is a pure function of its inputs)."""
    walls, datasets = timed_sweeps(zetas, lambdas, workers)
    differing, compared = 0, 0
    by_point = {(name, zeta, lam): row for name, zeta, lam, row in finished}
    for key, dataset in datasets.items():
        for name in STRUCTURES if key == "both" else [key]:
            values = dataset["fmax_normalised"].sel(structure=name).values
            statuses = dataset["status"].sel(structure=name).values
            for j, lam in enumerate(lambdas):
                for i, zeta in enumerate(zetas):
                    row = by_point.get((name, float(zeta), float(lam)))
                    if row is None:
                        continue
                    compared += 1
                    value = float(values[j, i])
                    same = (value == row["fmax_normalised"] or (np.isnan(value) and np.isnan(row["fmax_normalised"])))
                    differing += not (same and int(statuses[j, i]) == row["status"])
    alone = sum(walls[name] for name in STRUCTURES)
    return ["", "## The same grid as a user's sweep", "",
            f"`impactmaps.maps.compute.sweep.sweep` over the grid, {workers} workers (chunks of points per task, no "
            f"per-point guards): both structures in one call (one pool) **{walls['both']:.1f} s wall**; one "
            f"structure at a time {alone:.1f} s ("
            + ", ".join(f"{name} {walls[name]:.1f} s" for name in STRUCTURES)
            + f"); F̄max and status at {compared} points (both ways) compared with the per-point tasks above: "
            f"{differing} differ (bit for bit)."]


def side_by_side_section(args) -> list[str]:
    """The user's sweeps timed with this checkout and ``args.baseline`` in alternating child
    processes (``--repeats`` rounds, the order swapped each round), their walls, the ratios of
    the medians, and whether the two checkouts give the same bits at every point."""
    import statistics
    import tempfile

    roots = {"this": str(PACKAGE_ROOT), "baseline": str(pathlib.Path(args.baseline).resolve())}
    walls = {side: [] for side in roots}
    arrays = {}
    with tempfile.TemporaryDirectory() as scratch:
        for round_ in range(args.repeats):
            for side in (("this", "baseline") if round_ % 2 == 0 else ("baseline", "this")):
                save = os.path.join(scratch, f"{side}.npz")
                command = [sys.executable, str(pathlib.Path(__file__).resolve()), "--root", roots[side],
                           "--time-sweeps", save, "--workers", str(args.workers)] + (["--quick"] if args.quick else [])
                done = subprocess.run(command, capture_output=True, text=True, check=True)
                walls[side].append(json.loads(done.stdout.strip().splitlines()[-1]))
                with np.load(save) as stored:
                    arrays[side] = (stored["fmax"], stored["status"])
    same = (np.array_equal(arrays["this"][0], arrays["baseline"][0], equal_nan=True)
            and np.array_equal(arrays["this"][1], arrays["baseline"][1]))
    keys = ("both", *STRUCTURES)
    lines = ["", f"## Side by side with {args.baseline}", "",
             f"The user's sweep (as above) in child processes, this checkout and the baseline alternating, "
             f"{args.repeats} rounds; wall [s] per round, ratio = baseline median / this median:", "",
             "| sweep | this checkout | baseline | ratio |", "|---|---|---|---|"]
    for key in keys:
        mine = [w["walls"][key] for w in walls["this"]]
        base = [w["walls"][key] for w in walls["baseline"]]
        lines.append(f"| {'beam + plate, one call' if key == 'both' else key + ' alone'} | "
                     + " / ".join(f"{w:.1f}" for w in mine) + " | " + " / ".join(f"{w:.1f}" for w in base)
                     + f" | **{statistics.median(base) / statistics.median(mine):.2f}×** |")
    lines += ["", f"F̄max and status at all {arrays['this'][0].size} points: "
              + ("the same bits in both checkouts." if same else "**the checkouts differ**.")]
    return lines


def reference_section(finished, args, statuses) -> list[str]:
    """|F̄max − reference| at random finished points (reference: 8× cut-off and mode floor, 1/8 step)."""
    if not finished or args.reference == 0:
        return []
    rng = np.random.default_rng(args.seed)
    picks = rng.choice(len(finished), size=min(args.reference, len(finished)), replace=False)
    chosen = [finished[k] for k in picks]
    tasks = [("reference", name, zeta, lam) for name, zeta, lam, _ in chosen]
    start = time.perf_counter()
    outcomes = run_tasks(tasks, args.workers, 4 * args.point_cap, args.reference_budget)
    wall = time.perf_counter() - start
    rows = []
    for (name, zeta, lam, row), outcome in zip(chosen, outcomes):
        if outcome["state"] == "done":
            error = abs(row["fmax_normalised"] - outcome["row"]["fmax_normalised"])
            rows.append((name, zeta, lam, statuses[row["status"]], error, row["fmax_error"]))
    lines = ["", f"## Against the reference (8× cut-off and mode floor, 1/8 step) at {len(chosen)} random computed points",
             "", f"{len(rows)} references finished in {wall:.1f} s "
             f"({len(chosen) - len(rows)} not: over {4 * args.point_cap:g} s or the budget).", ""]
    plain = [r for r in rows if r[3] != "sensitive"]
    if plain:
        worst = max(plain, key=lambda r: r[4])
        over = [r for r in plain if r[4] > 1e-3]
        uncovered = [r for r in plain if r[4] > max(r[5], 1e-3)]
        lines += [f"- max |F̄max − reference| over {len(plain)} non-sensitive points: **{worst[4]:.2e}** "
                  f"({worst[0]}, ζ = {worst[1]:.3g}, λ = {worst[2]:.3g}, {worst[3]}); issue goal ≤ 1e-3",
                  f"- non-sensitive points above 1e-3: {len(over)}; above both 1e-3 and their own "
                  f"`fmax_error`: {len(uncovered)}"]
        for r in sorted(over, key=lambda r: -r[4])[:10]:
            lines.append(f"  - {r[0]} ζ = {r[1]:.3g}, λ = {r[2]:.3g} ({r[3]}): {r[4]:.2e} (fmax_error {r[5]:.1e})")
    sensitive = [r for r in rows if r[3] == "sensitive"]
    if sensitive:
        lines.append(f"- sensitive points checked: {len(sensitive)}; max |F̄max − reference| "
                     f"{max(r[4] for r in sensitive):.2e} (their band half-width: up to "
                     f"{max(r[5] for r in sensitive):.2e})")
    return lines


if __name__ == "__main__":
    main()
