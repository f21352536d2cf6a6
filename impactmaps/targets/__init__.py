"""Targets: anything that supplies modes at the impact point (beams, plates, half-space)."""

from .._checks import require_choice
from .base import InfiniteImpact, ModalBasis, Target
from .beam import Beam
from .halfspace import HalfSpace
from .options import STRUCTURE_KINDS
from .plate import Plate

__all__ = ["Beam", "HalfSpace", "InfiniteImpact", "ModalBasis", "Plate", "Target", "target_class"]


def target_class(kind: str) -> type[Target]:
    """The target class of a structure kind: ``"beam"`` → :class:`Beam`, ``"plate"`` → :class:`Plate`."""
    require_choice("kind", kind, STRUCTURE_KINDS)
    return {"beam": Beam, "plate": Plate}[kind]
