"""Issue 30 step 1: a lookup is an interpolation of what the map stores, nothing else.

Every shipped (ζ, λ) map stores the asymptote peaks its regimes are judged by
(``data_build/add_asymptote_peaks.py``); a lookup interpolates F̄max, its band, its status
and those peaks, and classifies. Checked here: with every asymptote function patched to
raise, every shipped map still answers ``lookup`` of numbers and of a case; the answers are
those of the code that computed the asymptotes per point (values recorded from the base
commit b4b262f, ``tests/data/lookup_reference.npz``: F̄max, band and status bit for bit,
regimes equal except where the stored peaks' interpolation error can reach across a
criterion); the prepared reader interpolates bit-identically to
:func:`impactmaps.maps.family.refinement.interpolate`; the stored peaks are the asymptotes at the
grid values; the cache of prepared maps follows the file.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr

from impactmaps.maps.family.accuracy import REIMPACT_ERROR_FLOOR
from impactmaps.maps.family.accuracy import BAND_TOLERANCE

from ..helpers import DATA, ROOT, VALIDATION, repository_module

REFERENCE = DATA / "lookup_reference.npz"
#: At most this fraction of the recorded points may change regime, each only where the
#: stored peaks' interpolation error reaches across a criterion (measured at 10⁴ points per
#: map by validation/lookup_equivalence.py: see docs/validation.rst).
REGIME_CHANGE_BOUND = 1e-3


def _equivalence(monkeypatch):
    monkeypatch.syspath_prepend(str(VALIDATION))
    return repository_module("validation/lookup_equivalence.py")


def _raise(*args, **kwargs):
    raise AssertionError("a lookup computed an asymptote")


def _patch_asymptotes(monkeypatch) -> None:
    """Every entry point that computes an asymptote peak raises."""
    import impactmaps.closed_forms.law_asymptotes as law_asymptotes
    import impactmaps.closed_forms.law_asymptotes.beam as beam
    import impactmaps.closed_forms.law_asymptotes.local as local
    import impactmaps.maps.compute.hertz_points as hertz_points
    import impactmaps.maps.family.regimes as regimes
    from impactmaps.maps.compute.hertz_points import HertzFamily
    from impactmaps.maps.compute.linear_points import LinearFamily
    from impactmaps.targets import Beam, Plate

    for module, names in ((law_asymptotes, ("asymptote", "infinite_beam_impact_any_law", "infinite_plate_impact",
                                            "quasi_static_impact", "halfspace_asymptote")),
                          (beam, ("infinite_beam_impact_any_law", "_march")),
                          (local, ("infinite_plate_impact", "quasi_static_impact", "_two_phase_impact")),
                          (hertz_points, ("asymptote", "hertz_asymptote_peak", "_asymptote_peak")),
                          (regimes, ("infinite_structure_peak", "quasi_static_peak"))):
        for name in names:
            monkeypatch.setattr(module, name, _raise)
    for cls in (LinearFamily, HertzFamily):
        monkeypatch.setattr(cls, "infinite_peak", _raise)
        monkeypatch.setattr(cls, "quasi_static_peak", _raise)
    for cls in (Beam, Plate):
        monkeypatch.setattr(cls, "infinite_structure_peak", classmethod(_raise))


def _inside_points(dataset: xr.Dataset, count: int, seed: int) -> dict:
    """Centres of ``count`` random grid cells whose corners all hold a value, and one grid point."""
    axes = [name for name in ("beta", "lambda_", "zeta") if name in dataset.dims]
    fmax = dataset["fmax_normalised"].isel(structure=0).values
    good = np.isfinite(fmax) & (dataset["status"].isel(structure=0).values != 4)  # 4: unresolved
    corners = np.ones(tuple(n - 1 for n in good.shape), bool)
    for offset in np.ndindex(*(2,) * good.ndim):
        corners &= good[tuple(slice(o, o + n - 1) for o, n in zip(offset, good.shape))]
    chosen = np.random.default_rng(seed).choice(np.flatnonzero(corners), count, replace=False)
    index = np.unravel_index(chosen, corners.shape)
    out = {}
    for axis, cell in zip(axes, index):
        grid = np.log(dataset[axis].values)
        out[axis] = np.exp(np.append(0.5 * (grid[cell] + grid[cell + 1]), grid[cell[0]]))
    return out


#: The maps and cases of the default run (one refined linear map, one refined Hertz map, one
#: slenderness member, one plastic map; a linear, a Hertz and a plastic case); the slow run: all.
_QUICK_MAPS = ("beam-euler-linear", "plate-kirchhoff-hertz", "plate-mindlin-linear-s10", "plate-kirchhoff-yc")
_QUICK_CASES = (0, 3, 9)


@pytest.mark.parametrize("every", [False, pytest.param(True, marks=pytest.mark.slow)], ids=["some", "every"])
def test_every_shipped_map_answers_with_the_asymptotes_patched_to_raise(monkeypatch, every):
    """Must show (issue 30): with the law asymptotes' entry points, the regimes module's peak
    functions and the families' and targets' peaks all raising, every shipped map (the slow
    run; the default run: four of them) is read from its file and answers ``lookup`` (or
    ``lookup(β, ζ, λ, law=…)``) vectorised and one point at a time at in-range points, and
    ``lookup(case=…)`` answers a case of every shipped family — the same answers as unpatched."""
    from impactmaps.maps.read import lookup as lookup_module
    from impactmaps import lookup

    equivalence = _equivalence(monkeypatch)
    warnings.simplefilter("ignore")  # the Mindlin maps' point-load warning
    keys = equivalence.shipped_keys()
    assert len(keys) == 23
    if not every:
        keys = [key for key in keys if equivalence._name(key) in _QUICK_MAPS]
    calls = []
    for number, key in enumerate(keys):
        numbers = _inside_points(equivalence._dataset(key), 6, number)
        if key[2] in ("linear", "hertz"):
            def call(zeta, lam, key=key):
                found = lookup(zeta, lam, kind=key[0], theory=key[1], law=key[2], slenderness=key[3])
                return found.fmax_normalised, found.fmax_error, found.status, found.regime
            calls.append((call, (numbers["zeta"], numbers["lambda_"])))
        else:
            def call(beta, zeta, lam, key=key):
                found = lookup(beta, zeta, lam, kind=key[0], theory=key[1], law=key[2])
                return found.fmax_normalised, found.fmax_error, found.status, found.restitution
            calls.append((call, (numbers["beta"], numbers["zeta"], numbers["lambda_"])))
    cases = _family_cases()
    if not every:
        cases = [cases[index] for index in _QUICK_CASES]

    lookup_module._prepared_shipped.cache_clear()  # read from the files under the patches
    with monkeypatch.context() as patches:
        _patch_asymptotes(patches)
        answered = [(call(*arguments), call(*(values[0] for values in arguments))) for call, arguments in calls]
        case_answers = [lookup(case=case, build=False) for case in cases]
    for (call, arguments), (many, single) in zip(calls, answered):
        assert np.all(np.isfinite(many[0])) and np.all(np.isin(many[2], ["converged", "refined", "interpolated",
                                                                          "sensitive", "asymptotic"]))
        for got, want, one in zip(many, call(*arguments), single):
            np.testing.assert_array_equal(got, want)
            assert one == np.asarray(want)[0]
    assert [lookup(case=case, build=False) for case in cases] == case_answers


def _family_cases() -> list:
    """One physical case of each shipped family ``lookup(case=…)`` reads: linear and Hertz on the SS
    Euler beam, the SSSS Kirchhoff plate and SS Timoshenko beams at slenderness 20 and 30;
    Yigit–Christoforou, Stronge and epp on the Euler beam, the Kirchhoff plate and the s = 20
    Timoshenko beam. (Mindlin plates: lookup refuses point loads, and a Hertz contact
    loads a patch.)"""
    from impactmaps.cases import parse_case
    from impactmaps.dimensionless import realise
    from impactmaps.closed_forms.hertz_similarity import realise_hertz
    from impactmaps.materials import material
    from impactmaps.targets import Beam, Plate

    steel = material("structural-steel")
    targets = {
        "euler": (Beam.rectangular(0.5, 0.02, 0.02, steel, theory="euler"),
                  'type = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.02\ntheory = "euler"'),
        "kirchhoff": (Plate.isotropic(0.3, 0.3, 0.004, steel),
                      'type = "plate"\nlength_x = 0.3\nlength_y = 0.3\nthickness = 0.004\ntheory = "kirchhoff"'),
        "timoshenko": (Beam.rectangular(0.5, 0.02, 0.025, steel, theory="timoshenko"),
                       'type = "beam"\nlength = 0.5\nwidth = 0.02\nheight = 0.025\ntheory = "timoshenko"'),
        "timoshenko-30": (Beam.rectangular(0.6, 0.02, 0.02, steel, theory="timoshenko"),
                          'type = "beam"\nlength = 0.6\nwidth = 0.02\nheight = 0.02\ntheory = "timoshenko"'),
    }
    cases = []
    for target, table in targets.values():
        table += '\nmaterial = "structural-steel"'
        impactor = realise(target, 0.7, 0.3)
        cases.append(parse_case(f'[impactor]\nradius = 0.005\nmaterial = "structural-steel"\n'
                                f'mass = {float(impactor.impactor_mass)!r}\nvelocity = 1.0\n[target]\n{table}\n'
                                f'[contact]\nlaw = "linear"\nstiffness = {float(impactor.contact_stiffness)!r}\n'))
        text = ('[impactor]\nradius = 0.005\nmaterial = "structural-steel"\nmass = 1.0\nvelocity = 1.0\n'
                f'[target]\n{table}\n[contact]\nlaw = "hertz"\n')
        impact = realise_hertz(target, 0.7, 0.3, parse_case(text).law)
        cases.append(parse_case(text.replace("mass = 1.0", f"mass = {impact.mass!r}")
                                .replace("velocity = 1.0", f"velocity = {impact.velocity!r}")))
    for law in ("yigit-christoforou", "stronge", "epp"):
        for name in ("euler", "kirchhoff", "timoshenko"):
            table = targets[name][1] + '\nmaterial = "structural-steel"'
            cases.append(parse_case(f'[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 1.0\n'
                                    f'[target]\n{table}\n[contact]\nlaw = "{law}"\n'))
    return cases


@pytest.mark.parametrize("every", [False, pytest.param(True, marks=pytest.mark.slow)], ids=["some", "every"])
def test_lookups_answer_what_the_asymptote_computing_lookups_answered(monkeypatch, every):
    """Answers at 12 random points per shipped map (the default run: the maps without a
    refinement and two with one, whose reading costs seconds) recorded from the base commit b4b262f
    (``lookup_equivalence.py --record``, regimes included): the same refusals, F̄max, band
    and status bit for bit; a regime differs only at a point where the stored peaks'
    interpolation error (twice its largest at the grid cells' midpoints) reaches across a
    criterion, and at no more than :data:`REGIME_CHANGE_BOUND` of the points."""
    from impactmaps.maps.files.shipped import shipped_name
    from impactmaps.maps.read.lookup import shipped_reader
    from impactmaps.maps.read.reader import read_values
    from impactmaps.maps.family.map_family import map_family

    equivalence = _equivalence(monkeypatch)
    recorded = np.load(REFERENCE, allow_pickle=False)
    changed = total = 0
    refined = {path.stem for path in (ROOT / "impactmaps" / "maps" / "data" / "refinements").iterdir()
               if path.suffix in (".nc", ".npz")}
    for key in equivalence.shipped_keys():
        name = equivalence._name(key)
        if not every and name not in _QUICK_MAPS and shipped_name(*key) in refined:
            continue
        numbers = {axis: recorded[f"{name}/{axis}"] for axis in ("beta", "zeta", "lambda_")
                   if f"{name}/{axis}" in recorded}
        new = equivalence.answers(key, numbers)
        answered = recorded[f"{name}/refusal"] == ""
        np.testing.assert_array_equal(new["refusal"].astype(str), recorded[f"{name}/refusal"])
        np.testing.assert_array_equal(new["fmax"][answered], recorded[f"{name}/fmax"][answered], err_msg=name)
        # the packed refinements keep each point's own band to 8 bits, rounded up (maps/files/data_io.py):
        # a band only widens, by less than 2⁻⁷ — and since issue 40 by the floors of the points' own
        # error (maps/family/accuracy.stated_error, applied when a map is read), by at most the larger floor
        band, recorded_band = new["band"][answered], recorded[f"{name}/band"][answered]
        assert np.all(band >= recorded_band), name
        assert np.all(band <= recorded_band * (1 + 2.0**-7) + REIMPACT_ERROR_FLOOR), name
        # a status changes only where the floors widened a converged answer's band past the tolerance
        status, recorded_status = new["status"][answered].astype(str), recorded[f"{name}/status"][answered].astype(str)
        widened = np.isin(recorded_status, ["converged", "refined"]) & (band > BAND_TOLERANCE)
        np.testing.assert_array_equal(np.where(widened, "interpolated", recorded_status), status, err_msg=name)
        differ = new["regime"][answered].astype(str) != recorded[f"{name}/regime"][answered]
        # the classifier's rule since the recording: a peak before the first reflection is never
        # quasi-static (maps/family/regimes.py): such points may move from quasi-static to
        # infinite-structure anywhere, not only where the interpolation reaches across a criterion
        differ &= ~((recorded[f"{name}/regime"][answered] == "quasi-static")
                    & (new["regime"][answered].astype(str) == "infinite-structure"))
        total += int(answered.sum())
        if differ.any():
            changed += int(differ.sum())
            structure, theory, law, slenderness = key
            errors = [2.0 * e for e in equivalence.peak_errors(key)]
            values = read_values(None, map_family(law), (numbers["zeta"][answered][differ],
                                                         numbers["lambda_"][answered][differ]),
                                 ("zeta", "lambda"), where=name,
                                 prepared=shipped_reader(structure, theory, law, slenderness)[0]).values
            assert equivalence.at_risk(values["fmax_normalised"], values["infinite_structure_peak"],
                                       values["quasi_static_peak"], *errors).all(), name
    assert total > (150 if every else 80)
    assert changed <= REGIME_CHANGE_BOUND * total


@pytest.mark.parametrize("name", ["plate-ssss-kirchhoff-hertz", "beam-ss-timoshenko-s20"])
def test_the_prepared_reader_interpolates_as_the_refinement_reader(name):
    """:class:`PlaneInterpolator` (the leaves as index tables) gives bit for bit the values,
    bands and corner statuses of :func:`impactmaps.maps.family.refinement.interpolate`, at random
    positions, on grid lines and nodes and on the last row and column."""
    from impactmaps.maps.read.interpolator import PlaneInterpolator, grid_bilinear
    from impactmaps.maps.files.shipped import load_shipped_map, load_shipped_refinement
    from impactmaps.maps.read.interpolator import interpolation_error
    from impactmaps.maps.family.refinement import Refinement, interpolate

    law = "hertz" if name.endswith("hertz") else "linear"
    key = ("plate", "kirchhoff", law) if name.startswith("plate") else ("beam", "timoshenko", law)
    dataset = load_shipped_map(*key)
    refinement = load_shipped_refinement(*key)
    base = {n: dataset[n].isel(structure=0).values
            for n in ("fmax_normalised", "fmax_error", "status", "log_peak_time", "log_reflection_time")}
    estimate = interpolation_error(base["fmax_normalised"])
    rng = np.random.default_rng(3)
    rows, cols = base["fmax_normalised"].shape
    row, col = rng.uniform(0, rows - 1, 4000), rng.uniform(0, cols - 1, 4000)
    row[:300], col[200:500] = np.round(row[:300]), np.round(col[200:500] * 8) / 8
    row[-20:], col[-10:] = rows - 1, cols - 1
    for reading in (refinement, None):
        old = interpolate(reading or Refinement.empty((rows, cols)), base, estimate, row, col)
        new = PlaneInterpolator(base, estimate, reading).interpolate(row, col)
        np.testing.assert_array_equal(new[0]["fmax_normalised"], old[0]["fmax_normalised"])
        np.testing.assert_array_equal(new[1], old[1])
        for got, want in zip(new[2], old[2]):
            np.testing.assert_array_equal(got, want)
    from impactmaps.maps.read import interpolator
    from impactmaps.maps.family.refinement import Leaves, leaf_estimate

    indexed = interpolator._IndexedRefinement.of(refinement)
    leaves = interpolator._leaves(indexed)
    pick = rng.choice(leaves.u.size, 5000, replace=False)
    some = Leaves(leaves.level[pick], leaves.u[pick], leaves.v[pick], leaves.side[pick])
    np.testing.assert_array_equal(interpolator._surplus_estimates(indexed, leaves)[pick],
                                  leaf_estimate(refinement, some, np.zeros(refinement.shape)))
    times = ("log_peak_time", "log_reflection_time")
    old = interpolate(Refinement.empty((rows, cols)), base, estimate, row, col, times)[0]
    new = grid_bilinear(base, row, col, times, Refinement.empty((rows, cols)).scale)
    for variable in times:
        np.testing.assert_array_equal(new[variable], old[variable])


@pytest.mark.parametrize("law", ["linear", pytest.param("hertz", marks=pytest.mark.slow)])
def test_the_stored_peaks_are_the_asymptotes_at_the_grid_values(monkeypatch, law):
    """Each shipped (ζ, λ) map stores the family's asymptote peaks at its grid values, bit for
    bit: the linear maps' at every grid value of the plates (closed forms) and every tenth of
    the beams (the infinite beam's root search); the Hertz maps' at three grid values each
    (each an integration: the slow run)."""
    from impactmaps.maps.family.map_family import ASYMPTOTE_PEAKS
    from impactmaps.maps.family.regimes import infinite_structure_peak, quasi_static_peak

    equivalence = _equivalence(monkeypatch)
    for key in equivalence.shipped_keys():
        structure = key[0]
        if key[2] != law:
            continue
        dataset = equivalence._dataset(key)
        assert all(name in dataset for name in ASYMPTOTE_PEAKS), key
        for name, axis, exact in (("infinite_structure_peak", "zeta", lambda x: infinite_structure_peak(x, structure, law)),
                                  ("quasi_static_peak", "lambda_", lambda x: quasi_static_peak(x, law))):
            size = dataset.sizes[axis]
            pick = ([0, size // 2, size - 1] if law == "hertz"
                    else slice(None, None, 10 if structure == "beam" and axis == "zeta" else 1))
            np.testing.assert_array_equal(dataset[name].isel(structure=0).values[pick],
                                          exact(dataset[axis].values[pick]), err_msg=f"{key} {name}")


def test_the_prepared_map_follows_its_file(tmp_path, monkeypatch):
    """The cache of prepared shipped maps is keyed by the file's identity: a map rewritten on
    disk is read again (a cache never changes an answer), an unchanged one is not."""
    from impactmaps.maps.read import lookup as lookup_module
    from impactmaps.maps.files.data_io import read_dataset
    from impactmaps.maps.files.store import save_atomic

    name = "plate-ssss-mindlin-s10"
    sources = lookup_module._shipped_sources(name)
    copy = tmp_path / f"{name}.nc"
    save_atomic(read_dataset(sources[0]), copy)
    monkeypatch.setattr(lookup_module, "_shipped_sources", lambda stem: (str(copy), str(tmp_path / "none.nc")))
    warnings.simplefilter("ignore")
    first = lookup_module.shipped_reader("plate", "mindlin", "linear", 10.0)[0]
    assert lookup_module.shipped_reader("plate", "mindlin", "linear", 10.0)[0] is first
    answer = lookup_module.point_answer(1.0, 0.2, kind="plate", theory="mindlin", slenderness=10.0).fmax_normalised
    changed = read_dataset(copy)
    changed["fmax_normalised"] = changed["fmax_normalised"] * 2.0
    save_atomic(changed, copy)
    assert lookup_module.shipped_reader("plate", "mindlin", "linear", 10.0)[0] is not first
    again = lookup_module.point_answer(1.0, 0.2, kind="plate", theory="mindlin", slenderness=10.0).fmax_normalised
    assert again == pytest.approx(2.0 * answer, rel=1e-12)
