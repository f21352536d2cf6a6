"""The modules one ``impactmaps lookup`` of a point, and of a case, walks through, traced (issue 38).

``sys.setprofile`` records the package modules whose functions the command calls, in the
order of their first call; calls made while a module is being imported are left out (the
trace is the lookup's own path). A case lookup is traced in two parts: building the case
from its file (``load_case``: materials, contact law, target) and the lookup after it. The
traces are printed (``pytest -rP``) and are the ones in ``docs/architecture.rst``; the caps
keep them from growing, and the read side of the maps never reaches the build side.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import impactmaps
from impactmaps.cli import main

ROOT = str(Path(impactmaps.__file__).resolve().parent)
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: The most package modules a point lookup walks through; lower it as the path shortens (16 since
#: ``cli/_signals.py``, the signal handling every command runs in, was given its own module).
MAX_POINT_LOOKUP_MODULES = 16
#: The most a ``--case`` lookup answered by a shipped map walks through after its case is built
#: (the command's own modules included), and in all (building the case: most of them); each with
#: ``cli/_signals.py``.
MAX_CASE_LOOKUP_MODULES = 35
MAX_CASE_MODULES = 44


def trace(argv: list[str]) -> tuple[list[str], list[str], int]:
    """The package modules ``impactmaps ARGV`` calls into, in the order of their first call; those it
    calls after ``cases/case.py``'s ``load_case`` returned (empty without a case); and how many
    of the first were called before that."""
    seen, after, top = {}, {}, sys._getframe()
    built = [None]

    def importing(frame) -> bool:  # a module body between the call and this function: an import
        while frame is not None and frame is not top:
            if frame.f_code.co_name == "<module>":
                return True
            frame = frame.f_back
        return False

    def profile(frame, event, arg):
        if not frame.f_code.co_filename.startswith(ROOT):
            return
        module = "impactmaps" + frame.f_code.co_filename[len(ROOT):]
        if event == "return" and module == "impactmaps/cases/case.py" and frame.f_code.co_name == "load_case":
            built[0] = len(seen)
        elif event == "call" and not importing(frame):
            seen.setdefault(module, None)
            if built[0] is not None:
                after.setdefault(module, None)

    sys.setprofile(profile)
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            main(argv)
    finally:
        sys.setprofile(None)
    return list(seen), list(after), len(seen) if built[0] is None else built[0]


def test_a_point_lookup_walks_few_modules_and_no_build_module(monkeypatch):
    monkeypatch.setenv("IMPACTMAPS_NO_BACKGROUND_WARMUP", "1")
    argv = ["lookup", "--kind", "plate", "--theory", "kirchhoff", "--zeta", "1.198", "--lambda", "0.425"]
    modules, _, _ = trace(argv)
    print(f"\n$ impactmaps {' '.join(argv)}: {len(modules)} package modules\n  " + "\n  ".join(modules))
    assert "impactmaps/maps/read/lookup.py" in modules and "impactmaps/maps/read/reader.py" in modules
    assert not [module for module in modules if module.startswith(("impactmaps/maps/compute/", "impactmaps/cases/",
                                                                   "impactmaps/_compile/"))]
    assert len(modules) <= MAX_POINT_LOOKUP_MODULES


def test_a_case_lookup_walks_few_modules_after_building_its_case(monkeypatch, tmp_path):
    """A case a shipped map answers (the aluminium example as an Euler beam): loading the case
    file builds its materials, target and contact law, most of the modules; the lookup after it
    names the case's map law from the families' layouts, so no build module is on the path."""
    monkeypatch.setenv("IMPACTMAPS_NO_BACKGROUND_WARMUP", "1")
    case_file = tmp_path / "beam.toml"
    case_file.write_text((EXAMPLES / "aluminium_beam_linear.toml").read_text(encoding="utf-8")
                         .replace('theory = "timoshenko"', 'theory = "euler"'), encoding="utf-8")
    argv = ["lookup", "--case", str(case_file), "--no-build", "--json"]
    modules, lookup, built = trace(argv)
    building = modules[:built]
    print(f"\n$ impactmaps lookup --case CASE.toml --no-build: {len(modules)} package modules\n"
          f"the command and building the case (first called before load_case returned): {len(building)}\n  "
          + "\n  ".join(building) + f"\nthe lookup (called after the case is built): {len(lookup)}, "
          f"{len([m for m in lookup if m not in building])} of them not called before\n  "
          + "\n  ".join(m + ("" if m not in building else "   (also building the case)") for m in lookup))
    assert "impactmaps/cases/case_lookup.py" in lookup and "impactmaps/maps/read/reader.py" in lookup
    assert not [module for module in modules if module.startswith(("impactmaps/maps/compute/", "impactmaps/_compile/"))]
    assert len(lookup) <= MAX_CASE_LOOKUP_MODULES and len(modules) <= MAX_CASE_MODULES


_CACHED_LOOKUP = """
import json, sys, warnings
warnings.simplefilter("ignore")
import impactmaps
from impactmaps.cases import load_case
from impactmaps.contact import available_contact_laws, contact_law_class
import impactmaps.cases.case_lookup, impactmaps.cases.on_demand  # the lookup's own imports
case = load_case(sys.argv[1])
before = set(sys.modules)
answer = impactmaps.lookup(case=case)
print(json.dumps({"new": sorted({name.split(".")[0] for name in set(sys.modules) - before}),
                  "compiled": [name for name in available_contact_laws() if contact_law_class(name).kernel.signatures],
                  "cache_file": answer.get("cache_file")}))
"""


@pytest.mark.slow
def test_a_case_lookup_reads_its_cached_tile_without_dask_or_compiled_kernels(tmp_path):
    """A case answered from an on-demand tile on disk (the aluminium example as an Euler beam
    struck off mid-span: 16 points, built once here) reads it with NumPy: in a process that
    imported the lookup's modules, the lookup imports no dask (xarray's opening of a file did)
    and loads no compiled contact kernel (its validity check and any
    asymptote evaluate the law in Python)."""
    case_file = tmp_path / "beam.toml"
    case_file.write_text((EXAMPLES / "aluminium_beam_linear.toml").read_text(encoding="utf-8")
                         .replace('theory = "timoshenko"', 'theory = "euler"')
                         .replace("impact_position = 0.25", "impact_position = 0.2"), encoding="utf-8")
    env = dict(os.environ, IMPACTMAPS_CACHE_DIR=str(tmp_path / "cache"), IMPACTMAPS_NO_BACKGROUND_WARMUP="1",
               PYTHONPATH=os.pathsep.join(filter(None, (str(Path(ROOT).parent), os.environ.get("PYTHONPATH")))))
    run = [sys.executable, "-c", _CACHED_LOOKUP, str(case_file)]
    first = json.loads(subprocess.run(run, capture_output=True, text=True, env=env, check=True).stdout)
    assert first["cache_file"]  # built and cached
    cached = json.loads(subprocess.run(run, capture_output=True, text=True, env=env, check=True).stdout)
    assert cached["cache_file"] == first["cache_file"]
    assert "dask" not in cached["new"], cached["new"]
    assert cached["compiled"] == []
