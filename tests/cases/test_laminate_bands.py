"""Bands of `lookup --case` on laminates hold the converged `simulate` and are ≤ 3 % where the
points converge (issue 39 item 4).

A refined-cell tile's re-impacting point states an error of at least 1 % of its F̄max
(:data:`~impactmaps.maps.family.accuracy.TILE_REIMPACT_RELATIVE_FLOOR`, between the one-impact
floor 2e-4 and 1e-3) instead of the shipped maps' absolute 1e-3, ~4 % of the F̄max ≈ 0.025 of
a 1 kg ball on a 1 mm laminate. Default: the two SSSS [45/0/−45/90] plates whose bands were
5.8 % and 3.2 % and the [0/90]4s SSSS plate whose band was 6.8 % (docs/lookup.rst), each from a
committed tile (built by this code; nothing built here) against its converged ``simulate``
(settings refined three times: cut-offs ×8, step /8) pinned below. Slow: the study of ``validation/laminate_tile_bands.py`` over its 12
laminate cases, each band holding the converged ``simulate`` computed afresh.

Every laminate's tile is a refined cell (the [0/90]4s SSSS plate's was a Navier 4 × 4 tile whose
second-difference band was 6.8 %), a patch-loaded cell's points follow ``simulate``'s
heavy-impactor corner rule up to what the basis resolves, and a cell's surpluses discount the
spread of its sensitive points (docs/accuracy.rst, "Bands of laminate tiles").
"""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

from impactmaps import lookup
from impactmaps.cases import parse_case
from impactmaps.cases.case_answer import case_map_law
from impactmaps.cases.on_demand import _tile_settings, case_structure
from impactmaps.contact.contact_scale import reference_contact_stiffness
from impactmaps.maps.compute import tiles
from impactmaps.maps.family.accuracy import (ERROR_FLOOR, REIMPACT_ERROR_FLOOR, STATUSES,
                                             TILE_REIMPACT_RELATIVE_FLOOR, stated_error)
from impactmaps.maps.family.structures import MapStructure
from impactmaps.solvers.modal_settings import ModalSettings, corner_ratios

from ..helpers import repository_module

study = repository_module("validation/laminate_tile_bands.py")

_TILES = Path(__file__).parents[1] / "data" / "tiles"
#: case name of the study → (its committed tile, the converged simulate's peak force [N]:
#: ``study.converged_simulate``, measured 2026-12-03; the defaults give 209.29, 1708.96 and 705.92 N).
#: The third: the [0/90]4s SSSS plate, a Navier 4 × 4 tile before (705.1 ± 48.1 N, 6.8 %).
_COMMITTED = {
    "ssss-qi-1kg": ("tile-80807baec6e4e7f9c0a1da1b2754de31.nc", 210.455),
    "ssss-qi2-5.5kg": ("tile-f81dbc1736d06959668febf87742e4ef.nc", 1709.105),
    "ssss-cp4-5kg": ("tile-c7e949d2197d45f29acf76f0f99c54b1.nc", 705.920),
}


def test_a_tile_points_reimpact_floor_is_relative_to_its_fmax_within_the_absolute_floors():
    """With ``fmax``: a re-impacting settled point's floor is 1 % of its F̄max, clipped to
    [2e-4, 1e-3]; a single impact keeps 2e-4, a sensitive point its error; idempotent; without
    ``fmax`` the shipped maps' floors, unchanged."""
    converged, sensitive = STATUSES.index("converged"), STATUSES.index("sensitive")
    fmax = np.array([0.0247, 0.0545, 0.005, 0.3, 0.0247, 0.0247])
    status = np.array([converged] * 5 + [sensitive])
    impacts = np.array([6, 2, 3, 2, 1, 6])
    once = stated_error(np.full(6, 1e-5), status, impacts, fmax)
    expected = [TILE_REIMPACT_RELATIVE_FLOOR * 0.0247, TILE_REIMPACT_RELATIVE_FLOOR * 0.0545, ERROR_FLOOR,
                REIMPACT_ERROR_FLOOR, ERROR_FLOOR, 1e-5]
    np.testing.assert_allclose(once, expected, rtol=1e-12)
    np.testing.assert_array_equal(stated_error(once, status, impacts, fmax), once)
    assert stated_error(1e-5, converged, 6) == REIMPACT_ERROR_FLOOR
    assert stated_error(5e-4, converged, 6, 0.0247) == 5e-4  # a larger measured change is kept


