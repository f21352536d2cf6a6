"""The exact linear contact phase (impactmaps.solvers.integrator.coupled_contact).

References: the same modal equations integrated by scipy ``solve_ivp``
(``benchmarks/baseline_solve_ivp``), exact invariants (energy in contact, momentum), and
the sampled exact-step scheme at a step small enough to be converged.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from impactmaps.contact import LinearContact
from impactmaps.solvers.integrator.coupled_contact import (
    CONTACT_RESOLUTION,
    _coarse_plan,
    _content_step,
    contact_phase,
    coupled_modes,
)
from impactmaps.solvers.integrator.history_rows import HistoryRows
from impactmaps.solvers.integrator.kernel_types import KernelCoupled, KernelModes
from impactmaps.solvers.modal import ModalSettings, simulate
from impactmaps.targets.base import ModalBasis

from ..helpers import repository_module
from .test_integrator import _case  # (basis, law, mass) realising (ζ, λ) on the closed-form structures

solve_ivp_fmax = repository_module("benchmarks/baseline_solve_ivp.py").solve_ivp_fmax

#: (kind, ζ, λ) where solve_ivp is affordable: a re-impact-free transition point, four
#: impacts on a beam, six impacts separated by long flights on a plate.
IVP_CASES = [("plate", 11.3, 0.425), ("beam", 1.0, 0.05), ("plate", 1.198, 0.01)]
#: Towards the quasi-static corner (heavy impactor, soft contact), where solve_ivp (and
#: the sampled scheme) must follow modes ~10⁴ ω for a contact of ~π/ω.
CORNER_CASES = [("plate", 100.0, 30.0), ("beam", 100.0, 30.0), ("plate", 300.0, 3.0)]
CASES = IVP_CASES + CORNER_CASES
EXACT = ModalSettings(contact_phase="exact")
#: The quasi-static corner at the finest refinement of a map point (SS Euler beam ζ = 706.7,
#: λ = 0.001758: 16 modes up to ~10³ ω, step scale 0.25, 144 contacts): the single-rate
#: phase takes ~1.1·10⁶ steps, ~7800 per contact.
QUASI_STATIC = ("beam", 706.7, 0.001758)
FINEST = ModalSettings(min_modes=16, cutoff_ratio=160.0, step_scale=0.25)


@pytest.mark.parametrize("kind, zeta, lam", IVP_CASES)
def test_exact_phase_matches_solve_ivp(kind, zeta, lam):
    """Same modes, same residual, same end time: F̄max within 1e-8 and the same number of
    impacts as solve_ivp (rtol 1e-10; measured differences ≈ 2e-12)."""
    basis, law, mass = _case(kind, zeta, lam)
    result = simulate(basis, law, mass, 1.0, record=False, settings=EXACT)
    assert result.details.contact_phase == "exact"
    reference = solve_ivp_fmax(basis, law.stiffness, mass, result.end_time, rtol=1e-10, atol=1e-12)
    assert result.impacts == reference.impacts
    assert result.fmax_normalised == pytest.approx(reference.fmax_normalised, abs=1e-8)


@pytest.mark.parametrize("kind, zeta, lam", CORNER_CASES)
def test_exact_phase_matches_the_sampled_scheme_near_the_quasi_static_corner(kind, zeta, lam):
    """Against the sampled scheme at its stability-limited step (10⁵–10⁶ steps; halving
    it moves F̄max by < 1e-7) and, for plate (100, 30), solve_ivp (rtol 1e-10, 217 s:
    0.98374131, not run here): within 2e-5. The exact phase samples the force ~10² times
    per period and leaves unsampled the fastest coupled modes that together carry
    < 5e-6 of the force content (:data:`CONTACT_RESOLUTION`); their ripple is what is
    left, at 4–24× fewer steps here (a coupled mode ~10³ ω above the contact that carries
    5e-5 of the force must be sampled) and ~10⁵× fewer in the corner itself."""
    basis, law, mass = _case(kind, zeta, lam)
    result = simulate(basis, law, mass, 1.0, record=False)
    assert result.details.contact_phase == "exact"
    sampled = simulate(basis, law, mass, 1.0, record=False, time_step=_sampled_step(basis, law, mass))
    assert result.impacts == sampled.impacts
    assert result.fmax_normalised == pytest.approx(sampled.fmax_normalised, abs=2e-5)
    assert result.details.steps * 3 < sampled.details.steps


@pytest.mark.parametrize("kind, zeta, lam", CASES)
def test_exact_phase_does_not_depend_on_its_step(kind, zeta, lam):
    """Halving the contact step twice moves F̄max by < 1e-5: the step only samples (what
    moves is the ripple of the coupled modes too fast to be sampled, < 1e-4 of the force
    content)."""
    basis, law, mass = _case(kind, zeta, lam)
    values = [simulate(basis, law, mass, 1.0, record=False,
                       settings=ModalSettings(step_scale=s, contact_phase="exact")).fmax_normalised
              for s in (1.0, 0.5, 0.25)]
    assert max(values) - min(values) < 1e-5


def test_quasi_static_corner_takes_hundreds_of_steps():
    """Plate ζ = λ = 1000 (issue 12): tens of steps instead of ~5·10⁷ (14.8 s before), F̄max
    = sqrt(λ/(1+λ)) of the quasi-static model to 1e-6 (the 4 modes the floor keeps lie
    ~10⁴ ω above the contact and respond statically)."""
    basis, law, mass = _case("plate", 1000.0, 1000.0)
    result = simulate(basis, law, mass, 1.0, record=False)
    assert result.details.steps < 500
    assert result.fmax_normalised == pytest.approx(math.sqrt(1000.0 / 1001.0), abs=1e-6)


def _sampled_step(basis, law, mass):
    from impactmaps.solvers.time_step import STABLE_TOP_STEP, coupled_top_frequency
    return STABLE_TOP_STEP / coupled_top_frequency(basis, law.stiffness, mass)


def test_exact_phase_history_is_exact():
    """Every recorded contact row conserves energy to round-off (no damping): impactor
    kinetic energy + structure energy (residual included) + contact spring energy = ½ m V0²,
    and rows in contact are uniformly spaced (one contact step)."""
    basis, law, mass = _case("plate", 1.198, 0.01)
    result = simulate(basis, law, mass, 1.0, record=True, settings=EXACT)
    assert result.details.contact_phase == "exact"
    history = result.history
    force = history["force_N"].to_numpy()
    spring = 0.5 * force**2 / law.stiffness
    total = history["impactor_kinetic_energy_J"] + history["structure_energy_J"] + spring
    assert np.max(np.abs(total - 0.5 * mass)) < 1e-9 * 0.5 * mass
    time_s = history["time_s"].to_numpy()
    touching = (force[1:] > 0.0) & (force[:-1] > 0.0)
    spacing = np.diff(time_s)[touching]
    steps = np.unique(np.round(spacing / spacing.max(), 9))
    assert spacing.size > 100 and steps.size <= result.impacts


def test_half_space_is_exactly_sin_tau():
    """No modes: the contact is m ẍ = −K x, F̄ = sin τ on [0, π], to round-off."""
    result = simulate(ModalBasis(np.zeros(0), np.zeros(0), 0.0), LinearContact(2.0e7), 0.05, 3.0,
                      record=True, settings=EXACT)
    history = result.normalised_history()
    tau = history["tau"].to_numpy()
    assert np.max(np.abs(history["force_normalised"] - np.where(tau <= np.pi, np.sin(tau), 0.0))) < 1e-12
    assert result.fmax_normalised == pytest.approx(1.0, abs=1e-14)
    assert result.contact_time_normalised == pytest.approx(np.pi, abs=1e-12)
    assert result.restitution == pytest.approx(1.0, abs=1e-12)


def test_coupled_modes_diagonalise_the_contact_system():
    """η = T x, x = B η, T B = I; F = c·η equals K_e (w_i − Σ φ q) for any state."""
    basis, law, mass = _case("beam", 1.0, 0.05)
    modes = coupled_modes(basis, law.stiffness, mass)
    identity = modes.to_coupled @ modes.from_coupled
    assert np.allclose(identity, np.eye(basis.size + 1), atol=1e-10)
    x = np.random.default_rng(1).normal(size=basis.size + 1)
    effective = law.stiffness / (1 + law.stiffness * basis.residual_compliance)
    direct = effective * (x[0] - basis.participation @ x[1:])
    assert modes.force_row @ (modes.to_coupled @ x) == pytest.approx(direct, rel=1e-9)


def test_damped_or_rigid_modes_keep_the_sampled_phase():
    basis, law, mass = _case("beam", 1.0, 0.05)
    damped = ModalBasis(basis.frequencies, basis.participation, basis.residual_compliance,
                        np.full(basis.size, 0.01))
    assert coupled_modes(damped, law.stiffness, mass) is None
    rigid = ModalBasis(np.concatenate(([0.0], basis.frequencies)), np.concatenate(([1.0], basis.participation)),
                       basis.residual_compliance)
    assert coupled_modes(rigid, law.stiffness, mass) is None


@pytest.mark.parametrize("case, settings", [(("beam", 1.0, 0.05), EXACT), (QUASI_STATIC, FINEST)])
def test_record_adds_rows_but_leaves_the_scalars_bit_identical(case, settings):
    """A recorded exact phase writes exact rows inside its steps (≤ time_step_ratio/ω
    apart, as fine as the sampled scheme's history) without changing its steps (beam
    ζ = 1: coarse steps of 3 fine steps; the quasi-static corner: two rates in ~150
    contacts), and every row conserves energy to round-off (no damping)."""
    basis, law, mass = _case(*case, settings=settings)
    plain = simulate(basis, law, mass, 1.0, record=False, settings=settings)
    recorded = simulate(basis, law, mass, 1.0, record=True, settings=settings)
    assert recorded.peak_force == plain.peak_force
    assert np.array_equal(recorded.contact_intervals, plain.contact_intervals)
    assert recorded.rebound_velocity == plain.rebound_velocity
    history = recorded.history
    force = history["force_N"].to_numpy()
    touching = (force[1:] > 0.0) & (force[:-1] > 0.0)
    spacing = np.diff(history["time_s"].to_numpy())[touching]
    assert spacing.max() <= settings.time_step_ratio / recorded.contact_frequency * (1 + 1e-9)
    spring = 0.5 * force**2 / law.stiffness
    total = history["impactor_kinetic_energy_J"] + history["structure_energy_J"] + spring
    assert np.max(np.abs(total - 0.5 * mass)) < 1e-9 * 0.5 * mass


def test_coupled_modes_refuse_bad_input():
    basis, law, mass = _case("beam", 1.0, 0.05)
    with pytest.raises(ValueError, match="contact_stiffness"):
        coupled_modes(basis, -1.0, mass)
    with pytest.raises(ValueError, match="impactor_mass"):
        coupled_modes(basis, law.stiffness, 0.0)


# -- the two-rate contact phase --------------------------------------------------------------


def _touchdowns(basis, count, seed):
    """(wi, vi, q, v) at ``count`` touchdowns: random modal states (the structure ringing
    in every mode, as between the contacts of a chattering impact), closing at 0.3 m/s."""
    rng = np.random.default_rng(seed)
    ratio = basis.frequencies[0] / basis.frequencies
    for _ in range(count):
        q = rng.normal(size=basis.size) * 1e-6 * ratio**1.5 / basis.frequencies[0]
        v = rng.normal(size=basis.size) * 1e-2 * ratio**0.5
        yield float(basis.participation @ q), float(basis.participation @ v) + 0.3, q, v


def _contact(modes, basis, step_scale, touchdown, two_rate, record=False):
    """One contact phase from ``touchdown``: (t_end, wi, vi, force, peak, peak_time, steps,
    separated, history, rec)."""
    wi, vi, q, v = touchdown
    coupled = KernelCoupled(modes.frequencies, modes.force_row, modes.from_coupled, modes.to_coupled, 1e-6,
                            step_scale)
    target = KernelModes(basis.frequencies, basis.participation, basis.damping_ratios, basis.residual_compliance)
    return contact_phase(coupled, target, (1e9, 10**12), (0.0, wi, vi, 0.0, 0.0, 0), q.copy(), v.copy(), record,
                         HistoryRows(np.zeros((1, 8)), 10**9), 0, two_rate)


def test_coarse_step_bounds_the_force():
    """The bound every coarse step rests on: over a coarse step, F (all coupled modes,
    sampled at 4001 instants) lies within ``margin`` of the range of the two samples of
    F_low (the modes the coarse step resolves)."""
    basis, law, mass = _case(*QUASI_STATIC, settings=FINEST)
    modes = coupled_modes(basis, law.stiffness, mass)
    for wi, vi, q, v in _touchdowns(basis, 20, seed=7):
        x = np.concatenate(([wi], q))
        xdot = np.concatenate(([vi], v))
        eta = modes.to_coupled @ x
        rate = modes.to_coupled @ xdot
        h = 0.25 * _content_step(modes.frequencies, modes.force_row, eta, rate, CONTACT_RESOLUTION)
        every, length, _cos, _sin, low, margin = _coarse_plan(modes.frequencies, modes.force_row, eta, rate, h)
        assert every >= 4 and 0 < low < basis.size + 1
        s = np.linspace(0.0, length, 4001)[:, None]
        terms = modes.force_row * (eta * np.cos(modes.frequencies * s)
                                   + rate / modes.frequencies * np.sin(modes.frequencies * s))
        force = terms.sum(axis=1)
        slow = terms[[0, -1], :low].sum(axis=1)
        assert force.min() >= slow.min() - margin
        assert force.max() <= slow.max() + margin


def test_two_rate_contacts_match_the_fine_step():
    """Against the same contacts at the fine step throughout (``two_rate=False``, the
    single-rate phase): the coarse samples lie on the fine grid and a coarse step is
    taken only where the fine samples could neither end the contact nor raise the peak,
    so peak, peak time, separation time and end state are the fine step's up to
    round-off (measured ≤ 2e-14 relative; 1e-11 allows for the phases of the fast modes
    reached along another path), with ≥ 4× fewer steps (measured 4.7×)."""
    basis, law, mass = _case(*QUASI_STATIC, settings=FINEST)
    modes = coupled_modes(basis, law.stiffness, mass)
    fine_steps = 0
    two_rate_steps = 0
    for touchdown in _touchdowns(basis, 10, seed=3):
        fine = _contact(modes, basis, 0.25, touchdown, False)
        both = _contact(modes, basis, 0.25, touchdown, True)
        assert fine[7] and both[7]  # separated
        duration = fine[0]
        assert both[0] == pytest.approx(fine[0], rel=1e-11)
        assert both[4] == pytest.approx(fine[4], rel=1e-11)
        assert both[5] == pytest.approx(fine[5], abs=1e-11 * duration)
        assert both[1] == pytest.approx(fine[1], rel=1e-9)  # w_i at separation
        assert both[2] == pytest.approx(fine[2], rel=1e-9)  # v_i at separation
        fine_steps += fine[6]
        two_rate_steps += both[6]
    assert 4 * two_rate_steps < fine_steps


def test_two_rate_phase_is_the_single_rate_loop_where_the_coarse_step_is_short():
    """Where the coarse step would hold fewer than COARSE_FACTOR fine steps the phase
    keeps the fine step: the results are bit-identical to the single-rate phase."""
    basis, law, mass = _case("plate", 11.3, 0.425)
    modes = coupled_modes(basis, law.stiffness, mass)
    touchdown = (0.0, 1.0, np.zeros(basis.size), np.zeros(basis.size))
    eta = modes.to_coupled[:, 0] * 0.0
    rate = modes.to_coupled[:, 0] * 1.0
    h = _content_step(modes.frequencies, modes.force_row, eta, rate, CONTACT_RESOLUTION)
    assert _coarse_plan(modes.frequencies, modes.force_row, eta, rate, h)[0] == 0
    fine = _contact(modes, basis, 1.0, touchdown, False)
    both = _contact(modes, basis, 1.0, touchdown, True)
    assert fine[:8] == both[:8]


def test_quasi_static_point_takes_a_tenth_of_the_single_rate_steps():
    """The quasi-static map point runs two rates in its contacts: ~10⁵ steps where the
    single-rate phase takes 1.13·10⁶ (measured 100159; F̄max the same to 2e-11)."""
    basis, law, mass = _case(*QUASI_STATIC, settings=FINEST)
    result = simulate(basis, law, mass, 1.0, record=False, settings=FINEST)
    assert result.details.contact_phase == "exact" and result.impacts > 100
    assert result.details.steps < 2.5e5


def _numpy_coupled_modes(basis, stiffness, mass):
    """The coupled modes as NumPy computed them before the set-up was compiled (2026-11-27)."""
    effective = stiffness / (1.0 + stiffness * basis.residual_compliance)
    gvec = np.concatenate(([1.0], -basis.participation))
    s0 = 1.0 / np.sqrt(mass)
    scaled = gvec.copy()
    scaled[0] = s0 * 1.0
    matrix = np.multiply.outer(scaled, scaled)
    matrix *= effective
    matrix.flat[basis.size + 2:: basis.size + 2] += basis.frequencies**2
    eigenvalues, vectors = np.linalg.eigh(matrix)
    from_coupled = np.array(vectors, order="C")
    from_coupled[0] *= s0
    to_coupled = np.array(vectors.T, order="C")
    to_coupled[:, 0] /= s0
    return np.sqrt(eigenvalues), effective * (gvec @ from_coupled), from_coupled, to_coupled


def test_compiled_set_up_gives_the_numpy_bits():
    """The compiled set-up (``_coupled_arrays``) returns NumPy's arrays bit for bit, at 300
    random bases of 1–130 modes (so the maps and every answer keep their bits)."""
    rng = np.random.default_rng(2026_11_27)
    for _ in range(300):
        n = int(rng.integers(1, 131))
        residual = float(10 ** rng.uniform(-9, -5)) * int(rng.integers(0, 2))
        basis = ModalBasis(np.sort(10 ** rng.uniform(0, 4, n)), rng.normal(size=n), residual)
        stiffness, mass = float(10 ** rng.uniform(3, 9)), float(10 ** rng.uniform(-3, 1))
        compiled = coupled_modes(basis, stiffness, mass)
        expected = _numpy_coupled_modes(basis, stiffness, mass)
        for got, want in zip((compiled.frequencies, compiled.force_row, compiled.from_coupled,
                              compiled.to_coupled), expected):
            assert np.array_equal(got, want)


def test_compiled_set_up_takes_read_only_bases():
    """A basis whose arrays are read-only views (a cached Ritz solution's) is copied, not refused."""
    frequencies = np.array([1e3, 4e3, 9e3])
    participation = np.array([1.0, -0.5, 0.25])
    frequencies.flags.writeable = False
    participation.flags.writeable = False
    basis = ModalBasis(frequencies, participation, 0.0)
    assert coupled_modes(basis, 1e6, 0.1).frequencies.shape == (4,)
