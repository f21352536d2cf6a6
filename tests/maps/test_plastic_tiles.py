"""Plastic on-demand tiles (issue 28 step 6): a plastic `lookup --case` on a structure no shipped map describes.

The tile of an elastic-plastic case is the 4 × 4 × 4 points of the plastic lattice
(the shipped plastic maps' grid, Δ log10 (β, ζ, λ) = (0.5, 1/6, 0.2)) around its
(β, ζ, λ), for exactly its structure, solved as the shipped plastic maps are and read with
their interpolation and band. Checked here: the answer (peak force, restitution, absorbed
energy) lies within its stated band of `simulate` on the same case; the committed tile of
the default test is the tile a fresh build gives, bit for bit (slow); a plastic impact whose
response depends on the sphere radius (a Mindlin plate) stays refused.
"""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from impactmaps.cases import parse_case, run_case
from impactmaps.maps.compute import tiles
from impactmaps import lookup
from impactmaps.maps.family.structures import MapStructure
from impactmaps.solvers.modal import simulate

#: A tile committed for the default test: the clamped–clamped aluminium beam of
#: :data:`_CLAMPED` struck at 1 m/s with the epp law (built by this very code; the slow
#: test rebuilds it and compares bits).
_COMMITTED_TILE = Path(__file__).parents[1] / "data" / "tiles" / "tile-6315946389e58cb0709fe40cfca9fa2d.nc"

_CLAMPED = ('[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
            '[target]\ntype = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.02\nmaterial = "aluminium-6061-t6"\n'
            'theory = "euler"\nsupports = "cc"\n[contact]\nlaw = "{law}"\n')


def _case(law: str = "epp", velocity: float = 1.0, radius: float = 0.01, text: str = _CLAMPED):
    return parse_case(text.format(radius=radius, velocity=velocity, law=law))


def _check_within_band(case, found: dict) -> None:
    """Peak force, restitution and absorbed energy of ``simulate`` within the lookup's bands,
    plus the direct run's own error (its change when refined twice, to the map points' finest
    level; at least 1e-3 of the force scale, the points' tolerance)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings
        _, summary = run_case(case)
        fine = simulate(case.target, case.law, case.impactor_mass, case.velocity,
                        settings=case.settings.refined().refined(), record=False, time_step=case.time_step)
    direct = max(1e-3 * found["force_scale_N"], abs(fine.peak_force - summary["peak_force_N"]))
    assert abs(found["peak_force_N"] - summary["peak_force_N"]) <= found["peak_force_error_N"] + direct, (found, summary)
    restitution = fine.rebound_velocity / case.velocity
    assert abs(found["restitution"] - summary["restitution"]) <= found["restitution_error"] + 1e-3 + abs(
        restitution - summary["restitution"]), (found, summary)
    energy = 0.5 * case.impactor_mass * case.velocity**2
    assert abs(found["absorbed_energy_J"] - fine.contact_dissipation) <= found["absorbed_energy_error_J"] + 1e-3 * energy


def test_plastic_lookup_on_a_clamped_beam_with_epp_is_answered_within_its_band_of_simulate(tmp_path):
    """The Must show of issue 28: `lookup --case` on a clamped–clamped beam with law = "epp" is
    answered (from the committed tile: no build), names its tile, and lies within its stated
    band of `simulate` on the same case — peak force, restitution and absorbed energy."""
    shutil.copy(_COMMITTED_TILE, tmp_path)
    lines = []
    case = _case()
    found = lookup(case=case, cache_dir=tmp_path, notify=lines.append)
    assert lines == [], "the committed tile answers: nothing is built"
    assert found["map"].startswith("on-demand tile beam-cc-euler-epp β ") and found["law"] == "epp"
    assert found["cache_file"] == str(tmp_path / _COMMITTED_TILE.name)
    assert found["status"] in ("converged", "refined", "interpolated", "sensitive")
    assert all(np.isfinite(found[key]) for key in ("peak_force_N", "peak_force_error_N", "restitution",
                                                   "restitution_error", "absorbed_energy_J", "beta"))
    _check_within_band(case, found)


def test_plastic_lookup_case_on_the_command_line(tmp_path, monkeypatch, capsys):
    """`impactmaps lookup --case … --json` prints the plastic tile's answer (the committed tile:
    nothing built, nothing on stderr); `--no-build` still refuses the clamped beam, naming its
    supports."""
    from impactmaps.cli import main

    shutil.copy(_COMMITTED_TILE, tmp_path)
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    path = tmp_path / "clamped.toml"
    path.write_text(_CLAMPED.format(radius=0.01, velocity=1.0, law="epp"))
    assert main(["lookup", "--case", str(path), "--quiet", "--json"]) == 0
    out = capsys.readouterr()
    assert '"law": "epp"' in out.out and "beam-cc-euler-epp" in out.out
    assert all(line.startswith("warning:") for line in out.err.splitlines())  # the case's validity warnings only
    assert main(["lookup", "--case", str(path), "--no-build"]) == 2
    assert "supports 'cc'" in capsys.readouterr().err


def test_a_plastic_tile_lies_on_the_plastic_lattice():
    """A plastic tile's β, ζ, λ are points of the shipped plastic maps' grid (2, 6 and 5 per decade),
    the case's cell is its middle one, and the key needs a β."""
    structure = MapStructure(kind="beam", theory="euler", supports="cc", impact_fraction=(0.5,))
    key = tiles.tile_for(structure, "epp", None, 0.078, 0.116, extra=(57.6,))
    (betas,), (zetas, lambdas) = key.extra_axes, key.axes
    for values, per_decade, point in ((betas, 2, 57.6), (zetas, 6, 0.078), (lambdas, 5, 0.116)):
        exponents = np.log10(values) * per_decade
        assert np.allclose(exponents, np.round(exponents), atol=1e-9)
        assert values[1] <= point <= values[2]
    assert key.fingerprint != tiles.tile_for(structure, "yc", None, 0.078, 0.116, extra=(57.6,)).fingerprint
    with pytest.raises(ValueError, match="extra"):
        tiles.tile_for(structure, "epp", None, 0.078, 0.116)


