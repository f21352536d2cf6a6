"""The kernel's share of a single-impact call: the Python around the compiled integrator.

For each case of :mod:`benchmarks.bench_modal` (λ = 0.425; plate and beam at ζ = 0.038,
1.198, 11.3; the closed-form bases of ``tests/analytic.py`` or, with ``--targets real``,
the library targets) one warm call of ``simulate(..., record=False)``, then ``--calls``
timed calls: the median CPU time of a call (``time.process_time``, steadier than wall time
on a shared machine) and the CPU time spent inside the integrator
(:data:`impactmaps.solvers.integrator.exact_step.integrate_impact`, timed by a wrapper put where
:mod:`impactmaps.solvers.modal_run` calls it). Kernel share = kernel time / call time
summed over the calls (issue 30 goal: ≥ 80 %). Where the rest goes, as shares of the call
(CPU time of wrappers put where :mod:`~impactmaps.solvers.modal_run` calls them): the run's
set-up (``prepare_run``, or the ``_prepare`` that ``run_once`` calls: basis, time step, budget) and, inside it, the coupled modes of the
exact linear contact phase (``coupled_modes``, an (n + 1)² ``eigh``), and the result object
(``_result``); the remainder is ``simulate``'s checks and the kernel's argument tuples.

Run for two checkouts in the same minutes to compare (``--root``):
``python benchmarks/studies/bench_thin_calls.py [--targets real] [--calls 400] [--root CHECKOUT]``.
Prints one Markdown table (the kernel's share per point) and the least share. The calls
repeat one set of inputs: from the second on, the run's set-up comes from the exact-input
cache of :mod:`impactmaps.solvers.modal_run` where the checkout has one; ``--fresh`` empties
that cache before each call, as for the new points of a sweep.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import statistics
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]


def measure(targets: str, calls: int, fresh: bool = False) -> list[tuple]:
    """(structure, ζ, modes, median call CPU [µs], kernel share, set-up share, coupled-modes
    share, result share) per bench_modal case."""
    from benchmarks.bench_modal import LOSS_FACTORS, _analytic_case, _real_case
    from impactmaps.solvers import modal_run
    from impactmaps.solvers.modal import ModalSettings, simulate

    settings = ModalSettings()
    build = _analytic_case if targets == "analytic" else _real_case
    real_kernel = modal_run.integrate_impact
    parts = {"kernel": 0.0, "prepare_run": 0.0, "coupled_modes": 0.0, "_result": 0.0}

    class TimedKernel:
        def __call__(self, *args):
            start = time.process_time()
            out = real_kernel(*args)
            parts["kernel"] += time.process_time() - start
            return out

        def __getattr__(self, name):  # compile, variant_of …: the real kernel's
            return getattr(real_kernel, name)

    def timed(name, function):
        def call(*args, **kwargs):
            start = time.process_time()
            out = function(*args, **kwargs)
            parts[name] += time.process_time() - start
            return out
        return call

    # run_once calls _prepare (prepare_run's fields as a tuple) where the checkout has it
    prepare = "_prepare" if hasattr(modal_run, "_prepare") else "prepare_run"
    originals = {prepare: getattr(modal_run, prepare), "_result": modal_run._result,
                 "coupled_modes": modal_run.coupled_modes}
    labels = {prepare: "prepare_run"}
    rows = []
    modal_run.integrate_impact = TimedKernel()
    for name, function in originals.items():
        setattr(modal_run, name, timed(labels.get(name, name), function))
    try:
        for kind in ("plate", "beam"):
            for zeta in LOSS_FACTORS:
                target, law, mass = build(kind, zeta, settings)
                result = simulate(target, law, mass, 1.0, settings=settings, record=False)  # compile or load
                durations = []
                for name in parts:
                    parts[name] = 0.0
                for _ in range(calls):
                    if fresh:  # a new input's call: the set-up computed, not read from the cache
                        getattr(modal_run, "_setup_cache", {}).clear()
                    start = time.process_time()
                    simulate(target, law, mass, 1.0, settings=settings, record=False)
                    durations.append(time.process_time() - start)
                total = sum(durations)
                rows.append((kind, zeta, result.n_modes, 1e6 * statistics.median(durations), parts["kernel"] / total,
                             parts["prepare_run"] / total, parts["coupled_modes"] / total, parts["_result"] / total))
    finally:
        modal_run.integrate_impact = real_kernel
        for name, function in originals.items():
            setattr(modal_run, name, function)
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", choices=("analytic", "real"), default="analytic")
    parser.add_argument("--calls", type=int, default=400)
    parser.add_argument("--fresh", action="store_true",
                        help="empty the run set-up cache before each call (a sweep's new points)")
    parser.add_argument("--root", type=pathlib.Path, default=ROOT, help="the checkout to measure (default this one)")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(args.root.resolve()))
    rows = measure(args.targets, max(args.calls, 10), args.fresh)
    print(f"`python benchmarks/studies/bench_thin_calls.py --targets {args.targets} --calls {args.calls}"
          f"{' --fresh' if args.fresh else ''}` "
          f"(code of {args.root.resolve().name})\n")
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}\n")
    print("| structure | ζ | modes | call CPU [µs] (median) | kernel share | set-up (coupled modes) | result |\n"
          "|---|---|---|---|---|---|---|")
    for kind, zeta, modes, call, share, setup, coupled, result in rows:
        print(f"| {kind} | {zeta} | {modes} | {call:.1f} | {100 * share:.0f} % | {100 * setup:.0f} % "
              f"({100 * coupled:.0f} %) | {100 * result:.0f} % |")
    print(f"\nkernel share: min {100 * min(row[4] for row in rows):.0f} % (goal ≥ 80 %)")


if __name__ == "__main__":
    main()
