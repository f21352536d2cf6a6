"""Smoke test: every ``validation/*.py`` and ``data_build/*.py`` script runs end to end on its
tiny ``--smoke`` setting.

Each script is run as from the command line (``runpy.run_path`` with ``__name__ ==
"__main__"`` and ``sys.argv = [script, "--smoke", "--out-dir", tmp]``), with its
directory on ``sys.path`` (as when Python runs a script in it). It must finish,
write its outputs into the temporary directory only (never into ``figures/``, the
package's data, ``validation/`` or ``data_build/``) and write at least one file there. The numbers a smoke
run prints are not checked: the studies' results are checked by the other tests.
``--smoke`` is described in ``validation/_script_options.py``.
"""

from __future__ import annotations

import runpy
import sys
import tomllib
import warnings

import pytest

from ..helpers import ROOT

VALIDATION = ROOT / "validation"
#: the scripts that build the package's shipped data: the folder pyproject.toml names
DATA_BUILD = ROOT / tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["impactmaps"]["data-build"]
SCRIPTS = sorted(str(p.relative_to(ROOT)) for folder in (VALIDATION, DATA_BUILD)
                 for p in folder.glob("*.py") if not p.name.startswith("_"))
#: the directories a full run writes into; a smoke run must leave them untouched
GUARDED = (ROOT / "figures", ROOT / "impactmaps" / "maps" / "data", VALIDATION, DATA_BUILD)


def _files(directories) -> dict:
    return {path: path.stat().st_mtime_ns for directory in directories if directory.exists()
            for path in directory.rglob("*") if path.is_file() and "__pycache__" not in path.parts}


def test_there_are_validation_scripts():
    assert len(SCRIPTS) >= 8, SCRIPTS
    assert sum(script.startswith(DATA_BUILD.name) for script in SCRIPTS) == 6, SCRIPTS


@pytest.mark.parametrize("script", SCRIPTS)
def test_validation_script_smoke_run(script, tmp_path, monkeypatch, capsys):
    out_dir = tmp_path / "out"
    before = _files(GUARDED)
    path = ROOT / script
    monkeypatch.syspath_prepend(str(path.parent))
    monkeypatch.setattr(sys, "argv", [str(path), "--smoke", "--out-dir", str(out_dir)])
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        # the studies run on purpose where the solvers give notices (capped modes, Mindlin
        # thickness-shear, records that end in contact); a smoke run only checks the plumbing
        warnings.simplefilter("ignore")
        runpy.run_path(str(path), run_name="__main__")
    assert capsys.readouterr().out.strip(), f"{script} printed nothing"
    assert any(path.is_file() for path in out_dir.rglob("*")), f"{script} wrote nothing into --out-dir"
    assert _files(GUARDED) == before, f"{script} --smoke wrote outside --out-dir"