@pytest.mark.parametrize("name", list(_COMMITTED))
def test_a_committed_laminate_tile_band_holds_the_converged_simulate_within_3_percent(name, tmp_path):
    """The SSSS [45/0/−45/90]s 1 kg (six impacts), [45/0/−45/90]2s 5.5 kg and [0/90]4s 5 kg
    plates: from their committed tiles, nothing built, a band ≤ 3 % of the answer that holds the
    converged ``simulate`` (were 5.8 %, 3.2 % — the 1e-3 re-impact floor — and 6.8 %, the Navier
    tile's second differences)."""
    tile, converged = _COMMITTED[name]
    shutil.copy(_TILES / tile, tmp_path)
    lines = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings (large deflection, the laminate near field)
        found = lookup(case=parse_case(study.CASES[name][1]), cache_dir=tmp_path, notify=lines.append)
    assert lines == [] and found["cache_file"] == str(tmp_path / tile), "the committed tile answers"
    assert found["status"] in ("converged", "refined", "interpolated"), found
    assert found["peak_force_error_N"] <= 0.03 * found["peak_force_N"], found
    assert abs(found["peak_force_N"] - converged) <= found["peak_force_error_N"], found


@pytest.mark.slow
@pytest.mark.parametrize("name", list(study.CASES))
def test_every_laminate_band_of_the_study_holds_the_converged_simulate(name, tmp_path):
    """Each case of the study (SSSS and CCCC, Mindlin and Kirchhoff, [45/0/−45/90]s and 2s,
    [0/90]4s, [0/45/90/−45]2s, 0.05–5.5 kg, one to seven impacts), its tile built from nothing:
    the band holds the converged ``simulate`` and ≤ 3 % where not ``sensitive`` (but the 0.2 kg
    SSSS plate, whose cell's λ-upper corners are sensitive: 4.7 %, was 10.8 %), and two random
    points inside its cell, solved as map points, lie within the band the tile states there."""
    row = study.case_row(name, tmp_path)
    assert row["error_over_band"] <= 1.0, row
    if row["status"] != "sensitive" and name != "ssss-qi-0.2kg":  # its cell has sensitive corners: 4.7 %
        assert row["band_percent"] <= 3.0, row
    if name in _COMMITTED:
        assert row["converged_N"] == pytest.approx(_COMMITTED[name][1], rel=1e-4), row
    for inside in study.inside_errors(name, tmp_path, 2):  # the tile inside its cell, against map points
        assert inside["error_over_band"] <= 1.0, inside


def _key(name: str, zeta: float, lam: float):
    """The tile key of a study case at (ζ_h, λ_h) (the case's own numbers in its lookup)."""
    case = parse_case(study.CASES[name][1])
    law = case_map_law(case)
    structure, patch = case_structure(case, law)
    return structure, tiles.tile_for(structure, law, patch, zeta, lam, _tile_settings(case, patch))


def test_every_laminate_has_a_refined_cell_tile_and_an_isotropic_ssss_plate_keeps_its_4_by_4_tile():
    """The [0/90]4s SSSS plate (no D16/D26, a Navier basis) has a refined cell as the coupled
    laminates have; an isotropic SSSS plate keeps the 4 × 4 tile and its settings."""
    structure, key = _key("ssss-cp4-5kg", 72.06, 0.002628)
    assert structure.stiffness is not None and not structure.build().bounded_modes
    assert tiles.refined_cell(structure, "hertz") and key.cell and key.point_count == 9
    isotropic = MapStructure(kind="plate", theory="mindlin", supports="SSSS", slenderness=100.0)
    assert not tiles.refined_cell(isotropic, "hertz")
    other = tiles.tile_for(isotropic, "hertz", 1.0, 72.06, 0.002628)
    assert not other.cell and other.settings == ModalSettings()


