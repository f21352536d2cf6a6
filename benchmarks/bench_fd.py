"""Timing of the finite-difference beam solver (not part of the tests).

Default case of the spec: seed-000 steel beam (SS, L = 780 mm, b × h = 60 × 27.8 mm),
N_l = 200 elements, 2 N_h = 20 layers, plastic section, refined-Stronge contact
(steel sphere R = 12.5 mm), 5 ms of response, default time step. Reported: the first
call in this process (numba cache load or compile, grid eigenvalue) and the median of
repeated calls afterwards; also the elastic (no layers) model and a Hertz law.

Run: ``python benchmarks/bench_fd.py [--repeats 7]``. Prints a Markdown table and appends
it to ``benchmarks/RESULTS_fd.md``.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import platform
import statistics
import time

import warnings

import numba
import numpy as np

from impactmaps.contact import HertzContact, StrongeContact, effective_modulus
from impactmaps.fd import FDBeam, simulate_fd

RESULTS = pathlib.Path(__file__).with_name("RESULTS_fd.md")


def _cpu_model() -> str:
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def _machine() -> str:
    return (f"{_cpu_model()}, {os.cpu_count()} logical CPUs, {platform.system()} "
            f"{platform.release()}, Python {platform.python_version()}, numpy {np.__version__}, "
            f"numba {numba.__version__}")


def main():
    warnings.filterwarnings("ignore", message="the record ends in contact")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--no-append", action="store_true", help="print only")
    args = parser.parse_args()

    e_star = float(effective_modulus(206e9, 0.3, 206e9, 0.3))
    stronge = StrongeContact(e_star, 0.0125, 235e6)
    hertz = HertzContact(4 / 3 * np.sqrt(0.0125) * e_star)
    cases = [
        ("plastic, Stronge, 5 kg at 5 m/s", dict(plastic=True), stronge, 5.0, 5.0),
        ("plastic, Hertz, 5 kg at 5 m/s (beam yields)", dict(plastic=True), hertz, 5.0, 5.0),
        ("elastic, Hertz, 1 kg at 2 m/s", dict(plastic=False), hertz, 1.0, 2.0),
    ]
    rows = []
    for label, options, law, mass, velocity in cases:
        beam = FDBeam(0.78, 0.06, 0.0278, 206e9, 7850.0, 235e6, n_elements=200, n_half_layers=10,
                      **options)
        start = time.perf_counter()
        result = simulate_fd(beam, law, mass, velocity, duration=5e-3)
        first = time.perf_counter() - start
        times = []
        for _ in range(args.repeats):
            start = time.perf_counter()
            simulate_fd(beam, law, mass, velocity, duration=5e-3)
            times.append(time.perf_counter() - start)
        rows.append((label, result.settings["n_steps"], result.time_step, first,
                     statistics.median(times), min(times), result.peak_force,
                     result.energy_balance_error))

    header = (f"\n## {datetime.datetime.now().isoformat(timespec='seconds')}\n\n"
              f"Machine: {_machine()}\n\n"
              f"N_l = 200, 2N_h = 20, 5 ms of response, {args.repeats} repeats "
              "(wall clock; the machine may be shared).\n\n"
              "| case | steps | Δt [s] | first call [s] | median [s] | min [s] | peak force [N] | ledger error |\n"
              "|---|---|---|---|---|---|---|---|\n")
    body = "".join(
        f"| {label} | {steps} | {dt:.3e} | {first:.3f} | {median:.3f} | {fastest:.3f} | {peak:.0f} | {err:.1e} |\n"
        for label, steps, dt, first, median, fastest, peak, err in rows
    )
    print(header + body)
    if not args.no_append:
        if not RESULTS.exists():
            RESULTS.write_text("# Finite-difference beam solver timings (benchmarks/bench_fd.py)\n")
        with RESULTS.open("a") as handle:
            handle.write(header + body)


if __name__ == "__main__":
    main()
