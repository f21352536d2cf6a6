"""The small items of issue 29 (item 7), each guarded by a test named after what it guards."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import pytest

from impactmaps.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _one_error_line(capsys) -> str:
    err = capsys.readouterr().err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if not line.startswith("warning:")]
    assert len(lines) == 1, err
    return lines[0]


# -- validity checks ------------------------------------------------------------------------
def test_infinite_structure_answer_is_not_called_a_large_deflection():
    """A 300 m plate answered by the infinite-plate asymptote moved 0.13 mm; the check used
    F × static compliance of the 300 m plate (4644 m). The answer's own displacement
    (``details.max_target_displacement``) is what the check must read."""
    from impactmaps.materials import material
    from impactmaps.targets import Plate
    from impactmaps.validity import validity_warnings

    plate = Plate.isotropic(300.0, 300.0, 0.002, material("aluminium-6061-t6"))
    result = SimpleNamespace(peak_force=373.1, max_indentation=1.4e-5, velocity=3.0,
                             method="infinite-structure-asymptote", history=None,
                             contact_intervals=[[0.0, 1.5e-3]],
                             details=SimpleNamespace(max_target_displacement=1.3e-4))
    assert 373.1 * plate.static_compliance() > 1000.0  # what the old estimate saw
    sphere = SimpleNamespace(radius=0.0085, material=material("structural-steel"))
    messages = validity_warnings(sphere, material("aluminium-6061-t6"), _elastic_law(), plate, result)
    assert not any(m.startswith("plate deflection") for m in messages), messages


def _elastic_law():
    from impactmaps.contact import HertzContact

    return HertzContact(1.0e10)


def test_contact_pressure_warning_does_not_blame_the_ball_on_a_laminate():
    """A steel ball (S_y 235 MPa) on a laminate of unknown strength whose transverse modulus
    is 7.9 GPa: the laminate is the softer body, so the ball's yield strength says nothing
    about whether the contact yields — no pressure sentence naming it."""
    from impactmaps.cases import load_case
    from impactmaps.validity import validity_warnings

    case = load_case(EXAMPLES / "composite_plate_sun_chen.toml")
    result = SimpleNamespace(peak_force=5000.0, max_indentation=1e-5, velocity=30.0, method="modal",
                             history=None, contact_intervals=[[0.0, 1e-4]], details=None,
                             max_target_displacement=1e-4)
    messages = validity_warnings(case.sphere, case.target_material, case.law, None, result)
    assert not any(m.startswith("contact pressure") for m in messages), messages


def test_contact_pressure_warning_names_the_body_that_yields():
    """Both strengths known: the lower one, and the sentence says whose it is."""
    from impactmaps.materials import material
    from impactmaps.validity import validity_warnings

    sphere = SimpleNamespace(radius=0.005, material=material("structural-steel"))
    result = SimpleNamespace(peak_force=5000.0, max_indentation=1e-5, velocity=1.0, method="modal",
                             history=None, contact_intervals=[[0.0, 1e-4]], details=None,
                             max_target_displacement=0.0)
    messages = validity_warnings(sphere, material("aluminium-6061-t6"), _elastic_law(), None, result)
    pressure = [m for m in messages if m.startswith("contact pressure")]
    assert len(pressure) == 1 and "of the impactor" in pressure[0]


# -- range refusals ----------------------------------------------------------------------------
def test_asymptote_with_absurd_zeta_is_refused_by_range(capsys):
    """--zeta 1e300 made the beam's root finder see NaN; refused by range now."""
    assert main(["asymptote", "infinite-beam", "--zeta", "1e300"]) == 2
    line = _one_error_line(capsys)
    assert "--zeta = 1e+300" in line and "(0, 1e+06]" in line


