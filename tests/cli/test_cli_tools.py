"""``impactmaps init`` writes case files that ``check`` accepts; ``check`` validates without
running and prints the numbers ``simulate`` and ``lookup`` use."""

from __future__ import annotations

import json

import pytest

from impactmaps.cli import main
from impactmaps.cli.commands_tools import CASE_TEMPLATES


@pytest.mark.parametrize("kind", sorted(CASE_TEMPLATES))
def test_init_writes_a_case_that_check_accepts(kind, tmp_path, capsys):
    path = tmp_path / f"{kind}.toml"
    assert main(["init", kind, str(path)]) == 0
    capsys.readouterr()
    text = path.read_text()
    assert text.startswith("#") and "impactmaps check" in text
    assert main(["check", str(path), "--json"]) == 0
    values = json.loads(capsys.readouterr().out)
    assert values["valid"] is True
    assert values["solver"] == ("fd" if kind == "fd" else "modal")
    assert values["zeta"] > 0 and values["lambda"] > 0


def test_init_does_not_overwrite_without_asking(tmp_path, capsys):
    path = tmp_path / "beam.toml"
    path.write_text("mine")
    assert main(["init", "beam", str(path)]) == 2
    assert "--overwrite" in capsys.readouterr().err and path.read_text() == "mine"
    assert main(["init", "beam", str(path), "--overwrite"]) == 0
    assert path.read_text() != "mine"


def test_check_prints_the_numbers_lookup_reads(tmp_path, capsys):
    """check's ζ, λ of the Hertz beam template are the Hertz numbers lookup --case uses, and
    it reads the same map force (no simulation)."""
    path = tmp_path / "beam.toml"
    assert main(["init", "beam", str(path)]) == 0
    capsys.readouterr()
    assert main(["check", str(path), "--json"]) == 0
    checked = json.loads(capsys.readouterr().out)
    assert main(["lookup", "--case", str(path), "--json"]) == 0
    looked = json.loads(capsys.readouterr().out)
    assert checked["zeta"] == looked["zeta"] and checked["lambda"] == looked["lambda"]
    assert checked["map_peak_force_N"] == looked["peak_force_N"]
    assert checked["vocabulary"] == "hertz" and checked["beta"] is None and "beta_note" in checked


def test_check_refuses_an_invalid_case_naming_the_key(tmp_path, capsys):
    path = tmp_path / "beam.toml"
    assert main(["init", "beam", str(path)]) == 0
    path.write_text(path.read_text().replace("velocity = 1.0", "velocity = -1.0"))
    capsys.readouterr()
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "impactor.velocity" in err and len(err.strip().splitlines()) == 1
