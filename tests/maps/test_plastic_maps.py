"""Elastic-plastic maps over (β, ζ, λ): the similarity they rest on, the shipped maps, their lookup.

Issue 13 item 2: for the Yigit–Christoforou and the refined Stronge law the impact number β
is the third axis (:mod:`impactmaps.maps.compute.plastic_points`).
"""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.materials import IsotropicMaterial
from impactmaps.solvers.modal_settings import ModalSettings
from impactmaps.solvers.modal import simulate
from impactmaps.targets import Beam, Plate

STEEL = IsotropicMaterial(youngs_modulus=210e9, poisson_ratio=0.3, density=7850.0)
ALUMINIUM = IsotropicMaterial(youngs_modulus=69e9, poisson_ratio=0.33, density=2700.0)


def _pair(kind):
    """Two physically different targets of one map family (sizes, materials, Poisson ratio
    of a Kirchhoff plate drop out of its normalised response only through D*, so keep ν)."""
    if kind == "beam":
        return (Beam.rectangular(0.5, 0.02, 0.01, STEEL, theory="euler"),
                Beam.rectangular(1.3, 0.05, 0.03, ALUMINIUM, theory="euler"))
    aluminium = IsotropicMaterial(youngs_modulus=69e9, poisson_ratio=0.3, density=2700.0)
    return Plate.isotropic(0.3, 0.3, 0.004, STEEL), Plate.isotropic(0.8, 0.8, 0.012, aluminium)


def _normalised(target, realised):
    from impactmaps.maps.compute.plastic_points import plastic_summary

    result = simulate(target, realised.law, realised.mass, realised.velocity, settings=ModalSettings(),
                      record=False)
    return plastic_summary(result, realised)


@pytest.mark.parametrize("law", ["yc", "stronge"])
@pytest.mark.parametrize("kind", ["beam", "plate"])
@pytest.mark.parametrize("numbers", [(30.0, 0.3, 0.5), (400.0, 0.05, 0.03), (2.0, 2.0, 5.0)])
def test_equal_numbers_give_equal_normalised_response(kind, law, numbers):
    """Two physically different impacts (other size, material, impactor mass and speed,
    K_h and α_y) with equal (β, ζ, λ) give equal F_max/(m V0 ω_y), restitution, absorbed
    and transferred energy fractions, number of impacts and contact time to 1e-6: the
    similarity the plastic maps rest on (docs/plastic_maps.rst)."""
    from impactmaps.maps.compute.plastic_points import plastic_numbers, realise_plastic

    beta, zeta, lam = numbers
    first, second = _pair(kind)
    one = realise_plastic(first, law, beta, zeta, lam, velocity=1.0)
    two = realise_plastic(second, law, beta, zeta, lam, velocity=7.3)
    assert abs(one.mass / two.mass - 1) > 0.5 and abs(float(one.numbers.force_scale) / two.numbers.force_scale - 1) > 0.5
    for realised, target in ((one, first), (two, second)):
        check = plastic_numbers(target, realised.law, realised.mass, realised.velocity)
        assert np.allclose([check.impact_number, check.loss_factor, check.relative_stiffness], numbers, rtol=1e-12)
    a, b = _normalised(first, one), _normalised(second, two)
    assert a["impacts"] == b["impacts"]
    for key in ("fmax_normalised", "restitution", "absorbed_energy_fraction", "energy_transferred_fraction",
                "contact_time_normalised", "peak_time_normalised"):
        assert a[key] == pytest.approx(b[key], rel=1e-6, abs=1e-9), key
    # the energy ledger closes: rebound + contact dissipation + structure = impact energy
    assert a["restitution"] ** 2 + a["absorbed_energy_fraction"] + a["energy_transferred_fraction"] == \
        pytest.approx(1.0, abs=1e-3)