def test_asymptote_at_the_largest_zeta_answers(capsys):
    """The top of the range answers with a finite peak (≈ 0.369 ζ^(-2/3) on the beam)."""
    assert main(["asymptote", "infinite-beam", "--zeta", "1e6", "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["fmax_normalised"] == pytest.approx(0.3690656 * 1e6 ** (-2 / 3), rel=1e-5)


def test_hertz_chart_with_tiny_lambda_is_refused_before_computing(tmp_path, capsys):
    """chart --law hertz --lambdas 1e-6 1 ended in a RuntimeError of the quasi-static
    integration after the sweep; refused by range now, before anything is computed."""
    out = tmp_path / "chart"
    assert main(["chart", "--law", "hertz", "--lambdas", "1e-06", "1", "--out", str(out)]) == 2
    assert "--lambdas = 1e-06" in _one_error_line(capsys)
    assert not out.exists()


def test_case_stiffness_1e300_is_refused_by_range(tmp_path, capsys):
    """contact.stiffness = 1e300 was accepted (and overflowed later)."""
    text = (EXAMPLES / "aluminium_beam_linear.toml").read_text().replace('law = "linear"',
                                                                          'law = "linear"\nstiffness = 1e300')
    path = tmp_path / "stiff.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    line = _one_error_line(capsys)
    assert "contact.stiffness" in line and "1e+300" in line


# -- contradictory options -------------------------------------------------------------------
@pytest.mark.parametrize("argv, fragment", [
    (["lookup", "--no-build", "--kind", "beam", "--theory", "euler", "--zeta", "0.1", "--lambda", "1"],
     "--no-build cannot be used without --case"),
    (["chart", "--betas", "1", "10", "--lambdas", "0.5", "2"], "--betas cannot be used with --law linear"),
    (["chart", "--law", "hertz", "--betas", "1", "--lambdas", "0.5", "2"], "--betas cannot be used with --law hertz"),
])
def test_contradictory_options_are_refused(argv, fragment, tmp_path, capsys):
    assert main([*argv] + (["--out", str(tmp_path / "o")] if argv[0] == "chart" else [])) == 2
    assert fragment in _one_error_line(capsys)


def test_fd_section_in_a_modal_case_is_refused(tmp_path, capsys):
    """An [fd] section is read by the finite-difference solver only: in a modal case it
    would be ignored silently."""
    text = (EXAMPLES / "aluminium_beam_linear.toml").read_text() + "\n[fd]\nn_elements = 50\n"
    path = tmp_path / "modal_with_fd.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "[fd]" in _one_error_line(capsys)


# -- outputs checked before computing ---------------------------------------------------------
def test_unwritable_out_is_refused_before_computing(tmp_path, capsys):
    """--out under a file cannot be created: refused first, naming the option."""
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    assert main(["simulate", str(EXAMPLES / "aluminium_beam_linear.toml"), "--out", str(blocker / "sub")]) == 2
    line = _one_error_line(capsys)
    assert "--out" in line and "a_file" in line


def test_unwritable_plot_is_refused_before_computing(tmp_path, capsys):
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    argv = ["point", "--target", "beam-ss", "--zeta", "1", "--lambda", "1", "--no-check"]
    assert main([*argv, "--plot", str(blocker / "history.png")]) == 2
    assert "--plot" in _one_error_line(capsys)
    assert main([*argv, "--plot", str(tmp_path / "history.notanimage")]) == 2
    assert "--plot" in _one_error_line(capsys)


# -- files named in errors --------------------------------------------------------------------
@pytest.mark.parametrize("content", [b"\xff\xfe\x00binary", b"[impactor\nradius = ", None])
def test_file_errors_name_the_file(content, tmp_path, capsys):
    """A binary file, broken TOML, a directory: each error names the file."""
    path = tmp_path / "the_case.toml"
    if content is None:
        path.mkdir()
    else:
        path.write_bytes(content)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "the_case.toml" in _one_error_line(capsys)


# -- plain text for users ---------------------------------------------------------------------
def test_help_and_laws_are_plain_text(capsys):
    """No project jargon (PHYSICS.md, seed numbers) or reStructuredText markup in what a user reads."""
    from impactmaps.cli import build_parser

    parser = build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    texts = [parser.format_help()] + [p.format_help() for p in commands.values()]
    assert main(["laws"]) == 0
    texts.append(capsys.readouterr().out)
    for text in texts:
        for jargon in ("PHYSICS.md", "seed 0", "``", ":func:"):
            assert jargon not in text, (jargon, text[:200])


def test_zeta_and_lambda_options_have_help_text():
    from impactmaps.cli import build_parser

    parser = build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    for name, sub in commands.items():
        for action in sub._actions:
            if action.dest in ("zeta", "lambda_"):
                assert action.help, f"{name} {action.option_strings} has no help text"


# -- broken pipe, failures ---------------------------------------------------------------------
def test_output_piped_into_head_exits_quietly():
    """``impactmaps laws | head -1``: the reader goes away; no BrokenPipeError traceback."""
    import subprocess
    import sys

    command = f"{sys.executable} -m impactmaps.cli materials | head -1"
    done = subprocess.run(command, shell=True, capture_output=True, text=True,
                          cwd=Path(__file__).resolve().parents[2], timeout=60)
    assert done.stdout.strip() == "materials"
    assert "Traceback" not in done.stderr and "BrokenPipe" not in done.stderr, done.stderr


def test_fd_run_ending_in_contact_explains_its_null_restitution(tmp_path):
    """A finite-difference run that stops with the sphere in contact has no restitution:
    null, with a ``restitution_note`` saying why (as every null of a summary has)."""
    text = (EXAMPLES / "steel_beam_fd_stronge.toml").read_text()
    text = text.replace("duration = 0.03 ", "duration = 0.0003").replace("n_elements = 200", "n_elements = 20")
    path = tmp_path / "short_fd.toml"
    path.write_text(text)
    assert main(["fd", str(path), "--out", str(tmp_path / "out")]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["time_limit_reached"] in (True, 1)
    assert summary["restitution"] is None and "still in contact" in summary["restitution_note"]
    assert all(f"{key}_note" in summary for key, value in summary.items() if value is None)
    assert not any(isinstance(v, float) and not math.isfinite(v) for v in summary.values())


def test_a_long_run_is_announced_before_it_runs(tmp_path, capsys, monkeypatch):
    """The command line printed every warning after the command's output, the long-run
    announcement too: a 20-minute fd run said so only at its end (or never, when stopped).
    The announcement now reaches stderr before the run starts; other warnings follow the output."""
    import impactmaps.fd.impact as impact

    text = (EXAMPLES / "steel_beam_fd_stronge.toml").read_text()
    text = text.replace("duration = 0.03 ", "duration = 0.0003").replace("n_elements = 200", "n_elements = 20")
    path = tmp_path / "fd.toml"
    path.write_text(text)
    monkeypatch.setattr(impact, "NODE_LAYER_STEPS_PER_SECOND", 1.0)  # pretend the machine is slow
    seen_before_the_run = []
    loop = impact.run_loop

    def spy(*args, **kwargs):
        seen_before_the_run.append(capsys.readouterr().err)
        return loop(*args, **kwargs)

    monkeypatch.setattr(impact, "run_loop", spy)
    assert main(["fd", str(path), "--out", str(tmp_path / "out")]) == 0
    assert seen_before_the_run and "on a 2-core machine" in seen_before_the_run[0]
    assert "on a 2-core machine" not in capsys.readouterr().err  # shown once


# -- Python API type errors ------------------------------------------------------------------------
def test_velocity_given_as_a_string_names_the_parameter():
    """simulate(..., velocity="3") failed deep inside with "unsupported operand type(s) for
    ** or pow(): 'str' and 'int'"; the checks now refuse strings (NumPy would convert "3")."""
    from impactmaps.contact import HertzContact
    from impactmaps.materials import material
    from impactmaps.solvers.modal import simulate
    from impactmaps.targets import Plate

    plate = Plate.isotropic(0.3, 0.3, 0.002, material("aluminium-6061-t6"))
    with pytest.raises(ValueError, match=r"velocity = '3' is a str, not a number \[m/s\]"):
        simulate(plate, HertzContact(1e10), 0.02, "3")
    with pytest.raises(ValueError, match=r"length_x = '0.3' is a str"):
        Plate.isotropic("0.3", 0.3, 0.002, material("aluminium-6061-t6"))


def test_require_instance_names_the_parameter_and_the_fix():
    from impactmaps._checks import require_instance
    from impactmaps.materials import IsotropicMaterial

    with pytest.raises(TypeError, match=r"material = 'aluminium-6061-t6' is a str, not IsotropicMaterial: use"):
        require_instance("material", "aluminium-6061-t6", IsotropicMaterial,
                         "use impactmaps.materials.material('aluminium-6061-t6')")


def test_plate_material_given_by_name_names_the_parameter():
    """Plate.isotropic(..., "aluminium-6061-t6") → AttributeError 'str' object has no
    attribute 'youngs_modulus'."""
    from impactmaps.targets import Plate

    with pytest.raises((TypeError, ValueError), match="material"):
        Plate.isotropic(0.3, 0.3, 0.002, "aluminium-6061-t6")



def test_beam_material_given_by_name_names_the_parameter():
    """The plate's twin: Beam.rectangular(..., "aluminium-6061-t6") was an AttributeError."""
    from impactmaps.targets import Beam

    with pytest.raises(TypeError, match="material = 'aluminium-6061-t6'"):
        Beam.rectangular(0.5, 0.02, 0.02, "aluminium-6061-t6")


def test_lookup_with_a_plastic_law_names_the_parameter():
    """lookup(..., law="yc") → a NumPy TypeError about boolean indexing: the yc maps have a
    β axis, so a lookup of two numbers must refuse, naming the law and the three numbers."""
    from impactmaps import lookup

    with pytest.raises(ValueError, match=r"law = 'yc': a point of its maps is 3 numbers \(beta, zeta, lambda\)"):
        lookup(0.1, 1.0, kind="beam", theory="euler", law="yc")


def test_a_combination_not_implemented_is_one_line_and_exit_2(tmp_path, capsys):
    """A Mindlin plate with clamped edges raised NotImplementedError through simulate, lookup
    --case and point (a traceback); the CLI reports it as a refusal. (When the Mindlin Ritz
    basis lands the command answers instead: exit 0.)"""
    status = main(["point", "--target", "plate-cccc", "--theory", "mindlin", "--zeta", "0.5", "--lambda", "1",
                   "--no-check"])
    captured = capsys.readouterr()
    assert status in (0, 2) and "Traceback" not in captured.err
    if status == 2:
        assert "mindlin" in _one_error_line_of(captured.err)


def _one_error_line_of(err: str) -> str:
    lines = [line for line in err.splitlines() if not line.startswith("warning:")]
    assert len(lines) == 1, err
    return lines[0]


@pytest.mark.parametrize("zeta, lam, fragment", [("1e-300", "1", "--zeta = 1e-300"), ("1", "1e300", "--lambda = 1e+300"),
                                                  ("1", "1e-300", "--lambda = 1e-300")])
def test_simulated_point_out_of_range_names_the_option(zeta, lam, fragment, capsys):
    """ζ = 1e-300 was refused as 'impactor_mass = 0.0', λ = 1e300 as 'contact_frequency = 0.0':
    names the user never typed. Refused by range on the options now."""
    assert main(["point", "--target", "beam-ss", "--zeta", zeta, "--lambda", lam, "--no-check"]) == 2
    assert fragment in _one_error_line(capsys)


@pytest.mark.parametrize("argv, fragment", [
    (["point", "--target", "plate-ss", "--zeta", "1", "--lambda", "1", "--aspect", "1e300"],
     "--aspect = 1e+300 is invalid: the plate aspect ratio b/a must be in [0.001, 1000]"),
    (["point", "--target", "beam-ss", "--zeta", "1", "--lambda", "1", "--position", "1e-300"],
     "--position = 1e-300 is invalid: the impact point x0/L must be in [1e-06, 0.999999]"),
])
def test_fuzzed_point_options_are_refused_by_range(argv, fragment, capsys):
    """Found by fuzzing `point`: --aspect 1e300 overflowed ("the computation failed"), 1e-300 divided
    by zero; --position 1e-300 was refused by the target under its Python name."""
    assert main(argv) == 2
    assert fragment in _one_error_line(capsys)


def test_a_command_that_warns_and_then_fails_prints_both(capsys):
    """A warning raised before a refusal: the loop printing the warnings reused the error
    message's name, so the refusal printed a TypeError traceback instead of its line."""
    import warnings

    from impactmaps.cli import _run

    def handler(args):
        warnings.warn("something doubtful", UserWarning)
        raise ValueError("x = 1 is invalid")

    args = SimpleNamespace(handler=handler, command="point", json=False)
    assert _run(args) == 2
    err = capsys.readouterr().err
    assert "warning: something doubtful" in err and "impactmaps point: error: x = 1 is invalid" in err


def test_point_on_a_mindlin_plate_says_the_point_load_once(capsys):
    """``point`` on a Mindlin plate answered "converged" with an error of 3e-5 and no word on
    the point load that ``lookup`` and ``sweep`` warn about (its value has no converged answer:
    ``validation/mindlin_point_load.md``); it now says the map's point-load warning, once."""
    status = main(["point", "--target", "plate-ss", "--theory", "mindlin", "--zeta", "18.1471",
                   "--lambda", "0.00342442", "--json"])
    captured = capsys.readouterr()
    assert status == 0
    notes = [line for line in captured.err.splitlines() if line.startswith("warning: point load")]
    assert len(notes) == 1 and "this Mindlin point strikes" in notes[0] and "no converged value" in notes[0]
    main(["point", "--target", "plate-ss", "--zeta", "18.1471", "--lambda", "0.00342442", "--json"])
    assert "point load" not in capsys.readouterr().err
