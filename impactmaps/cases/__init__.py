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

from .case import (
    SOLVER_KINDS,
    TARGET_TYPES,
    Case,
    OutputSettings,
    load_case,
    parse_case,
)
from .numbers import case_dimensionless, case_numbers
from .run import (
    case_summary,
    read_case_outputs,
    run_case,
    write_case_outputs,
)

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
