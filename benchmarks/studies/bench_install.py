"""A fresh install as the README does it, then its first commands: the shipped kernels against compiling.

For each checkout (``--base``, e.g. a worktree of the previous commit, and this one), in
rounds alternating the two: a new virtual environment (``python -m venv``), ``pip install
CHECKOUT`` in it (timed: wall and CPU of pip and what it starts — the build, and since the
wheel ships the compiled kernels, their compile), the size of the wheel pip built and of
the installed package (with numba's cache files in it, if any); then, in an empty working
directory and with numba's cache where an installation keeps it (``NUMBA_CACHE_DIR``
unset):

1. ``impactmaps --no-background-warm-up chart --quiet`` — the README's first command;
2. ``impactmaps --no-background-warm-up simulate --json examples/steel_plate_hertz.toml`` —
   the first integrating command (the compile helper on, as for a user);
3. the same again (warm).

The two checkouts' ``simulate`` answers are compared (JSON without the output paths, and the
written ``history.csv``): a run from the wheel's cache against a run that compiled. Wall and
CPU times (``getrusage`` of the ended children) with the load average. pip's own caches (its
HTTP and wheel caches of the dependencies) are used as a user's pip would.

Run: ``python benchmarks/studies/bench_install.py --base CHECKOUT [--rounds 2] [--print-only]``;
writes a section at the top of ``benchmarks/studies/RESULTS_cold_start.md`` unless ``--print-only``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import pathlib
import re
import resource
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASE = ROOT / "examples" / "steel_plate_hertz.toml"


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _timed(argv, **kwargs) -> tuple[float, float, subprocess.CompletedProcess]:
    """(wall [s], CPU [s], the completed process) of ``argv``; raises if it fails."""
    cpu, start = _cpu(), time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, **kwargs)
    wall, used = time.perf_counter() - start, _cpu() - cpu
    if done.returncode != 0:
        raise RuntimeError(f"{argv} failed:\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    return wall, used, done


def _size(path: pathlib.Path, pattern: str = "**/*") -> float:
    return sum(item.stat().st_size for item in path.glob(pattern) if item.is_file()) / 1e6


def measure(checkout: pathlib.Path, work: pathlib.Path) -> dict:
    """Install ``checkout`` into a new environment under ``work`` and run its first commands."""
    venv = work / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    env = {name: value for name, value in os.environ.items()
           if name not in ("NUMBA_CACHE_DIR", "PYTHONPATH", "IMPACTMAPS_NO_BACKGROUND_WARMUP")}
    env["OMP_NUM_THREADS"] = "1"
    install = _timed([str(venv / "bin" / "pip"), "install", "-v", str(checkout)], env=env, cwd=work)
    wheel = re.search(r"Created wheel for impactmaps: filename=(\S+) size=(\d+)", install[2].stdout)
    package = next((venv / "lib").glob("python*/site-packages/impactmaps"))
    row = {"install": install[:2], "wheel": wheel.group(1), "wheel_mb": int(wheel.group(2)) / 1e6,
           "package_mb": _size(package), "cache_mb": _size(package, "**/__pycache__/*.nb[ic]")}
    run = work / "run"
    run.mkdir()
    command = [str(venv / "bin" / "impactmaps"), "--no-background-warm-up"]
    row["chart"] = _timed([*command, "chart", "--quiet"], env=env, cwd=run)[:2]
    for name, out in (("simulate", "first"), ("warm", "again")):
        wall, cpu, done = _timed([*command, "simulate", "--json", "--out", out, str(CASE)], env=env, cwd=run)
        row[name] = (wall, cpu)
        if out == "first":
            answer = json.loads(done.stdout)
            answer.pop("outputs", None)
            row["answer"] = (answer, (run / out / "history.csv").read_bytes())
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=pathlib.Path, required=True, help="the checkout to compare with")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--print-only", action="store_true", help="print, do not write RESULTS_cold_start.md")
    args = parser.parse_args(argv)
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    rows, loads = {"base": [], "this": []}, [os.getloadavg()[0]]
    for _ in range(args.rounds):
        for label, checkout in (("base", args.base), ("this", ROOT)):
            with tempfile.TemporaryDirectory(prefix=f"bench_install_{label}_") as work:
                rows[label].append(measure(checkout.resolve(), pathlib.Path(work)))
            loads.append(os.getloadavg()[0])
    same = all(row["answer"] == rows["base"][0]["answer"] for label in rows for row in rows[label])

    def cell(label, key):
        return ", ".join(f"{row[key][0]:.1f} ({row[key][1]:.1f})" for row in rows[label])

    lines = [f"`python benchmarks/studies/bench_install.py --base {args.base} --rounds {args.rounds}`, run {started}, "
             f"load average {min(loads):.1f}–{max(loads):.1f} on {os.cpu_count()} cores; one fresh venv per "
             "install, rounds alternating base / this branch; wall [s] (CPU [s]) of each round:", "",
             "| what | base | this branch |", "|---|---|---|"]
    for key, text in (("install", "`pip install CHECKOUT` into a fresh venv"),
                      ("chart", "then `impactmaps chart` (README's first command)"),
                      ("simulate", "then the first `impactmaps simulate examples/steel_plate_hertz.toml`"),
                      ("warm", "the same again (warm)")):
        lines.append(f"| {text} | {cell('base', key)} | {cell('this', key)} |")
    for key, text in (("wheel_mb", "wheel [MB]"), ("package_mb", "installed package [MB]"),
                      ("cache_mb", "of which numba's cache files [MB]")):
        lines.append(f"| {text} | {rows['base'][0][key]:.1f} | {rows['this'][0][key]:.1f} |")
    lines.append(f"| wheel | `{rows['base'][0]['wheel']}` | `{rows['this'][0]['wheel']}` |")
    lines += ["", f"The first `simulate`'s answers (JSON without output paths, and `history.csv`) are "
              f"{'the same bits' if same else 'NOT the same'} in every run of both checkouts.", ""]
    text = "\n".join(lines)
    print(text)
    if not args.print_only:
        results = ROOT / "benchmarks" / "studies" / "RESULTS_cold_start.md"
        title, rest = results.read_text().split("\n", 1)
        results.write_text(f"{title}\n\n## Fresh install (bench_install.py, {started})\n\n{text}{rest}")


if __name__ == "__main__":
    main()
