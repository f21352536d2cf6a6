"""Helpers shared by the tests: where the repository's files are, and strict JSON.

The tests import the *installed* package (``pytest`` runs with
``--import-mode=importlib``); what they read beside it — the examples, the validation
scripts and results, the docs — comes from this checkout, located here once.
Closed-form test systems are in :mod:`tests.analytic`.
"""

from __future__ import annotations

import json
from pathlib import Path

#: The repository checkout the tests run from.
ROOT = Path(__file__).resolve().parents[1]
#: Case files and short scripts (``examples/``).
EXAMPLES = ROOT / "examples"
#: Validation scripts and their committed results (``validation/``).
VALIDATION = ROOT / "validation"
#: Small data files of the tests (``tests/data/``).
DATA = ROOT / "tests" / "data"


def _refuse_constant(name):
    raise ValueError(f"not strict JSON: {name}")


def strict_json_loads(text: str):
    """``json.loads`` that rejects NaN, Infinity and -Infinity (they are not JSON)."""
    return json.loads(text, parse_constant=_refuse_constant)
