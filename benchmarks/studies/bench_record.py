"""Cost of recording the history: ``simulate(..., record=True)`` against ``record=False``.

Workload: the README example (``examples/readme_example.py``): a 12.7 mm steel ball at
3 m/s on the centre of a simply supported 300 mm × 300 mm × 4 mm aluminium Mindlin plate,
Hertz contact. Each variant is run once to compile and build the basis, then ``--repeats``
times; the median wall time of one ``simulate`` call is reported, with the ratio
record/no-record (issue 12: must be ≤ 2), the number of history rows and whether the
scalars (peak force, its time, energy transferred, contact intervals) agree bit for bit.

Run: ``python benchmarks/studies/bench_record.py [--repeats N]``.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps, not an installed one


def readme_case():
    """(plate, law, mass [kg], velocity [m/s]) of the README example."""
    from impactmaps.contact import Sphere, law_for_sphere
    from impactmaps.materials import material
    from impactmaps.targets.plates.plate import Plate

    plate = Plate.isotropic(0.3, 0.3, 0.004, material("aluminium-6061-t6"), theory="mindlin")
    sphere = Sphere(0.0127 / 2, material("structural-steel"))
    law = law_for_sphere("hertz", sphere, material("aluminium-6061-t6"))
    return plate, law, sphere.mass, 3.0


def timed(record: bool, repeats: int):
    """Median wall time [s] of ``simulate`` with ``record`` and the last result."""
    from impactmaps.solvers.modal import simulate

    plate, law, mass, velocity = readme_case()
    result = simulate(plate, law, mass, velocity, record=record)  # compile, build the basis
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = simulate(plate, law, mass, velocity, record=record)
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21, help="timed calls per variant (default 21)")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        raise ValueError(f"--repeats = {args.repeats} is invalid: valid range is [1, inf)")
    off, result_off = timed(False, args.repeats)
    on, result_on = timed(True, args.repeats)
    same = (result_on.peak_force == result_off.peak_force
            and result_on.energy_transferred == result_off.energy_transferred
            and list(map(tuple, result_on.contact_intervals)) == list(map(tuple, result_off.contact_intervals)))
    rows = 0 if result_on.history is None else len(result_on.history)
    print("| variant | median wall per call | history rows |")
    print("|---|---|---|")
    print(f"| record=False | {off * 1e3:.2f} ms | – |")
    print(f"| record=True | {on * 1e3:.2f} ms | {rows} |")
    print(f"\nratio record/no-record: {on / off:.2f} (issue 12: ≤ 2); scalars identical: {same}")


if __name__ == "__main__":
    main()