def test_a_physical_case_is_realised_by_its_numbers():
    """A physical Yigit–Christoforou case (steel ball on a steel beam, from a case file) has
    numbers (β, ζ, λ); their realisation on the map's reference beam gives the same
    normalised answer — the route `lookup --case` takes."""
    from impactmaps.cases import parse_case
    from impactmaps.maps.compute.plastic_points import plastic_numbers, realise_plastic
    from impactmaps.maps.family.structures import DEFAULT_STRUCTURES

    case = parse_case('[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 0.05\n'
                      '[target]\ntype = "beam"\nlength = 0.6\nwidth = 0.02\nheight = 0.01\n'
                      'material = "structural-steel"\ntheory = "euler"\n[contact]\nlaw = "yigit-christoforou"\n')
    numbers = plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)
    reference = DEFAULT_STRUCTURES[0].build()
    realised = realise_plastic(reference, "yc", numbers.impact_number, numbers.loss_factor,
                               numbers.relative_stiffness)
    direct = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=ModalSettings(),
                      record=False)
    mapped = _normalised(reference, realised)
    assert direct.peak_force / numbers.force_scale == pytest.approx(mapped["fmax_normalised"], rel=1e-6)
    assert direct.restitution == pytest.approx(mapped["restitution"], rel=1e-6)


def test_numbers_refuse_other_laws():
    from impactmaps.contact.hertz import HertzContact
    from impactmaps.contact.plastic.stronge import StrongeContact
    from impactmaps.maps.family.builtin_families import plastic_law_of

    assert plastic_law_of(StrongeContact(1e11, 0.01, 3e8)) == "stronge"
    with pytest.raises(ValueError, match="plastic_pressure_factor"):
        plastic_law_of(StrongeContact(1e11, 0.01, 3e8, plastic_pressure_factor=3.0))
    with pytest.raises(ValueError, match="not an elastic-plastic law"):
        plastic_law_of(HertzContact(1e10))


# -- the shipped maps ---------------------------------------------------------------------------
def _shipped():
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps.maps.files.shipped import load_shipped_map

    return [load_shipped_map(kind, theory, law) for kind, theory in PLASTIC_MAPS for law in ("yc", "stronge")]


def test_shipped_plastic_maps_are_complete_and_consistent():
    """Every shipped plastic map: every point solved, with a status; finite values and errors
    of all three quantities except at ``unresolved`` points (beyond what the Timoshenko
    theory holds: no value at all); the energy ledger closed (e² + absorbed + transferred
    = 1 wherever the sphere separated); its law recorded (it cannot be read as a linear or
    Hertz map)."""
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.files.shipped import require_map_law

    for dataset in _shipped():
        law = dataset.attrs["contact_law"]
        assert law in ("yc", "stronge") and int(dataset.attrs["complete"]) == 1
        assert set(dataset["fmax_normalised"].dims) == {"structure", "beta", "lambda_", "zeta"}
        assert np.all(dataset["done"].values == 1) and np.all(dataset["status"].values >= 0)
        resolved = dataset["status"].values != STATUSES.index("unresolved")
        assert resolved.mean() > 0.75  # Timoshenko beams: light impactors pass a quarter of the thickness-shear
        # cut-off (targets/shear_range.py), 17 % (YC) and 22 % (Stronge) of the grid; Euler and Kirchhoff: none
        for name in ("fmax_normalised", "fmax_error", "absorbed_energy_fraction", "absorbed_energy_error"):
            assert np.all(np.isfinite(dataset[name].values[resolved])), name
            assert np.all(np.isnan(dataset[name].values[~resolved])), name
        separated = np.isfinite(dataset["restitution"].values)
        ledger = (dataset["restitution"] ** 2 + dataset["absorbed_energy_fraction"]
                  + dataset["energy_transferred_fraction"]).values[separated]
        assert separated.sum() > 0.99 * resolved.sum() and np.allclose(ledger, 1.0, atol=5e-3)
        with pytest.raises(ValueError, match="not the linear law"):
            require_map_law(dataset, "linear")


def test_a_map_point_is_the_direct_solution():
    """A grid point of a shipped map is what solve_plastic_points gives for it (to a few ulp:
    the map was built with another build of the numeric libraries; same-build bit equality is
    tested by the sweep tests)."""
    from impactmaps.maps.files.shipped import load_shipped_map
    from impactmaps import lookup
    from impactmaps.maps.compute.plastic_points import solve_plastic_points
    from impactmaps.maps.family.structures import DEFAULT_STRUCTURES

    dataset = load_shipped_map("beam", "euler", "yc")
    beta, lam, zeta = (float(dataset[axis].values[k]) for axis, k in (("beta", 4), ("lambda_", 9), ("zeta", 12)))
    row = solve_plastic_points(DEFAULT_STRUCTURES[0], "yc", [(beta, zeta, lam)])[0]
    stored = dataset.isel(structure=0).sel(beta=beta, lambda_=lam, zeta=zeta)
    for name in ("fmax_normalised", "restitution", "absorbed_energy_fraction", "fmax_error"):
        assert float(stored[name]) == pytest.approx(row[name], rel=1e-14, abs=1e-15), name
    found = lookup(beta, zeta, lam, kind="beam", theory="euler", law="yc")
    assert found.fmax_normalised == pytest.approx(row["fmax_normalised"], abs=1e-12)


