"""Hertz maps over (ζ_h, λ_h): the sweep, the shipped maps, lookups, regimes and the chart.

A Hertz map point is the Hertz impact realising (ζ_h, λ_h) on the structure's reference
target, stored in the Hertz half-space scales (F_max/F_hs, times/t*). By the similarity
of Hertz impacts (tests/contact/test_hertz_similarity.py) it holds for every physical case of
the family with the same numbers: checked here against direct simulations of cases of
other sizes, materials and Hertz stiffnesses.
"""

from __future__ import annotations

import json
import re
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import impactmaps as im
from impactmaps.cli import main
from impactmaps.contact import HertzContact
from impactmaps.closed_forms.hertz_similarity import realise_hertz, unit_speed_stiffness
from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.compute.hertz_points import hertz_asymptote_peak, solve_hertz_points
from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map, require_map_law
from impactmaps.maps.family.regimes import classify
from impactmaps.maps.files.store import StoreMismatchError
from impactmaps.maps.family.structures import MapStructure, structure_from_name
from impactmaps.maps.compute.sweep import _prepare, sweep
from impactmaps.maps.family.map_family import map_law
from impactmaps.solvers.modal_settings import ModalSettings

from ..helpers import ROOT

ALLOY = im.IsotropicMaterial(70e9, 0.3, 2700.0)  # ν of the reference material: same family
STEEL = im.IsotropicMaterial(200e9, 0.3, 7900.0)


def _physical_target(kind):
    """A target of the shipped family of ``kind`` that is not the map's reference target."""
    if kind == "beam":
        return im.Beam.rectangular(0.37, 0.021, 0.013, ALLOY, theory="euler")
    return im.Plate.isotropic(0.27, 0.27, 0.0031, ALLOY)


@pytest.mark.parametrize("structure, theory", [("beam", "euler"), ("plate", "kirchhoff")])
def test_a_map_point_is_a_direct_simulation_of_another_case(structure, theory):
    """A stored Hertz map point equals a direct `simulate` of a physically different case
    with the same (ζ_h, λ_h), run with the settings the stored value was solved with (the
    first refinement), within the point's stated error (+1e-6: where a handful of modes
    suffice, the map keeps ``min_modes`` participating modes and `simulate` ``min_modes``
    modes of which only the participating ones stay, a ~1e-7 difference); a run at the
    default settings lies within the sweep's tolerance (1e-3) of it."""
    dataset = load_shipped_map(structure, theory, "hertz")
    target = _physical_target(structure)
    law = HertzContact(7.3e9)
    for lambda_h, z_index in ((0.0998, 20), (0.792, 45), (5.0, 70)):
        point = dataset.isel(structure=0, zeta=z_index).sel(lambda_=lambda_h, method="nearest")
        assert int(point["status"]) == 0  # converged: stored = first refinement
        zeta_h, lambda_h = float(point["zeta"]), float(point["lambda_"])
        case = realise_hertz(target, zeta_h, lambda_h, law)
        assert abs(math.log10(case.velocity)) > 0.05  # not the map's 1 m/s
        runs = {name: im.simulate(target, law, case.mass, case.velocity, settings=settings, record=False)
                for name, settings in (("refined", ModalSettings().refined()), ("default", ModalSettings()))}
        stored, error = float(point["fmax_normalised"]), float(point["fmax_error"])
        assert abs(runs["refined"].peak_force / case.numbers.force_scale - stored) <= error + 1e-6
        assert abs(runs["default"].peak_force / case.numbers.force_scale - stored) <= 1e-3
        contact = runs["refined"].total_contact_time / case.numbers.time_scale
        assert contact == pytest.approx(float(point["contact_time_normalised"]), rel=1e-5)


