"""Peak memory of a 10 000-point sweep.

Workload: ``impactmaps.maps.compute.sweep.sweep`` over 100 log-spaced ζ (0.005 … 100) × 50
log-spaced λ (0.05 … 20) × 2 structures (the default chart's SS Euler beam and SS
square Kirchhoff plate), default ``ModalSettings``, ``progress=False``, the resumable
result file in a temporary directory, the default local process pool (all cores).
If a chart structure cannot be built (e.g. ``impactmaps.targets.beams.beam`` missing), a
second plate family (SSSS Kirchhoff, aspect ratio 2) stands in for it, so that the
sweep still has 10 000 points over two basis tables; the table says so.

The sweep runs in a fresh Python process. Reported:

* peak of the summed resident set size (RSS) of that process and all its descendants,
  sampled every 0.1 s from here with psutil — an upper bound of the physical memory
  used, since pages shared between the forked workers count once per process;
* peak of the summed proportional set size (PSS, shared pages split between sharers),
  the best estimate of the real footprint, sampled at the same times;
* ``ru_maxrss`` of the orchestrating process itself and of its largest pool worker
  (``resource.getrusage`` of self and of the reaped children).

Target of the issue: < 1 GiB.

``--corners`` measures instead the light-impactor corners of issue 12 ("Corners blow
up"), each as the ``impactmaps`` command a user types, in a fresh process: wall time,
peak RSS (``ru_maxrss`` of that process, from ``os.wait4``), exit status and which
method answered (:data:`CORNERS`; the case files are the tests' data). Target: each
answers or refuses within 1 GiB and 30 s.

Run: ``python benchmarks/bench_memory.py [--zetas 100 --lambdas 50]`` or
``python benchmarks/bench_memory.py --corners``.
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
import threading
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))

from benchmarks.bench_chart import buildable_structures, count_points, reap_pool_workers, run_child  # noqa: E402

TARGET_BYTES = 1024**3
#: Wall-time target of one corner [s].
CORNER_TARGET_S = 30.0
_DATA = pathlib.Path(__file__).resolve().parents[1] / "tests" / "data"
#: The corners: (label, ``impactmaps`` arguments; ``{out}`` is a temporary directory).
CORNERS = (
    ("point plate-ss, ζ = 1e-6, λ = 1",
     ["point", "--target", "plate-ss", "--zeta", "1e-6", "--lambda", "1", "--json"]),
    ("case: 1e-9 kg steel sphere, 4 mm steel Kirchhoff plate, Hertz",
     ["simulate", str(_DATA / "light_sphere_1e-9kg_kirchhoff.toml"), "--out", "{out}", "--json"]),
    ("case: 1e-12 kg steel sphere, same plate",
     ["simulate", str(_DATA / "light_sphere_1e-12kg_kirchhoff.toml"), "--out", "{out}", "--json"]),
    ("case: 1e-9 kg steel sphere, 4 mm steel Mindlin plate (refused)",
     ["simulate", str(_DATA / "light_sphere_1e-9kg.toml"), "--out", "{out}", "--json"]),
    ("case: 1e-12 kg steel sphere, same Mindlin plate (refused)",
     ["simulate", str(_DATA / "light_sphere_1e-12kg.toml"), "--out", "{out}", "--json"]),
    ("case: 1e-9 kg sphere 1 mm from an edge (refused)",
     ["simulate", str(_DATA / "light_sphere_near_edge.toml"), "--out", "{out}", "--json"]),
)


class TreeMemorySampler:
    """Samples RSS and PSS summed over a process and its descendants in a thread."""

    def __init__(self, pid: int, interval: float = 0.1):
        import psutil

        self._psutil = psutil
        self._root = psutil.Process(pid)
        self._interval = interval
        self._stop = threading.Event()
        self.peak_rss = 0
        self.peak_pss = 0
        self.peak_processes = 0
        self.samples = 0
        self._thread = threading.Thread(target=self._loop, daemon=True)
        self._thread.start()

    def _loop(self):
        psutil = self._psutil
        while not self._stop.is_set():
            try:
                processes = [self._root, *self._root.children(recursive=True)]
            except psutil.Error:
                break
            rss = pss = 0
            for process in processes:
                try:
                    info = process.memory_full_info()
                except psutil.Error:
                    continue
                rss += info.rss
                pss += getattr(info, "pss", info.rss)
            self.peak_rss = max(self.peak_rss, rss)
            self.peak_pss = max(self.peak_pss, pss)
            self.peak_processes = max(self.peak_processes, len(processes))
            self.samples += 1
            self._stop.wait(self._interval)

    def stop(self):
        self._stop.set()
        self._thread.join()

    def report(self) -> dict:
        return {"peak_tree_rss_bytes": self.peak_rss, "peak_tree_pss_bytes": self.peak_pss,
                "peak_processes": self.peak_processes, "samples": self.samples}


def _child(out_dir: str, zeta_count: int, lambda_count: int) -> dict:

    from impactmaps.plotting.chart import CHART_STRUCTURES
    from impactmaps.maps.family.structures import MapStructure
    from impactmaps.maps.compute.sweep import log_grid, sweep

    structures, notes = buildable_structures(CHART_STRUCTURES)
    if len(structures) < len(CHART_STRUCTURES):
        stand_in = MapStructure(kind="plate", theory="kirchhoff", supports="SSSS", aspect_ratio=2.0)
        structures.append(stand_in)
        notes.append(f"{stand_in.name} stands in for the missing structure")
    zetas = log_grid(0.005, 100.0, zeta_count)
    lambdas = log_grid(0.05, 20.0, lambda_count)
    start, cpu = time.perf_counter(), time.process_time()
    dataset = sweep(structures, zetas, lambdas, path=pathlib.Path(out_dir) / "sweep.nc", progress=False)
    wall = time.perf_counter() - start
    reap_pool_workers()
    cpu = time.process_time() - cpu
    computed, converged = count_points(dataset)
    workers = resource.getrusage(resource.RUSAGE_CHILDREN)
    return {"structures": [s.name for s in structures], "notes": notes,
            "grid": [len(structures), int(lambdas.size), int(zetas.size)],
            "points": computed, "converged": converged, "wall_s": wall,
            "cpu_parent_s": cpu, "cpu_workers_s": workers.ru_utime + workers.ru_stime,
            "self_maxrss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
            "worker_maxrss_bytes": workers.ru_maxrss * 1024,
            "dataset_bytes": int(dataset.nbytes), "workers": os.cpu_count()}


def run(zeta_count: int = 100, lambda_count: int = 50) -> dict:
    """Run the sweep in a fresh process under the memory sampler; return the report."""
    with tempfile.TemporaryDirectory(prefix="impactmaps-bench-memory-") as out_dir:
        return run_child([str(pathlib.Path(__file__).resolve()), "--child", "--out", out_dir,
                          "--zetas", str(zeta_count), "--lambdas", str(lambda_count)],
                         sampler=TreeMemorySampler)


def markdown(report: dict) -> str:
    """The report as a Markdown table with the verdict against the target."""
    if "error" in report:
        return f"Memory benchmark failed: {report['error']}"
    mib = 1024**2
    peak = report["peak_tree_rss_bytes"]
    lines = [
        f"Sweep of {report['points']} points ({' × '.join(map(str, report['grid']))}: structures × λ × ζ; "
        f"{report['converged']} converged), default `ModalSettings`, {report['workers']} worker processes, "
        f"result file in a temporary directory. Target: < 1 GiB.",
        "",
        "| structures | peak RSS, process tree [MiB] | peak PSS, process tree [MiB] | max RSS orchestrator [MiB] "
        "| max RSS largest worker [MiB] | result dataset [MiB] | wall [s] | CPU parent + workers [s] | target |",
        "|---|---|---|---|---|---|---|---|---|",
        f"| {', '.join(report['structures'])} | {peak / mib:.0f} | {report['peak_tree_pss_bytes'] / mib:.0f} | "
        f"{report['self_maxrss_bytes'] / mib:.0f} | {report['worker_maxrss_bytes'] / mib:.0f} | "
        f"{report['dataset_bytes'] / mib:.1f} | {report['wall_s']:.1f} | "
        f"{report['cpu_parent_s']:.1f} + {report['cpu_workers_s']:.1f} | "
        f"{'met' if peak < TARGET_BYTES else '**missed**'} |",
        "",
        f"Tree sampled {report['samples']} times (every 0.1 s, up to {report['peak_processes']} processes); "
        "RSS counts pages shared by the forked workers once per process (upper bound), PSS splits them.",
    ]
    lines += [f"- {note}" for note in report.get("notes", [])]
    return "\n".join(lines)


def corner(arguments) -> dict:
    """Run ``python -m impactmaps.cli ARGUMENTS`` in a fresh process: wall time [s], peak
    RSS [B] (its own ``ru_maxrss``), exit status and the method and F̄max it printed."""
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(__file__).resolve().parents[1]))
    with tempfile.TemporaryDirectory(prefix="impactmaps-corner-") as out_dir, \
            tempfile.TemporaryFile("w+") as stdout, tempfile.TemporaryFile("w+") as stderr:
        argv = [a.replace("{out}", out_dir) for a in arguments]
        start = time.perf_counter()
        process = subprocess.Popen([sys.executable, "-m", "impactmaps.cli", *argv], stdout=stdout,
                                   stderr=stderr, env=env, cwd=str(pathlib.Path(__file__).resolve().parents[1]))
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
        process.returncode = os.waitstatus_to_exitcode(status)
        stdout.seek(0)
        stderr.seek(0)
        lines = stdout.read().strip().splitlines()
        values = json.loads(lines[-1]) if lines else {}
        errors = [line for line in stderr.read().splitlines() if not line.startswith("warning:")]
    return {"wall_s": wall, "peak_rss_bytes": usage.ru_maxrss * 1024, "exit": process.returncode,
            "method": values.get("method"), "fmax_normalised": values.get("fmax_normalised"),
            "asymptote": values.get("asymptote"), "error": errors[0] if errors else None}


def corners_markdown(reports) -> str:
    """The corner measurements as a Markdown table with the verdict against the targets."""
    mib = 1024**2
    lines = [f"Light-impactor corners (issue 12), each a fresh `impactmaps` process. Targets: < 1 GiB, "
             f"< {CORNER_TARGET_S:g} s.", "",
             "| corner | wall [s] | peak RSS [MiB] | exit | answered by | F̄max | target |",
             "|---|---|---|---|---|---|---|"]
    for label, report in reports:
        met = report["peak_rss_bytes"] < TARGET_BYTES and report["wall_s"] < CORNER_TARGET_S
        how = report["asymptote"] or report["method"] or f"refused: {report['error']}"
        fmax = "-" if report["fmax_normalised"] is None else f"{report['fmax_normalised']:.7f}"
        lines.append(f"| {label} | {report['wall_s']:.1f} | {report['peak_rss_bytes'] / mib:.0f} | "
                     f"{report['exit']} | {how} | {fmax} | {'met' if met else '**missed**'} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--child", action="store_true")
    parser.add_argument("--out")
    parser.add_argument("--zetas", type=int, default=100)
    parser.add_argument("--lambdas", type=int, default=50)
    parser.add_argument("--corners", action="store_true", help="measure the light-impactor corners instead")
    args = parser.parse_args()
    if args.corners:
        print(corners_markdown([(label, corner(arguments)) for label, arguments in CORNERS]))
        return
    if args.child:
        print(json.dumps(_child(args.out, args.zetas, args.lambdas)))
        return
    print(markdown(run(args.zetas, args.lambdas)))


if __name__ == "__main__":
    main()