def test_lookup_plastic_refuses_next_to_an_unresolved_point():
    """Where the Timoshenko map holds no value (beyond its theory) the lookup refuses."""
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.files.shipped import load_shipped_map
    from impactmaps import lookup

    dataset = load_shipped_map("beam", "timoshenko", "yc").isel(structure=0)
    at = np.argwhere(dataset["status"].values == STATUSES.index("unresolved"))[0]
    beta, lam, zeta = (float(dataset[axis].values[k]) for axis, k in zip(("beta", "lambda_", "zeta"), at))
    with pytest.raises(ValueError, match="holds no value .unresolved"):
        lookup(beta, zeta, lam, kind="beam", theory="timoshenko", law="yc")


def test_lookup_plastic_refuses_outside_the_map():
    from impactmaps import lookup

    with pytest.raises(ValueError, match=r"beta = 5000.0 is outside the shipped map: valid range is \[1, "):
        lookup(5000.0, 0.1, 0.1, kind="beam", theory="euler", law="yc")
    with pytest.raises(ValueError, match="relative_stiffness .* outside the shipped map: valid range is"):
        lookup(10.0, 0.1, 0.005, kind="plate", theory="kirchhoff", law="yc")
    with pytest.raises(ValueError, match="kind, theory"):
        lookup(10.0, 0.1, 0.1, kind="plate", theory="mindlin", law="yc")


_YC_BEAM = ('[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 1.0\n'
            '[target]\ntype = "beam"\nlength = 0.6\nwidth = 0.02\nheight = 0.02\n'
            'material = "structural-steel"\ntheory = "euler"\n[contact]\nlaw = "yigit-christoforou"\n')


