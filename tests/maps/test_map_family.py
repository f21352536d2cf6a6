"""A map family added without touching the package: one subclass and one registration.

The toy family below has a third axis, γ, and reports the linear impact at (ζ, λ) with its
force scaled by γ (``F_max γ/(m V0 ω)``): by the similarity of linear impacts its map is
γ times the linear map, exactly, which is what the tests check after sweeping it,
interrupting and resuming the sweep, and reading it back through the package's one map
reader. Everything else — the point solver, the dataset, the sweep file, the resume, the
lookup with its band and status — is the package's, unchanged.
"""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.maps.compute import sweep as sweep_module
from impactmaps.maps.compute.linear_points import LINEAR
from impactmaps.maps.family.map_family import Axis, MapFamily, PointPlan, available_map_families, register_map_family
from impactmaps.maps.read.reader import read_values
from impactmaps.maps.family.registry import map_family
from impactmaps.maps.files.store import SweepInterrupted
from impactmaps.maps.family.structures import MapStructure

BEAM = MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,))
GAMMAS, ZETAS, LAMBDAS = [1.0, 3.0], [0.05, 0.5, 5.0], [0.1, 1.0]


class _Scaled:
    """A linear run read with its force scaled by γ."""

    def __init__(self, result, gamma: float):
        self.result, self.gamma = result, gamma

    @property
    def fmax_normalised(self) -> float:
        return self.result.fmax_normalised * self.gamma

    @property
    def impacts(self) -> int:
        return self.result.impacts

    def normalised_summary(self) -> dict:
        return self.result.normalised_summary() | {"fmax_normalised": self.fmax_normalised}


class ToyFamily(MapFamily):
    """Points (γ, ζ, λ): the linear impact at (ζ, λ), force × γ."""

    name = "toy-gamma"
    axes = (Axis("gamma", "force factor γ"), *LINEAR.axes)

    def realise(self, target, point):
        gamma, zeta, lam = point
        return _Toy(LINEAR.realise(target, (zeta, lam)), float(gamma))

    def plan(self, target, realised, point, cap, settings):
        linear = LINEAR.plan(target, realised.impact, point[1:], cap, settings)
        return PointPlan(linear.method) if linear.asymptote is None else PointPlan(None)  # no toy asymptote

    def scaled(self, result, realised):
        return _Scaled(result, realised.gamma)


class _Toy:
    """A realised toy point: the linear impact's law, mass, speed, ω, reflection, and γ."""

    def __init__(self, impact, gamma):
        self.impact, self.gamma = impact, gamma
        self.law, self.mass, self.velocity = impact.law, impact.mass, impact.velocity
        self.omega, self.reflection = impact.omega, impact.reflection


TOY = register_map_family(ToyFamily())


def test_the_toy_family_is_registered_and_found_by_name():
    """One registration: the registry lists it and answers it by name."""
    assert "toy-gamma" in available_map_families() and map_family("toy-gamma") is TOY
    with pytest.raises(ValueError, match="lambda_"):
        register_map_family(type("Bad", (ToyFamily,), {"name": "bad", "axes": (Axis("zeta", "ζ"),)})())


def test_the_toy_family_sweeps_resumes_and_reads(tmp_path, monkeypatch):
    """Swept with an interruption after its first chunk, then resumed from the file: every
    point computed once, and the map is γ × the linear map (the same modal runs, bit for bit).
    Read back by the package's reader: on grid points the stored values, between them the
    multilinear interpolation, with a band and a status."""
    path = tmp_path / "toy.nc"
    real, calls = sweep_module.solve_map_points, []

    def interrupt_second(family, structure, points, settings):
        calls.append(len(points))
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(family, structure, points, settings)

    monkeypatch.setattr(sweep_module, "solve_map_points", interrupt_second)
    with pytest.raises(SweepInterrupted) as stop:
        sweep_module.sweep([BEAM], ZETAS, LAMBDAS, law="toy-gamma", axes={"gamma": GAMMAS}, path=path,
                           max_workers=1, progress=False)
    assert (stop.value.saved, stop.value.total) == (len(ZETAS), len(GAMMAS) * len(LAMBDAS) * len(ZETAS))
    monkeypatch.setattr(sweep_module, "solve_map_points", real)
    counted = []
    monkeypatch.setattr(sweep_module, "solve_map_points",
                        lambda *args: counted.append(len(args[2])) or real(*args))
    toy = sweep_module.sweep([BEAM], ZETAS, LAMBDAS, law="toy-gamma", axes={"gamma": GAMMAS}, path=path,
                             max_workers=1, progress=False)
    assert sum(counted) == len(GAMMAS) * len(LAMBDAS) * len(ZETAS) - len(ZETAS)  # only the missing points
    assert toy["fmax_normalised"].dims == ("structure", "gamma", "lambda_", "zeta")
    assert toy.attrs["contact_law"] == "toy-gamma" and toy.attrs["complete"] == 1 and "regime" not in toy
    linear = sweep_module.sweep([BEAM], ZETAS, LAMBDAS, max_workers=1, progress=False)
    for k, gamma in enumerate(GAMMAS):
        np.testing.assert_array_equal(toy["fmax_normalised"].values[0, k], linear["fmax_normalised"].values[0] * gamma)
        np.testing.assert_array_equal(toy["status"].values[0, k], linear["status"].values[0])

    on_grid = read_values(toy, TOY, (3.0, 0.5, 1.0), ("gamma", "zeta", "lambda"), where="toy map")
    assert float(on_grid.values["fmax_normalised"]) == float(toy["fmax_normalised"].sel(gamma=3.0, zeta=0.5,
                                                                                            lambda_=1.0)[0])
    between = read_values(toy, TOY, (np.sqrt(3.0), 0.5, 1.0), ("gamma", "zeta", "lambda"), where="toy map")
    expected = 0.5 * (1.0 + 3.0) * float(linear["fmax_normalised"].sel(zeta=0.5, lambda_=1.0)[0])
    assert float(between.values["fmax_normalised"]) == pytest.approx(expected, rel=1e-12)  # linear in log γ
    assert float(between.errors["fmax_error"]) >= 0.0 and str(between.status) in ("converged", "refined",
                                                                                 "interpolated", "sensitive")
    with pytest.raises(ValueError, match=r"gamma = 4.0 is outside the shipped map: valid range is \[1, 3\]"):
        read_values(toy, TOY, (4.0, 0.5, 1.0), ("gamma", "zeta", "lambda"), where="toy map")
