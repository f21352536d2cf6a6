"""Speed of the clamped Mindlin laminate and of lookups on clamped plates (issue 39 item 7).

Measures, in one process each (a fresh interpreter per measurement, the numba kernels
already in their cache):

* ``simulate`` of ``examples/drop_weight_quasi_isotropic.toml`` (clamped Mindlin
  quasi-isotropic laminate): warm kernels (loaded by an untimed run of another plate of the
  same kind in the same process), the basis built in the run ("warm incl. basis"; wall and CPU time),
  then the same run again in the process (basis cached);
* the same with ``edges = "SSSS"`` and the couplings of a cross-ply (Navier);
* ``lookup --case`` of a clamped Mindlin plate (150 × 100 × 3 mm 6061-T6, 20 mm steel ball,
  5.4 m/s: :data:`LOOKUP_CASE`) with an empty cache (the plate's basis and the tile are
  built), again (the tile cached), and at another speed (a new tile of the same plate: its
  basis read from the disk cache); each a fresh process (interpreter and imports
  included), and in one process after its imports: the first lookup call and the next
  ones (the tile cached on disk), with the heavy packages and compiled contact kernels the
  calls load; the imports of a fresh cached ``lookup --case`` (``python -X importtime``)
  beside a bare ``import numpy, scipy.linalg``;
* ``lookup --case`` of the drop-weight example itself (a clamped Mindlin quasi-isotropic
  laminate with D16/D26: its own tile, :data:`impactmaps.maps.compute.tiles`) with an empty
  cache and again, each a fresh process, with the CPU time of the process beside the wall
  time (less sensitive to the machine's load); with ``--cold-numba`` the first one also with
  an empty numba cache (its kernels compiled in the run, as a user's first run without the
  shipped kernels).

Run:  PYTHONPATH=. python benchmarks/bench_plates_any_edges.py [--root CHECKOUT] [--lookup-only | --simulate-only] [--cold-numba]  (writes
nothing; prints Markdown for benchmarks/RESULTS_plates_any_edges.md; ``--root`` times
another checkout, e.g. main before a change). Wall-clock times depend on the machine's
load: the load average is printed before and after.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "drop_weight_quasi_isotropic.toml"

#: The lookup case: the clamped plate of issue 39 as a Mindlin plate.
LOOKUP_CASE = """
name = "20 mm steel ball, 5.4 m/s, clamped 150 x 100 x 3 mm 6061-T6 plate (Mindlin)"
[impactor]
radius = 0.01
material = "structural-steel"
velocity = {velocity}
[target]
type = "plate"
length_x = 0.15
length_y = 0.10
thickness = 0.003
material = "aluminium-6061-t6"
theory = "mindlin"
edges = "CCCC"
[contact]
law = "hertz"
"""

_IN_PROCESS = textwrap.dedent("""
    import contextlib, io, sys, time, warnings
    warnings.simplefilter("ignore")
    t0 = time.perf_counter()
    from impactmaps.cli import main
    import impactmaps.cases.case_lookup, impactmaps.cases.on_demand  # the lookup's own imports
    t1 = time.perf_counter()
    calls, before = [], set(sys.modules)
    for _ in range(3):
        start = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            main(["lookup", "--case", sys.argv[1], "--json"])
        calls.append(time.perf_counter() - start)
    new = set(sys.modules) - before
    heavy = [name for name in ("dask", "xarray", "pandas", "scipy.integrate") if name in new] or ["none"]
    from impactmaps.contact import available_contact_laws, contact_law_class
    compiled = [name for name in available_contact_laws() if contact_law_class(name).kernel.signatures] or ["none"]
    print(f"{t1 - t0:.3f} " + " ".join(f"{t:.4f}" for t in calls) + " " + ",".join(heavy) + " " + ",".join(compiled))
""")

#: The packages whose import the fresh ``lookup --case`` process is checked for.
_HEAVY = ("numba", "scipy.special", "scipy.integrate", "pandas", "xarray", "dask")

_RUN_TWICE = textwrap.dedent("""
    import sys, time, warnings
    warnings.simplefilter("ignore")
    from impactmaps.cases import load_case, run_case
    case = load_case(sys.argv[1])
    run_case(load_case(sys.argv[2]))  # load the kernels on another plate of the same kind: not timed
    c0, t0 = time.process_time(), time.perf_counter()
    result, summary = run_case(case)
    c1, t1 = time.process_time(), time.perf_counter()
    result2, _ = run_case(case); t2 = time.perf_counter()
    print(f"{t1 - t0:.3f} {c1 - c0:.3f} {t2 - t1:.3f} {result.peak_force:.2f} {summary['n_modes']} {summary['method']}")
