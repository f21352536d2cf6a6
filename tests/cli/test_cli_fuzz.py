"""Fuzz every subcommand's options and every case-file key: exit 0 or 2, never a traceback,
never NaN/inf in ``--json`` output, memory under 1 GiB.

The options are read from the parser itself, so a new option is fuzzed without editing
this file. Values are drawn from the edges a user meets (0, negatives, NaN, ±inf, 1e±300,
words where numbers belong, empty strings) and plain valid numbers. Hypothesis runs
derandomised (a fixed seed), so CI sees the same inputs every run.

The default test keeps each example cheap: the commands whose valid inputs start a
computation (a chart, a sweep, a simulation) always get at least one out-of-range value,
so they must refuse it — before computing — with exit 2; the other commands run whatever
is drawn. The ``slow`` tests run everything drawn, computations included, on tiny grids
and short cases.
"""

from __future__ import annotations

import json
import resource
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st

from impactmaps.cli import build_parser, main

from ..helpers import HERTZ_BEAM_CASE

#: In-process memory ceiling: the peak resident set of this test process may grow by no
#: more than this while fuzzing (ru_maxrss is a high-water mark, so one bad example shows).
MEMORY_LIMIT_BYTES = 1 << 30
#: Commands whose valid inputs run a computation of seconds or more.
HEAVY = {"chart", "point", "classify", "sweep", "simulate", "fd", "lookup", "warm-up"}
#: Values every numeric option must refuse (and refuse before computing).
BAD_NUMBERS = ("nan", "inf", "-inf", "-1", "0", "1e300", "-1e300", "abc", "")
EDGE_NUMBERS = BAD_NUMBERS + ("1e-300", "1e-6", "0.5", "1", "2", "20", "1e6")


def derandomised(seed_value: int, examples: int, **strategies):
    """The Hypothesis decorators of every test here: ``examples`` draws of ``strategies`` from a fixed
    seed (the same draws every run), no deadline, no example database."""
    def decorate(test):
        fuzzed = given(**strategies)(test)
        fuzzed = settings(max_examples=examples, deadline=None, derandomize=True, database=None,
                          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])(fuzzed)
        return seed(seed_value)(fuzzed)
    return decorate


HERTZ_BEAM = 'name = "fuzz"\n' + HERTZ_BEAM_CASE + "[solver]\nduration = 0.0005\n"

FD_BEAM = HERTZ_BEAM.replace('law = "hertz"', 'law = "stronge"').replace(
    "[solver]\n", '[solver]\nkind = "fd"\n').replace('material = "aluminium-6061-t6"', 'material = "structural-steel"') \
    + "[fd]\nn_elements = 20\n"

SWEEP = """output = "out"
[grid]
zeta = {min = 0.5, max = 1.0, count = 2}
lambda = [1.0]
[[structure]]
kind = "beam"
"""


