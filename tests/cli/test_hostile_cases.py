"""Hostile case files a new user wrote (issue 40): each is answered, refused with one line, or
announced — never a hang, never a quiet slip."""

from __future__ import annotations

import json
import re
import warnings

import pytest

from impactmaps.cli import main
from impactmaps.cli.commands_tools import CASE_TEMPLATES


def _template(kind: str, **replace) -> str:
    """The body of ``impactmaps init KIND`` with ``key = value`` lines replaced (first match)."""
    text = f'name = "{kind}"\n' + CASE_TEMPLATES[kind][2]
    lines = text.splitlines()
    for key, value in replace.items():
        for i, line in enumerate(lines):
            if line.split("=")[0].strip() == key:
                lines[i] = f"{key} = {value}"
                break
        else:
            raise KeyError(key)
    return "\n".join(lines) + "\n"


def _write(tmp_path, kind: str, **replace):
    path = tmp_path / f"{kind}.toml"
    path.write_text(_template(kind, **replace), encoding="utf-8")
    return path


# -- item 2: a plate a few micrometres thick --------------------------------------------------
def test_check_integrates_nothing_on_a_micrometre_plate(tmp_path, monkeypatch, capsys):
    """``check`` on a plate 4 µm thick hung (> 150 s) inside the infinite-plate asymptote's
    ``solve_ivp`` reached from its cost estimate: check never integrates now (solve_ivp is made
    to fail if called) and its estimate says the asymptote answers."""
    import scipy.integrate

    from impactmaps.closed_forms.law_asymptotes import local

    def no_integration(*_args, **_kw):
        raise AssertionError("check integrated")

    monkeypatch.setattr(local, "solve_ivp", no_integration)
    monkeypatch.setattr(scipy.integrate, "solve_ivp", no_integration)
    path = _write(tmp_path, "plate", thickness="4e-6")
    status = main(["check", str(path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert status == 0, out
    # the infinite-plate asymptote is exact only while no reflection returns, and this contact
    # never ends (the plate is a dashpot far softer than the contact): refused with the reason,
    # from arithmetic, at once (issue 39: no asymptote answers beyond its exactness)
    assert out["valid"] is False and "reflected from the boundary returns" in out["valid_note"]


@pytest.mark.parametrize("thickness", [3e-6, 6e-6])
def test_the_infinite_plate_asymptote_of_a_micrometre_plate_is_answered_at_once(thickness):
    """The dashpot of a plate a few micrometres thick is far softer than the Hertz contact: the
    equations are stiff (relaxation ~10⁶ times faster than the contact scale), so DOP853 needed
    billions of steps. Radau answers; the peak force is then the dashpot's, F = Z V0 to within
    the indentation rate at the peak (α̇ = 0 there: F = Z v with v ≈ V0), and the impactor has
    not left the plate within the scaled time limit (the contact lasts ~m/Z)."""
    from impactmaps.contact import law_for_sphere
    from impactmaps.contact import Sphere
    from impactmaps.closed_forms.law_asymptotes.local import infinite_plate_impact, plate_impedance
    from impactmaps.materials import material
    from impactmaps.targets.plates.plate import Plate

    steel = material("structural-steel")
    plate = Plate.isotropic(0.25, 0.25, thickness, steel)
    sphere = Sphere(0.00635, steel)
    law = law_for_sphere("hertz", sphere, steel)
    result = infinite_plate_impact(plate, law, sphere.mass, 2.0)
    assert result.peak_force == pytest.approx(plate_impedance(plate) * 2.0, rel=1e-3)
    assert result.time_limit_reached


def test_an_asymptote_over_its_budget_is_refused(monkeypatch):
    """Every integration has a budget: past MAX_EVALUATIONS the asymptote is a ValueError naming
    the reason, not a run without end."""
    from impactmaps.contact import HertzContact
    from impactmaps.closed_forms.law_asymptotes import local

    monkeypatch.setattr(local, "MAX_EVALUATIONS", 50)
    with pytest.raises(ValueError, match="more than 50 evaluations"):
        local.quasi_static_impact(1e6, HertzContact(1e10), 0.01, 1.0)


# -- item 3: memory refused from arithmetic, before allocation ---------------------------------
def _peak_bytes(call) -> int:
    import tracemalloc

    tracemalloc.start()
    try:
        call()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_a_3000_by_3000_sweep_is_refused_before_anything_is_allocated(tmp_path, capsys):
    """The issue's sweep reached 3.8 GB of memory (the docs promise a refusal above 1 GiB): it is
    refused with one line naming the size, nothing written, a few MB allocated."""
    config = tmp_path / "big.toml"
    config.write_text('output = "out"\n[grid]\nzeta = {min = 0.01, max = 10, count = 3000}\n'
                      'lambda = {min = 0.01, max = 10, count = 3000}\n[[structure]]\nkind = "beam"\n')
    status = []
    peak = _peak_bytes(lambda: status.append(main(["sweep", str(config), "--quiet"])))
    err = capsys.readouterr().err
    assert status == [2], err
    assert "9e+06 points" in err and "GiB (limit 1 GiB)" in err and err.count("\n") == 1
    assert not (tmp_path / "out" / "sweep.nc").exists()
    assert peak < 50 * 2**20


def test_a_chart_of_1e8_zeta_values_is_refused_before_anything_is_allocated(tmp_path, capsys):
    """``chart --zeta-count 100000000`` allocated 1.7 GB before refusing."""
    status = []
    peak = _peak_bytes(lambda: status.append(main(["chart", "--zeta-count", "100000000", "--out",
                                                   str(tmp_path / "c"), "--quiet"])))
    err = capsys.readouterr().err
    assert status == [2] and "--zeta-count" in err and "GiB" in err
    assert peak < 50 * 2**20


@pytest.mark.slow
def test_a_sweep_holds_at_most_map_copies_copies_of_its_map(tmp_path, monkeypatch):
    """The refusal's arithmetic bounds what a sweep really holds: its tasks are made as they are
    submitted (a list of them took ~165 B a point, two copies of the map) and the peak of a
    2·10⁴-point sweep, saved to NetCDF and classified, stays below MAP_COPIES copies of its map."""
    import numpy as np

    from impactmaps.maps.compute import sweep as sweep_module
    from impactmaps.maps.family.structures import MapStructure

    family = sweep_module.map_family("linear")

    def fake_points(_family, _structure, points, _settings):
        row = {name: np.array(1, dtype=spec[0]).item() for name, spec in family.variables.items()}
        return [row | {"method": 0} for _ in points]

    monkeypatch.setattr(sweep_module, "solve_map_points", fake_points)
    count = 150
    structure = [MapStructure(kind="beam", theory="euler", supports="ss")]
    axis = np.geomspace(0.05, 5.0, count)
    map_bytes = count * count * (sum(np.dtype(spec[0]).itemsize for spec in family.variables.values()) + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep_module.sweep(structure, axis[:3], axis[:3], path=tmp_path / "w.nc", max_workers=1,
                           progress=False)  # the modules' imports, not counted below
        peak = _peak_bytes(lambda: sweep_module.sweep(structure, axis, axis, path=tmp_path / "s.nc", max_workers=1,
                                                      progress=False, pacing=sweep_module.Pacing(count, 1e9)))
    assert peak < sweep_module.MAP_COPIES * map_bytes, peak / map_bytes


# -- item 5: sizes that look like a unit slip ---------------------------------------------------
def test_a_plate_thicker_than_half_its_side_is_refused_naming_the_key(tmp_path, capsys):
    """``thickness = 3`` (3 mm typed as metres: a plate 3 m thick and 0.25 m wide) answered 3052 N;
    now refused with one line naming target.thickness and the range that holds."""
    path = _write(tmp_path, "plate", thickness="3")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "target.thickness = 3 m is invalid" in err
    assert "valid range: target.thickness ≤ 0.125 m" in err
    assert main(["simulate", str(path), "--out", str(tmp_path / "o")]) == 2


def test_a_ten_metre_ball_is_announced_naming_the_key(tmp_path, capsys):
    """``radius = 10`` (a 33 000 t steel ball) was accepted without a word: a warning naming
    impactor.radius and the ball's mass; an ordinary case has none."""
    path = _write(tmp_path, "plate", radius="10")
    assert main(["check", str(path), "--json"]) == 0
    err = capsys.readouterr().err
    assert "impactor.radius = 10 m is unusually large" in err
    mass = float(re.search(r"a sphere of (\S+) kg", err).group(1))  # a steel ball: 4/3 π (10 m)³ × ~7.8 t/m³
    assert mass == pytest.approx(3.29e7, rel=0.02)
    assert main(["check", str(_write(tmp_path, "plate")), "--json"]) == 0
    assert "unusually large" not in capsys.readouterr().err


@pytest.mark.parametrize("kind, key, value", [("plate", "thickness", "0.1"), ("beam", "height", "0.2")])
def test_a_thick_plate_or_deep_beam_that_holds_is_announced_not_refused(tmp_path, kind, key, value, capsys):
    """Unusual but possible sizes are warned of (above 0.5 m), not refused; a plate of side/thickness
    ≥ 2 and a beam of L/h ≥ 2 are valid models."""
    from impactmaps._checks import UnusualValueWarning
    from impactmaps.cases import parse_case

    big = "0.6"
    text = _template(kind, **{key: big, **({"length_x": "2.0", "length_y": "2.0", "impact_point": "[1.0, 1.0]"}
                                           if kind == "plate" else {"length": "2.0", "impact_position": "1.0"})})
    with pytest.warns(UnusualValueWarning, match=f"target.{key} = 0.6 m is unusually large"):
        parse_case(text)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnusualValueWarning)
        parse_case(_template(kind, **{key: value}))


# -- item 6: one set of validity warnings, printed by every command that answers a case -------
EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[2] / "examples"


def _tags(messages) -> set:
    return {message.split(":")[0] for message in messages}


def test_check_and_lookup_say_the_contact_yields_as_simulate_does(tmp_path, monkeypatch, capsys):
    """The README's headline case (Hertz pressure 11× the yield pressure): ``simulate`` said the
    contact yields, ``check`` and ``lookup --case`` did not. All three now print the same set
    (impactmaps.validity.case_warnings), on stderr and in ``model_warnings``."""
    from impactmaps.cases import load_case
    from impactmaps.validity import case_warnings

    case_file = EXAMPLES / "steel_plate_hertz.toml"
    monkeypatch.setattr("impactmaps.cases.case_lookup._case_answer",
                        lambda case, **_kw: {"peak_force_N": 731.0, "peak_force_error_N": 1.0})
    monkeypatch.setattr("impactmaps.cli.commands_tools._estimated_cost", lambda case, values: {})  # the modes: slow
    answers = {}
    for command in (["check"], ["lookup", "--case"]):
        assert main([*command, str(case_file), "--json"]) == 0
        captured = capsys.readouterr()
        out = json.loads(captured.out)
        answers[command[0]] = out["model_warnings"]
        assert "warning: contact pressure" in captured.err
    assert _tags(answers["check"]) == _tags(answers["lookup"]) == {"contact pressure"}
    # simulate's set at its own peak force (731.25 N): the same sentence as lookup's at 731.0 N, to rounding
    case = load_case(case_file)
    assert _tags(case_warnings(case, peak_force=731.25)) == {"contact pressure"}
    assert "4.22" in answers["lookup"][0]


def test_the_epp_calibration_warning_is_printed_by_check_too(tmp_path, capsys):
    """The epp calibration warning appeared in ``simulate`` only: steel on steel holds ν = 0.3 and
    s = 0.50, not the law's default rigid sphere."""
    path = tmp_path / "epp.toml"
    text = _template("plate", material='"structural-steel"')
    path.write_text(text.replace('law = "hertz"', 'law = "epp"'), encoding="utf-8")
    assert main(["check", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "epp calibration" in _tags(out["model_warnings"])


def test_the_contact_radius_check_is_one_of_the_set_not_a_guess_of_the_estimate(tmp_path, capsys):
    """A contact-radius warning appeared in ``check`` only (from its cost estimate's first guess,
    which simulate's own docs say does not apply); it is now a check of impactmaps.validity,
    from the answer's indentation, on a Mindlin plate whose contact radius exceeds half its thickness."""
    from impactmaps.cases import parse_case
    from impactmaps.validity import case_warnings

    thin = _template("plate", thickness="0.0005", theory='"mindlin"')
    case = parse_case(thin)
    messages = case_warnings(case)  # at the half-space bound
    assert "contact radius" in _tags(messages)
    thick = parse_case(_template("plate", theory='"mindlin"'))
    assert "contact radius" not in _tags(case_warnings(thick))


# -- item 7: a band wider than 10 % of its value is announced -----------------------------------
@pytest.mark.parametrize("error, announced", [(2415.0, True), (200.0, False)])
def test_a_lookup_band_wider_than_a_tenth_of_its_value_says_simulate_it(tmp_path, monkeypatch, capsys, error,
                                                                        announced):
    """``peak_force_N 2421 ± 2415`` (status interpolated) was printed with no word: a warning on
    stderr and ``band_warning`` in --json say the band is wide and to simulate the case; a band of
    8 % is not announced."""
    monkeypatch.setattr("impactmaps.cases.case_lookup._case_answer", lambda case, **_kw: {
        "peak_force_N": 2421.0, "peak_force_error_N": error, "status": "interpolated"})
    case_file = EXAMPLES / "steel_plate_hertz.toml"
    assert main(["lookup", "--case", str(case_file), "--json"]) == 0
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert ("band_warning" in out) is announced
    assert ("simulate it (impactmaps simulate" in captured.err) is announced
    if announced:
        assert "100% of the value" in out["band_warning"]
    assert main(["lookup", "--case", str(case_file)]) == 0
    assert ("simulate it" in capsys.readouterr().err) is announced


def test_a_normalised_lookup_with_a_wide_band_says_simulate_it(monkeypatch, capsys):
    from impactmaps.maps.read import lookup as lookup_module  # the command reads a point there

    real = lookup_module.point_answer

    def wide(*args, **kwargs):
        found = real(*args, **kwargs)
        return found._replace(fmax_error=0.5 * found.fmax_normalised) if hasattr(found, "_replace") else \
            __import__("dataclasses").replace(found, fmax_error=0.5 * found.fmax_normalised)

    monkeypatch.setattr(lookup_module, "point_answer", wide)
    assert main(["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "0.5", "--lambda", "0.1",
                 "--json"]) == 0
    captured = capsys.readouterr()
    assert "50% of the value" in json.loads(captured.out)["band_warning"]
    assert "simulate it (impactmaps point" in captured.err


# -- item 12: smaller words that disagreed --------------------------------------------------------
def test_lookup_of_a_plate_takes_the_documented_default_theory(capsys):
    """``lookup --kind plate`` needed ``--theory``: it defaults to the classical theory (Kirchhoff),
    the same answer as with ``--theory kirchhoff``."""
    assert main(["lookup", "--kind", "plate", "--zeta", "0.5", "--lambda", "0.1", "--json"]) == 0
    default = json.loads(capsys.readouterr().out)
    assert main(["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "0.5", "--lambda", "0.1",
                 "--json"]) == 0
    explicit = json.loads(capsys.readouterr().out)
    assert default == explicit and default["map"]


def test_init_help_names_the_file_it_writes(tmp_path, monkeypatch, capsys):
    """``init`` wrote plate.toml while its help said TEMPLATE.toml."""
    from impactmaps.cli import build_parser

    monkeypatch.chdir(tmp_path)
    assert main(["init", "plate", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["case"] == "plate.toml" and (tmp_path / "plate.toml").exists()
    init = build_parser()._subparsers._group_actions[0].choices["init"]
    assert "plate.toml for init plate" in init.format_help().replace("\n", " ").replace("  ", " ")


@pytest.mark.parametrize("beta, status", [(1e8, 0), (1e9, 2)])
def test_restitution_enforces_the_documented_range(beta, status, capsys):
    """The docs say β in (0, 1e8]; β = 1e9 was accepted."""
    assert main(["restitution", "--beta", f"{beta:g}"]) == status
    if status:
        assert "--beta = 1e+09 is invalid" in capsys.readouterr().err


def test_a_resumed_sweep_says_what_was_saved_and_overwrite_what_it_discards(tmp_path, capsys, monkeypatch):
    from impactmaps.maps.compute import sweep as sweep_module
    from impactmaps.maps.family.structures import MapStructure

    family = sweep_module.map_family("linear")

    def fake_points(_family, _structure, points, _settings):
        row = {name: __import__("numpy").array(1, dtype=spec[0]).item() for name, spec in family.variables.items()}
        return [row | {"method": 0} for _ in points]

    monkeypatch.setattr(sweep_module, "solve_map_points", fake_points)
    structure, path = [MapStructure(kind="beam", theory="euler", supports="ss")], tmp_path / "s.nc"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep_module.sweep(structure, [0.5, 1.0, 2.0], [1.0], path=path, max_workers=1, progress=False)
        capsys.readouterr()
        sweep_module.sweep(structure, [0.5, 1.0, 2.0], [1.0], path=path, max_workers=1, progress=True)
    assert f"resuming {path}: 3 of 3 points already saved" in capsys.readouterr().err
    with pytest.warns(UserWarning, match="discarding 3 finished point"):
        sweep_module.sweep(structure, [0.5, 1.0, 2.0], [1.0], path=path, max_workers=1, progress=False,
                           overwrite=True)


# -- item 1: the finite-difference run has a budget from arithmetic, in check as in fd ---------------
def test_check_estimates_the_fd_run_and_fd_refuses_what_it_refuses(tmp_path, capsys):
    """``timeout 90 impactmaps fd`` on a 100 s duration ran for 425 s: ``check`` now gives the fd
    run's estimate from arithmetic (steps, memory, seconds) and calls the case invalid where ``fd``
    refuses it, with the same words; nothing is integrated."""
    path = _write(tmp_path, "fd", duration="100")
    assert main(["check", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["estimated_method"] == "finite-difference" and out["valid"] is False
    assert out["estimated_expected_steps"] > 1e8 and out["estimated_seconds"] > 60
    assert main(["fd", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "may take 16.8 GiB (limit 1 GiB)" in err and "may take 16.8 GiB" in out["valid_note"]
    path = _write(tmp_path, "fd")
    assert main(["check", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["valid"] is True and 0 < out["estimated_seconds"] < 60
