"""Infinite-beam asymptote for any contact law: time per run against the number of CQ steps.

Workload: :func:`impactmaps.closed_forms.law_asymptotes.infinite_beam_impact_any_law` on an Euler steel
beam (20 × 20 mm, E = 210 GPa) struck at 2 m/s by a 5 kg sphere — heavy enough that the run
never separates, so every run takes all N = duration/step steps (duration 100/ω, step 100/N).
Laws: Hertz (steel sphere r = 10 mm) and elastic–perfectly-plastic (yield 350 MPa, the
costliest kernel). Three marches, side by side in one process:

* ``old`` — the O(N²) Python march of the base commit (``--base``, loaded from git: the
  shipped code before the FFT history sum);
* ``direct`` — the compiled march of today with one leaf holding every step (the direct
  O(N²) sum, compiled);
* ``blocked`` — today's default: the Hairer–Lubich–Schlichte FFT blocks, O(N log² N).

Reported: CPU time per run (``time.process_time``, best of the repeats; the machine may be
shared), ratios, the exponent p of a least-squares fit ``time − set-up ∝ N^p`` over the N
measured, the CPU time of the set-up every march shares (the law's contact frequency), and the largest
relative difference of the peak force, indentation and beam deflection
between ``blocked`` and ``old``. The first (compiling) call is made before timing.

Run: ``PYTHONPATH=. python benchmarks/studies/bench_infinite_beam.py [--max-steps 100000] [--base COMMIT]``
(writes ``benchmarks/studies/RESULTS_infinite_beam.md`` with ``--write``).
"""

from __future__ import annotations

import argparse
import datetime
import importlib.util
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import impactmaps as im  # noqa: E402
from impactmaps.contact import HertzContact, effective_modulus  # noqa: E402
from impactmaps.contact.plastic.epp import EppContact  # noqa: E402
from impactmaps.closed_forms.law_asymptotes import beam as fast  # noqa: E402
from impactmaps.closed_forms.law_asymptotes.result import contact_frequency_of  # noqa: E402
from impactmaps.closed_forms import infinite_beam_cq  # noqa: E402

BASE_COMMIT = "c70b96b"  # main before the FFT history sum
BEAM_PATH = "impactmaps/closed_forms/law_asymptotes/beam.py"
FIELDS = ("peak_force", "max_indentation", "max_target_displacement")