def _rss_bytes() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # kB on Linux


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Input files a user may point a command at: valid, broken, binary, missing, a directory."""
    root = tmp_path_factory.mktemp("fuzz")
    (root / "case.toml").write_text(HERTZ_BEAM)
    (root / "fd.toml").write_text(FD_BEAM)
    (root / "sweep.toml").write_text(SWEEP)
    (root / "broken.toml").write_text("[impactor\nradius = ")
    (root / "binary.toml").write_bytes(b"\xff\xfe\x00\x01")
    (root / "a_directory.toml").mkdir()
    (root / "a_file").write_text("x")
    return {"valid_case": root / "case.toml", "valid_sweep": root / "sweep.toml", "root": root,
            "fd_case": root / "fd.toml",
            "bad": [root / "broken.toml", root / "binary.toml", root / "a_directory.toml", root / "missing.toml"],
            "a_file": root / "a_file"}


def _subcommands():
    parser = build_parser()
    return next(a for a in parser._actions if a.dest == "command").choices


SUBCOMMANDS = _subcommands()


#: Words for the free-text options (--law, --target, --material, …): valid ones and not.
WORDS = {"law": ["hertz", "linear", "yigit-christoforou", "stronge", "xyz"],
         "target": ["beam-ss", "beam-cf", "plate-ss", "plate-cccc", "plate-sfsf", "beam-xx", "plate"],
         "material": ["structural-steel", "aluminium-6061-t6", "t300-934", "unobtainium"],
         "target_material": ["structural-steel", "aluminium-6061-t6", "t300-934", "unobtainium"],
         "theory": ["euler", "rayleigh", "timoshenko", "kirchhoff", "mindlin", "xyz"]}


def _value(draw, action, numbers):
    if action.choices is not None:
        return draw(st.sampled_from([*map(str, action.choices), "not-a-choice"]))
    if action.type in (float, int):
        return draw(st.one_of(st.sampled_from(numbers), st.floats(1e-3, 1e3).map(repr),
                              st.floats(allow_nan=False, width=64).map(repr)))
    return draw(st.sampled_from(WORDS.get(action.dest, ["hertz", "structural-steel", "xyz", "", "1"])))


def _bases(files) -> dict:
    """A valid command line per subcommand (tiny where it computes): the fuzz mutates these."""
    root = files["root"]
    return {
        "chart": ["chart", "--out", str(root / "chart"), "--zeta-range", "0.5", "1", "--zeta-count", "2",
                  "--lambdas", "0.5", "2", "--workers", "1", "--quiet"],
        "point": ["point", "--target", "beam-ss", "--zeta", "0.5", "--lambda", "1", "--no-check"],
        "asymptote": ["asymptote", "infinite-beam", "--zeta", "1.5"],
        "classify": ["classify", "--zeta", "1", "--lambda", "1", "--kind", "plate", "--from-map"],
        "lookup": ["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1", "--lambda", "1"],
        "sweep": ["sweep", str(files["valid_sweep"]), "--workers", "1", "--quiet"],
        "simulate": ["simulate", str(files["valid_case"]), "--out", str(root / "sim")],
        "fd": ["fd", str(files["fd_case"]), "--out", str(root / "fd")],
        "halfspace": ["halfspace", "--law", "hertz", "--radius", "0.005", "--velocity", "3", "--material",
                      "structural-steel", "--target-material", "aluminium-6061-t6"],
        "restitution": ["restitution", "--beta", "10"],
        "plot": ["plot", str(Path(__file__).resolve().parents[2] / "impactmaps" / "maps" / "data"
                             / "beam-ss-euler-epp.npz"), "--beta", "10", "--out", str(root / "epp.png")],
        "init": ["init", "plate", str(root / "new.toml"), "--overwrite"],
        "check": ["check", str(files["valid_case"])],
        "modes": ["modes", str(files["valid_case"]), "--count", "4"],
        "materials": ["materials"],
        "laws": ["laws"],
        "warm-up": ["warm-up", "--workers", "1"],
    }


def _set_option(argv: list, action, values: list) -> list:
    """``argv`` with ``action``'s option given ``values`` (replacing its values if present)."""
    flags = set(action.option_strings)
    out, skip = [], False
    for item in argv:
        if item in flags:
            skip = True
            continue
        if skip and not item.startswith("--"):
            continue
        skip = False
        out.append(item)
    return out + [action.option_strings[-1], *values]