@pytest.mark.parametrize("key", list(SHIPPED_MAPS), ids=list(SHIPPED_MAPS.values()))
def test_shipped_hertz_maps_are_complete_hertz_maps_below_the_half_space(key):
    """Every point computed, marked as a Hertz map, F_max/F_hs ≤ 1 (the half-space is the
    stiffest target: no structure makes the contact force larger) and its band holds it;
    a point without a value is exactly an ``unresolved`` one (a Timoshenko/Mindlin
    light-impactor corner beyond the theory), and only shear-deformable maps have them."""
    dataset = load_shipped_map(*key, "hertz")
    assert map_law(dataset) == "hertz" and dataset.attrs["complete"] == 1
    assert dataset["done"].values.all()
    unresolved = dataset["status"].values == STATUSES.index("unresolved")
    assert (key[1] in ("timoshenko", "mindlin")) or not unresolved.any()
    fmax = dataset["fmax_normalised"].values
    assert np.array_equal(~np.isfinite(fmax), unresolved)
    fmax, resolved = fmax[~unresolved], ~unresolved
    assert np.all(fmax > 0.0)
    assert np.all(fmax <= 1.0 + 1e-3)
    assert np.all(dataset["fmax_low"].values[resolved] <= fmax + 1e-15)
    assert np.all(fmax <= dataset["fmax_high"].values[resolved] + 1e-15)
    assert np.all(dataset["time_limit_reached"].values[resolved] == 0)
    # the Hertz grid (ζ_h ∈ [0.005, 100], λ_h ∈ [1e-3, 20] — Mindlin [0.05, 20] —, 40 and
    # 20 per decade) lies inside the linear map's range
    linear = load_shipped_map(*key)
    zetas, lambdas = dataset["zeta"].values, dataset["lambda_"].values
    smallest = 0.05 if key[1] == "mindlin" else 1e-3
    assert np.allclose(zetas, np.geomspace(0.005, 100.0, 173))
    assert np.allclose(lambdas, np.geomspace(smallest, 20.0, 87 if smallest == 1e-3 else 53))
    assert linear["zeta"].values.min() <= zetas.min() and zetas.max() <= linear["zeta"].values.max() * (1 + 1e-12)
    assert linear["lambda_"].values.min() <= lambdas.min() and lambdas.max() <= linear["lambda_"].values.max() * (1 + 1e-12)


def test_a_hertz_map_is_never_read_as_a_linear_one(tmp_path):
    """The law is part of a map's identity: the attribute, the fingerprint (for the Hertz
    law; the linear fingerprints are those of the shipped files) and the file name."""
    hertz = load_shipped_map("plate", "kirchhoff", "hertz")
    with pytest.raises(ValueError, match="hertz contact law, not the linear law"):
        require_map_law(hertz, "linear")
    with pytest.raises(ValueError, match="linear contact law, not the hertz law"):
        require_map_law(load_shipped_map("plate", "kirchhoff"), "hertz")
    structure = MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,))
    linear_description = _prepare([structure], [1.0], [1.0], ModalSettings(), "linear").description
    hertz_description = _prepare([structure], [1.0], [1.0], ModalSettings(), "hertz").description
    assert "law" not in linear_description and hertz_description["law"] == "hertz"
    path = tmp_path / "map.nc"
    sweep([structure], [1.0], [1.0], law="hertz", path=path, progress=False, max_workers=1)
    with pytest.raises(StoreMismatchError, match="changed: law"):
        sweep([structure], [1.0], [1.0], path=path, progress=False, max_workers=1)
    with pytest.raises(ValueError, match="law = 'plastic'"):
        sweep([structure], [1.0], [1.0], law="plastic", progress=False, max_workers=1)
    with pytest.raises(ValueError, match=r"stronge maps: give the grids of \['beta'\]"):
        sweep([structure], [1.0], [1.0], law="stronge", progress=False, max_workers=1)


def test_hertz_asymptotes_and_regimes():
    """The Hertz asymptotes: the quasi-static spring solves F̄^{5/3} + (25/16) F̄²/λ_h = 1
    (energy: ½mV0² = (2/5)K_h α^{5/2} + F²/(2K_st), in the Hertz scales); the infinite plate
    tends to the half-space (1) as ζ_h → 0 and falls with ζ_h. A point at small ζ_h is
    local, one on the quasi-static value is quasi-static."""
    lam = np.array([0.05, 1.0, 20.0])
    quasi = hertz_asymptote_peak("quasi-static", "plate", lambda_h=lam)
    np.testing.assert_allclose(quasi ** (5 / 3) + 25 / 16 * quasi**2 / lam, 1.0, rtol=1e-8)
    plate = hertz_asymptote_peak("infinite", "plate", [1e-4, 0.1, 1.0])
    assert plate[0] == pytest.approx(1.0, abs=2e-3) and plate[0] > plate[1] > plate[2]
    labels = classify([0.99, float(quasi[1])], [0.001, 30.0], [1.0, 1.0], "plate", law="hertz")
    assert list(labels) == ["local", "quasi-static"]
    with pytest.raises(ValueError, match="which"):
        hertz_asymptote_peak("half-space", "plate", 1.0)


