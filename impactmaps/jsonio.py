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
    """A copy of ``value`` made of JSON types only (``dict``, ``list``, ``str``, numbers,
    ``bool``, ``None``); non-finite floats become ``None``, unknown objects their ``str``.

    Parameters
    ----------
    value : object
        Nested dicts, lists, tuples, NumPy arrays and scalars, paths, strings.

    Returns
    -------
    object
        The JSON-ready copy.
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
    """Strict JSON text of ``value`` (via :func:`plain`; ``allow_nan=False``).

    Parameters
    ----------
    value : object
        Anything :func:`plain` accepts.
    **options
        Passed to :func:`json.dumps` (``indent``, ``sort_keys``).

    Returns
    -------
    str
    """
    return json.dumps(plain(value), allow_nan=False, **options)