""")

def _warm_twin(text: str) -> str:
    """Another plate of the example's kind (the same kernel variants, another basis): a
    [0/45/-45/90]2s layup on a 150 × 100 mm span, run untimed first so that "warm" means the
    kernels are loaded, not that the example's basis is."""
    return (text.replace("angles_deg = [45, 0, -45, 90, 45, 0, -45, 90]", "angles_deg = [0, 45, -45, 90, 0, 45, -45, 90]")
            .replace("length_x = 0.125 ", "length_x = 0.150 ").replace("length_y = 0.075 ", "length_y = 0.100 "))


def _twin(text: str) -> str:
    """The example with SSSS edges and a cross-ply (specially orthotropic: Navier)."""
    return (text.replace('edges = "CCCC"', 'edges = "SSSS"')
            .replace("angles_deg = [45, 0, -45, 90, 45, 0, -45, 90]", "angles_deg = [0, 90, 0, 90, 0, 90, 0, 90]"))


def _environment(root: Path, **extra) -> dict:
    """The environment of a measured process: BLAS threads left at their default (2 here);
    OMP_NUM_THREADS=2 and OPENBLAS_NUM_THREADS=2, set by the first version of this script,
    doubled the CPU time of a first lookup on the loaded machine (34.7 s against 16.7 s)."""
    return dict(os.environ, PYTHONPATH=str(root), **extra)


def _run(root: Path, code: str, *args: str, **extra) -> str:
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=root,
                          env=_environment(root, **extra), check=True).stdout.strip()


def _lookup(root: Path, case: Path, cache: Path, **extra) -> tuple[float, str, float]:
    """(wall time [s], peak force answer, CPU time of the process [s]) of ``impactmaps lookup --case``
    in a fresh process."""
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "impactmaps.cli", "lookup", "--case", str(case), "--json"],
                          capture_output=True, text=True, cwd=root,  # -m and -c import from the working directory
                          env=_environment(root, IMPACTMAPS_CACHE_DIR=str(cache), **extra))
    seconds = time.perf_counter() - start
    now = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (now.ru_utime - used.ru_utime) + (now.ru_stime - used.ru_stime)
    try:
        answer = json.loads(done.stdout)
        return seconds, f"{answer['peak_force_N']:.2f} ± {answer['peak_force_error_N']:.1f} N", cpu
    except (ValueError, KeyError):
        return seconds, "refused: " + (done.stderr.strip().splitlines() or ["?"])[-1][:120], cpu


def _import_profile(root: Path, case: Path, cache: Path) -> str:
    """``python -X importtime`` of a fresh ``lookup --case`` (tile cached): the summed import time of
    the process's top-level imports and the cumulative time of each heavy package it imports."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "impactmaps.cli", "lookup", "--case", str(case),
                           "--json"], capture_output=True, text=True, cwd=root,
                          env=_environment(root, IMPACTMAPS_CACHE_DIR=str(cache)))
    total, heavy = 0, {}
    for line in done.stderr.splitlines():
        if not line.startswith("import time:") or "cumulative" in line:
            continue
        _, cumulative, name = (part.rstrip() for part in line[len("import time:"):].split("|"))
        if not name.startswith("  "):  # a top-level import (its cumulative time holds its children)
            total += int(cumulative)
        if name.strip() in _HEAVY:
            heavy[name.strip()] = heavy.get(name.strip(), 0) + int(cumulative)
    shown = ", ".join(f"{name} {heavy[name] / 1e6:.2f}" for name in _HEAVY if name in heavy)
    return f"imports {total / 1e6:.2f} s in all; of them {shown or 'none'} s (cumulative)"


def _bare() -> float:
    """Wall time [s] of a fresh ``python -c "import numpy, scipy.linalg"`` (the floor of any command)."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import numpy, scipy.linalg"], check=True)
    return time.perf_counter() - start


