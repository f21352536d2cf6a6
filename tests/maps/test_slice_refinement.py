"""Refinement of a map with an extra axis (β of a plastic map), one (λ, ζ) refinement per slice.

A small map of the ``epp`` family over (β, λ, ζ) holds a known function (kinks and a ripple in
(λ, ζ), curved in log β); the point solver is that function, so every "fresh point solve" is
exact. Refined slice by slice (:func:`impactmaps.maps.family.slice_refinement.refine_slices`) and read
through the package's one map reader (:func:`impactmaps.maps.read.reader.read_values`).
"""

import warnings

import numpy as np
import pytest
import xarray as xr

from impactmaps.maps.read.reader import prepare_map, read_values
from impactmaps.maps.read.interpolator import slice_estimates
from impactmaps.maps.family.refinement import Refinement
from impactmaps.maps.family.map_family import map_family
from impactmaps.maps.family.slice_refinement import SlicedRefinement, read_slices, refine_slices

EPP = map_family("epp")
BETAS = np.array([1.0, 10.0, 100.0])
LAMBDAS = np.geomspace(0.01, 1.0, 7)
ZETAS = np.geomspace(0.1, 10.0, 11)
LABELS = ("beta", "loss_factor", "relative_stiffness")


def position(values, grid):
    """Fractional grid position of values on a log-spaced grid."""
    return np.log(values / grid[0]) / np.log(grid[1] / grid[0])


def truth(beta, zeta, lambda_):
    """F̄max-like: kinks (a max of two branches) and a ripple in (λ, ζ) grid units, curved in log β."""
    row, col = position(lambda_, LAMBDAS), position(zeta, ZETAS)
    plane = np.maximum(np.sin(0.5 * row) + 0.08 * col, 1.0 - 0.05 * col + 0.3 * np.abs(np.sin(row * col / 5.0)))
    return 0.3 * plane + 0.002 * np.log10(beta) ** 2


def solve(zetas, lambdas, extra):
    """The exact function as the point solver at the slice's β."""
    return [{"fmax_normalised": float(truth(extra[0], z, lam)), "fmax_error": 1e-5, "status": 0}
            for z, lam in zip(zetas, lambdas)]


def small_map() -> xr.Dataset:
    beta, lam, zeta = np.meshgrid(BETAS, LAMBDAS, ZETAS, indexing="ij")
    fmax = truth(beta, zeta, lam)
    dims = ("structure", "beta", "lambda_", "zeta")
    variables = {"fmax_normalised": fmax, "fmax_error": np.full(fmax.shape, 1e-5), "status": np.zeros(fmax.shape, "i1"),
                 "restitution": 0.5 + 0.1 * np.log10(beta), "restitution_error": np.full(fmax.shape, 1e-4),
                 "absorbed_energy_fraction": 0.4 - 0.05 * np.log(lam), "absorbed_energy_error": np.full(fmax.shape, 1e-4)}
    return xr.Dataset({name: (dims, value[None]) for name, value in variables.items()},
                      coords={"structure": ["toy"], "beta": BETAS, "lambda_": LAMBDAS, "zeta": ZETAS},
                      attrs={"fingerprint": "small", "contact_law": "epp"})


def coordinates(row, col):
    """(ζ, λ) at fractional grid positions (log-linear)."""
    return (ZETAS[0] * (ZETAS[1] / ZETAS[0]) ** np.asarray(col, float),
            LAMBDAS[0] * (LAMBDAS[1] / LAMBDAS[0]) ** np.asarray(row, float))


def refined(dataset, **options) -> SlicedRefinement:
    table = {name: dataset[name].isel(structure=0).values for name in ("fmax_normalised", "fmax_error", "status")}
    plane, _ = slice_estimates(table["fmax_normalised"], EPP)
    bases = [{name: value[k] for name, value in table.items()} for k in range(BETAS.size)]
    return refine_slices(bases, list(plane), coordinates, solve, [(b,) for b in BETAS], **options)


@pytest.fixture(scope="module")
def built():
    dataset = small_map()
    return dataset, refined(dataset)


def read(dataset, numbers, refinement=None):
    return read_values(dataset, EPP, numbers, LABELS, where="small epp map", refinement=refinement)


def random_numbers(count, seed):
    rng = np.random.default_rng(seed)
    return tuple(np.exp(rng.uniform(np.log(grid[0]), np.log(grid[-1]), count)) for grid in (BETAS, ZETAS, LAMBDAS))


def test_each_slice_is_refined_purely_and_round_trips(built):
    """Every slice adds points where its kinks are; built again, the same bits; through its
    dataset (with and without the surplus) the same refinement."""
    dataset, refinement = built
    assert refinement.shape == (3, 7, 11) and all(part.codes.size > 20 for part in refinement.slices)
    again = refined(dataset)
    stored = refinement.dataset({"base_fingerprint": "small"})
    packed = SlicedRefinement.from_dataset(stored.drop_vars("surplus"), dataset["fmax_normalised"].values[0])
    for other in (again, SlicedRefinement.from_dataset(stored), packed):
        for part, same in zip(refinement.slices, other.slices):
            assert np.array_equal(part.codes, same.codes)
            for name, values in part.values.items():
                np.testing.assert_array_equal(values, same.values[name])


