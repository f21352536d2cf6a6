"""The hot path of a map point is fast without moving a bit: truncations of a basis
table give the residual compliance of a fresh summation, the internal run of a map point
gives what :func:`impactmaps.solvers.modal.simulate` gives, and validation still refuses
bad input."""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.maps.family.structures import structure_from_name
from impactmaps.targets.base import ModalBasis


def _old_residual(basis: ModalBasis, count: int) -> float:
    """The residual of a truncation to ``count`` modes as ModalBasis.truncate summed it
    before the table kept its sums (a cumsum over the dropped modes, highest first)."""
    frequencies = basis.frequencies[count:]
    dropped = np.zeros_like(frequencies)
    elastic = frequencies > 0
    dropped[elastic] = basis.participation[count:][elastic] ** 2 / frequencies[elastic] ** 2
    return float(np.cumsum(dropped[::-1])[-1]) + basis.residual_compliance


@pytest.fixture(scope="module")
def beam_table():
    from impactmaps.maps.compute.sweep import basis_table

    return basis_table(structure_from_name("beam-ss-euler"), 4)


def test_table_truncation_residual_is_bit_identical_to_a_fresh_sum(beam_table):
    basis = beam_table.basis
    assert basis.size > 1000
    rng = np.random.default_rng(3)
    counts = sorted({4, 5, basis.size - 2, basis.size - 1, *rng.integers(4, basis.size, 300).tolist()})
    for count in counts:
        # a cut-off between mode count-1 and mode count keeps exactly count modes
        cutoff = 0.5 * (basis.frequencies[count - 1] + basis.frequencies[count])
        fast = beam_table.truncate(cutoff, 4)
        plain = basis.truncate(cutoff, 4)
        assert fast.size == plain.size == count
        assert fast.residual_compliance == plain.residual_compliance == _old_residual(basis, count)
        assert np.array_equal(fast.frequencies, basis.frequencies[:count])
        assert np.array_equal(fast.participation, basis.participation[:count])
        assert np.array_equal(fast.damping_ratios, basis.damping_ratios[:count])
    assert beam_table.truncate(2 * basis.frequencies[-1], 4) is basis
    assert beam_table.truncate(0.0, 7).size == 7


def test_truncation_of_a_plain_basis_with_rigid_modes_is_unchanged():
    rng = np.random.default_rng(5)
    frequencies = np.concatenate(([0.0, 0.0], np.sort(rng.uniform(1.0, 1e4, 500))))
    basis = ModalBasis(frequencies, rng.normal(size=frequencies.size), 3e-7)
    for count in range(2, basis.size):
        cutoff = 0.5 * (frequencies[count - 1] + frequencies[count]) if frequencies[count] > 0 else 0.0
        truncated = basis.truncate(cutoff, count)
        assert truncated.size == count
        assert truncated.residual_compliance == _old_residual(basis, count)


@pytest.mark.parametrize("value", [0.0, -1.0, -1, 0, float("nan"), float("inf"), -float("inf"), np.float64(-2.0),
                                   np.float64("nan"), 2**60, -(2**60), 3.5, 7, np.float64(4.0), True])
def test_scalar_checks_answer_as_the_array_checks(value):
    """The checks' scalar fast paths accept and refuse exactly what their NumPy paths do,
    with the same message."""
    from impactmaps import _checks

    def outcome(check, *args, **kwargs):
        try:
            check("x", value, *args, **kwargs)
        except ValueError as error:
            return str(error)
        return None

    def as_array(check, *args, **kwargs):
        try:
            check("x", np.array([value], dtype=float), *args, **kwargs)
        except ValueError:
            return "refused"
        return None

    for check, args, kwargs in [(_checks.require_positive, (), {}), (_checks.require_nonnegative, (), {}),
                                (_checks.require_in_range, (0, 5), {}),
                                (_checks.require_in_range, (0, 5), {"low_inclusive": False, "high_inclusive": False}),
                                (_checks.require_in_range, (-np.inf, np.inf), {})]:
        fast = outcome(check, *args, **kwargs)
        assert (fast is None) == (as_array(check, *args, **kwargs) is None), (check, value)
        if fast is not None:
            assert fast.startswith(f"x = {value!r}") or fast.startswith(f"x = {float(value)!r}"), fast


def test_a_bad_setting_still_raises_the_same_error():
    from impactmaps.solvers.modal import ModalSettings

    with pytest.raises(ValueError, match=r"min_modes = -1 is invalid: valid range is \[0, 100000\]"):
        ModalSettings(min_modes=-1)
    with pytest.raises(ValueError, match=r"time_step_ratio = 1.5 is invalid: valid range is \(0, 1\]"):
        ModalSettings(time_step_ratio=1.5)
    with pytest.raises(ValueError, match=r"cutoff_ratio = nan is invalid: must be finite"):
        ModalSettings(cutoff_ratio=float("nan"))


@pytest.mark.parametrize("values", [[1.0, 2.0], [1.0, 0.0], [1.0, -3.0], [np.nan, 1.0], [1.0, np.inf], [5e-324],
                                    [[1.0, 2.0], [3.0, np.nan]], []])
def test_positive_check_of_arrays_answers_as_before(values):
    """The float-array fast path of require_positive refuses what the element checks refuse."""
    from impactmaps._checks import require_positive

    array = np.array(values, dtype=float)
    bad = array.size > 0 and not (np.all(np.isfinite(array)) and np.all(array > 0))
    if bad:
        with pytest.raises(ValueError, match="^x = array of shape"):
            require_positive("x", array)
    else:
        require_positive("x", array)


def test_coupled_stiffness_diagonal_is_added_as_before():
    """coupled_modes adds ω_j² on the diagonal through ``flat``: the same matrix, bit for bit,
    as through ``np.diag_indices`` (so the same eigenvectors)."""
    from impactmaps.solvers.integrator.coupled_contact import coupled_modes

    rng = np.random.default_rng(11)
    for n in (1, 4, 17, 120):
        basis = ModalBasis(np.sort(rng.uniform(1.0, 1e5, n)), rng.normal(size=n), float(rng.uniform(0, 1e-3)))
        stiffness, mass = float(rng.uniform(0.1, 1e4)), float(rng.uniform(1e-3, 10.0))
        effective = stiffness / (1.0 + stiffness * basis.residual_compliance)
        gvec = np.concatenate(([1.0], -basis.participation))
        scale = np.concatenate(([1.0 / np.sqrt(mass)], np.ones(n)))
        matrix = effective * np.outer(scale * gvec, scale * gvec)
        matrix[np.diag_indices(n + 1)] += np.concatenate(([0.0], basis.frequencies**2))
        eigenvalues, vectors = np.linalg.eigh(matrix)
        coupled = coupled_modes(basis, stiffness, mass)
        assert np.array_equal(coupled.frequencies, np.sqrt(eigenvalues))
        assert np.array_equal(coupled.from_coupled, scale[:, None] * vectors)
