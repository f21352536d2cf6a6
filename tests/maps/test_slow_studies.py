"""Whole-chart verification studies.

They repeat, at full size, what the other tests check on samples: the whole default
chart grid (8 λ × 60 ζ, beams and plates) is converged and bounded, and the shipped
lookup maps agree with direct simulation over many random points.

They used to carry the ``slow`` marker; measured with ``--durations=0`` on 2 cores each
takes under 2 s (1.7 s the longest, 3.7 s all eight), so they run by default.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from impactmaps.plotting.chart import DEFAULT_CHART_LAMBDAS
from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.solvers.modal_settings import ModalSettings
from tests.maps.test_lookup import assert_lookup_or_refusal

CHART_STRUCTURES = ("beam-ss-euler", "plate-ssss-kirchhoff")


@pytest.mark.parametrize("name", CHART_STRUCTURES)
def test_default_chart_grid_is_converged_and_bounded(name):
    """Every point of the default chart: 0 ≤ F̄max ≤ 1 (linear contact), and F̄max moves by
    less than 4e-3 when the cut-off is doubled (80 ω) and the step halved. Measured: beam
    max 1e-4; plate max 3.2e-3, all at λ = 0.05, ζ ≈ 7–26 (two or three impacts, 4–8
    modes: the re-impacts are sensitive to the cut-off, 0.2632 → 0.2664 → 0.2665 at
    40/80/160 ω for ζ = 13.3), elsewhere < 1e-3. The step is converged everywhere
    (halving it moves F̄max < 1e-4)."""
    zetas = np.geomspace(0.005, 100.0, 60)
    points = [(z, lam) for lam in DEFAULT_CHART_LAMBDAS for z in zetas]
    structure = structure_from_name(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # capped-mode notices (method recorded)
        default = solve_points(structure, points, ModalSettings())
        refined = solve_points(structure, points, ModalSettings().refined())
    coarse = np.array([row["fmax_normalised"] for row in default])
    fine = np.array([row["fmax_normalised"] for row in refined])
    assert np.all((coarse > 0.0) & (coarse <= 1.0))
    assert not any(row["time_limit_reached"] == 1 for row in default)
    assert np.max(np.abs(coarse - fine)) < 4e-3


@pytest.mark.parametrize("structure, theory", sorted(SHIPPED_MAPS))
def test_shipped_maps_match_direct_simulation(structure, theory):
    """60 random (ζ, λ) points per shipped map: lookup within 0.03 of direct simulation
    (docs/validation.rst gives the measured median, 95th percentile and maximum)."""
    name = SHIPPED_MAPS[(structure, theory)]
    rng = np.random.default_rng(7)
    zetas = np.exp(rng.uniform(np.log(0.005), np.log(100.0), 60))
    lambdas = np.exp(rng.uniform(np.log(0.05), np.log(20.0), 60))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # Mindlin thickness-shear notice
        rows = solve_points(structure_from_name(name), list(zip(zetas, lambdas)), ModalSettings())
    direct = np.array([row["fmax_normalised"] for row in rows])
    assert_lookup_or_refusal(load_shipped_map(structure, theory), zetas, lambdas, direct, structure, theory, 0.03)


@pytest.mark.parametrize("name", CHART_STRUCTURES)
def test_sampled_loop_is_stable_up_to_and_beyond_the_cap(name):
    """The step rule never lets ω_top·Δt exceed STABLE_TOP_STEP = 2. Forcing ω_top·Δt = 2
    and 3 (1.5× the cap) on 150 random (ζ, λ) points of the chart range, with min_modes
    pulling modes far above the contact frequency into the basis, no run breaks the
    linear-contact bound F̄max ≤ 1 (blow-ups were seen at ω_top·Δt ≈ 4 and 19)."""
    import math

    from impactmaps.contact import LinearContact
    from impactmaps.dimensionless import realise
    from impactmaps.maps.family.structures import BasisTable
    from impactmaps.solvers.time_step import STABLE_TOP_STEP, coupled_top_frequency
    from impactmaps.solvers.modal_run import basis_for
    from impactmaps.solvers.modal import simulate

    structure = structure_from_name(name)
    target = structure.build()
    rng = np.random.default_rng(11)
    zetas = np.exp(rng.uniform(np.log(0.005), np.log(100.0), 150))
    lambdas = np.exp(rng.uniform(np.log(0.05), np.log(20.0), 150))
    impactors = realise(target, zetas, lambdas)
    table = BasisTable(target, 1e8 if structure.kind == "beam" else 3e6, 4)
    settings = ModalSettings(max_time_ratio=200)
    for k in range(zetas.size):
        mass = float(impactors.impactor_mass[k])
        stiffness = float(impactors.contact_stiffness[k])
        omega = math.sqrt(stiffness / mass)
        basis = basis_for(table.truncate(40 * omega, 4), omega, settings)
        top = coupled_top_frequency(basis, stiffness, mass)
        for ratio in (STABLE_TOP_STEP, 1.5 * STABLE_TOP_STEP):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = simulate(basis, LinearContact(stiffness), mass, 1.0, record=False, settings=settings,
                                  time_step=min(ratio / top, 0.0125 / omega))
            assert result.fmax_normalised <= 1.0 + 1e-9, (zetas[k], lambdas[k], ratio)
