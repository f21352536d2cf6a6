"""``impactmaps modes CASE.toml`` (issue 39 item 5)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from impactmaps.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_modes_of_a_navier_plate_are_labelled_by_half_waves(capsys):
    assert main(["modes", str(EXAMPLES / "composite_plate_sun_chen.toml"), "--count", "4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["labels"][0] == "(1, 1)" and len(out["frequencies_hz"]) == 4
    assert out["frequencies_hz"] == sorted(out["frequencies_hz"]) and out["resolved"] is True


def test_modes_of_a_clamped_laminate_give_the_basis_and_its_resolved_frequency(capsys):
    assert main(["modes", str(EXAMPLES / "drop_weight_quasi_isotropic.toml"), "--count", "6", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["labels"] == ["1", "2", "3", "4", "5", "6"] and out["resolved"] is True
    assert out["frequencies_hz"][-1] <= out["resolved_frequency_hz"]
    assert "functions per field" in out["basis"]


def test_modes_of_a_beam(capsys):
    assert main(["modes", str(EXAMPLES / "aluminium_beam_linear.toml"), "--count", "3", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["frequencies_hz"]) == 3


@pytest.mark.parametrize("count", ["0", "100000"])
def test_bad_count_is_one_line_and_exit_2(capsys, count):
    assert main(["modes", str(EXAMPLES / "aluminium_beam_linear.toml"), "--count", count]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "--count" in err