def test_the_sweep_point_runs_at_unit_speed():
    """The sweep realises each point with the K_h that makes V0 = 1 m/s (no 1e-9 or 1e6 m/s
    runs over the map range) and solve_hertz_points returns the Hertz-scaled row."""
    structure = structure_from_name("beam-ss-euler")
    target = structure.build()
    for zeta_h, lambda_h in ((0.005, 0.05), (100.0, 20.0)):
        case = realise_hertz(target, zeta_h, lambda_h, unit_speed_stiffness(target, zeta_h, lambda_h))
        assert case.velocity == pytest.approx(1.0, rel=1e-12)
    (row,) = solve_hertz_points(structure, [(0.005, 0.05)], ModalSettings())
    assert row["fmax_normalised"] == pytest.approx(0.985, abs=0.01)  # near the half-space
    assert row["peak_time_normalised"] == pytest.approx(1.47, rel=0.05)  # half-space: 1.4716 t*


def test_lookup_case_on_the_steel_plate_hertz_example(capsys, tmp_path, monkeypatch):
    """examples/steel_plate_hertz.toml (Mindlin plate, a/h = 62.5, λ_h = 0.043): no shipped
    map describes it — `simulate` loads a Hertz impact on a Mindlin plate over the contact
    patch, whose radius the point-loaded maps do not have (the Kirchhoff map would answer
    for another family, +6.4 % against simulate's 731 N). Issues 13/14: lookup builds the
    tile of its structure and patch number P = sqrt(R α_m)/h on demand (one line on stderr
    saying so) and answers within 1 % of simulate and within its own band; from the cache
    the same bits, silently; with --no-build it refuses and points to simulate (it used to
    answer 293 N)."""
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    example = ROOT / "examples" / "steel_plate_hertz.toml"
    assert main(["lookup", "--case", str(example), "--json"]) == 0
    captured = capsys.readouterr()
    values = json.loads(captured.out)
    assert "NaN" not in captured.out and "Infinity" not in captured.out
    # the case's validity warnings (one set, printed by every command that answers a case) aside
    err = [line for line in captured.err.strip().splitlines() if not line.startswith("warning:")]
    assert err[0].startswith("building an on-demand map tile of 16 points for "
                             "plate-ssss-mindlin-s62.5-hertz-P0.07992")
    assert all(re.fullmatch(r"\s*\d+/16 points \(\d+ s\)", line) for line in err[1:])  # its progress
    assert values["map"].startswith("on-demand tile plate-ssss-mindlin-s62.5-hertz-P0.07992")
    assert values["cache_file"].startswith(str(tmp_path)) and values["cache_file"] in err[0]
    assert values["patch_number"] == pytest.approx(0.0799242, rel=1e-5)
    from impactmaps.cases import load_case, run_case

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the contact yields (validity warning): the comparison is elastic
        _, summary = run_case(load_case(example))
    assert summary["peak_force_N"] == pytest.approx(778.56, abs=0.01)  # 731.25 before the 3D-consistent near field
    assert values["peak_force_N"] == pytest.approx(summary["peak_force_N"], rel=0.01)
    assert abs(values["peak_force_N"] - summary["peak_force_N"]) <= values["peak_force_error_N"]
    assert main(["lookup", "--case", str(example), "--json"]) == 0
    cached = capsys.readouterr()
    assert json.loads(cached.out) == values  # from the cache: no building, only the case's validity warnings
    assert all(line.startswith("warning:") for line in cached.err.splitlines())
    assert main(["lookup", "--case", str(example), "--no-build", "--json"]) == 2
    captured = capsys.readouterr()
    assert "Mindlin plate, which simulate loads over the contact patch" in json.loads(captured.out)["error"]
    assert "impactmaps simulate" in json.loads(captured.out)["error"]
    assert len(captured.err.strip().splitlines()) == 1