def test_lookup_command_answers_a_plastic_case(tmp_path, capsys):
    """`impactmaps lookup --case` on a Yigit–Christoforou case prints the peak force with its
    band and the status, the restitution and the absorbed energy; outside the map, with
    --no-build, it exits 2 with one line naming the number and suggesting simulate (without,
    a plastic tile answers)."""
    import json

    from impactmaps.cli import main

    case = tmp_path / "yc.toml"
    case.write_text(_YC_BEAM)
    assert main(["lookup", "--case", str(case), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["law"] == "yc" and out["map"] == "beam-ss-euler-yc"
    for key in ("peak_force_N", "peak_force_error_N", "status", "restitution", "restitution_error",
                "absorbed_energy_J", "absorbed_energy_error_J", "beta", "zeta", "lambda"):
        assert key in out, key
    assert 0 < out["restitution"] < 1 and out["absorbed_energy_J"] > 0 and out["peak_force_error_N"] >= 0
    case.write_text(_YC_BEAM.replace("velocity = 1.0", "velocity = 80.0"))
    assert main(["lookup", "--case", str(case), "--no-build"]) == 2
    error = capsys.readouterr().err.strip()
    assert len(error.splitlines()) == 1
    assert "no shipped map covers this case: beta" in error and "impactmaps simulate" in error
    # without --no-build: a plastic tile of the same family beyond the map (tests/maps/test_plastic_tiles.py)
    assert main(["lookup", "--case", str(case), "--json", "--quiet"]) == 0
    assert json.loads(capsys.readouterr().out)["map"].startswith("on-demand tile beam-ss-euler-yc β ")


# -- the chart ------------------------------------------------------------------------------------
def test_plastic_chart_from_the_maps(tmp_path):
    """`chart --law yc` (make_plastic_chart): F̄max, restitution and absorbed energy against ζ
    at a few β for one λ, drawn from the shipped maps; the data drawn in a CSV."""
    import argparse

    import pandas as pd

    from impactmaps.cli.commands_maps import cmd_chart

    args = argparse.Namespace(law="yc", out=str(tmp_path / "chart"), lambdas=[0.3], workers=None,
                              overwrite=False, betas=[3.0, 300.0], zeta_range=(0.005, 100.0), zeta_count=200,
                              quiet=True)
    paths = cmd_chart(args)
    for key in ("png", "svg", "csv"):
        assert (tmp_path / "chart" / f"fmax_chart_yc.{key}").exists() and key in paths
    frame = pd.read_csv(paths["csv"])
    assert set(frame["structure"]) == {"beam-ss-euler", "plate-ssss-kirchhoff"}
    assert frame["beta"].nunique() == 2 and frame.groupby("structure")["lambda"].nunique().eq(1).all()
    with pytest.raises(ValueError, match=r"--lambdas = 0.001 is invalid: valid range is \[0.01"):
        cmd_chart(argparse.Namespace(**{**vars(args), "lambdas": [0.001]}))
    with pytest.raises(ValueError, match="give one λ"):
        cmd_chart(argparse.Namespace(**{**vars(args), "lambdas": [0.1, 1.0]}))


def test_fmax_chart_labels_follow_the_maps_law():
    """plot_fmax_chart labels its axes for the law of the map it draws (linear, Hertz, plastic)
    and refuses a plastic map over β (one β at a time, or plot_plastic_chart)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from impactmaps.maps.files.shipped import load_shipped_map
    from impactmaps.plotting import FMAX_LABELS, plot_fmax_chart

    dataset = load_shipped_map("beam", "euler", "stronge")
    with pytest.raises(ValueError, match="select one β"):
        plot_fmax_chart(dataset)
    ax = plot_fmax_chart(dataset.sel(beta=100.0, method="nearest"), lambdas=[0.1, 1.0])
    assert ax.get_xlabel() == FMAX_LABELS["plastic"][0] and ax.get_ylabel() == FMAX_LABELS["plastic"][1]
    assert ax.get_ylim()[1] > 1.5  # the Stronge law's F̄max exceeds 1 (its plastic branch is stiffer than K_y)
    from impactmaps.maps.files.shipped import load_shipped_map

    for law in ("linear", "hertz"):
        ax = plot_fmax_chart(load_shipped_map("beam", "euler", law), lambdas=[0.1, 1.0], asymptotes=False)
        assert (ax.get_xlabel(), ax.get_ylabel()) == FMAX_LABELS[law]
    plt.close("all")


def test_lookup_command_at_given_numbers():
    """cmd_lookup with an elastic-plastic --law reads the plastic map at (--beta, --zeta,
    --lambda) (the parser's --law choices and --beta option are the lead's to add)."""
    import argparse

    from impactmaps.cli.commands_maps import cmd_lookup
    from impactmaps import lookup

    args = argparse.Namespace(case=None, law="yc", beta=100.0, zeta=0.1, lambda_=0.5, kind="beam",
                              theory="euler")
    out = cmd_lookup(args)
    assert out["fmax_normalised"] == lookup(100.0, 0.1, 0.5, kind="beam", theory="euler", law="yc").fmax_normalised
    assert out["map"] == "beam-ss-euler-yc" and {"restitution", "absorbed_energy_fraction"} <= set(out)
    with pytest.raises(ValueError, match="--beta is required with --law yc"):
        cmd_lookup(argparse.Namespace(**{**vars(args), "beta": None}))
    with pytest.raises(ValueError, match="--beta cannot be used with the hertz law"):
        cmd_lookup(argparse.Namespace(**{**vars(args), "law": "hertz"}))
    with pytest.raises(ValueError, match="--zeta, --lambda, --beta cannot be used with --case"):
        cmd_lookup(argparse.Namespace(**{**vars(args), "case": "case.toml"}))


@pytest.mark.parametrize("law", ["yc", "stronge"])
def test_the_shipped_plastic_maps_are_sweeps_of_their_family(law):
    """Each shipped plastic map is the result of the sweep of its family over the grid of
    ``data_build/build_plastic_maps.py``: the sweep's fingerprint is the map's, so the
    build resumes from (and is checked against) the same description, and the dataset a
    sweep writes has the shipped map's layout."""
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps.maps.files.shipped import load_shipped_map
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.sweep import sweep_fingerprint

    betas, zetas = np.logspace(0.0, 3.5, 8), np.logspace(-3.0, 1.0, 25)
    for (kind, theory), name in PLASTIC_MAPS.items():
        dataset = load_shipped_map(kind, theory, law)
        lambdas = np.logspace(-2.0, 1.5, 18) if kind == "plate" else np.logspace(-3.0, 1.5, 23)
        digest = sweep_fingerprint([structure_from_name(name)], zetas, lambdas, law=law, axes={"beta": betas})
        assert digest == dataset.attrs["fingerprint"], name
        assert dataset["fmax_normalised"].dims == ("structure", "beta", "lambda_", "zeta")


def test_a_redefined_law_changes_the_fingerprint(monkeypatch):
    """A law whose definition changed (``ContactLaw.revision``: the refined Stronge law is at
    2, its energy-consistent form) gives its sweeps a new fingerprint, so a stored sweep of
    the old definition is neither resumed nor read as current; laws at revision 1 keep the
    fingerprints they had (the YC maps' above)."""
    from impactmaps.contact.plastic.stronge import StrongeContact
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.sweep import sweep_fingerprint

    grid = ([structure_from_name("beam-ss-euler")], [0.1, 1.0], [0.1, 1.0])
    current = sweep_fingerprint(*grid, law="stronge", axes={"beta": [10.0]})
    monkeypatch.setattr(StrongeContact, "revision", 1)
    assert sweep_fingerprint(*grid, law="stronge", axes={"beta": [10.0]}) != current


# -- the epp law (issue 28 step 6) --------------------------------------------------------------
_EPP_BEAM = _YC_BEAM.replace('law = "yigit-christoforou"', 'law = "epp"')


@pytest.mark.parametrize("kind", ["beam", "plate"])
@pytest.mark.parametrize("numbers", [(30.0, 0.3, 0.5), (400.0, 0.05, 0.03)])
def test_equal_numbers_give_equal_normalised_epp_response(kind, numbers):
    """The similarity of the plastic maps holds for ``epp`` too: two physically different
    impacts with equal (β, ζ, λ) give equal normalised answers to 1e-6 (its curves are fixed
    in units α_y, K_h α_y^{3/2} at fixed options; docs/plastic_maps.rst)."""
    from impactmaps.maps.compute.plastic_points import plastic_numbers, realise_plastic

    beta, zeta, lam = numbers
    first, second = _pair(kind)
    one = realise_plastic(first, "epp", beta, zeta, lam, velocity=1.0)
    two = realise_plastic(second, "epp", beta, zeta, lam, velocity=7.3)
    for realised, target in ((one, first), (two, second)):
        check = plastic_numbers(target, realised.law, realised.mass, realised.velocity)
        assert np.allclose([check.impact_number, check.loss_factor, check.relative_stiffness], numbers, rtol=1e-12)
    a, b = _normalised(first, one), _normalised(second, two)
    assert a["impacts"] == b["impacts"]
    for key in ("fmax_normalised", "restitution", "absorbed_energy_fraction", "energy_transferred_fraction"):
        assert a[key] == pytest.approx(b[key], rel=1e-6, abs=1e-9), key
    assert a["restitution"] ** 2 + a["absorbed_energy_fraction"] + a["energy_transferred_fraction"] == \
        pytest.approx(1.0, abs=1e-3)


def test_an_epp_case_is_realised_by_its_numbers():
    """A physical ``epp`` case (10 mm steel ball on a steel beam: R = 1 cm, E*, Y of the pair)
    and its realisation on the map's reference beam (R = 1 m, other E*, Y, m, V0) at the same
    (β, ζ, λ) give the same F_max/(m V0 ω_y) and restitution to 1e-6: β of the
    Yigit–Christoforou α_y and the scale K_y = 1.5 K_h α_y^{1/2} fix the epp impact
    (δ_y/α_y = c_y²/2.72 and F_y = K_h δ_y^{3/2} are the same for every E*, R, Y)."""
    from impactmaps.cases import parse_case
    from impactmaps.contact.plastic.epp import EppContact
    from impactmaps.maps.compute.plastic_points import plastic_numbers, realise_plastic
    from impactmaps.maps.family.structures import DEFAULT_STRUCTURES

    case = parse_case(_EPP_BEAM.replace("velocity = 1.0", "velocity = 0.05"))
    assert isinstance(case.law, EppContact)
    numbers = plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)
    assert numbers.impact_number == pytest.approx(float(case.law.impact_number(case.impactor_mass, case.velocity)),
                                                  rel=1e-12)
    reference = DEFAULT_STRUCTURES[0].build()
    realised = realise_plastic(reference, "epp", numbers.impact_number, numbers.loss_factor,
                               numbers.relative_stiffness)
    assert float(realised.law.radius) == 1.0 and float(case.law.radius) == 0.01
    direct = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=ModalSettings(),
                      record=False)
    mapped = _normalised(reference, realised)
    assert direct.peak_force / numbers.force_scale == pytest.approx(mapped["fmax_normalised"], rel=1e-6)
    assert direct.restitution == pytest.approx(mapped["restitution"], rel=1e-6)