def test_a_lookup_on_a_refined_lattice_point_is_the_point(built):
    """At β of a slice and (λ, ζ) of one of its refinement points, read in a refined leaf: the
    point's F̄max bit for bit, its own error as the band (at the exact lattice position; a number
    given as (ζ, λ) lands there to ~1e-15 grid units, and reads the point to ~1e-16 but where
    that rounds it across a leaf's edge)."""
    dataset, refinement = built
    prepared = prepare_map(dataset, EPP, refinement)
    for k, part in enumerate(refinement.slices):
        u, v = part.position(part.codes)
        at = np.full(u.size, k)
        fmax, band, deep, between, _ = read_slices(prepared.slices, (3,), u / part.scale, v / part.scale,
                                                   [(at, at, np.zeros(u.size))])
        assert deep.mean() > 0.8 and not between.any()
        assert np.array_equal(fmax[deep], part.values["fmax_normalised"][deep].astype(float))
        assert np.array_equal(band[deep], part.values["fmax_error"][deep].astype(float))
        zeta, lam = coordinates(u / part.scale, v / part.scale)
        found = read(dataset, (np.full(u.size, BETAS[k]), zeta, lam), refinement)
        close = np.isclose(found.values["fmax_normalised"][deep], fmax[deep], rtol=1e-13, atol=0)
        assert close.mean() > 0.99  # the others rounded across a leaf's edge, into its neighbour


def test_the_band_covers_fresh_solves_and_refinement_narrows_it(built):
    """At 4000 random (β, ζ, λ) the band covers the error against the exact point at every one,
    refined or not; refined, far fewer answers err by more than 1e-3 in F̄max."""
    dataset, refinement = built
    numbers = random_numbers(4000, seed=1)
    exact = truth(*numbers)
    alone, fine = read(dataset, numbers), read(dataset, numbers, refinement)
    for reading in (alone, fine):
        error = np.abs(reading.values["fmax_normalised"] - exact)
        assert np.all(error <= reading.errors["fmax_error"])
        assert np.all(np.isfinite(reading.errors["fmax_error"]))
    alone_error = np.abs(alone.values["fmax_normalised"] - exact)
    fine_error = np.abs(fine.values["fmax_normalised"] - exact)
    on_slices = read(dataset, (np.full(4000, BETAS[1]), *numbers[1:]), refinement)
    slice_error = np.abs(on_slices.values["fmax_normalised"] - truth(BETAS[1], *numbers[1:]))
    assert np.mean(fine_error > 1e-3) < 0.8 * np.mean(alone_error > 1e-3)
    assert np.mean(slice_error > 1e-3) < 0.05 < np.mean(alone_error > 1e-3)
    for name in ("restitution", "absorbed_energy_fraction"):  # read on the grid, as before
        assert np.array_equal(fine.values[name], alone.values[name])


def test_unrefined_slices_and_cells_answer_as_before(built):
    """Between two slices without points, and in the unsplit cells of refined ones, every value,
    band and status is the one read without a refinement, bit for bit."""
    dataset, refinement = built
    partial = SlicedRefinement(refinement.extra_shape, (refinement.slices[0], Refinement.empty((7, 11)),
                                                        Refinement.empty((7, 11))))
    numbers = random_numbers(3000, seed=2)
    alone = read(dataset, numbers)
    for candidate in (partial, SlicedRefinement.empty((3, 7, 11))):
        found = read(dataset, numbers, candidate)
        same = (numbers[0] >= BETAS[1]) if candidate is partial else np.ones(3000, bool)
        assert same.sum() > 1000
        for name in found.values:
            assert np.array_equal(found.values[name][same], alone.values[name][same])
        for name in found.errors:
            assert np.array_equal(found.errors[name][same], alone.errors[name][same])
        assert np.array_equal(found.status[same], alone.status[same])


def test_a_sliced_refinement_is_read_only_with_its_map(built):
    """refinement_of takes a stored sliced refinement of this map, and refuses (warning, None) one
    built for another version of it or another β grid."""
    from impactmaps.maps.files.shipped import refinement_of

    dataset, refinement = built
    stored = refinement.dataset({"base_fingerprint": "small"})
    taken = refinement_of(stored, dataset)
    assert isinstance(taken, SlicedRefinement) and taken.size == refinement.size
    for bad in (stored.assign_attrs(base_fingerprint="other"), stored.assign_attrs(slice_points=[4])):
        with pytest.warns(UserWarning, match="another version of the map"):
            assert refinement_of(bad, dataset) is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="refinement"):
            read(dataset, (10.0, 1.0, 0.1), Refinement.empty((7, 11)))
