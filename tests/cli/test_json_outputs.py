"""Every subcommand's ``--json`` output is strict JSON (no NaN, no Infinity).

The table below names one invocation per subcommand; a test checks that the table
covers every subcommand of the parser, so a new command cannot skip this check.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from impactmaps.cli import build_parser, main

from ..helpers import EXAMPLES, SWEEP_CONFIG, strict_json_loads


COMMANDS = ("chart", "point", "asymptote", "classify", "lookup", "sweep", "simulate", "fd", "halfspace",
            "restitution", "plot", "init", "check", "modes", "warm-up", "materials", "laws")
#: A shipped elastic-plastic map: `plot` draws it at one β.
SHIPPED_EPP_MAP = Path(__file__).resolve().parents[2] / "impactmaps" / "maps" / "data" / "beam-ss-euler-epp.npz"


def _invocations(tmp_path):
    (tmp_path / "sweep.toml").write_text(SWEEP_CONFIG)
    return {
        "chart": ["chart", "--out", str(tmp_path / "chart"), "--zeta-range", "0.1", "1", "--zeta-count", "2",
                  "--lambdas", "0.5", "2", "--workers", "1", "--quiet"],
        "point": ["point", "--target", "beam-ff", "--zeta", "0.5", "--lambda", "1", "--no-check"],
        "asymptote": ["asymptote", "infinite-beam", "--zeta", "1.5"],
        "classify": ["classify", "--zeta", "1", "--lambda", "1", "--kind", "plate", "--from-map"],
        "lookup": ["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1", "--lambda", "1"],
        "sweep": ["sweep", str(tmp_path / "sweep.toml"), "--workers", "1", "--quiet"],
        "simulate": ["simulate", str(EXAMPLES / "aluminium_beam_linear.toml"), "--out", str(tmp_path / "sim")],
        "fd": ["fd", str(EXAMPLES / "steel_beam_fd_stronge.toml"), "--out", str(tmp_path / "fd")],
        "halfspace": ["halfspace", "--law", "yigit-christoforou", "--radius", "0.005", "--velocity", "3",
                      "--material", "structural-steel", "--target-material", "aluminium-6061-t6"],
        "restitution": ["restitution", "--beta", "1e8"],
        "plot": ["plot", str(SHIPPED_EPP_MAP), "--beta", "10", "--out", str(tmp_path / "epp.png")],
        "init": ["init", "plate", str(tmp_path / "plate.toml")],
        "check": ["check", str(EXAMPLES / "steel_plate_hertz.toml")],
        "modes": ["modes", str(EXAMPLES / "steel_plate_hertz.toml"), "--count", "8"],
        # in this process: the kernels the commands above compiled are reused, the rest compiled once
        "warm-up": ["warm-up", "--workers", "1"],
        "materials": ["materials"],
        "laws": ["laws"],
    }


def test_every_subcommand_is_covered(tmp_path):
    parser = build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    assert set(commands) == set(_invocations(tmp_path)) == set(COMMANDS)


@pytest.mark.parametrize("command", COMMANDS)
def test_json_output_is_strict(command, tmp_path, capsys):
    argv = _invocations(tmp_path)[command]
    status = main([*argv, "--json"])
    out = capsys.readouterr().out
    assert status == 0
    values = strict_json_loads(out)
    assert isinstance(values, dict) and values
    for key, value in values.items():
        if value is None:
            stem = key.split("_")[0]
            assert any(k.startswith(stem) and k.endswith("_note") for k in values), \
                f"{command}: {key} is null without a companion note"
    shutil.rmtree(tmp_path, ignore_errors=True)


@pytest.mark.parametrize("argv", [
    ["asymptote", "infinite-beam", "--zeta", "1.5"],
    ["point", "--target", "beam-ff", "--zeta", "0.5", "--lambda", "1", "--no-check"],
    ["restitution", "--beta", "1e300"],
    ["point", "--target", "plate-ss", "--zeta", "nan", "--lambda", "1"],
])
def test_json_never_prints_nan_or_infinity(argv, capsys):
    """The issue's reproducers: values that do not exist are null with a note, or an error."""
    main([*argv, "--json"])
    out = capsys.readouterr().out
    assert "NaN" not in out and "Infinity" not in out
    strict_json_loads(out)


def test_strict_loads_rejects_nan():
    with pytest.raises(ValueError):
        strict_json_loads('{"a": NaN}')
