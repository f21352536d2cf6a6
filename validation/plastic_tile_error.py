"""Plastic `lookup --case` from on-demand tiles against `simulate`, on random physical cases.

N random elastic-plastic cases that no shipped plastic map describes — a steel ball of
random radius (2–20 mm) and speed (0.3–5 m/s, log-uniform), a random law among
Yigit–Christoforou, the refined Stronge law and ``epp``, on a random steel or aluminium
target: 70 % Euler beams (clamped–clamped, clamped–simply supported or cantilever, length
0.2–1 m, struck anywhere in the middle 60 %), 30 % Kirchhoff plates (SSSS or CCCC, side
0.1–0.5 m, aspect 0.5–2, span/thickness 30–200, struck anywhere in the middle 60 %) —
each answered by :func:`impactmaps.lookup` (``case=``) (a 4 × 4 × 4 tile of the
plastic lattice, :mod:`impactmaps.cases.on_demand`) and by ``simulate``
(:func:`impactmaps.cases.run_case`, and once refined twice for its own error). An answer is
inside its band when |lookup − simulate| ≤ band + the direct run's own error (its change
when refined twice, at least 1e-3 of the force scale) for the peak force, ≤ band + 1e-3 +
that change for the restitution, ≤ band + 1e-3 of the impact energy for the absorbed energy.
Prints one line per case and a summary; writes ``plastic_tile_error.csv``
(``validation/`` by default).

    python validation/plastic_tile_error.py [--cases 24] [--seed 7]
    python validation/plastic_tile_error.py --smoke    # 1 case: epp on a clamped–clamped beam
"""

from __future__ import annotations

import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from impactmaps.cases import parse_case, run_case
from impactmaps import lookup
from impactmaps.solvers.modal import simulate

from _script_options import parse

HERE = Path(__file__).resolve().parent
LAWS = ("epp", "stronge", "yigit-christoforou")
#: The smoke run's case: a 20 mm steel ball at 1 m/s on a clamped–clamped aluminium beam, epp.
SMOKE_CASE = ('[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 1.0\n[target]\ntype = "beam"\n'
              'length = 0.5\nwidth = 0.02\nheight = 0.02\nmaterial = "aluminium-6061-t6"\ntheory = "euler"\n'
              'supports = "cc"\n[contact]\nlaw = "epp"\n')


def random_case(rng):
    """A random plastic case (module docstring) and its law."""
    def uniform(low, high):
        return float(rng.uniform(low, high))

    metal = str(rng.choice(["structural-steel", "aluminium-6061-t6"]))
    law = str(rng.choice(LAWS))
    if rng.uniform() < 0.7:
        length, width, height = uniform(0.2, 1.0), uniform(0.01, 0.05), uniform(0.005, 0.03)
        supports, position = str(rng.choice(["cc", "cs", "cf"])), length * uniform(0.2, 0.8)
        target = (f'type = "beam"\nlength = {length!r}\nwidth = {width!r}\nheight = {height!r}\n'
                  f'material = "{metal}"\ntheory = "euler"\nsupports = "{supports}"\nimpact_position = {position!r}')
    else:
        side, aspect, slenderness = uniform(0.1, 0.5), uniform(0.5, 2.0), uniform(30, 200)
        edges = str(rng.choice(["CCCC", "SSSS"]))
        target = (f'type = "plate"\nlength_x = {side!r}\nlength_y = {side * aspect!r}\n'
                  f'thickness = {side / slenderness!r}\nmaterial = "{metal}"\ntheory = "kirchhoff"\n'
                  f'edges = "{edges}"\nimpact_point = [{side * uniform(0.2, 0.8)!r}, '
                  f'{side * aspect * uniform(0.2, 0.8)!r}]')
    radius, velocity = 10 ** uniform(np.log10(0.002), np.log10(0.02)), 10 ** uniform(np.log10(0.3), np.log10(5.0))
    return parse_case(f'[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
                      f'[target]\n{target}\n[contact]\nlaw = "{law}"\n'), law


def measure(case, law: str, cache_dir) -> dict:
    """One case: the lookup with its bands, simulate, and whether each answer lies in its band."""
    row = {"law": law, "target": case.target.map_structure().kind}
    start = time.perf_counter()
    try:
        found = lookup(case=case, cache_dir=cache_dir)
    except ValueError as error:
        return row | {"answered": False, "reason": str(error).split(";")[0][:160]}
    row |= {"answered": True, "lookup_seconds": time.perf_counter() - start, "map": found["map"],
            "status": found["status"], "lookup_N": found["peak_force_N"], "band_N": found["peak_force_error_N"],
            "restitution": found["restitution"], "restitution_band": found["restitution_error"]}
    _, summary = run_case(case)
    fine = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=case.settings.refined().refined(),
                    record=False, time_step=case.time_step)
    direct = max(1e-3 * found["force_scale_N"], abs(fine.peak_force - summary["peak_force_N"]))
    energy = 0.5 * case.impactor_mass * case.velocity**2
    e_change = abs(fine.rebound_velocity / case.velocity - summary["restitution"])
    row |= {"simulate_N": summary["peak_force_N"], "simulate_restitution": summary["restitution"],
            "force_inside": abs(found["peak_force_N"] - summary["peak_force_N"]) <= found["peak_force_error_N"] + direct,
            "restitution_inside": (abs(found["restitution"] - summary["restitution"])
                                   <= found["restitution_error"] + 1e-3 + e_change)
            if np.isfinite(found["restitution"]) else np.nan,
            "energy_inside": abs(found["absorbed_energy_J"] - fine.contact_dissipation)
            <= found["absorbed_energy_error_J"] + 1e-3 * energy}
    return row


def main(argv=None) -> None:
    def options(parser):
        parser.add_argument("--cases", type=int, default=24)
        parser.add_argument("--seed", type=int, default=7)

    args = parse(__doc__.splitlines()[0], argv, default_out=HERE, add_arguments=options)
    rng = np.random.default_rng(args.seed)
    rows = []
    with tempfile.TemporaryDirectory(prefix="impactmaps-tiles-") as cache, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings of the extreme draws
        for index in range(1 if args.smoke else args.cases):
            row = measure(*((parse_case(SMOKE_CASE), "epp") if args.smoke else random_case(rng)), cache)
            rows.append(row)
            print(index, {key: value for key, value in row.items() if key not in ("map",)}, flush=True)
    frame = pd.DataFrame(rows)
    frame.to_csv(args.out_dir / "plastic_tile_error.csv", index=False, float_format="%.9g")
    answered = frame[frame.answered]
    if len(answered):
        error = (answered.lookup_N - answered.simulate_N).abs()
        print(f"answered {len(answered)}/{len(frame)}; peak force inside its band {int(answered.force_inside.sum())}, "
              f"restitution {int((answered.restitution_inside == True).sum())} of "  # noqa: E712 (NaN: ended in contact)
              f"{int(answered.restitution_inside.notna().sum())}, absorbed energy {int(answered.energy_inside.sum())}; "
              f"largest |error|/band {float((error / answered.band_N).max()):.2f}, median band "
              f"{100 * float((answered.band_N / answered.lookup_N).median()):.2f} %, largest "
              f"{100 * float((answered.band_N / answered.lookup_N).max()):.1f} %; lookup (tile built) "
              f"{answered.lookup_seconds.min():.1f}–{answered.lookup_seconds.max():.1f} s wall")


if __name__ == "__main__":
    main()