def test_a_patch_cells_points_follow_the_corner_rule():
    """The heavy-impactor rule raises the patch cut-off of a cell's points to at least every
    point's corner ratio (Navier [0/90]4s plate, 5 kg: 420 ω): a two-significant-digit ratio,
    a pure function of the key; a point-load tile keeps 20."""
    _, key = _key("ssss-cp4-5kg", 72.06, 0.002628)
    target, family = key.structure.build(), tiles._family(key)
    zetas, lambdas = key.axes
    points = [(float(z), float(lam)) for lam in lambdas for z in zetas] + tiles._splitting_points(key)
    ratio = key.settings.patch_cutoff_ratio
    for impact in family.realise_points(target, points):
        stiffness = reference_contact_stiffness(impact.law, impact.mass, impact.velocity)
        assert ratio >= corner_ratios(ModalSettings(), target, impact.mass, stiffness)[0] > 100.0
    assert ratio == float(f"{ratio:.2g}") and tiles.with_corner_cutoff(key) == key
    structure, point_load = _key("ssss-qi2-k-0.5kg", 15.3, 0.0075)
    assert point_load.patch is None and point_load.settings == ModalSettings()


@pytest.mark.slow
def test_the_corner_rule_of_a_ritz_cell_stops_at_what_its_basis_resolves():
    """[45/0/−45/90]s SSSS Mindlin, 1 kg: the corner asks for ~580 ω, the Ritz basis resolves
    ~28–33 ω at the cell's points; the ratio is raised above 20 but to no more than the lowest
    of those (no point turned capped). Slow: the plate's largest basis (~18 s from nothing)."""
    _, ritz = _key("ssss-qi-1kg", 100.32, 0.000627)
    target, family = ritz.structure.build(), tiles._family(ritz)
    cap = tiles.map_cap(target)
    zetas, lambdas = ritz.axes
    points = [(float(z), float(lam)) for lam in lambdas for z in zetas] + tiles._splitting_points(ritz)
    omegas = [impact.omega for impact in family.realise_points(target, points)]
    assert ModalSettings().patch_cutoff_ratio < ritz.settings.patch_cutoff_ratio <= min(cap / omega for omega in omegas)


def _cell(surplus, status, error, base_status, base_error):
    """A refined cell's tile (xarray) with the given split (points at lattice (U, V) = (0, 1),
    (1, 0), (1, 1), (1, 2), (2, 1)) and base corners ((λ, ζ) arrays)."""
    import xarray as xr

    split = ("refinement_point",)
    corners = ("structure", "lambda_", "zeta")
    return xr.Dataset({
        "fmax_normalised": (corners, np.full((1, 2, 2), 0.05)), "fmax_error": (corners, np.asarray([base_error])),
        "status": (corners, np.asarray([base_status], np.int8)), "refinement_code": (split, np.array([1, 3, 4, 5, 7])),
        "refinement_fmax_normalised": (split, np.full(5, 0.05, np.float32)),
        "refinement_fmax_error": (split, np.asarray(error, np.float32)),
        "refinement_status": (split, np.asarray(status, np.int8)),
        "refinement_surplus": (split, np.asarray(surplus, np.float32)),
        "refinement_impacts": (split, np.ones(5))},
        coords={"structure": ["s"], "lambda_": [1.0, 2.0], "zeta": [1.0, 2.0]})


def test_a_cells_surplus_discounts_the_spread_of_its_sensitive_points_as_interpolation_weighs_it():
    """A sensitive corner of half-spread e: the middles of its two edges lose e/2 of their
    surplus, the centre e/4 (never below 0); a sensitive splitting point its own e; no sensitive
    point: the surpluses as measured."""
    converged, sensitive = STATUSES.index("converged"), STATUSES.index("sensitive")
    surplus, e = np.full(5, 1.2e-3), 2e-3
    quiet = _cell(surplus, [converged] * 5, np.full(5, 1e-5), np.full((2, 2), converged), np.full((2, 2), 1e-5))
    np.testing.assert_allclose(tiles.tile_refinement(quiet).values["surplus"], surplus, rtol=1e-6)
    base_status = np.array([[converged, converged], [converged, sensitive]])  # (λ, ζ) = (high, high): lattice (2, 2)
    base_error = np.where(base_status == sensitive, e, 1e-5)
    noisy = _cell(surplus, [converged] * 4 + [sensitive], np.array([1e-5] * 4 + [5e-4]), base_status, base_error)
    found = tiles.tile_refinement(noisy).values["surplus"]  # codes 1, 3, 4, 5, 7: (0,1) (1,0) (1,1) (1,2) (2,1)
    np.testing.assert_allclose(found, [1.2e-3, 1.2e-3, 1.2e-3 - e / 4, 1.2e-3 - e / 2, 0.0],
                               atol=1e-9)