@pytest.mark.parametrize("option, value", [("poisson_ratio", 0.33), ("sphere_compliance", 0.5)])
def test_epp_maps_describe_only_their_options(option, value):
    """Both epp options change the normalised response (the FE calibration: docs/epp_calibration.rst),
    so the epp maps, built at the defaults, describe an epp law only at those values: otherwise a
    lookup refuses, naming the option, its value and the maps' value."""
    from impactmaps.cases import parse_case
    from impactmaps.contact.plastic.epp import EppContact
    from impactmaps.contact.plastic.stronge import StrongeContact
    from impactmaps import lookup
    from impactmaps.maps.compute.plastic_points import EPP_MAP_OPTIONS
    from impactmaps.maps.family.builtin_families import plastic_law_of
    from impactmaps.maps.family.map_family import map_family

    assert EPP_MAP_OPTIONS == {"poisson_ratio": 0.3, "sphere_compliance": 0.0}
    family = map_family("epp")
    assert family.describes(EppContact(1e11, 0.01, 3e8)) and plastic_law_of(EppContact(1e11, 0.01, 3e8)) == "epp"
    assert not map_family("yc").describes(EppContact(1e11, 0.01, 3e8))
    assert not family.describes(StrongeContact(1e11, 0.01, 3e8))
    other = EppContact(1e11, 0.01, 3e8, **{option: value})
    reason = rf"contact law 'epp' with {option} = {value:g} \(the maps' value: {EPP_MAP_OPTIONS[option]:g}\)"
    with pytest.raises(ValueError, match=reason):
        family.describes(other)
    # the response really moves: the same impact at the other option value
    base, moved = EppContact(1e11, 0.01, 3e8), other
    delta = 30.0 * float(base.yield_indentation)
    assert abs(float(moved.force(delta)) / float(base.force(delta)) - 1.0) > 1e-3
    case = parse_case(_EPP_BEAM.replace('law = "epp"', f'law = "epp"\n{option} = {value}'))
    with pytest.raises(ValueError, match="no shipped map covers this case: " + reason + ".*impactmaps simulate"):
        lookup(case=case)