@st.composite
def command_lines(draw, files, cheap: bool, name: str):
    """A command line of subcommand ``name``: a valid one with 0–3 options (or its input
    file) set to drawn values."""
    sub = SUBCOMMANDS[name]
    argv = list(_bases(files)[name])
    options = [a for a in sub._actions if a.option_strings and a.dest not in ("help", "json")]
    for _ in range(draw(st.integers(0, 3))):
        if not options:
            break
        action = draw(st.sampled_from(options))
        if action.nargs == 0:
            argv = [a for a in argv if a not in action.option_strings] + (
                [action.option_strings[-1]] if draw(st.booleans()) else [])
            continue
        if action.dest in ("out", "plot"):
            target = draw(st.sampled_from(["out", "a_file", "a_file/sub", "plot.png", "plot.xyz"]))
            argv = _set_option(argv, action, [str(files["root"] / target)])
            continue
        if action.dest == "case":
            argv = _set_option(argv, action, [str(draw(st.sampled_from([files["valid_case"], *files["bad"]])))])
            continue
        count = action.nargs if isinstance(action.nargs, int) else (draw(st.integers(1, 3)) if action.nargs else 1)
        argv = _set_option(argv, action, [_value(draw, action, EDGE_NUMBERS) for _ in range(count)])
    positional = [a for a in sub._actions if not a.option_strings and a.dest not in ("help",)]
    if positional and draw(st.integers(0, 3)) == 0:  # the input file or the choice
        action = draw(st.sampled_from(positional))
        index = 1 + positional.index(action)
        if index < len(argv):
            if action.dest in ("case", "config"):
                argv[index] = str(draw(st.sampled_from(files["bad"])))
            elif action.dest == "file":
                argv[index] = str(files["root"] / draw(st.sampled_from(["a_file/x.toml", "a_directory.toml"])))
            else:
                argv[index] = _value(draw, action, EDGE_NUMBERS)
    if cheap and name in HEAVY:
        # a heavy command must refuse an out-of-range value before computing: give it one
        numerics = [a for a in options if a.type in (float, int) and a.nargs is None]
        if numerics:
            action = draw(st.sampled_from(numerics))
            argv = _set_option(argv, action, [draw(st.sampled_from(("nan", "-1", "-inf", "abc")))])
        else:  # simulate, fd: a file it must refuse
            argv[1] = str(draw(st.sampled_from(files["bad"])))
    if draw(st.booleans()):
        argv.append("--json")
    return argv


def _run(argv, capsys, out_dir: Path):
    """Run one command line in-process; the checks every example must pass."""
    import os

    before = os.getcwd()
    os.chdir(out_dir)  # default outputs (./impactmaps-output, KIND.toml) land in the fuzz directory
    try:
        status = main(argv)
    finally:
        os.chdir(before)
    captured = capsys.readouterr()
    if os.environ.get("FUZZ_LOG"):  # optional: append each command line and its status to this file
        with open(os.environ["FUZZ_LOG"], "a") as log:
            log.write(f"{status} {argv}\n")
    assert status in (0, 2), (argv, status, captured.err[-2000:])
    assert "Traceback" not in captured.err, (argv, captured.err[-2000:])
    if "--json" in argv and captured.out.strip():
        json.loads(captured.out, parse_constant=lambda name: pytest.fail(f"{argv}: {name} in JSON output"))
    if status == 2:
        lines = [line for line in captured.err.splitlines() if line and not line.startswith("warning:")]
        assert len(lines) == 1, (argv, captured.err[-2000:])
    return status


def _fuzz(data, files, capsys, cheap, start_rss, name):
    argv = data.draw(command_lines(files, cheap, name))
    status = _run(argv, capsys, files["root"])
    if cheap and argv[0] in HEAVY:
        assert status == 2, argv  # a bad value was given: refused, nothing computed
    assert _rss_bytes() - start_rss < MEMORY_LIMIT_BYTES, argv


@pytest.fixture(scope="module")
def start_rss():
    """The peak resident set when this module's tests start [bytes]."""
    return _rss_bytes()


@pytest.mark.parametrize("name", sorted(SUBCOMMANDS))
@derandomised(20261126, 15, data=st.data())
def test_fuzz_every_subcommand_exits_0_or_2(name, data, files, capsys, start_rss):
    _fuzz(data, files, capsys, cheap=True, start_rss=start_rss, name=name)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SUBCOMMANDS))
@derandomised(7, 8, data=st.data())
def test_fuzz_every_subcommand_with_computations(name, data, files, capsys, start_rss):
    _fuzz(data, files, capsys, cheap=False, start_rss=start_rss, name=name)


