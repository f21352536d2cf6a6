"""Smoke test of benchmarks/studies/bench_plane.py: its guarded pool solves points exactly as a
sweep does (same bits), and a point over the per-point cap is killed and reported."""

from __future__ import annotations

import numpy as np

from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.sweep import solve_points
from impactmaps.solvers.modal import ModalSettings

from ..helpers import repository_module

bench_plane = repository_module("benchmarks/studies/bench_plane.py")


def test_pool_points_equal_solve_points_and_the_cap_kills_a_slow_point():
    tasks = [("map", "beam-ss-euler", 1.0, 1.0), ("map", "beam-ss-euler", 0.1, 0.2)]
    outcomes = bench_plane.run_tasks(tasks, workers=2, point_cap=60.0, budget=60.0)
    assert [o["state"] for o in outcomes] == ["done", "done"]
    direct = solve_points(structure_from_name("beam-ss-euler"), [(1.0, 1.0), (0.1, 0.2)], ModalSettings())
    for outcome, row in zip(outcomes, direct):
        assert outcome["row"]["fmax_normalised"] == row["fmax_normalised"]
        assert outcome["row"]["status"] == row["status"]
    # a light impactor on the plate integrates ~3000 modes at its finest level (~0.3 s):
    # a 0.05 s cap kills it, the pool goes on
    slow = bench_plane.run_tasks([("map", "plate-ssss-kirchhoff", 1.8, 0.001), ("map", "beam-ss-euler", 1.0, 1.0)],
                                 workers=1, point_cap=0.05, budget=60.0)
    assert slow[0]["state"] == "timeout"
    assert slow[1]["state"] in ("done", "timeout")


def test_finest_mode_counts_cover_the_grid():
    counts = bench_plane.finest_mode_counts("beam-ss-euler", np.array([0.01, 1.0, 100.0]), np.array([0.1, 10.0]))
    assert counts.shape == (3, 2) and np.all(counts >= 16)


def test_cost_section_shares_the_cpu_by_class():
    from impactmaps.maps.family.accuracy import STATUSES

    rows = [("beam-ss-euler", 0.1, 0.1, {"status": 0, "n_modes": 10, "impacts": 1, "seconds": 3.0}),
            ("beam-ss-euler", 1.0, 0.1, {"status": 2, "n_modes": 500, "impacts": 30, "seconds": 1.0})]
    line = bench_plane.cost_section(rows, STATUSES)[-1]
    for part in ("converged: 75 % (50 %)", "sensitive: 25 % (50 %)", "1–16: 75 %", "401–1000: 25 %", "≥ 20: 25 %"):
        assert part in line, (part, line)


def test_profile_plane_sorts_the_runs_of_a_point_by_kind():
    from dataclasses import replace

    profile_plane = repository_module("benchmarks/studies/profile_plane.py")
    base = ModalSettings()
    assert profile_plane.run_kind(base, base) == "base"
    assert profile_plane.run_kind(base.refined(), base) == "refinement 1"
    assert profile_plane.run_kind(base.refined().refined(), base) == "refinement 2"
    assert profile_plane.run_kind(replace(base, step_scale=0.99), base) == "perturbed (sensitive)"


def test_sweep_share_times_the_compiled_code_inside_the_sweep_and_restores_it():
    """``benchmarks/studies/bench_sweep_share.py`` on 2 λ rows of the beam: the compiled code's CPU lies
    within the grid's, and the kernel and set-up are the package's own again afterwards."""
    from impactmaps.solvers import modal_run

    share = repository_module("benchmarks/studies/bench_sweep_share.py")
    kernels = (modal_run.integrate_impact, modal_run.coupled_modes)
    total, integrator, setup, points = share.share("beam-ss-euler", 25)
    assert points == 400
    assert 0.0 < integrator and 0.0 <= setup and integrator + setup <= total
    assert (modal_run.integrate_impact, modal_run.coupled_modes) == kernels
