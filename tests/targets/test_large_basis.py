"""The eigen-solution of a large Ritz basis (block Krylov, :mod:`impactmaps._krylov`),
the rectangular basis of a rectangular plate (:func:`plate_any_edges.functions`) and the simply
supported twin solved in its own symmetry classes: each against what it replaced."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg

from impactmaps.cases import load_case
from impactmaps import _krylov
from impactmaps.targets.plates import plate_any_edges, plate_general
from impactmaps.materials import material
from impactmaps.targets.plates.plate import Plate
from tests.helpers import ROOT

EXAMPLE = ROOT / "examples" / "drop_weight_quasi_isotropic.toml"


def _example_plate():
    return load_case(EXAMPLE).target


def test_krylov_finds_every_eigenvalue_below_the_bound_with_its_multiplicity():
    """A matrix with known eigenvalues, triples among them: every one ≤ upper, each as often as it
    occurs, to 1e-9, orthonormal vectors with small residuals; none above."""
    rng = np.random.default_rng(7)
    size = 900
    eigenvalues = np.sort(np.concatenate([np.repeat([1.0, 2.5, 4.0], 3), rng.uniform(1.0, 1e6, size - 9)]))
    q = np.linalg.qr(rng.standard_normal((size, size)))[0]
    matrix = (q * eigenvalues) @ q.T
    factor = scipy.linalg.cho_factor(matrix)
    upper = 2000.0
    found = _krylov.lowest_by_krylov(lambda x: scipy.linalg.cho_solve(factor, x), size, upper)
    assert found is not None
    values, vectors = found
    wanted = eigenvalues[eigenvalues <= upper]
    assert values.size == wanted.size
    np.testing.assert_allclose(values, wanted, rtol=1e-9)  # the matrix itself is exact to eps ‖A‖ ~ 1e-10
    np.testing.assert_allclose(vectors.T @ vectors, np.eye(values.size), atol=1e-10)
    residual = np.linalg.norm(matrix @ vectors - vectors * values, axis=0) / values
    assert residual.max() < 1e-6


def test_krylov_gives_the_same_bits_every_time():
    rng = np.random.default_rng(3)
    q = np.linalg.qr(rng.standard_normal((1200, 1200)))[0]
    matrix = (q * np.arange(1.0, 1201.0) ** 2) @ q.T  # a plate's: ω² grows as the mode number squared
    factor = scipy.linalg.cho_factor(matrix)
    first = _krylov.lowest_by_krylov(lambda x: scipy.linalg.cho_solve(factor, x), 1200, 900.0)
    again = _krylov.lowest_by_krylov(lambda x: scipy.linalg.cho_solve(factor, x), 1200, 900.0)
    assert first is not None and first[0].size > 20
    assert np.array_equal(first[0], again[0]) and np.array_equal(first[1], again[1])


def test_a_large_basis_by_krylov_equals_the_dense_solution():
    """The drop-weight laminate (clamped, D16/D26) at n = 40: 1680 unknowns, solved by block
    Krylov; the dense solution of the same matrix has the same modes below the resolved
    frequency, ω to 1e-9, the same mode shapes."""
    plate = _example_plate()
    classes = plate_any_edges.class_groups(plate)[0]
    n_x, n_y = plate_any_edges.functions(plate, 40)
    inputs = plate_any_edges._inputs(plate)
    top = plate_any_edges.resolved_frequency(plate, n_x, n_y)
    matrix, scale = plate_general._standard_problem(*inputs, n_x, n_y, classes)
    assert matrix.shape[0] >= _krylov.KRYLOV_MIN_UNKNOWNS  # the Krylov path
    krylov = plate_general._eigen_solution(*inputs, n_x, n_y, top, classes)
    dense, shapes = scipy.linalg.eigh(matrix, subset_by_value=(-np.inf, top**2), driver="evr")
    assert krylov["frequencies"].size == dense.size > 40
    np.testing.assert_allclose(krylov["frequencies"], np.sqrt(dense), rtol=1e-9)
    cosines = np.abs(np.sum((krylov["coefficients"] / scale[:, None]) * shapes, axis=0))
    assert cosines.min() > 1.0 - 1e-9


def test_a_rectangular_plate_has_fewer_functions_across_its_short_side():
    """125 × 75 mm: n functions along x, fewer along y, the same resolved frequency as n × n, and
    its modes below it those of the n × n basis within 1e-6 (measured 2.8e-7 at n = 20, 2.4e-8 at 30)."""
    plate = _example_plate()
    classes = plate_any_edges.class_groups(plate)[0]
    for n in (20, 30):
        n_x, n_y = plate_any_edges.functions(plate, n)
        assert n_x == n and n_y < n
        top = plate_any_edges.resolved_frequency(plate, n, n)
        assert plate_any_edges.resolved_frequency(plate, n_x, n_y) == top
        inputs = plate_any_edges._inputs(plate)
        square = plate_general.solve_general_plate.__wrapped__(*inputs, n, n, top, classes).frequencies
        rectangle = plate_general.solve_general_plate.__wrapped__(*inputs, n_x, n_y, top, classes).frequencies
        assert rectangle.size == square.size
        assert np.all(rectangle >= square * (1.0 - 1e-12))  # a subspace: never lower
        np.testing.assert_allclose(rectangle, square, rtol=1e-6)
    square = Plate.isotropic(0.2, 0.2, 0.004, material("aluminium-6061-t6"), theory="mindlin", edges="CCCC")
    assert plate_any_edges.functions(square, 30) == (30, 30)


@pytest.mark.parametrize("edges", ["CCCC", "CFCF"])
def test_the_twin_in_its_own_classes_has_the_compliance_of_all_of_them(edges):
    """The simply supported twin (no couplings) of a centrally struck plate, solved in the class
    a centred load excites, has the static compliance of the twin solved in the plate's classes
    (the load is orthogonal to the others) to 1e-12."""
    plate = replace(_example_plate(), edges=edges)
    classes = plate_any_edges.class_groups(plate)[0]
    twin = plate_any_edges._twin_classes(plate)
    assert twin == ((0, 0),)
    n_x, n_y = plate_any_edges.functions(plate, 14)
    ssss = plate_any_edges._inputs(plate, "SSSS", coupled=False)

    def compliance(kept):
        stand_in = plate_general.GeneralPlateSolution(plate.length_x, plate.length_y, plate.theory, "SSSS", n_x, n_y,
                                                      np.zeros(0), np.zeros((0, 0)), 0.0, kept)
        load = plate_any_edges._patch_load(stand_in, plate.impact_point, 0.002)
        return plate_general.general_static_compliance(*ssss[:6], n_x, n_y, load, kept)

    assert compliance(twin) == pytest.approx(compliance(classes), rel=1e-12)


def test_a_cantilever_basis_by_krylov_is_accurate_where_the_dense_solution_is_not():
    """CFFF 200 × 100 × 3 mm Mindlin: the largest basis's highest eigenvalue is 1.3e10 times its
    lowest, so the dense solution's lowest ω² is off by ~1e-6 (its error is eps·‖A‖). The Krylov
    pairs, whose residual stops falling at ~1.2e-10 there (accepted below KRYLOV_FLOOR), satisfy
    A⁻¹y = y/λ to 1e-10 relative, the lowest mode included; the same count as the dense one."""
    plate = Plate.isotropic(0.2, 0.1, 0.003, material("aluminium-6061-t6"), theory="mindlin", edges="CFFF")
    classes = plate_any_edges.class_groups(plate)[0]
    n_x, n_y = plate_any_edges.functions(plate, plate_any_edges.max_functions(plate.theory, classes))
    inputs = plate_any_edges._inputs(plate)
    top = plate_any_edges.resolved_frequency(plate, n_x, n_y)
    matrix, scale = plate_general._standard_problem(*inputs, n_x, n_y, classes)
    krylov = plate_general._eigen_solution(*inputs, n_x, n_y, top, classes)
    dense = scipy.linalg.eigh(matrix, subset_by_value=(-np.inf, top**2), driver="evr", eigvals_only=True)
    assert krylov["frequencies"].size == dense.size > 50
    factor = scipy.linalg.cho_factor(matrix)
    eigenvalues, vectors = krylov["frequencies"] ** 2, krylov["coefficients"] / scale[:, None]
    residual = np.linalg.norm(scipy.linalg.cho_solve(factor, vectors) - vectors / eigenvalues, axis=0) * eigenvalues
    assert residual.max() < 1e-9  # (the dense lowest eigenvalue: 1.4e-6 from its own vector's, measured)
