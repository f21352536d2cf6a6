"""One point at a time reads the map as the vectorised lookup does, bit for bit.

A lookup of one point takes a path in Python floats (:meth:`PlaneInterpolator.interpolate_one`,
``reader._read_plane_one``: the same operations in the same order as the NumPy path); these
tests compare it with the vectorised path on every shipped (ζ, λ) map: random points, every
grid value of both axes (a position exactly on a grid line or a refinement point), and the
ends of the map's range.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from impactmaps.maps.read.lookup import shipped_reader
from impactmaps.maps.files.shipped import SHIPPED_MAPS
from impactmaps import lookup


def _bits(values) -> np.ndarray:
    return np.asarray(values, float).view(np.uint64)


@pytest.mark.parametrize("law", ["linear", "hertz"])
@pytest.mark.parametrize("kind_theory", sorted(SHIPPED_MAPS))
def test_one_point_at_a_time_reads_the_same_bits_as_the_vectorised_lookup(law, kind_theory):
    structure, theory = kind_theory
    prepared, _ = shipped_reader(structure, theory, law)
    (z_low, z_high), (l_low, l_high) = prepared.ranges["zeta"], prepared.ranges["lambda_"]
    rng = np.random.default_rng(30)
    zeta = np.exp(rng.uniform(np.log(z_low), np.log(z_high), 60))
    lam = np.exp(rng.uniform(np.log(l_low), np.log(l_high), 60))
    grid_z, grid_l = np.exp(prepared.grids["zeta"]), np.exp(prepared.grids["lambda_"])
    zeta = np.concatenate([zeta, grid_z[::7], [z_low, z_high, z_low, z_high], rng.choice(grid_z, 6)])
    lam = np.concatenate([lam, rng.choice(grid_l, grid_z[::7].size), [l_low, l_high, l_high, l_low], grid_l[:6]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            together = lookup(zeta, lam, kind=structure, theory=theory, law=law)
        except ValueError:  # an unresolved point among them: compare the points one by one only where they answer
            together = None
        compared = 0
        for index, (z, lam_value) in enumerate(zip(zeta, lam)):
            try:
                one = lookup(float(z), float(lam_value), kind=structure, theory=theory, law=law)
                alone = (together if together is not None else  # two points: the vectorised path
                         lookup(np.array([z, z]), np.array([lam_value, lam_value]), kind=structure,
                                theory=theory, law=law))
            except ValueError as error:  # both paths refuse the same points
                with pytest.raises(ValueError, match="holds no value"):
                    lookup(np.array([z, z]), np.array([lam_value, lam_value]), kind=structure, theory=theory,
                           law=law)
                assert "holds no value" in str(error)
                continue
            at = index if together is not None else 0
            assert _bits(one.fmax_normalised) == _bits(np.ravel(alone.fmax_normalised)[at]), (z, lam_value)
            assert _bits(one.fmax_error) == _bits(np.ravel(alone.fmax_error)[at]), (z, lam_value)
            assert one.status == np.ravel(alone.status)[at] and one.regime == np.ravel(alone.regime)[at]
            compared += 1
    assert compared > 60


_PLASTIC_FIELDS = ("fmax_normalised", "fmax_error", "restitution", "restitution_error", "absorbed_energy_fraction",
                   "absorbed_energy_error")


@pytest.mark.parametrize("law", ["yc", "stronge", "epp"])
def test_one_plastic_point_at_a_time_reads_the_same_bits_as_the_vectorised_lookup(law):
    """The (β, ζ, λ) maps: one point (``reader._read_cube_one``) against the vectorised read."""
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps import lookup

    rng = np.random.default_rng(29)
    for structure, theory in sorted(PLASTIC_MAPS):
        prepared, _ = shipped_reader(structure, theory, law)
        numbers = []
        for axis in ("beta", "zeta", "lambda_"):
            low, high = prepared.ranges[axis]
            drawn = np.exp(rng.uniform(np.log(low), np.log(high), 40))
            numbers.append(np.concatenate([drawn, np.exp(prepared.grids[axis][:3]), [low, high]]))
        size = min(len(n) for n in numbers)
        beta, zeta, lam = (n[:size] for n in numbers)
        compared = 0
        for b, z, lam_value in zip(beta, zeta, lam):
            def read(*point):
                return lookup(*point, kind=structure, theory=theory, law=law)
            try:
                one = read(float(b), float(z), float(lam_value))
            except ValueError:  # refused alone: refused in the vectorised read too
                with pytest.raises(ValueError):
                    read(np.array([b, b]), np.array([z, z]), np.array([lam_value, lam_value]))
                continue
            together = read(np.array([b, b]), np.array([z, z]), np.array([lam_value, lam_value]))
            for name in _PLASTIC_FIELDS:
                assert _bits(getattr(one, name)) == _bits(np.ravel(getattr(together, name))[0]), (name, b, z, lam_value)
            assert one.status == np.ravel(together.status)[0]
            compared += 1
        assert compared > 20
