"""What a plastic `lookup --case` costs when no shipped map describes the case: its on-demand tile.

For a few elastic-plastic cases on structures without a shipped plastic map (a clamped–
clamped Euler beam with ``epp`` at two speeds, a clamped–simply supported beam struck
off-centre with the Stronge law, a simply supported Timoshenko beam of slenderness 25 with
``epp``, a clamped square Kirchhoff plate with Yigit–Christoforou): the first lookup (a
fresh cache: the 64-point tile built serially in this process), the lookup again (from the
cache), and ``simulate`` on the same case, in wall-clock and CPU seconds of this process;
then the answer against ``simulate`` in units of its band. The first case runs once
before timing (numba's compiled kernels loaded from their cache).

    python benchmarks/studies/bench_plastic_tiles.py
"""

from __future__ import annotations

import tempfile
import time
import warnings

from impactmaps.cases import parse_case, run_case
from impactmaps import lookup

_BALL = '[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
_BEAM = ('[target]\ntype = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.02\nmaterial = "aluminium-6061-t6"\n'
         'theory = "{theory}"\nsupports = "{supports}"\nimpact_position = {position!r}\n')
_PLATE = ('[target]\ntype = "plate"\nlength_x = 0.3\nlength_y = 0.3\nthickness = 0.004\n'
          'material = "aluminium-6061-t6"\ntheory = "kirchhoff"\nedges = "CCCC"\n')

CASES = {
    "beam-cc-euler, epp, 20 mm ball, 1 m/s": (_BEAM.format(theory="euler", supports="cc", position=0.25), "epp",
                                              0.01, 1.0),
    "beam-cc-euler, epp, 20 mm ball, 3 m/s": (_BEAM.format(theory="euler", supports="cc", position=0.25), "epp",
                                              0.01, 3.0),
    "beam-cs-euler x0 = 0.2 m, stronge, 20 mm ball, 1 m/s": (_BEAM.format(theory="euler", supports="cs",
                                                                           position=0.2), "stronge", 0.01, 1.0),
    "beam-ss-timoshenko L/h 25, epp, 20 mm ball, 1 m/s": (_BEAM.format(theory="timoshenko", supports="ss",
                                                                        position=0.25), "epp", 0.01, 1.0),
    "plate-cccc-kirchhoff 300 × 300 × 4 mm, yc, 20 mm ball, 1 m/s": (_PLATE, "yigit-christoforou", 0.01, 1.0),
}


def _case(target: str, law: str, radius: float, velocity: float):
    return parse_case(_BALL.format(radius=radius, velocity=velocity) + target + f'[contact]\nlaw = "{law}"\n')


def _timed(call):
    wall, cpu = time.perf_counter(), time.process_time()
    out = call()
    return out, time.perf_counter() - wall, time.process_time() - cpu


def main() -> None:
    warnings.simplefilter("ignore")  # validity warnings of the direct runs
    with tempfile.TemporaryDirectory() as warm:
        lookup(case=_case(*next(iter(CASES.values()))), cache_dir=warm)
    print("| case | first lookup (tile built) wall / CPU [s] | cached lookup [ms] | simulate [ms] "
          "| F_max lookup ± band vs simulate [N] | e lookup ± band vs simulate | status |")
    print("|---|---|---|---|---|---|---|")
    for name, spec in CASES.items():
        case = _case(*spec)
        with tempfile.TemporaryDirectory() as cache:
            found, wall, cpu = _timed(lambda: lookup(case=case, cache_dir=cache))
            _, cached, _ = _timed(lambda: lookup(case=case, cache_dir=cache))
        (_, summary), direct, _ = _timed(lambda: run_case(case))
        print(f"| {name} | {wall:.1f} / {cpu:.1f} | {cached * 1e3:.0f} | {direct * 1e3:.0f} "
              f"| {found['peak_force_N']:.0f} ± {found['peak_force_error_N']:.0f} vs {summary['peak_force_N']:.0f} "
              f"| {found['restitution']:.3f} ± {found['restitution_error']:.3f} vs {summary['restitution']:.3f} "
              f"| {found['status']} |")


if __name__ == "__main__":
    main()
