"""Old spellings of renamed parameters, still accepted for a while with a ``FutureWarning``.

One word per concept (``docs/architecture.rst``, "Words"): ``kind`` is beam or plate,
``structure`` a map structure (kind, supports, theory, …). The public functions that took
the kind as ``structure=`` accept that spelling through :func:`renamed_keyword`.
"""

from __future__ import annotations

import functools
import warnings

__all__ = ["renamed_keyword"]


def renamed_keyword(old: str, new: str):
    """Decorator: a call with keyword ``old`` is a call with ``new`` (a ``FutureWarning`` says
    so; ``TypeError`` when both are given)."""

    def decorate(function):
        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            if old in kwargs:
                if new in kwargs:
                    raise TypeError(f"{function.__name__}() got both {new!r} and its old name {old!r}")
                warnings.warn(f"{function.__name__}({old}=...) is now {function.__name__}({new}=...) "
                              f"(beam or plate); the old name will be removed", FutureWarning, stacklevel=2)
                kwargs[new] = kwargs.pop(old)
            return function(*args, **kwargs)

        return wrapper

    return decorate
