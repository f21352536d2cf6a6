"""The hot path's shortcuts give what the plain code gives: ``ImpactResult.from_fields`` the
constructor's object, the contact durations and their sum NumPy's ``diff``/``nansum`` bits."""

from __future__ import annotations

import dataclasses

import numpy as np

from impactmaps.contact.linear import LinearContact
from impactmaps.solvers.modal import ModalSettings, simulate
from impactmaps.result import ImpactResult

from ..analytic import ss_beam_impactor, ss_euler_beam_basis


def _result():
    settings = ModalSettings()
    mass, stiffness = ss_beam_impactor(1.198, 0.425)
    basis = ss_euler_beam_basis(settings.cutoff_ratio * np.sqrt(stiffness / mass), settings.min_modes)
    return simulate(basis, LinearContact(stiffness), mass, 1.0, settings=settings, record=False)


def test_from_fields_is_the_constructors_result():
    result = _result()
    fields = {field.name: getattr(result, field.name) for field in dataclasses.fields(ImpactResult)}
    built = ImpactResult.from_fields(fields)
    assert type(built) is ImpactResult and built == ImpactResult(**fields)
    assert built.__dict__.keys() == ImpactResult(**fields).__dict__.keys()
    partial = dict(fields)
    del partial["convergence_note"]  # a field left to its default goes through the constructor
    assert ImpactResult.from_fields(partial).convergence_note == ""


def test_durations_and_their_sum_are_numpys_bits():
    result = _result()
    cases = [np.array([[0.1, 0.35], [1.0, 1.7], [2.5, np.nan]]), np.array([[0.1, 0.2] for _ in range(19)]) * 1.37,
             np.zeros((0, 2)), np.array([[0.0, 0.3]])]
    for intervals in cases:
        mine = dataclasses.replace(result, contact_intervals=intervals)
        expected = np.diff(intervals, axis=1).ravel()
        assert mine.contact_durations.tobytes() == expected.tobytes()
        assert np.float64(mine.total_contact_time).tobytes() == np.float64(np.nansum(expected)).tobytes()
        assert mine.first_contact_duration == (float(expected[0]) if expected.size else 0.0) or np.isnan(expected[0])
        summary = mine.normalised_summary()
        assert summary["contact_time_normalised"] == mine.contact_time_normalised
        assert summary["first_contact_normalised"] == mine.first_contact_duration_normalised \
            or np.isnan(mine.first_contact_duration_normalised)
    as_tuples = dataclasses.replace(result, contact_intervals=((0.0, 0.25),))  # an asymptote's intervals
    assert as_tuples.contact_durations.tolist() == [0.25] and as_tuples.total_contact_time == 0.25
