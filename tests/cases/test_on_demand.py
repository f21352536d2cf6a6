"""On-demand map tiles (issues 13 item 4 and 14): `lookup --case` for a case no shipped map describes.

The tile of a case is the 4 × 4 points of the global lattice around its (ζ, λ), for
exactly its structure (and its patch number for a patch-loaded Hertz case), solved as
the shipped maps are; it is cached by fingerprint. Checked here: the answer is within its
band of `simulate` on random physical cases outside the shipped maps; a cached tile
answers the same bits as a fresh one; a corrupted or foreign cache file is rebuilt,
never used; the cache is bounded; what no map structure describes is still refused.
Every test uses its own cache directory.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from impactmaps.cases import parse_case, run_case
from impactmaps.maps.compute import tiles
from impactmaps.maps.files import tile_files
from impactmaps import lookup
from impactmaps.maps.family.structures import MapStructure

_BALL = '[impactor]\nradius = {radius!r}\nmaterial = "structural-steel"\nvelocity = {velocity!r}\n'


def _case(target: str, law: str, radius: float = 0.01, velocity: float = 1.0):
    return parse_case(_BALL.format(radius=radius, velocity=velocity) + f"[target]\n{target}\n"
                      f'[contact]\nlaw = "{law}"\n')


_CLAMPED_BEAM = ('type = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.02\nmaterial = "structural-steel"\n'
                 'theory = "euler"\nsupports = "cc"')


def _random_case(rng, kind: str):
    """A random physical case that no shipped map describes: a steel ball (radius 3–20 mm,
    0.3–5 m/s) with a linear (K_y) or Hertz law on

    * ``clamped-beam``: a clamped-clamped, clamped-simply supported or cantilever beam
      (Euler, or one in four Timoshenko of slenderness 10–40: the first tile of a clamped
      Timoshenko beam takes minutes, the sweep counting its finite-element modes for its
      mode cap), struck anywhere in its middle 60 %;
    * ``off-centre``: an SS Euler beam or an SSSS square Kirchhoff plate struck off-centre;
    * ``rectangular``: an SSSS Kirchhoff plate of aspect ratio 0.4–2.5, struck anywhere;
    * ``thick-mindlin``: a Hertz impact on an SSSS Mindlin plate of slenderness 5–9 (below
      the families), loaded over the contact patch. (A linear law loads a Mindlin plate at
      a point, whose shear deflection diverges: the maps' points, shipped or on demand,
      hold the shear of the modes up to the sweep's cap in their residual while
      `simulate` stops at its cut-off; they differ by 0.2–3 %, beyond the band, for the
      shipped s = 20 map as for a tile — a known limit of point-loaded Mindlin maps, not
      of the tiles.)
    * ``mindlin-hertz``: a Hertz impact on an SSSS Mindlin plate of slenderness 10–80
      (loaded over the contact patch by `simulate`), of aspect ratio 1–2.
    """
    def uniform(low, high):
        return float(rng.uniform(low, high))

    metal = str(rng.choice(["structural-steel", "aluminium-6061-t6"]))
    law = str(rng.choice(["linear", "hertz"])) if "mindlin" not in kind else "hertz"
    if kind in ("clamped-beam", "off-centre") and (kind == "clamped-beam" or uniform(0, 1) < 0.5):
        length, width = uniform(0.2, 1.0), uniform(0.01, 0.05)
        theory = "timoshenko" if kind == "clamped-beam" and uniform(0, 1) < 0.25 else "euler"
        height = length / uniform(10, 40) if theory == "timoshenko" else uniform(0.005, 0.03)
        supports = str(rng.choice(["cc", "cs", "cf"])) if kind == "clamped-beam" else "ss"
        position = length * uniform(0.2, 0.8) if kind == "clamped-beam" else length * uniform(0.1, 0.4)
        target = (f'type = "beam"\nlength = {length!r}\nwidth = {width!r}\nheight = {height!r}\n'
                  f'material = "{metal}"\ntheory = "{theory}"\nsupports = "{supports}"\n'
                  f'impact_position = {position!r}')
    else:
        side = uniform(0.1, 0.5)
        aspect = {"rectangular": uniform(0.4, 2.5), "mindlin-hertz": uniform(1.0, 2.0)}.get(kind, 1.0)
        slenderness = {"thick-mindlin": uniform(5, 9), "mindlin-hertz": uniform(10, 80)}.get(
            kind, uniform(30, 200))
        theory = "mindlin" if "mindlin" in kind else "kirchhoff"
        centre = kind == "mindlin-hertz" or (kind == "thick-mindlin" and uniform(0, 1) < 0.5)
        point = (0.5, 0.5) if centre else (uniform(0.2, 0.8), uniform(0.2, 0.8))
        target = (f'type = "plate"\nlength_x = {side!r}\nlength_y = {side * aspect!r}\n'
                  f'thickness = {side / slenderness!r}\nmaterial = "{metal}"\ntheory = "{theory}"\n'
                  f'impact_point = [{side * point[0]!r}, {side * aspect * point[1]!r}]')
    return _case(target, law, radius=10 ** uniform(np.log10(0.003), np.log10(0.02)),
                 velocity=10 ** uniform(np.log10(0.3), np.log10(5.0)))


_KINDS = ("clamped-beam", "off-centre", "rectangular", "thick-mindlin", "mindlin-hertz")


def _direct_error(case, peak_force: float) -> float:
    """The direct run's own error [N]: its change when refined twice (cut-off ×4, step /4),
    to the finest level of the map points (point loads on Mindlin plates drift with the
    cut-off, ~1e-3 per doubling: the map stores its finest value)."""
    from impactmaps.solvers.modal import simulate

    fine = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=case.settings.refined().refined(),
                    record=False, time_step=case.time_step)
    return abs(fine.peak_force - peak_force)


def _check_against_simulate(cases, cache_dir) -> int:
    """Each case: lookup within its band of simulate (plus the direct run's own error: its
    change when refined to the map's finest level, at least 1e-3 normalised), or refused
    next to an unresolved tile point; the count answered."""
    answered = 0
    for case in cases:
        try:
            found = lookup(case=case, cache_dir=cache_dir)
        except ValueError as error:
            assert "holds no value next to it" in str(error) and "impactmaps simulate" in str(error), str(error)
            continue
        assert found["map"].startswith("on-demand tile ")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # validity warnings of the extreme draws
            _, summary = run_case(case)
            direct = max(1e-3 * found["force_scale_N"], _direct_error(case, summary["peak_force_N"]))
        assert abs(found["peak_force_N"] - summary["peak_force_N"]) <= found["peak_force_error_N"] + direct, \
            (case.source_text, found, summary)
        answered += 1
    return answered


def test_lookup_matches_simulate_on_random_cases_outside_the_shipped_maps(tmp_path):
    """One random physical case of each kind no shipped map describes (clamped beam,
    off-centre impact, non-square plate, Mindlin plate thicker than the families, Hertz
    on a patch-loaded Mindlin plate): the on-demand answer lies within its band of
    simulate's peak force. (The ≥ 50-case version is marked slow.)"""
    rng = np.random.default_rng(3)
    assert _check_against_simulate([_random_case(rng, kind) for kind in _KINDS], tmp_path) == len(_KINDS)


@pytest.mark.slow
def test_lookup_matches_simulate_on_many_random_cases_outside_the_shipped_maps(tmp_path):
    """60 random physical cases, 12 of each kind: within the band of simulate, or refused
    next to an unresolved tile point (at least 50 answered)."""
    rng = np.random.default_rng(2026)
    assert _check_against_simulate([_random_case(rng, kind) for kind in _KINDS for _ in range(12)], tmp_path) >= 50


def test_a_cached_tile_answers_the_same_bits_as_a_fresh_one(tmp_path):
    """Fresh, from the cache, and fresh again in another directory: equal dicts, bit for bit
    (only the cache file differs); the build is announced once, the cache answers silently."""
    case = _case(_CLAMPED_BEAM, "hertz")
    lines = []
    fresh = lookup(case=case, cache_dir=tmp_path / "a", notify=lines.append)
    cached = lookup(case=case, cache_dir=tmp_path / "a", notify=lines.append)
    again = lookup(case=case, cache_dir=tmp_path / "b")
    assert len(lines) == 1 and lines[0].startswith("building an on-demand map tile of 16 points for beam-cc-euler")
    assert fresh == cached
    assert {**again, "cache_file": fresh["cache_file"]} == fresh
    assert all(math.isfinite(value) for value in fresh.values() if isinstance(value, float))


def test_a_corrupted_or_foreign_cache_file_is_rebuilt_not_used(tmp_path):
    case = _case(_CLAMPED_BEAM, "linear")
    lines = []
    answer = lookup(case=case, cache_dir=tmp_path, notify=lines.append)
    path = tmp_path / answer["cache_file"].rsplit("/", 1)[-1]
    path.write_bytes(path.read_bytes()[:200])  # truncated
    assert lookup(case=case, cache_dir=tmp_path, notify=lines.append) == answer and len(lines) == 2
    other = lookup(case=_case(_CLAMPED_BEAM.replace('"cc"', '"cs"'), "linear"), cache_dir=tmp_path / "other")
    path.write_bytes((tmp_path / "other" / other["cache_file"].rsplit("/", 1)[-1]).read_bytes())  # foreign tile
    assert lookup(case=case, cache_dir=tmp_path, notify=lines.append) == answer and len(lines) == 3
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as opened:  # right fingerprint, altered data
        tampered = opened.load()
    tampered["fmax_normalised"] = tampered["fmax_normalised"] * 1.01
    tiles.save_atomic(tampered, path)
    assert lookup(case=case, cache_dir=tmp_path, notify=lines.append) == answer and len(lines) == 4


def test_the_cache_is_bounded_and_found_where_the_environment_says(tmp_path, monkeypatch):
    monkeypatch.setattr(tile_files, "MAX_CACHED_TILES", 2)
    for supports in ("cc", "cs", "cf"):
        lookup(case=_case(_CLAMPED_BEAM.replace('"cc"', f'"{supports}"'), "linear"), cache_dir=tmp_path)
    assert len(list(tmp_path.glob("tile-*.nc"))) == 2
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path / "env"))
    assert tiles.cache_directory() == tmp_path / "env"
    assert lookup(case=_case(_CLAMPED_BEAM, "linear"))["cache_file"].startswith(str(tmp_path / "env"))
    monkeypatch.delenv("IMPACTMAPS_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert tiles.cache_directory() == tmp_path / "xdg" / "impactmaps"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert tiles.cache_directory() == tmp_path / "home" / ".cache" / "impactmaps"
    assert tiles.cache_directory(tmp_path / "given") == tmp_path / "given"


def test_nearby_cases_share_a_tile_of_the_global_lattice():
    """A tile's ζ, λ lie on the lattice of the shipped linear maps (0.05 and 0.1 decades),
    the case's cell is its middle one, and cases in one cell share it."""
    assert tiles.lattice_steps() == (0.05, 0.1)
    structure = MapStructure(kind="beam", theory="euler", supports="cc", impact_fraction=(0.5,))
    key = tiles.tile_for(structure, "linear", None, 0.3, 2.0)
    zetas, lambdas = key.axes
    assert np.allclose(np.log10(zetas) / 0.05, np.round(np.log10(zetas) / 0.05), atol=1e-9)
    assert zetas[1] <= 0.3 <= zetas[2] and lambdas[1] <= 2.0 <= lambdas[2]
    assert tiles.tile_for(structure, "linear", None, 0.31, 2.1).fingerprint == key.fingerprint
    assert tiles.tile_for(structure, "hertz", None, 0.31, 2.1).fingerprint != key.fingerprint
    assert tiles.tile_for(structure, "linear", None, 0.4, 2.0).fingerprint != key.fingerprint


@pytest.mark.parametrize("target, law, expected", [
    ('type = "plate"\nlength_x = 0.2\nlength_y = 0.3\nthickness = 0.004\nmaterial = "structural-steel"\n'
     'theory = "kirchhoff"\ndamping_ratio = 0.01', "linear", "damping_ratio = 0.01"),
    ('type = "plate"\nlength_x = 0.2\nlength_y = 0.3\ntheory = "mindlin"\nlayup = { ply = "t300-934", '
     'angles_deg = [0, 90, 0, 90, 0], symmetric = true, ply_thickness = 0.000269 }\ndamping_ratio = 0.01', "hertz",
     "damping_ratio = 0.01"),
    ('type = "plate"\nlength_x = 0.2\nlength_y = 0.3\nthickness = 0.01\nmaterial = "structural-steel"\n'
     'theory = "mindlin"', "yigit-christoforou", "fourth number"),
    ('type = "halfspace"\nmaterial = "structural-steel"', "hertz", "target type 'halfspace'"),
])
def test_what_no_map_structure_describes_is_still_refused(target, law, expected):
    """Structural damping (on an isotropic plate and on a laminate: an undamped laminate is
    answered from its own tile, tests/cases/test_laminate_tiles.py), an elastic-plastic law on a Mindlin plate (the sphere radius a fourth number: its clamped beam
    is answered from a plastic tile, tests/maps/test_plastic_tiles.py) and a half-space stay
    refused, naming why and pointing to simulate."""
    case = _case(target, law)
    with pytest.raises(ValueError, match="no shipped map covers this case") as info:
        lookup(case=case, cache_dir="/nonexistent/never-written")
    assert expected in str(info.value) and "impactmaps simulate" in str(info.value)


def test_a_case_no_map_point_can_be_realised_at_is_refused_before_a_tile_is_built(tmp_path, monkeypatch):
    """Found by fuzzing `lookup --case`: a beam 1e-300 m wide has ζ ≈ 6e296; the lookup built a
    tile there (overflows, then a zero Hertz stiffness). Numbers beyond the family's
    ``axis_ranges`` are refused with the reason, and nothing is solved."""
    from impactmaps.cases.case_answer import NoMapError

    def no_tile(*args, **kwargs):
        raise AssertionError("a tile was built")

    monkeypatch.setattr(tiles, "build_tile", no_tile)
    case = _case('type = "beam"\nlength = 0.5\nwidth = 1e-300\nheight = 0.02\nmaterial = "aluminium-6061-t6"\n'
                 'supports = "cc"\n', "hertz")
    with pytest.raises(NoMapError, match=r"no on-demand map reaches its ζ = .*e\+29\d: the hertz map points are "
                                         r"realised for ζ in \[1e-09, 1e\+06\]"):
        lookup(case=case, cache_dir=tmp_path)