def _epp_maps():
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps.maps.files.shipped import load_shipped_map

    return {name: load_shipped_map(kind, theory, "epp") for (kind, theory), name in PLASTIC_MAPS.items()}


def test_shipped_epp_maps_are_complete_sweeps_stating_their_options():
    """Each shipped epp map is the sweep of the epp family over the grid of
    ``data_build/build_plastic_maps.py`` (its fingerprint), every point solved, finite values
    and errors wherever resolved, the energy ledger closed (e² + absorbed + transferred = 1
    where the sphere separated), and its attributes state the law options it was built at."""
    from impactmaps.maps.family.accuracy import STATUSES
    from impactmaps.maps.compute.plastic_points import EPP_MAP_OPTIONS
    from impactmaps.maps.family.structures import structure_from_name
    from impactmaps.maps.compute.sweep import sweep_fingerprint

    betas, zetas = np.logspace(0.0, 3.5, 8), np.logspace(-3.0, 1.0, 25)
    for name, dataset in _epp_maps().items():
        lambdas = np.logspace(-2.0, 1.5, 18) if name.startswith("plate") else np.logspace(-3.0, 1.5, 23)
        digest = sweep_fingerprint([structure_from_name(name)], zetas, lambdas, law="epp", axes={"beta": betas})
        assert digest == dataset.attrs["fingerprint"] and dataset.attrs["contact_law"] == "epp", name
        assert int(dataset.attrs["complete"]) == 1 and np.all(dataset["done"].values == 1)
        for option, value in EPP_MAP_OPTIONS.items():
            assert float(dataset.attrs[f"law_option_{option}"]) == value
            assert f"{option} = {value:g}" in dataset.attrs["method"]
        resolved = dataset["status"].values != STATUSES.index("unresolved")
        assert resolved.mean() > 0.75, name
        for variable in ("fmax_normalised", "fmax_error", "absorbed_energy_fraction", "absorbed_energy_error"):
            assert np.all(np.isfinite(dataset[variable].values[resolved])), (name, variable)
        separated = np.isfinite(dataset["restitution"].values)
        ledger = (dataset["restitution"] ** 2 + dataset["absorbed_energy_fraction"]
                  + dataset["energy_transferred_fraction"]).values[separated]
        assert separated.sum() > 0.99 * resolved.sum() and np.allclose(ledger, 1.0, atol=5e-3), name


