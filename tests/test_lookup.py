"""Shipped lookup maps against direct simulation, and the lookup/classify commands."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactmaps.cli import main
from impactmaps.maps.lookup import SHIPPED_MAPS, design_formula, load_shipped_map, lookup
from impactmaps.maps.structures import structure_from_name
from impactmaps.maps.sweep import solve_points
from impactmaps.solvers.modal import ModalSettings

#: Documented interpolation error (README "Validation"): over 150 random points per map
#: the largest |lookup − direct| was 0.023 (Mindlin plate); 0.03 leaves room for other seeds.
LOOKUP_TOLERANCE = 0.03


def _available(structure, theory):
    try:
        load_shipped_map(structure, theory)
    except FileNotFoundError:
        return False
    return True


@pytest.mark.parametrize("structure, theory", list(SHIPPED_MAPS), ids=list(SHIPPED_MAPS.values()))
def test_lookup_matches_direct_simulation(structure, theory):
    """Random (ζ, λ) inside the map: interpolated F̄max within the documented error of a
    direct simulation; grid points are reproduced exactly."""
    if not _available(structure, theory):
        pytest.skip("map not built")
    dataset = load_shipped_map(structure, theory)
    rng = np.random.default_rng(7)
    zetas = np.exp(rng.uniform(np.log(0.005), np.log(100), 8))
    lambdas = np.exp(rng.uniform(np.log(0.05), np.log(20), 8))
    name = SHIPPED_MAPS[(structure, theory)]
    rows = solve_points(structure_from_name(name), list(zip(zetas, lambdas)), ModalSettings())
    direct = np.array([row["fmax_normalised"] for row in rows])
    found = lookup(zetas, lambdas, structure=structure, theory=theory)
    assert np.max(np.abs(found.fmax_normalised - direct)) <= LOOKUP_TOLERANCE
    zeta, lam = dataset["zeta"].values[10], dataset["lambda_"].values[5]
    stored = dataset["fmax_normalised"].isel(structure=0).sel(zeta=zeta, lambda_=lam).item()
    assert lookup(zeta, lam, structure=structure, theory=theory).fmax_normalised == pytest.approx(stored, abs=1e-12)


def test_design_formula_is_exact_at_its_asymptotes():
    """max(F̄∞(ζ), sqrt(λ/(1+λ))): half-space limit 1 and quasi-static limit."""
    assert float(design_formula(1e-6, 1.0, "plate")) == pytest.approx(1.0, abs=1e-5)
    assert float(design_formula(1e3, 4.0, "beam")) == pytest.approx(np.sqrt(0.8), abs=1e-12)


def test_lookup_rejects_out_of_range():
    if not _available("plate", "kirchhoff"):
        pytest.skip("map not built")
    with pytest.raises(ValueError, match="loss_factor = .* outside the shipped map"):
        lookup(1e-4, 1.0, structure="plate", theory="kirchhoff")
    with pytest.raises(ValueError, match="theory"):
        lookup(1.0, 1.0, structure="plate", theory="euler")


def test_lookup_and_classify_commands(capsys):
    if not _available("plate", "kirchhoff"):
        pytest.skip("map not built")
    assert main(["lookup", "--structure", "plate", "--theory", "kirchhoff", "--zeta", "11.3",
                 "--lambda", "0.425", "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["regime"] == "quasi-static"
    assert set(values) >= {"fmax_normalised", "regime"}
    assert main(["classify", "--zeta", "0.038", "--lambda", "0.425", "--structure", "plate", "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["regime"] == "local" and values["fmax_normalised"] > 0.9
