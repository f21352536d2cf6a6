"""The run set-up cache of :mod:`impactmaps.solvers.modal_run` cannot change an answer: a
repeated run (set-up from the cache) gives the bits of a run with an empty cache, and
inputs that differ in one bit are different keys."""

from __future__ import annotations

import numpy as np

from impactmaps.contact.linear import LinearContact
from impactmaps.solvers import modal_run
from impactmaps.solvers.modal import ModalSettings, simulate

from ..analytic import ss_beam_impactor, ss_euler_beam_basis


def _case(zeta):
    settings = ModalSettings()
    mass, stiffness = ss_beam_impactor(zeta, 0.425)
    basis = ss_euler_beam_basis(settings.cutoff_ratio * np.sqrt(stiffness / mass), settings.min_modes)
    return basis, LinearContact(stiffness), mass, settings


def _bits(result):
    return (result.peak_force, result.peak_time, result.max_indentation, result.rebound_velocity,
            result.energy_transferred, result.end_time, result.time_step, result.n_modes,
            result.details.steps, result.details.contact_phase, result.contact_intervals.tobytes())


def test_cached_set_up_gives_the_bits_of_a_cold_one():
    for zeta in (0.038, 11.3):
        basis, law, mass, settings = _case(zeta)
        modal_run._setup_cache.clear()
        cold = simulate(basis, law, mass, 1.0, settings=settings, record=True)
        assert modal_run._setup_cache  # the set-up was kept …
        warm = simulate(basis, law, mass, 1.0, settings=settings, record=True)  # … and used
        assert _bits(warm) == _bits(cold)
        assert warm.history.equals(cold.history)


def test_one_bit_of_input_is_another_key():
    basis, law, mass, settings = _case(1.198)
    modal_run._setup_cache.clear()
    simulate(basis, law, mass, 1.0, settings=settings, record=False)
    nudged = float(np.nextafter(mass, np.inf))
    simulate(basis, law, nudged, 1.0, settings=settings, record=False)
    assert len(modal_run._setup_cache) == 2
    modal_run._setup_cache.clear()
    alone = simulate(basis, law, nudged, 1.0, settings=settings, record=False)
    assert len(modal_run._setup_cache) == 1
    simulate(basis, law, mass, 1.0, settings=settings, record=False)
    again = simulate(basis, law, nudged, 1.0, settings=settings, record=False)
    assert _bits(again) == _bits(alone)


def test_the_cache_is_bounded():
    basis, law, mass, settings = _case(1.198)
    modal_run._setup_cache.clear()
    for k in range(modal_run.SETUP_CACHE_SIZE + 3):
        simulate(basis, law, mass * (1.0 + 1e-3 * k), 1.0, settings=settings, record=False)
    assert 0 < len(modal_run._setup_cache) <= modal_run.SETUP_CACHE_SIZE


def test_large_bases_are_not_kept(monkeypatch):
    basis, law, mass, settings = _case(0.038)
    modal_run._setup_cache.clear()
    monkeypatch.setattr(modal_run, "SETUP_CACHE_MODES", 1)
    simulate(basis, law, mass, 1.0, settings=settings, record=False)
    assert not modal_run._setup_cache
