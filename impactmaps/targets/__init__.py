"""Targets: anything that supplies modes at the impact point (beams, plates, half-space).

The classes are imported on first use (``impactmaps.targets.Beam`` loads
:mod:`impactmaps.targets.beams.beam`), so a module that needs only :mod:`.options` (the
command line's parser) does not import the modal solvers.
"""

from __future__ import annotations

import importlib

from .._checks import require_choice
from .options import STRUCTURE_KINDS

__all__ = ["Beam", "HalfSpace", "InfiniteImpact", "ModalBasis", "Plate", "Target", "target_class"]

_EXPORTS = {
    "Beam": ".beams.beam",
    "HalfSpace": ".halfspace",
    "InfiniteImpact": ".base",
    "ModalBasis": ".base",
    "Plate": ".plates.plate",
    "Target": ".base",
}


def __getattr__(name: str):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted({*globals(), *__all__})


def target_class(kind: str):
    """The target class of a structure kind: ``"beam"`` → :class:`Beam`, ``"plate"`` → :class:`Plate`."""
    require_choice("kind", kind, STRUCTURE_KINDS)
    return __getattr__({"beam": "Beam", "plate": "Plate"}[kind])
