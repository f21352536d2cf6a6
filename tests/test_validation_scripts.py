"""Smoke test: every ``validation/*.py`` script runs end to end on its tiny ``--smoke`` setting.

Each script is run as from the command line (``runpy.run_path`` with ``__name__ ==
"__main__"`` and ``sys.argv = [script, "--smoke", "--out-dir", tmp]``), with the
validation directory on ``sys.path`` (as when Python runs a script in it). It must finish,
write its outputs into the temporary directory only (never into ``figures/``, the
package's data or ``validation/``) and write at least one file there. The numbers a smoke
run prints are not checked: the studies' results are checked by the other tests.
``--smoke`` is described in ``validation/_script_options.py``.
"""

from __future__ import annotations

import runpy
import sys
import warnings

import pytest

from .helpers import ROOT

VALIDATION = ROOT / "validation"
SCRIPTS = sorted(p.name for p in VALIDATION.glob("*.py") if not p.name.startswith("_"))
#: the directories a full run writes into; a smoke run must leave them untouched
GUARDED = (ROOT / "figures", ROOT / "impactmaps" / "maps" / "data", VALIDATION)


def _files(directories) -> dict:
    return {path: path.stat().st_mtime_ns for directory in directories if directory.exists()
            for path in directory.rglob("*") if path.is_file() and "__pycache__" not in path.parts}


def test_there_are_validation_scripts():
    assert len(SCRIPTS) >= 8, SCRIPTS


@pytest.mark.parametrize("script", SCRIPTS)
def test_validation_script_smoke_run(script, tmp_path, monkeypatch, capsys):
    out_dir = tmp_path / "out"
    before = _files(GUARDED)
    monkeypatch.syspath_prepend(str(VALIDATION))
    monkeypatch.setattr(sys, "argv", [str(VALIDATION / script), "--smoke", "--out-dir", str(out_dir)])
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        # the studies run on purpose where the solvers give notices (capped modes, Mindlin
        # thickness-shear, records that end in contact); a smoke run only checks the plumbing
        warnings.simplefilter("ignore")
        runpy.run_path(str(VALIDATION / script), run_name="__main__")
    assert capsys.readouterr().out.strip(), f"{script} printed nothing"
    assert any(path.is_file() for path in out_dir.rglob("*")), f"{script} wrote nothing into --out-dir"
    assert _files(GUARDED) == before, f"{script} --smoke wrote outside --out-dir"