def test_a_plastic_impact_on_a_mindlin_plate_stays_refused(tmp_path):
    """Its contact patch (or the point load's divergent shear deflection) makes the sphere
    radius a fourth number: no plastic map, shipped or on demand."""
    text = ('[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'
            '[target]\ntype = "plate"\nlength_x = 0.2\nlength_y = 0.2\nthickness = 0.01\n'
            'material = "structural-steel"\ntheory = "mindlin"\n[contact]\nlaw = "{law}"\n')
    with pytest.raises(ValueError, match="no shipped map covers this case.*theory 'mindlin'.*fourth number"):
        lookup(case=_case(text=text), cache_dir=tmp_path)
    assert not list(tmp_path.glob("tile-*.nc"))


@pytest.mark.slow
def test_the_committed_tile_is_what_a_fresh_build_gives(tmp_path):
    """The default test's tile, rebuilt: the same fingerprint and the same bits (built in four
    (λ, ζ) planes, each reported to ``progress``)."""
    calls = []
    found = lookup(case=_case(), cache_dir=tmp_path, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(16, 64), (32, 64), (48, 64), (64, 64)]
    fresh = Path(found["cache_file"])
    assert fresh.name == _COMMITTED_TILE.name
    with xr.open_dataset(fresh, engine="scipy") as a, xr.open_dataset(_COMMITTED_TILE, engine="scipy") as b:
        assert a.attrs["data_digest"] == b.attrs["data_digest"] and a.attrs["fingerprint"] == b.attrs["fingerprint"]
        xr.testing.assert_identical(a, b)


#: Plastic cases no shipped map describes: law, velocity [m/s], sphere radius [m], edit of the
#: clamped beam's text (none: the clamped–clamped Euler beam).
_SLOW_CASES = [
    ("epp", 0.3, 0.01, ()), ("epp", 3.0, 0.01, ()), ("epp", 1.0, 0.005, ()), ("stronge", 1.0, 0.01, ()),
    ("yigit-christoforou", 2.0, 0.015, ()),
    ("epp", 1.0, 0.01, ('supports = "cc"', 'supports = "cs"\nimpact_position = 0.2')),
    ("epp", 1.0, 0.01, ('theory = "euler"\nsupports = "cc"', 'theory = "timoshenko"\nsupports = "ss"')),  # L/h 25
]


@pytest.mark.slow
@pytest.mark.parametrize("law, velocity, radius, edit", _SLOW_CASES)
def test_plastic_lookups_on_structures_without_a_shipped_map_match_simulate(law, velocity, radius, edit, tmp_path):
    """Clamped–clamped beams with each plastic law at several speeds and ball sizes, a
    clamped–simply supported beam struck off-centre and a Timoshenko beam of slenderness 25
    (the shipped plastic map is at 20): each answered from a tile, within its bands of simulate."""
    case = _case(law, velocity, radius, _CLAMPED.replace(*edit) if edit else _CLAMPED)
    found = lookup(case=case, cache_dir=tmp_path)
    assert found["map"].startswith("on-demand tile ")
    _check_within_band(case, found)


@pytest.mark.slow
def test_a_plastic_case_beyond_the_shipped_map_is_answered_from_a_tile(tmp_path):
    """A case of a shipped plastic family (SS Euler beam at mid-span) whose ζ lies below the
    shipped map's 1e-3 (a 2 mm ball on a stout aluminium beam 300 × 20 × 30 mm: ζ = 1.3e-4) is
    refused with build=False, and answered from a tile of the same family otherwise, within
    its bands."""
    text = _CLAMPED.replace('supports = "cc"', 'supports = "ss"').replace("length = 0.5", "length = 0.3").replace(
        "height = 0.02", "height = 0.03")
    case = _case("epp", 1.0, 0.001, text)
    with pytest.raises(ValueError, match="outside the shipped map"):
        lookup(case=case, build=False)
    found = lookup(case=case, cache_dir=tmp_path)
    assert found["zeta"] < 1e-3 and found["map"].startswith("on-demand tile beam-ss-euler-epp β ")
    _check_within_band(case, found)
