"""The graze spin of the exact contact phase (fixed before 0.1.0).

A plate map point whose sphere re-touches the plate a moment after its first contact ended
(the gap re-closes within one free-flight step) took zero-length steps at the instant of
that separation until its step budget (11 097 899 steps, ``time_limit_reached``, one
impact): the touchdown search accepted the step's start — touching to round-off but
opening — as the touchdown, the contact phase found no force there (a graze) and left at
the same instant, and the flight found that touchdown again. The finest sampled run shows
the second contact is real.
"""

from __future__ import annotations

import numpy as np

from impactmaps.maps.compute.linear_points import LINEAR
from impactmaps.maps.compute.points import basis_table
from impactmaps.maps.family.structures import MAX_MODES
from impactmaps.solvers.mode_budget import frequency_cap
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.solvers.integrator.coupled_contact import _least_advance, contact_phase, coupled_modes
from impactmaps.solvers.integrator.exact_step import STALL_LIMIT, _progress
from impactmaps.solvers.integrator.history_rows import HistoryRows
from impactmaps.solvers.integrator.kernel_types import KernelCoupled, KernelModes
from impactmaps.solvers.modal import ModalSettings, simulate
from impactmaps.targets.base import ModalBasis

#: The map point of the spin: ``plate-ssss-kirchhoff`` on the 200 × 50 grid of
#: ``benchmarks/studies/bench_plane.py`` (ζ = 434.70, λ = 0.37276), on its 2 modes.
ZETA = float(np.geomspace(1e-3, 1e3, 200)[187])
LAMBDA = float(np.geomspace(1e-3, 1e3, 50)[21])


def _map_point_run(settings: ModalSettings):
    """The run of the map point with ``settings``, as a sweep's worker builds it, and ω [rad/s]."""
    structure = structure_from_name("plate-ssss-kirchhoff")
    impact = LINEAR.realise(structure.build(), (ZETA, LAMBDA))
    basis = basis_table(structure, settings.min_modes).truncate(
        min(settings.cutoff_ratio * impact.omega, frequency_cap(structure.build(), MAX_MODES)), settings.min_modes)
    return simulate(basis, impact.law, impact.mass, impact.velocity, settings=settings, record=False), impact.omega


def test_re_touch_just_after_a_separation_is_found_not_spun_on():
    """The spin's settings: a few thousand steps, both contacts, time moving on through them,
    and the contacts of the finest sampled run (2.7·10⁶ steps) to 10⁻⁵/ω."""
    result, omega = _map_point_run(ModalSettings(min_modes=2, force_resolution=4e-5))
    assert result.details.contact_phase == "exact"
    assert result.details.steps < 10**5 and not result.time_limit_reached
    reference, _ = _map_point_run(ModalSettings(min_modes=2, contact_phase="sampled", time_step_ratio=2e-4,
                                                resolve_ratio=2e-3, force_resolution=1e-9))
    assert not reference.time_limit_reached and reference.impacts == 2
    assert result.impacts == reference.impacts
    times = np.asarray(result.contact_intervals).ravel()
    assert np.all(np.diff(times) > 0.0) and result.end_time > times[-1]
    assert np.allclose(result.contact_intervals * omega, reference.contact_intervals * omega, rtol=0.0, atol=1e-5)
    assert abs(result.fmax_normalised - reference.fmax_normalised) < 1e-6


def test_graze_leaves_the_contact_phase_later_with_the_gap_open():
    """A touchdown handed over just past a separation (the gap open by 10⁻¹⁸ m and opening at
    0.2 m/s): no force anywhere, so a graze — left strictly later, however late the run
    (here at t = 2.3 s, where 10⁻¹⁴ of the step does not move the time), the gap open."""
    basis = ModalBasis(frequencies=np.array([1500.0, 7700.0]), participation=np.array([0.1, 0.14]),
                       damping_ratios=np.zeros(2), residual_compliance=2e-10)
    mass = 8e7
    modes = coupled_modes(basis, 5.6e8, mass)
    q = np.array([2e-6, -3e-8])
    v = np.array([1e-3, 2e-4])
    wi = float(basis.participation @ q) - 1e-18
    vi = float(basis.participation @ v) - 0.2
    coupled = KernelCoupled(modes.frequencies, modes.force_row, modes.from_coupled, modes.to_coupled, 1e-6, 1.0)
    target = KernelModes(basis.frequencies, basis.participation, basis.damping_ratios, basis.residual_compliance)
    t0 = 2.3
    t, wi_end, _vi, force, _peak, _peak_time, steps, separated, _history, _rec = contact_phase(
        coupled, target, (1e9, 10**12), (t0, wi, vi, 0.0, 0.0, 7), q, v, False, HistoryRows(np.zeros((1, 8)), 1),
        0)
    assert separated and steps == 7 and force == 0.0
    assert t > t0
    assert wi_end - basis.participation @ q < 0.0  # q holds the modes at the exit


def test_least_advance_moves_any_time():
    for t in (0.0, 1e-9, 2.3, 1e6):
        s = _least_advance(t, 1e-5)
        assert s >= 1e-19 and t + s > t


def test_stall_guard_counts_phases_that_do_not_move_the_time_on():
    """:func:`_progress`: a phase ending later than the mark resets the count and sets the mark
    10⁻⁹ h on; phases ending at or before it count up (even by round-off steps), and the run
    ends after :data:`STALL_LIMIT` of them — a bounded number, never the step budget."""
    h = 1e-4
    stalls, mark = _progress(2.3, -1.0, 0, h)
    assert stalls == 0 and mark > 2.3
    t = 2.3
    for expected in range(1, STALL_LIMIT + 2):
        t = np.nextafter(t, np.inf)  # a creep by one ulp per phase still counts
        stalls, mark = _progress(t, mark, stalls, h)
        assert stalls == expected
    assert stalls > STALL_LIMIT and STALL_LIMIT <= 1000
    stalls, mark = _progress(2.3 + h, mark, stalls, h)
    assert stalls == 0