def test_epp_lookups_against_committed_direct_runs():
    """validation/lookup_error_epp.csv holds direct epp solves at 200 random (β, ζ, λ) per shipped
    epp map (``validation/lookup_error.py --law epp``, seed 1). Read again from the current maps:
    every answer's band (plus the direct solve's own error) covers its error in F̄max,
    restitution and absorbed energy; every point the direct solve leaves unresolved is refused
    (on the Timoshenko beam 56 of 200 are refused, next to unresolved map points)."""
    from pathlib import Path

    import pandas as pd

    from impactmaps.maps.files.shipped import map_file_stem
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps import lookup
    from impactmaps.maps.compute.plastic_points import ERROR_OF

    table = pd.read_csv(Path(__file__).resolve().parents[2] / "validation" / "lookup_error_epp.csv")
    for (kind, theory), name in PLASTIC_MAPS.items():
        mine = table[table["map"] == map_file_stem(name, "epp")]
        assert np.all(mine["status"][~np.isfinite(mine["fmax_normalised_direct"])] == "refused"), name
        runs = mine[mine["status"] != "refused"]
        assert len(runs) > (140 if theory == "timoshenko" else 190), name
        found = lookup(runs["beta"].to_numpy(), runs["zeta"].to_numpy(), runs["lambda"].to_numpy(),
                               kind=kind, theory=theory, law="epp")
        for variable, error in ERROR_OF.items():
            direct = runs[f"{variable}_direct"].to_numpy()
            ok = np.isfinite(direct)
            np.testing.assert_allclose(getattr(found, variable)[ok], runs[f"{variable}_lookup"].to_numpy()[ok],
                                       rtol=1e-12, atol=1e-14)
            miss = np.abs(getattr(found, variable) - direct)[ok]
            assert np.all(miss <= getattr(found, error)[ok] + runs[f"{variable}_direct_error"].to_numpy()[ok]), \
                (name, variable)


def test_epp_chart_and_lookup_commands(tmp_path):
    """`chart --law epp` draws from the shipped epp maps and `lookup --law epp --beta …` reads
    them (the CLI's law choices come from the map-family registry)."""
    import argparse

    from impactmaps.cli.commands_maps import cmd_chart, cmd_lookup
    from impactmaps.maps.files.shipped import ALL_MAP_LAWS
    from impactmaps import lookup

    assert "epp" in ALL_MAP_LAWS
    args = argparse.Namespace(law="epp", out=str(tmp_path / "chart"), lambdas=[0.3], workers=None,
                              overwrite=False, betas=[3.0, 300.0], zeta_range=(0.005, 100.0), zeta_count=50,
                              quiet=True)
    paths = cmd_chart(args)
    assert (tmp_path / "chart" / "fmax_chart_epp.png").exists() and "csv" in paths
    args = argparse.Namespace(case=None, law="epp", beta=100.0, zeta=0.1, lambda_=0.5, kind="beam",
                              theory="euler")
    out = cmd_lookup(args)
    found = lookup(100.0, 0.1, 0.5, kind="beam", theory="euler", law="epp")
    assert out["fmax_normalised"] == found.fmax_normalised and out["map"] == "beam-ss-euler-epp"
