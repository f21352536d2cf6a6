"""Case files: a physical impact described in TOML, built into impactmaps objects.

A case file describes one impact of a sphere on a beam, a plate or a half-space, in SI
units (the format: docs/cases.rst). It is validated key by key: every error is a
``ValueError`` naming the key path (``target.length``), the value and the valid range;
an unknown key lists the allowed keys. :func:`run_case` runs it,
:func:`write_case_outputs` writes ``history.csv``, ``summary.json`` and ``case.toml``;
:func:`case_dimensionless` and :func:`case_numbers` give its numbers
(docs/output_keys.rst).
"""

from __future__ import annotations

import importlib

#: The package's names, each loaded from its module on first use (importing ``impactmaps.cases``
#: stays cheap: a lookup reaches :mod:`impactmaps.cases.case_lookup` without the solver that
#: :func:`run_case` needs).
_EXPORTS = {
    "Case": "case", "OutputSettings": "case", "SOLVER_KINDS": "case", "TARGET_TYPES": "case",
    "load_case": "case", "parse_case": "case",
    "case_dimensionless": "numbers", "case_numbers": "numbers",
    "run_case": "run", "case_summary": "run", "write_case_outputs": "run", "read_case_outputs": "run",
}

__all__ = [
    "Case",
    "OutputSettings",
    "SOLVER_KINDS",
    "TARGET_TYPES",
    "load_case",
    "parse_case",
    "run_case",
    "case_dimensionless",
    "case_numbers",
    "case_summary",
    "write_case_outputs",
    "read_case_outputs",
]


def __getattr__(name: str):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'impactmaps.cases' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted([*globals(), *__all__])
