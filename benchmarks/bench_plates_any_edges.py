"""Speed of the clamped Mindlin laminate (issue 39 item 7), next to its SSSS Navier twin.

Measures, in one process each (a fresh interpreter per measurement, the numba kernels
already in their cache):

* ``simulate`` of ``examples/drop_weight_quasi_isotropic.toml`` (clamped Mindlin
  quasi-isotropic laminate): warm kernels, the basis built in the run ("warm incl. basis"),
  then the same run again in the process (basis cached);
* the same with ``edges = "SSSS"`` and the couplings of a cross-ply (Navier);
* ``lookup --case`` of a clamped plate new to the tile cache (the tile is built), then
  again (cached tile).

Run:  PYTHONPATH=. python benchmarks/bench_plates_any_edges.py  (writes nothing; prints a
Markdown table for benchmarks/RESULTS_plates_any_edges.md). Wall-clock times depend on the
machine's load: the table says what the load average was.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "drop_weight_quasi_isotropic.toml"

_RUN_TWICE = textwrap.dedent("""
    import sys, time, warnings
    warnings.simplefilter("ignore")
    from impactmaps.cases import load_case, run_case
    case = load_case(sys.argv[1])
    run_case(load_case(sys.argv[2]))  # load the kernels on another Mindlin case: not timed
    t0 = time.perf_counter(); result, summary = run_case(case); t1 = time.perf_counter()
    result2, _ = run_case(case); t2 = time.perf_counter()
    print(f"{t1 - t0:.3f} {t2 - t1:.3f} {result.peak_force:.2f} {summary['n_modes']} {summary['method']}")
""")

_WARM_CASE = """
[impactor]
radius = 0.005
mass = 1.0
material = "structural-steel"
velocity = 1.0
[target]
type = "plate"
length_x = 0.2
length_y = 0.2
thickness = 0.005
material = "aluminium-6061-t6"
theory = "mindlin"              # the same kernel variants as the timed runs (contact patch)
edges = "SSSS"
[contact]
law = "hertz"
"""


def _twin(text: str) -> str:
    """The example with SSSS edges and a cross-ply (specially orthotropic: Navier)."""
    return (text.replace('edges = "CCCC"', 'edges = "SSSS"')
            .replace("angles_deg = [45, 0, -45, 90, 45, 0, -45, 90]", "angles_deg = [0, 90, 0, 90, 0, 90, 0, 90]"))


def _run(code: str, *args: str) -> str:
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="2", OMP_NUM_THREADS="2")
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=env,
                          check=True).stdout.strip()


def _lookup(case: Path, cache: Path) -> float:
    env = dict(os.environ, PYTHONPATH=str(ROOT), IMPACTMAPS_CACHE_DIR=str(cache))
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "impactmaps.cli", "lookup", "--case", str(case), "--json"],
                   capture_output=True, text=True, env=env)
    return time.perf_counter() - start


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        warm = folder / "warm.toml"
        warm.write_text(_WARM_CASE)
        twin = folder / "twin.toml"
        twin.write_text(_twin(EXAMPLE.read_text()))
        rows = []
        for label, path in (("clamped Mindlin [45/0/-45/90]2s (general basis)", EXAMPLE),
                            ("SSSS Mindlin [0/90]4s (Navier)", twin)):
            first, second, peak, modes, method = _run(_RUN_TWICE, str(path), str(warm)).split()
            rows.append(f"| {label} | {float(first):.2f} | {float(second):.3f} | {peak} | {modes} | {method} |")
        cache = folder / "cache"
        first_lookup = _lookup(EXAMPLE, cache)
        cached_lookup = _lookup(EXAMPLE, cache)
    load = os.getloadavg()
    print(f"load average during the run: {load[0]:.1f} {load[1]:.1f} {load[2]:.1f} ({os.cpu_count()} cores)\n")
    print("| case | simulate, warm incl. basis [s] | simulate, basis cached [s] | peak [N] | modes | method |")
    print("|---|---|---|---|---|---|")
    print("\n".join(rows))
    print(f"\nlookup --case (clamped example, new tile): {first_lookup:.2f} s; cached: {cached_lookup:.2f} s "
          "(each a fresh process: includes the interpreter and imports)")


if __name__ == "__main__":
    main()