def old_module(commit: str):
    """The base commit's ``closed_forms/law_asymptotes/beam.py`` as a module of the package (relative
    imports resolve against today's package: the pieces it imports are unchanged)."""
    source = subprocess.run(["git", "-C", str(ROOT), "show", f"{commit}:{BEAM_PATH}"],
                            capture_output=True, text=True, check=True).stdout
    path = pathlib.Path(tempfile.mkdtemp()) / "old_beam.py"
    path.write_text(source)
    spec = importlib.util.spec_from_file_location("impactmaps.closed_forms.law_asymptotes._old_beam", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def laws():
    e_star = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
    radius = 0.01
    return {"hertz": HertzContact(4.0 / 3.0 * np.sqrt(radius) * e_star),
            "epp": EppContact(e_star, radius, 350e6)}


def timed(run, repeats):
    best, result = np.inf, None
    for _ in range(repeats):
        start = time.process_time()
        result = run()
        best = min(best, time.process_time() - start)
    return best, result


def direct(beam, law, steps):
    saved = infinite_beam_cq.LEAF_STEPS
    infinite_beam_cq.LEAF_STEPS = steps + 1
    try:
        return fast.infinite_beam_impact_any_law(beam, law, 5.0, 2.0, time_step=100.0 / steps)
    finally:
        infinite_beam_cq.LEAF_STEPS = saved


def measure(max_steps: int, base: str):
    old = old_module(base)
    steel = im.IsotropicMaterial(210e9, 0.3, 7800.0)
    beam = im.Beam.rectangular(1.0, 0.02, 0.02, steel, theory="euler")
    counts = [n for n in (1_000, 3_000, 10_000, 30_000, 100_000) if n <= max_steps]
    rows = []
    for name, law in laws().items():
        fast.infinite_beam_impact_any_law(beam, law, 5.0, 2.0)  # compile / load the cache
        for steps in counts:
            repeats = max(1, min(20, 20_000 // steps))
            marches = {
                "old": lambda: old.infinite_beam_impact_any_law(beam, law, 5.0, 2.0, time_step=100.0 / steps),
                "direct": lambda: direct(beam, law, steps),
                "blocked": lambda: fast.infinite_beam_impact_any_law(beam, law, 5.0, 2.0,
                                                                     time_step=100.0 / steps),
            }
            times, results = {}, {}
            for key, run in marches.items():
                times[key], results[key] = timed(run, 1 if key != "blocked" and steps > 10_000 else repeats)
            times["setup"] = timed(lambda: contact_frequency_of(law, 5.0, 2.0), repeats)[0]
            assert all(r.time_limit_reached for r in results.values())  # every step taken
            difference = max(abs(getattr(results["blocked"], f) / getattr(results["old"], f) - 1.0)
                             for f in FIELDS)
            rows.append((name, steps, times, difference))
            print(name, steps, {k: f"{v * 1e3:.2f} ms" for k, v in times.items()}, f"{difference:.1e}",
                  flush=True)
    return counts, rows


def exponent(counts, seconds):
    return float(np.polyfit(np.log(counts), np.log(seconds), 1)[0])


def report(counts, rows, base, max_steps) -> str:
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    lines = [
        "# Infinite-beam asymptote: O(N²) march against the FFT history sum",
        "",
        f"Generated by `PYTHONPATH=. python benchmarks/studies/bench_infinite_beam.py --max-steps {max_steps} "
        f"--base {base} --write`; do not edit by hand.",
        "",
        f"- Date: {datetime.datetime.now(datetime.timezone.utc).isoformat(timespec='seconds')}",
        f"- Load average after the run (1, 5, 15 min): {load} (2 cores, shared)",
        f"- Python {sys.version.split()[0]}, numpy {np.__version__}",
        "",
        "CPU time per run (best of the repeats), 5 kg sphere at 2 m/s on a 20 × 20 mm steel Euler "
        "beam, every run taking all N steps. `old`: the Python O(N²) march of the base commit; "
        "`direct`: today's compiled march as one direct O(N²) sum; `blocked`: today's default "
        "(FFT blocks). Δ: largest relative difference of peak force, maximum indentation and "
        "maximum beam deflection, blocked against old.",
        "",
        "| law | N steps | old [ms] | direct [ms] | blocked [ms] | old / blocked | direct / blocked | Δ | set-up [ms] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name, steps, times, difference in rows:
        lines.append(f"| {name} | {steps} | {times['old'] * 1e3:.1f} | {times['direct'] * 1e3:.1f} | "
                     f"{times['blocked'] * 1e3:.2f} | {times['old'] / times['blocked']:.0f}× | "
                     f"{times['direct'] / times['blocked']:.1f}× | {difference:.1e} | {times['setup'] * 1e3:.2f} |")
    lines += ["", "Set-up: the law's contact frequency (``contact_frequency_of``, the same in every "
              "march, a fixed cost per call: for epp it is most of a short run). Fitted exponent p of "
              "(time − set-up) ∝ N^p over the N measured:", "",
              "| law | old | direct | blocked |", "|---|---|---|---|"]
    for name in dict.fromkeys(row[0] for row in rows):
        mine = [row for row in rows if row[0] == name]
        fits = [exponent(counts, [max(row[2][key] - row[2]["setup"], 1e-6) for row in mine])
                for key in ("old", "direct", "blocked")]
        lines.append(f"| {name} | " + " | ".join(f"{p:.2f}" for p in fits) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-steps", type=int, default=100_000)
    parser.add_argument("--base", default=BASE_COMMIT)
    parser.add_argument("--write", action="store_true", help="write benchmarks/studies/RESULTS_infinite_beam.md")
    args = parser.parse_args(argv)
    counts, rows = measure(args.max_steps, args.base)
    text = report(counts, rows, args.base, args.max_steps)
    print(text)
    if args.write:
        (ROOT / "benchmarks" / "studies" / "RESULTS_infinite_beam.md").write_text(text)


if __name__ == "__main__":
    main()