# -- case-file keys -------------------------------------------------------------------------------
#: Every key of a case file by section (the schema of impactmaps.cases), with a valid base.
CASE_KEYS = {
    "impactor": ("radius", "material", "mass", "density", "velocity"),
    "target": ("type", "length", "width", "height", "supports", "theory", "impact_position", "length_x",
               "length_y", "thickness", "edges", "impact_point", "shear_correction", "damping_ratio",
               "material", "yield_strength", "layup", "plies"),
    "contact": ("law", "target_radius", "yield_strength", "stiffness", "yield_pressure_factor",
                "plastic_pressure_factor", "plastic_indentation_ratio"),
    "solver": ("kind", "duration", "time_step", "cutoff_ratio", "min_modes", "residual_flexibility",
               "time_step_ratio", "resolve_ratio", "force_resolution", "max_time_ratio", "max_events",
               "check_convergence", "tolerance"),
    "output": ("history_stride", "normalised"),
    "fd": ("n_elements", "n_half_layers", "plastic", "hardening_modulus", "damping_per_length", "gravity",
           "safety_factor", "time_step", "history_stride", "gauge_positions"),
}
TOML_VALUES = ("0", "-1", "1e300", "1e-300", "nan", "inf", "-inf", "0.5", "3", "1e9", "true", '"abc"', '""',
               '"ss"', '"CCCC"', '"hertz"', '"linear"', '"mindlin"', '"plate"', '"halfspace"', '"fd"',
               '"structural-steel"', "[0.1, 0.1]", "[]", "{}", '{ply = "t300-934", angles_deg = [0, 90]}')
BASE = {
    "impactor": {"radius": "0.00635", "material": '"structural-steel"', "velocity": "1.0"},
    "target": {"type": '"beam"', "length": "0.5", "width": "0.02", "height": "0.02", "supports": '"ss"',
               "theory": '"euler"', "material": '"aluminium-6061-t6"'},
    "contact": {"law": '"hertz"'},
    "solver": {"duration": "0.0005"},
}


def _render(sections: dict) -> str:
    lines = []
    for section, entries in sections.items():
        lines.append(f"[{section}]")
        lines += [f"{key} = {value}" for key, value in entries.items()]
    return "\n".join(lines) + "\n"


@st.composite
def case_files(draw):
    sections = {name: dict(entries) for name, entries in BASE.items()}
    for _ in range(draw(st.integers(1, 3))):
        section = draw(st.sampled_from(sorted(CASE_KEYS)))
        key = draw(st.sampled_from(CASE_KEYS[section]))
        value = draw(st.one_of(st.sampled_from(TOML_VALUES), st.floats(1e-4, 10.0).map(repr),
                               st.floats(allow_nan=False, allow_infinity=False, width=64).map(repr)))
        sections.setdefault(section, {})[key] = value
    return _render(sections)


def _run_case_file(text, files, capsys, start_rss, command, *options):
    """``impactmaps COMMAND FILE OPTIONS --json`` on the case-file ``text``: the checks of :func:`_run`, memory bounded."""
    path = files["root"] / "mutated.toml"
    path.write_text(text)
    _run([command, str(path), *options, "--json"], capsys, files["root"])
    assert _rss_bytes() - start_rss < MEMORY_LIMIT_BYTES


@derandomised(20261126, 120, text=case_files())
def test_fuzz_case_keys_check_exits_0_or_2(text, files, capsys, start_rss):
    """``impactmaps check`` (validation and derived numbers, no run) on mutated case files."""
    _run_case_file(text, files, capsys, start_rss, "check")


@pytest.mark.slow
@derandomised(11, 40, text=case_files())
def test_fuzz_case_keys_simulate_exits_0_or_2(text, files, capsys, start_rss):
    """``impactmaps simulate`` on mutated (short) case files: runs or refuses, never a traceback."""
    _run_case_file(text, files, capsys, start_rss, "simulate", "--out", str(files["root"] / "sim"))

