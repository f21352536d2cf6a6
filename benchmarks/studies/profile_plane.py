"""Where the CPU of the whole (ζ, λ) plane goes: run kinds, kernel, set-up and the rest.

Workload: the grid of ``benchmarks/studies/bench_plane.py`` (200 × 50 log grid over [1e-3, 1e3]²,
``beam-ss-euler`` and ``plate-ssss-kirchhoff``), solved serially in this one process as a
sweep's worker solves it (:func:`impactmaps.maps.compute.points.solve_map_points`, chunks of 40
points along ζ), with ``--stride k`` every k-th λ row only. Timers wrap, without changing
any arithmetic:

* every modal run of a point (``simulate`` as :mod:`impactmaps.maps.compute.points` calls it),
  sorted by kind: the base run, the first and second refinement (step scale 1/2, 1/4) and
  the perturbed runs of a sensitive point; per kind its runs, CPU and mode-steps
  (Σ steps × modes integrated: the integrator's work);
* inside them the compiled integrator (``integrate_impact``) and the coupled modes'
  set-up of the exact contact phase (``coupled_modes``, an (n + 1)² eigenproblem).

Everything is ``time.process_time`` of this process (CPU, not wall: the machine may be
shared). What is left of a point's CPU outside those is the per-run and per-point Python
(settings, basis truncation, step choice, results).

Run: ``python benchmarks/studies/profile_plane.py [--stride 1] [--out benchmarks/studies/RESULTS_plane_profile.md]``.
"""

from __future__ import annotations

import argparse
import collections
import datetime
import os
import pathlib
import signal
import sys
import time
import warnings

if __name__ == "__main__":
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps, not an installed one
STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")
KINDS = ("base", "refinement 1", "refinement 2", "perturbed (sensitive)")


def run_kind(settings, base) -> str:
    """The kind of a point's run from its settings: base, refinement k, or a perturbation."""
    if settings == base:
        return KINDS[0]  # (a ζ-perturbed run has the base settings: counted as base)
    level = base
    for k in (1, 2):
        level = level.refined()
        if settings == level:
            return KINDS[k]
    return KINDS[3]


class Timers:
    """CPU [s] and counts of the wrapped calls, by name and by run kind."""

    def __init__(self):
        self.cpu = collections.Counter()
        self.count = collections.Counter()
        self.mode_steps = collections.Counter()

    def wrap(self, name, function, after=None):
        def timed(*args, **kwargs):
            start = time.process_time()
            result = function(*args, **kwargs)
            key = name if after is None else after(args, kwargs, result)
            self.cpu[key] += time.process_time() - start
            self.count[key] += 1
            return result
        for attribute in ("variant_of", "compile"):  # a lazy kernel's methods (modal_run calls them)
            if hasattr(function, attribute):
                setattr(timed, attribute, getattr(function, attribute))
        return timed


def profile(name: str, zetas, lambdas, timers: Timers) -> float:
    """Solve the grid on ``name`` serially with the timers in place; its CPU [s]."""
    from impactmaps.maps.compute import points
    from impactmaps.maps.compute.linear_points import LINEAR
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.solvers import modal_run
    from impactmaps.solvers.modal import ModalSettings

    base = ModalSettings()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # as in a sweep's worker (init_worker): no kernel thread

    def kind_of(args, kwargs, result):
        kind = run_kind(kwargs["settings"], base)
        timers.mode_steps[kind] += result.details.steps * result.n_modes
        return kind

    originals = (points.simulate, modal_run.integrate_impact, modal_run.coupled_modes)
    points.simulate = timers.wrap("run", points.simulate, kind_of)
    modal_run.integrate_impact = timers.wrap("integrator (compiled)", modal_run.integrate_impact)
    modal_run.coupled_modes = timers.wrap("coupled modes set-up", modal_run.coupled_modes)
    structure = structure_from_name(name)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            points.solve_map_points(LINEAR, structure, [(1.0, 1.0)], base)  # warm: tables, kernels
            timers.cpu.clear()
            timers.count.clear()
            timers.mode_steps.clear()
            start = time.process_time()
            for lam in lambdas:
                for first in range(0, zetas.size, 40):
                    points.solve_map_points(LINEAR, structure, [(float(z), float(lam)) for z in zetas[first:first + 40]],
                                            base)
            return time.process_time() - start
    finally:
        points.simulate, modal_run.integrate_impact, modal_run.coupled_modes = originals


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stride", type=int, default=1, help="every k-th λ row of the 50 (default 1: all)")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "studies" / "RESULTS_plane_profile.md"))
    args = parser.parse_args(argv)
    if args.stride < 1:
        raise ValueError(f"--stride = {args.stride} is invalid: valid range is [1, 50]")
    zetas, lambdas = np.geomspace(1e-3, 1e3, 200), np.geomspace(1e-3, 1e3, 50)[::args.stride]
    lines = [f"# Where the CPU of the (ζ, λ) plane goes: 200 × {lambdas.size} points per structure", "",
             f"`python benchmarks/studies/profile_plane.py {' '.join(sys.argv[1:] if argv is None else argv)}`"
             .replace(" `", "`"),
             f"run {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, serially in one process, "
             f"CPU time (`time.process_time`); the machine's load average at the start: {os.getloadavg()[0]:.1f}", "",
             "| structure | CPU [s] | compiled integrator | coupled-modes set-up | the rest (Python) "
             "| runs and CPU by kind: base (with a sensitive point's ζ ± 1 % runs) / refinement 1 / refinement 2 / cut-off and step perturbed | mode-steps by kind [10⁶] |",
             "|---|---|---|---|---|---|---|"]
    for name in STRUCTURES:
        timers = Timers()
        total = profile(name, zetas, lambdas, timers)
        kernel, setup = timers.cpu["integrator (compiled)"], timers.cpu["coupled modes set-up"]
        kinds = " / ".join(f"{timers.count[k]}: {timers.cpu[k]:.1f} s" for k in KINDS)
        steps = " / ".join(f"{timers.mode_steps[k] / 1e6:.0f}" for k in KINDS)
        lines.append(f"| {name} | {total:.1f} | {kernel:.1f} s ({100 * kernel / total:.0f} %) | {setup:.1f} s "
                     f"({100 * setup / total:.0f} %) | {total - kernel - setup:.1f} s "
                     f"({100 * (total - kernel - setup) / total:.0f} %) | {kinds} | {steps} |")
        print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    pathlib.Path(args.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
