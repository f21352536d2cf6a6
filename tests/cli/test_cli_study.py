"""``simulate CASE --vary KEY=A:B:N``: a parameter study, checked against an exact scaling
law and resumed from its saved runs."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest

from impactmaps.cli import main
from impactmaps.cli.study import parse_vary, render_toml, set_key

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

HALFSPACE = """name = "ball on a half-space"
[impactor]
radius = 0.005
material = "structural-steel"
velocity = 1.0
[target]
type = "halfspace"
material = "aluminium-6061-t6"
[contact]
law = "hertz"
"""


def test_study_follows_the_hertz_velocity_scaling_and_resumes(tmp_path, capsys):
    """On a half-space the Hertz peak force is K_h α_m^{3/2} with α_m ∝ V0^{4/5}: F ∝ V0^{6/5}
    exactly, so the study's peaks at V0 = 1, 2, 3 m/s stand in the ratios 2^1.2 and 3^1.2
    (to the solver's force resolution, 1e-4 relative). A second run reuses every saved run
    and gives the same table."""
    case = tmp_path / "halfspace.toml"
    case.write_text(HALFSPACE)
    argv = ["simulate", str(case), "--vary", "impactor.velocity=1:3:3", "--out", str(tmp_path / "out"), "--json"]
    assert main(argv) == 0
    first = json.loads(capsys.readouterr().out)
    peaks = first["peak_force_N"]
    assert first["runs"] == 3 and first["reused"] == 0
    assert peaks[1] / peaks[0] == pytest.approx(2**1.2, rel=1e-4)
    assert peaks[2] / peaks[0] == pytest.approx(3**1.2, rel=1e-4)
    table = (tmp_path / "out" / "study.csv").read_text()
    assert table.splitlines()[0].startswith("impactor.velocity,peak_force_N")
    assert (tmp_path / "out" / "study_forces.png").exists()
    assert main(argv) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["reused"] == 3 and again["peak_force_N"] == peaks


@pytest.mark.parametrize("spec, fragment", [
    ("velocity=1:2:3", "SECTION.KEY"),
    ("impactor.velocity", "SECTION.KEY"),
    ("impactor.velocity=1:2:0", "[1, 200]"),
    ("impactor.velocity=1:2:1e9", "[1, 200]"),
    ("impactor.velocity=1:nan:3", "finite"),
    ("impactor.velocity=a,b", "finite"),
])
def test_bad_vary_is_refused(spec, fragment):
    with pytest.raises(ValueError, match="--vary") as error:
        parse_vary(spec)
    assert fragment in str(error.value)


def test_vary_values_are_validated_before_the_first_run(tmp_path, capsys):
    """A value out of the key's range is refused naming the key and the value, before any run."""
    case = tmp_path / "halfspace.toml"
    case.write_text(HALFSPACE)
    assert main(["simulate", str(case), "--vary", "impactor.velocity=1,-2", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "--vary impactor.velocity = -2" in err and "impactor.velocity" in err
    assert not (tmp_path / "out" / "study").exists()


def test_vary_of_a_text_key_is_refused():
    data = tomllib.loads(HALFSPACE)
    with pytest.raises(ValueError, match="not a number"):
        set_key(data, "contact.law", 1.0)


@pytest.mark.parametrize("example", sorted(EXAMPLES.glob("*.toml")))
def test_rendered_case_reads_back_the_same(example):
    """The study rewrites a case through render_toml: every shipped example survives the round trip."""
    data = tomllib.loads(example.read_text())
    assert tomllib.loads(render_toml(data)) == data