def _load() -> str:
    return " ".join(f"{value:.1f}" for value in os.getloadavg())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=ROOT, help="the checkout to time (default: this one)")
    parser.add_argument("--lookup-only", action="store_true", help="time the lookups only (not simulate)")
    parser.add_argument("--simulate-only", action="store_true", help="time simulate only (not the lookups)")
    parser.add_argument("--cold-numba", action="store_true",
                        help="time the drop-weight example's first lookup with an empty numba cache too")
    options = parser.parse_args()
    root = options.root.resolve()
    example = root / "examples" / "drop_weight_quasi_isotropic.toml"
    before = _load()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        twin = folder / "twin.toml"
        twin.write_text(_twin(example.read_text()))
        warm, warm_twin = folder / "warm.toml", folder / "warm_twin.toml"
        warm.write_text(_warm_twin(example.read_text()))
        warm_twin.write_text(_warm_twin(_twin(example.read_text())))
        rows = []
        for label, path, warm_path in () if options.lookup_only else (
                ("clamped Mindlin [45/0/-45/90]2s (general basis)", example, warm),
                ("SSSS Mindlin [0/90]4s (Navier)", twin, warm_twin)):
            first, cpu, second, peak, modes, method = _run(root, _RUN_TWICE, str(path), str(warm_path),
                                                           IMPACTMAPS_CACHE_DIR=str(folder / "simulate-cache")).split()
            rows.append(f"| {label} | {float(first):.2f} ({float(cpu):.2f}) | {float(second):.3f} | {peak} | {modes} "
                        f"| {method} |")
        if options.simulate_only:
            print(f"load average (1, 5, 15 min) before: {before}; after: {_load()} ({os.cpu_count()} cores, shared)\n")
            print("| case | simulate, warm incl. basis: wall (CPU) [s] | simulate, basis cached [s] | peak [N] | modes | method |")
            print("|---|---|---|---|---|---|")
            print("\n".join(rows))
            return
        case, other = folder / "case.toml", folder / "other.toml"
        case.write_text(LOOKUP_CASE.format(velocity=5.4))
        other.write_text(LOOKUP_CASE.format(velocity=3.0))
        cache = folder / "cache"
        lookups = [("new plate, empty cache (basis and tile built)", *_lookup(root, case, cache)),
                   ("again (tile cached)", *_lookup(root, case, cache)),
                   ("same plate at 3.0 m/s (a new tile; the basis on disk)", *_lookup(root, other, cache))]
        laminate_cache = folder / "laminate-cache"
        lookups += [("drop-weight example (clamped Mindlin laminate), empty cache", *_lookup(root, example, laminate_cache)),
                    ("drop-weight example again (tile cached)", *_lookup(root, example, laminate_cache))]
        if options.cold_numba:
            lookups.append(("drop-weight example, empty cache and empty numba cache",
                            *_lookup(root, example, folder / "cold-cache", NUMBA_CACHE_DIR=str(folder / "numba"))))
        imports, *calls, heavy, compiled = _run(root, _IN_PROCESS, str(case), IMPACTMAPS_CACHE_DIR=str(cache)).split()
        profile = _import_profile(root, case, cache)
    bare = _bare()
    after = _load()
    print(f"load average (1, 5, 15 min) before: {before}; after: {after} ({os.cpu_count()} cores, shared)\n")
    if rows:
        print("| case | simulate, warm incl. basis: wall (CPU) [s] | simulate, basis cached [s] | peak [N] | modes | method |")
        print("|---|---|---|---|---|---|")
        print("\n".join(rows))
    print("\n| lookup --case (fresh process each) | wall [s] | CPU [s] | answer |")
    print("|---|---|---|---|")
    print("\n".join(f"| {label} | {seconds:.2f} | {cpu:.2f} | {answer} |" for label, seconds, answer, cpu in lookups))
    print(f"\nIn one process (tile cached on disk): imports {float(imports):.2f} s; lookup calls "
          + ", ".join(f"{float(t):.3f}" for t in calls) + " s (first, second, third); imported by the calls: "
          + heavy.replace(",", ", ") + "; compiled contact kernels loaded: " + compiled.replace(",", ", "))
    print(f"\nA fresh `lookup --case` (tile cached), `python -X importtime`: {profile}; a bare "
          f"`python -c 'import numpy, scipy.linalg'`: {bare:.2f} s wall")


if __name__ == "__main__":
    main()
