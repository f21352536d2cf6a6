"""Helpers shared by the tests: where the repository's files are, and strict JSON.

The tests import the *installed* package (``pytest`` runs with
``--import-mode=importlib``); what they read beside it — the examples, the validation
scripts and results, the docs — comes from this checkout, located here once.
Closed-form test systems are in :mod:`tests.analytic`.
"""

from __future__ import annotations

import importlib.util
import json
import sys
import textwrap
from pathlib import Path

#: The repository checkout the tests run from.
ROOT = Path(__file__).resolve().parents[1]
#: Case files and short scripts (``examples/``).
EXAMPLES = ROOT / "examples"
#: Validation scripts and their committed results (``validation/``).
VALIDATION = ROOT / "validation"
#: Small data files of the tests (``tests/data/``).
DATA = ROOT / "tests" / "data"

def case_text(target: str, *, radius: float = 0.005, velocity: float = 1.0, mass: float | None = None,
              law: str = "hertz", name: str = "", after: str = "") -> str:
    """Case-file text: a structural-steel sphere of ``radius`` [m] (and ``mass`` [kg], if given) at
    ``velocity`` [m/s] on the ``[target]`` table of the lines ``target``, with contact ``law``; ``after``:
    the lines that follow (more contact keys, then other tables); ``name``: the case's name, if any."""
    lines = [f'name = "{name}"'] if name else []
    lines += ["[impactor]", f"radius = {radius!r}"] + ([f"mass = {mass!r}"] if mass is not None else [])
    lines += ['material = "structural-steel"', f"velocity = {velocity!r}",
              "[target]", textwrap.dedent(target).strip(), "[contact]", f'law = "{law}"']
    return "\n".join(lines) + "\n" + textwrap.dedent(after).lstrip()


#: The ``[target]`` lines of a clamped (CCCC) 120 × 100 × 3 mm aluminium Kirchhoff plate: the
#: isotropic plate of the clamped and the laminate tile tests.
CLAMPED_PLATE_TARGET = """
    type = "plate"
    length_x = 0.12
    length_y = 0.1
    thickness = 0.003
    material = "aluminium-6061-t6"
    theory = "kirchhoff"
    edges = "CCCC"
"""


#: A Hertz impact of a 12.7 mm steel ball at 1 m/s on a simply supported 500 × 20 × 20 mm
#: aluminium Euler beam struck at mid-span (case-file text, no name): the family of the
#: shipped Hertz beam map, so ``lookup`` answers from it.
HERTZ_BEAM_CASE = case_text("""
    type = "beam"
    length = 0.5
    width = 0.02
    height = 0.02
    supports = "ss"
    theory = "euler"
    material = "aluminium-6061-t6"
""", radius=0.00635)


#: A small sweep file for the ``sweep`` command: two ζ, one λ, one beam structure.
SWEEP_CONFIG = """
output = "out"
[grid]
zeta = {min = 0.2, max = 2.0, count = 2}
lambda = [1.0]
[[structure]]
kind = "beam"
"""


def _refuse_constant(name):
    raise ValueError(f"not strict JSON: {name}")


def strict_json_loads(text: str):
    """``json.loads`` that rejects NaN, Infinity and -Infinity (they are not JSON)."""
    return json.loads(text, parse_constant=_refuse_constant)


def repository_module(relative_path: str):
    """Import a script of this checkout (``benchmarks/…``, ``validation/…``) by its path.

    The checkout is not on ``sys.path`` (the tests import the installed package), so its
    scripts are loaded from their files; a script imported twice is the same module.
    """
    path = ROOT / relative_path
    name = "_repository_" + "_".join(path.relative_to(ROOT).with_suffix("").parts)
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


def assert_committed_tile_answers(tile: Path, case, cache_dir: Path, map_prefix: str) -> None:
    """The committed on-demand ``tile`` answers ``case`` from ``cache_dir`` with nothing built,
    from a map named ``map_prefix``…, with a band ≤ 3 % of the peak force that holds ``simulate``'s."""
    import shutil
    import warnings

    from impactmaps import lookup
    from impactmaps.cases import run_case

    shutil.copy(tile, cache_dir)
    lines = []
    found = lookup(case=case, cache_dir=cache_dir, notify=lines.append)
    assert lines == [], "the committed tile answers: nothing is built"
    assert found["cache_file"] == str(cache_dir / tile.name)
    assert found["map"].startswith(map_prefix), found["map"]
    assert found["peak_force_error_N"] <= 0.03 * found["peak_force_N"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings
        _, summary = run_case(case)
    assert abs(found["peak_force_N"] - summary["peak_force_N"]) <= found["peak_force_error_N"], (found, summary)
