"""What a user meets: bad input exits 2 with one line naming the option as typed;
outputs say what they are; the figures and listings exist."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from impactmaps.cli import main

from ..helpers import EXAMPLES


@pytest.fixture
def a_file(tmp_path):
    path = tmp_path / "a_file"
    path.write_text("x")
    return path


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (["chart", "--zeta-count", "0"], "--zeta-count = 0"),
        (["chart", "--zeta-count", "1"], "--zeta-count = 1"),
        (["chart", "--lambdas", "1"], "--lambdas = 1"),
        (["chart", "--lambdas", "1.0", "1.0"], "--lambdas"),
        (["chart", "--zeta-range", "1", "0.1"], "--zeta-range"),
        (["chart", "--workers", "0"], "--workers = 0"),
        (["restitution", "--beta", "inf"], "--beta = inf"),
        (["restitution", "--beta", "nan"], "--beta = nan"),
        (["point", "--target", "plate-ss", "--zeta", "1", "--lambda", "-1"], "--lambda = -1"),
        (["point", "--target", "plate-ss", "--zeta", "1", "--lambda", "1", "--position", "2"], "--position = 2"),
        (["point", "--target", "beam-ss", "--zeta", "1", "--lambda", "1", "--aspect", "2"], "--aspect"),
        (["point", "--target", "beam-xx", "--zeta", "1", "--lambda", "1"], "supports"),
        (["asymptote", "infinite-beam", "--zeta", "1", "--lambda", "2"], "--lambda"),
        (["asymptote", "quasi-static", "--zeta", "1", "--lambda", "2"], "--zeta"),
        (["asymptote", "infinite-plate"], "--zeta is required"),
        (["classify", "--zeta", "1", "--lambda", "1", "--kind", "beam", "--tolerance", "5"], "--tolerance = 5"),
        (["classify", "--zeta", "1", "--lambda", "1", "--kind", "beam", "--tolerance", "0"], "--tolerance = 0"),
        (["classify", "--zeta", "1", "--lambda", "1", "--kind", "beam", "--from-map", "--position", "0.3"],
         "--position"),
        (["classify", "--zeta", "1", "--lambda", "1", "--kind", "plate", "--from-map", "--aspect", "2"],
         "--aspect"),
        (["halfspace", "--law", "hertz", "--radius", "0.01", "--velocity", "1", "--material", "structural-steel",
          "--target-material", "structural-steel", "--youngs-modulus", "1e9"], "--youngs-modulus"),
        (["halfspace", "--law", "hertz", "--radius", "0.01", "--velocity", "-1", "--material", "structural-steel",
          "--target-material", "structural-steel"], "--velocity = -1"),
        (["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "0", "--lambda", "1"], "--zeta = 0"),
        (["simulate", "does-not-exist.toml"], "does-not-exist.toml"),
        (["sweep", "does-not-exist.toml"], "does-not-exist.toml"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(argv, fragment, capsys):
    status = main(argv)
    err = capsys.readouterr().err
    assert status == 2
    lines = [line for line in err.splitlines() if not line.startswith("warning:")]
    assert len(lines) == 1 and fragment in lines[0], err
    assert "Traceback" not in err


@pytest.mark.parametrize("command", ["chart", "simulate"])
def test_out_that_is_a_file_is_refused(command, a_file, capsys):
    argv = ["chart", "--zeta-count", "2", "--lambdas", "1", "2"] if command == "chart" else \
        ["simulate", str(EXAMPLES / "aluminium_beam_linear.toml")]
    assert main([*argv, "--out", str(a_file)]) == 2
    assert "is a file, not a directory" in capsys.readouterr().err


def test_lambdas_checked_before_anything_is_computed(tmp_path, capsys):
    out = tmp_path / "chart"
    assert main(["chart", "--lambdas", "1", "--out", str(out)]) == 2
    assert not out.exists()


def test_version(capsys):
    from impactmaps import __version__

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and __version__ in capsys.readouterr().out


def test_materials_and_laws_list_the_registries(capsys):
    from impactmaps.contact import available_contact_laws
    from impactmaps.materials import available_materials

    assert main(["materials", "--json"]) == 0
    materials = json.loads(capsys.readouterr().out)["materials"]
    assert set(materials) == set(available_materials())
    assert materials["structural-steel"]["youngs_modulus"] == 210e9
    assert all(entry["source"] for entry in materials.values()), "every catalogue entry names its source"
    assert "EN 1993-1-1" in materials["structural-steel"]["source"]
    assert main(["laws", "--json"]) == 0
    laws = json.loads(capsys.readouterr().out)["laws"]
    assert set(laws) == set(available_contact_laws())
    assert "stiffness" in laws["hertz"]["options"] and laws["stronge"]["options"]["plastic_indentation_ratio"] == 84.0
    assert main(["laws"]) == 0 and "yigit-christoforou" in capsys.readouterr().out


@pytest.mark.parametrize("zeta, impacts, repeated", [(0.2, 1, False), (0.5, None, True), (1.5, 1, False)])
def test_infinite_beam_impacts_follow_the_recontact_range(zeta, impacts, repeated, capsys):
    """ζ_r < ζ < ζ_crit: the infinite beam is struck again, not "impacts: 1"."""
    assert main(["asymptote", "infinite-beam", "--zeta", str(zeta), "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["impacts"] == impacts and values["repeated_impacts"] is repeated
    if repeated:
        assert "impacts_note" in values


def test_classify_uses_tolerance_when_simulating(capsys):
    """A loose tolerance puts a transition point on an asymptote; a tight one does not."""
    argv = ["classify", "--zeta", "1.198", "--lambda", "0.425", "--kind", "plate", "--no-check", "--json"]
    assert main([*argv, "--tolerance", "0.01"]) == 0
    tight = json.loads(capsys.readouterr().out)["regime"]
    assert main([*argv, "--tolerance", "1"]) == 0
    loose = json.loads(capsys.readouterr().out)["regime"]
    assert tight == "transition" and loose != "transition"


def test_point_reports_convergence_and_plots(tmp_path, capsys):
    figure = tmp_path / "point.png"
    assert main(["point", "--target", "plate-ss", "--zeta", "1", "--lambda", "1", "--plot", str(figure),
                 "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["converged"] is True and values["plot"] == str(figure)
    assert figure.stat().st_size > 1000


def test_simulate_writes_a_history_figure(tmp_path, capsys):
    out = tmp_path / "sim"
    assert main(["simulate", str(EXAMPLES / "aluminium_beam_linear.toml"), "--out", str(out), "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert Path(values["outputs"]["figure"]) == out / "history.png"
    assert (out / "history.png").stat().st_size > 1000 and (out / "history.csv").exists()


@pytest.mark.parametrize("argv", [[], ["point", "--zeta", "abc"], ["nope"], ["asymptote", "infinite-shell"],
                                  ["restitution", "--beta", "2", "--json", "--extra"]])
def test_unparsable_command_lines_are_one_line_and_exit_2(argv, capsys):
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert len(captured.err.strip().splitlines()) == 1 and "usage" not in captured.err
    if "--json" in argv:
        assert "error" in json.loads(captured.out)


def test_ctrl_c_inside_compiled_code_exits_130(monkeypatch, capsys):
    """numba turns a KeyboardInterrupt into a SystemError; the command still exits 130."""
    import impactmaps.closed_forms.halfspace as compact

    def interrupted(*args, **kwargs):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as stop:
            raise SystemError("returned a result with an exception set") from stop

    monkeypatch.setattr(compact, "restitution", interrupted)
    assert main(["restitution", "--beta", "2"]) == 130
    assert capsys.readouterr().err.strip() == "impactmaps restitution: interrupted"


@pytest.mark.parametrize("beta", ["1e17", "1e30", "1e50", "1e150", "1e300"])
def test_restitution_of_huge_impact_numbers_is_computed_not_overflowed(beta, capsys):
    """The issue's reproducers (1e17 → 0.0, 1e30 → 0.225, 1e50 → 6336, 1e150 → NaN): the
    closed form is now evaluated without overflow or cancellation, so every finite β gets
    its value, checked against the same energy balance in 800-digit arithmetic."""
    import mpmath as mp

    mp.mp.dps = 800
    b = mp.mpf(beta)
    energy = b**2 / 2
    peak = 1 + (mp.sqrt(1 + 3 * (energy - mp.mpf("0.4"))) - 1) / mp.mpf(1.5)
    final15 = peak**mp.mpf(1.5) - mp.mpf(1.5) * peak + mp.mpf(0.5)
    final = final15 ** (mp.mpf(2) / 3)
    recovered = mp.mpf("0.4") * (peak**mp.mpf(2.5) - final**mp.mpf(2.5)) - final15 * (peak - final)
    expected = float(mp.sqrt(recovered / energy))
    assert main(["restitution", "--beta", beta, "--json"]) == 0
    value = json.loads(capsys.readouterr().out)["restitution"]
    assert value == pytest.approx(expected, rel=1e-12)
