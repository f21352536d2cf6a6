"""The modules one ``impactmaps lookup`` of a point, and of a case, walks through, traced (issue 38).

``sys.setprofile`` records the package modules whose functions the command calls, in the
order of their first call; calls made while a module is being imported are left out (the
trace is the lookup's own path). The trace is printed (``pytest -rP``) and is the one in
``docs/architecture.rst``; the cap keeps it from growing, and the read side of the maps
never reaches the build side.
"""

from __future__ import annotations

import contextlib
import io
import sys
from pathlib import Path

import impactmaps
from impactmaps.cli import main

ROOT = str(Path(impactmaps.__file__).resolve().parent)
#: The most package modules a point lookup walks through; lower it as the path shortens.
MAX_POINT_LOOKUP_MODULES = 20
#: The most a ``--case`` lookup answered by a shipped map walks through (loading the case file
#: builds its materials, target and contact law: most of them).
MAX_CASE_LOOKUP_MODULES = 47


def trace(argv: list[str]) -> list[str]:
    """The package modules ``impactmaps ARGV`` calls into, in the order of their first call."""
    seen, top = {}, sys._getframe()

    def importing(frame) -> bool:  # a module body between the call and this function: an import
        while frame is not None and frame is not top:
            if frame.f_code.co_name == "<module>":
                return True
            frame = frame.f_back
        return False

    def profile(frame, event, arg):
        if event == "call" and frame.f_code.co_filename.startswith(ROOT) and not importing(frame):
            seen.setdefault("impactmaps" + frame.f_code.co_filename[len(ROOT):], None)

    sys.setprofile(profile)
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            main(argv)
    finally:
        sys.setprofile(None)
    return list(seen)


def test_a_point_lookup_walks_few_modules_and_no_build_module(monkeypatch):
    monkeypatch.setenv("IMPACTMAPS_NO_BACKGROUND_WARMUP", "1")
    argv = ["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1.198", "--lambda", "0.425"]
    modules = trace(argv)
    print(f"\n$ impactmaps {' '.join(argv)}: {len(modules)} package modules\n  " + "\n  ".join(modules))
    assert "impactmaps/maps/read/lookup.py" in modules and "impactmaps/maps/read/reader.py" in modules
    assert not [module for module in modules if module.startswith("impactmaps/maps/compute/")]
    assert len(modules) <= MAX_POINT_LOOKUP_MODULES


def test_a_case_lookup_walks_few_modules(monkeypatch, tmp_path):
    """A case a shipped map answers (the aluminium example as an Euler beam): loading the case
    file builds its materials, target and contact law, most of the modules; naming its map law
    asks the family (``map_family(law).describes``), which loads the family's point solver
    (``maps/compute/linear_points.py``): the one build module on the path, not yet removed."""
    monkeypatch.setenv("IMPACTMAPS_NO_BACKGROUND_WARMUP", "1")
    example = Path(__file__).resolve().parents[2] / "examples" / "aluminium_beam_linear.toml"
    case_file = tmp_path / "beam.toml"
    case_file.write_text(example.read_text(encoding="utf-8").replace('theory = "timoshenko"', 'theory = "euler"'),
                         encoding="utf-8")
    argv = ["lookup", "--case", str(case_file), "--no-build", "--json"]
    modules = trace(argv)
    print(f"\n$ impactmaps lookup --case CASE.toml --no-build: {len(modules)} package modules\n  " + "\n  ".join(modules))
    assert "impactmaps/cases/case_lookup.py" in modules and "impactmaps/maps/read/reader.py" in modules
    assert [module for module in modules if module.startswith("impactmaps/maps/compute/")] == \
        ["impactmaps/maps/compute/linear_points.py"]
    assert len(modules) <= MAX_CASE_LOOKUP_MODULES
