"""Strict JSON for every output: plain Python values, no NaN or Infinity (a non-finite float
becomes ``null``).
"""

from __future__ import annotations

import json
import math
from pathlib import PurePath

import numpy as np

__all__ = ["plain", "dumps"]


def plain(value):
    """A JSON-ready copy of ``value`` (nested dicts, lists, tuples, NumPy arrays and scalars,
    paths, strings) made of JSON types only; non-finite floats become ``None``, unknown
    objects their ``str``.
    """
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [plain(v) for v in list(value)]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, PurePath):
        return str(value)
    return str(value)


def dumps(value, **options) -> str:
    """Strict JSON text of ``value`` (via :func:`plain`; ``allow_nan=False``); ``options`` go to
    :func:`json.dumps`.
    """
    return json.dumps(plain(value), allow_nan=False, **options)