def test_lookup_command_with_the_hertz_law(capsys, tmp_path):
    """`lookup --law hertz --zeta --lambda` reads the Hertz map (strict JSON with band and
    status); `--case` with a Hertz case answers in newtons, as simulate within the band; a --law that contradicts the
    case, or an unknown law, exits 2 with one line."""
    assert main(["lookup", "--kind", "beam", "--theory", "euler", "--zeta", "0.3", "--lambda", "2",
                 "--law", "hertz", "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["map"] == "beam-ss-euler-hertz" and values["law"] == "hertz"
    assert 0.0 < values["fmax_normalised"] <= 1.0 and values["status"] in ("converged", "refined", "interpolated", "sensitive")
    case = tmp_path / "case.toml"
    case.write_text(
        '[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 1.0\n'
        '[target]\ntype = "beam"\nlength = 0.3\nwidth = 0.02\nheight = 0.03\n'
        'material = "aluminium-6061-t6"\ntheory = "euler"\nsupports = "ss"\n'
        '[contact]\nlaw = "hertz"\n')
    assert main(["lookup", "--case", str(case), "--json"]) == 0
    text = capsys.readouterr().out
    values = json.loads(text)
    assert "NaN" not in text and "Infinity" not in text
    assert values["law"] == "hertz" and values["peak_force_N"] == pytest.approx(
        values["fmax_normalised"] * values["force_scale_N"])
    from impactmaps.cases import load_case, run_case

    _, summary = run_case(load_case(case))  # a 20 mm ball at 1 m/s on a 0.3 m beam: ζ_h 0.055, λ_h 0.16
    assert abs(values["peak_force_N"] - summary["peak_force_N"]) <= \
        values["peak_force_error_N"] + 1e-3 * values["force_scale_N"]
    assert main(["lookup", "--case", str(case), "--law", "linear"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--law = linear contradicts the case (hertz)" in err[0]
    assert main(["lookup", "--kind", "beam", "--theory", "euler", "--zeta", "0.3", "--lambda", "2",
                 "--law", "stronge"]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_chart_command_with_the_hertz_law(capsys, tmp_path):
    """`chart --law hertz` on a tiny grid: the Hertz sweep, figures and table (strict JSON of
    the paths); the same output directory refuses a linear chart without --overwrite."""
    out = tmp_path / "chart"
    args = ["chart", "--out", str(out), "--zeta-range", "0.05", "1", "--zeta-count", "3",
            "--lambdas", "0.5", "2", "--workers", "1", "--quiet", "--json"]
    assert main([*args, "--law", "hertz"]) == 0
    paths = json.loads(capsys.readouterr().out)
    assert Path(paths["png"]).is_file() and Path(paths["netcdf"]).is_file()
    assert "F_hs" in Path(paths["markdown"]).read_text()
    import xarray as xr

    with xr.open_dataset(paths["netcdf"], engine="scipy") as stored:
        assert map_law(stored) == "hertz"
    assert main(args) == 2
    assert "changed: law" in capsys.readouterr().err


def test_sweep_config_with_the_hertz_law(capsys, tmp_path):
    """`impactmaps sweep` takes ``law = "hertz"`` at the top of the TOML file; an unknown law
    exits 2 with one line naming the key, an elastic-plastic law without its β grid with one
    line naming the grid it needs."""
    config = tmp_path / "hertz.toml"
    config.write_text('output = "out"\nlaw = "hertz"\n[grid]\nzeta = [0.1, 1.0]\nlambda = [1.0]\n'
                      '[[structure]]\nkind = "beam"\n')
    assert main(["sweep", str(config), "--quiet", "--workers", "1", "--json"]) == 0
    import xarray as xr

    with xr.open_dataset(json.loads(capsys.readouterr().out)["netcdf"], engine="scipy") as stored:
        assert map_law(stored) == "hertz"
        assert np.all(stored["fmax_normalised"].values <= 1.0)
    config.write_text(config.read_text().replace('"hertz"', '"plastic"'))
    assert main(["sweep", str(config), "--quiet", "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "law = 'plastic' is invalid" in err[0]
    config.write_text(config.read_text().replace('"plastic"', '"stronge"'))
    assert main(["sweep", str(config), "--quiet", "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "[grid] of the stronge law needs 'zeta', 'lambda', 'beta'" in err[0]
