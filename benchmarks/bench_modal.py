"""Single-impact speed: impactmaps ``simulate`` against a scipy ``solve_ivp`` baseline.

Cases (spec §4, scaling figures of seed 001): SS square Kirchhoff plate struck at the
centre and SS Euler beam struck at mid-span, λ = 0.425, ζ = 0.038 (local), 1.198
(transition), 11.3 (quasi-static). Bases: the closed-form ones of ``tests/analytic.py``
(unit structures; the normalised problem depends on (ζ, λ) only), or with
``--targets real`` the library targets built by ``impactmaps.maps.family.structures`` (plate
always; beam if ``impactmaps.targets.beams.beam`` exists).

Both solvers integrate the same modes with the same residual compliance to the same
end time (:mod:`benchmarks.baseline_solve_ivp`, DOP853, rtol 1e-8, atol 1e-10 on the
normalised states). impactmaps: one warm-up call (numba compile or cache load), then
the median of ``--repeats`` calls of ``simulate(..., record=False)``; baseline: median
of ``--baseline-repeats`` calls. Wall and CPU (``time.process_time``) times are both
reported because the machine may be shared; the speed ratio uses CPU time.

Run: ``python benchmarks/bench_modal.py [--repeats 7] [--baseline-repeats 3]``.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import statistics
import sys
import time
from dataclasses import dataclass

ROOT = pathlib.Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from benchmarks.baseline_solve_ivp import baseline_like  # noqa: E402
from impactmaps.contact import LinearContact  # noqa: E402
from impactmaps.solvers.modal import ModalSettings, simulate  # noqa: E402

RELATIVE_STIFFNESS = 0.425
LOSS_FACTORS = (0.038, 1.198, 11.3)
TARGET_RATIO = 100.0
TARGET_DIFFERENCE = 1e-4


@dataclass
class ModalRow:
    """One benchmark case: accuracy and timings of both solvers (times in seconds)."""

    structure: str
    zeta: float
    n_modes: int
    steps: int
    fmax_impactmaps: float
    fmax_baseline: float
    first_call: float
    wall_impactmaps: float
    cpu_impactmaps: float
    wall_baseline: float
    cpu_baseline: float
    baseline_evaluations: int

    @property
    def difference(self) -> float:
        return self.fmax_impactmaps - self.fmax_baseline

    @property
    def ratio_cpu(self) -> float:
        return self.cpu_baseline / self.cpu_impactmaps

    @property
    def ratio_wall(self) -> float:
        return self.wall_baseline / self.wall_impactmaps

    @property
    def meets_target(self) -> bool:
        return self.ratio_cpu >= TARGET_RATIO and abs(self.difference) <= TARGET_DIFFERENCE


def _analytic_case(kind, zeta, settings):
    from tests.analytic import ss_beam_impactor, ss_euler_beam_basis, ss_plate_impactor, ss_square_plate_basis

    impactor = ss_beam_impactor if kind == "beam" else ss_plate_impactor
    bases = ss_euler_beam_basis if kind == "beam" else ss_square_plate_basis
    mass, stiffness = impactor(zeta, RELATIVE_STIFFNESS)
    omega = math.sqrt(stiffness / mass)
    return bases(settings.cutoff_ratio * omega, settings.min_modes), LinearContact(stiffness), mass


def _real_case(kind, zeta, settings):
    from impactmaps.dimensionless import realise
    from impactmaps.plotting.chart import CHART_STRUCTURES

    structure = next(s for s in CHART_STRUCTURES if s.kind == kind)
    target = structure.build()  # ImportError if the target module does not exist yet
    impactor = realise(target, zeta, RELATIVE_STIFFNESS)
    return target, LinearContact(impactor.contact_stiffness), impactor.impactor_mass


def _timed(function, repeats):
    walls, cpus, value = [], [], None
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        value = function()
        cpus.append(time.process_time() - cpu)
        walls.append(time.perf_counter() - wall)
    return statistics.median(walls), statistics.median(cpus), value


def run(repeats: int = 7, baseline_repeats: int = 3, targets: str = "analytic",
        settings: ModalSettings | None = None) -> tuple[list[ModalRow], list[str]]:
    """Time every case; return the rows and notes (skipped cases and why).

    Parameters
    ----------
    repeats : int
        Timed impactmaps calls per case (after one warm-up call), ≥ 5.
    baseline_repeats : int
        Timed solve_ivp calls per case, ≥ 3.
    targets : {"analytic", "real"}
        Closed-form bases of ``tests/analytic.py`` or the library targets.
    settings : ModalSettings, optional
        impactmaps settings (default settings when omitted).
    """
    settings = settings or ModalSettings()
    build = _analytic_case if targets == "analytic" else _real_case
    rows, notes = [], []
    for kind in ("plate", "beam"):
        for zeta in LOSS_FACTORS:
            try:
                target, law, mass = build(kind, zeta, settings)
            except ImportError as error:
                notes.append(f"{kind} ζ = {zeta}: skipped ({error})")
                continue

            def fast():
                return simulate(target, law, mass, 1.0, settings=settings, record=False)

            start = time.perf_counter()
            result = fast()  # warm-up: numba compile or cache load on the first case
            first = time.perf_counter() - start
            wall, cpu, result = _timed(fast, max(repeats, 5))
            base_wall, base_cpu, reference = _timed(
                lambda: baseline_like(result, target, settings), max(baseline_repeats, 3)
            )
            rows.append(ModalRow(
                structure=kind, zeta=zeta, n_modes=result.n_modes,
                steps=int(round(result.end_time / result.time_step)),
                fmax_impactmaps=result.fmax_normalised, fmax_baseline=reference.fmax_normalised,
                first_call=first, wall_impactmaps=wall, cpu_impactmaps=cpu,
                wall_baseline=base_wall, cpu_baseline=base_cpu,
                baseline_evaluations=reference.function_evaluations,
            ))
    return rows, notes


_COLD_START = """
import time
start = time.perf_counter()
import numpy as np
from impactmaps.contact import LinearContact
from impactmaps.solvers.modal import simulate
from impactmaps.targets.base import ModalBasis
imported = time.perf_counter()
simulate(ModalBasis(np.array([3.0e3]), np.array([1.0]), 1e-4), LinearContact(1.0e6), 1.0, 1.0, record=False)
first = time.perf_counter()
simulate(ModalBasis(np.array([3.0e3]), np.array([1.0]), 1e-4), LinearContact(1.0e6), 1.0, 1.0, record=False)
print(imported - start, first - imported, time.perf_counter() - first)
"""


def cold_start() -> tuple[float, float, float]:
    """(import time, first simulate call, second call) [s] in a fresh interpreter: the
    price every new process (each sweep worker) pays before its first point."""
    import os
    import subprocess

    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    done = subprocess.run([sys.executable, "-c", _COLD_START], capture_output=True, text=True, env=env,
                          check=True)
    imported, first, second = (float(x) for x in done.stdout.split())
    return imported, first, second


def markdown(rows: list[ModalRow], notes: list[str], targets: str = "analytic") -> str:
    """The rows as a Markdown table with a one-line verdict."""
    source = ("closed-form bases of tests/analytic.py" if targets == "analytic"
              else "library targets (impactmaps.targets via maps.structures)")
    lines = [
        f"Single impacts, λ = {RELATIVE_STIFFNESS}, {source}; default `ModalSettings`. "
        "Times are medians per run; ratio = baseline / impactmaps (CPU time; wall in brackets). "
        f"Target: ratio ≥ {TARGET_RATIO:g}× at |ΔF̄max| ≤ {TARGET_DIFFERENCE:g}.",
        "",
        "| structure | ζ | modes | steps | F̄max impactmaps | F̄max solve_ivp | Δ | first call [s] "
        "| impactmaps wall / CPU [ms] | solve_ivp wall / CPU [ms] | solve_ivp RHS evals | ratio CPU (wall) | target |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r.structure} | {r.zeta:g} | {r.n_modes} | {r.steps} | {r.fmax_impactmaps:.7f} | "
            f"{r.fmax_baseline:.7f} | {r.difference:+.1e} | {r.first_call:.3f} | "
            f"{1e3 * r.wall_impactmaps:.2f} / {1e3 * r.cpu_impactmaps:.2f} | "
            f"{1e3 * r.wall_baseline:.0f} / {1e3 * r.cpu_baseline:.0f} | {r.baseline_evaluations} | "
            f"{r.ratio_cpu:.0f}× ({r.ratio_wall:.0f}×) | {'met' if r.meets_target else '**missed**'} |"
        )
    if rows:
        ratios = np.array([r.ratio_cpu for r in rows])
        worst = max(abs(r.difference) for r in rows)
        lines += ["", f"Speed ratio (CPU): min {ratios.min():.0f}×, geometric mean "
                  f"{np.exp(np.mean(np.log(ratios))):.0f}×, max {ratios.max():.0f}×; "
                  f"max |ΔF̄max| = {worst:.1e}; target met in "
                  f"{sum(r.meets_target for r in rows)} of {len(rows)} cases."]
    lines += [f"- {note}" for note in notes]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--baseline-repeats", type=int, default=3)
    parser.add_argument("--targets", choices=("analytic", "real"), default="analytic")
    args = parser.parse_args()
    rows, notes = run(args.repeats, args.baseline_repeats, args.targets)
    print(markdown(rows, notes, args.targets))
    imported, first, second = cold_start()
    print(f"\nFresh interpreter: import {imported:.2f} s, first simulate {first:.3f} s, second {1e3 * second:.2f} ms.")


if __name__ == "__main__":
    main()
