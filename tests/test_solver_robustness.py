"""Issue 29 on the solver side: every modal input is answered right, refused or announced.

Each test is named after what it guards; the reproducers are the inputs of the issue.
"""

from __future__ import annotations

import pytest

from impactmaps.cli import main

MINDLIN_CASE = """
[impactor]
radius = 0.005
material = "structural-steel"
velocity = 2.0
[target]
type = "plate"
length_x = 0.25
length_y = 0.25
thickness = 0.004
material = "structural-steel"
theory = "mindlin"
edges = "{edges}"
[contact]
law = "hertz"
"""

MINDLIN_SWEEP = """
output = "{out}"
[grid]
zeta = {{min = 0.2, max = 2.0, count = 2}}
lambda = [1.0]
[[structure]]
kind = "plate"
theory = "mindlin"
supports = "{edges}"
"""


@pytest.mark.parametrize("command", ["simulate", "lookup", "sweep"])
def test_mindlin_plate_with_clamped_edges_is_a_clean_refusal(tmp_path, capsys, command):
    """A Mindlin plate with edges other than SSSS: exit status 2 and one line naming the
    option, its value and what is supported — never a NotImplementedError traceback
    (issue 29 item 2: ``simulate``, ``lookup --case``, ``sweep``)."""
    if command == "sweep":
        path = tmp_path / "sweep.toml"
        path.write_text(MINDLIN_SWEEP.format(out=tmp_path / "out", edges="CCCC"))
        argv = ["sweep", str(path), "--quiet", "--workers", "1"]
    else:
        path = tmp_path / "case.toml"
        path.write_text(MINDLIN_CASE.format(edges="CCCC"))
        argv = (["simulate", str(path), "--out", str(tmp_path / "out")] if command == "simulate"
                else ["lookup", "--case", str(path)])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "theory = 'mindlin'" in err and "edges = 'CCCC'" in err and "'SSSS'" in err
