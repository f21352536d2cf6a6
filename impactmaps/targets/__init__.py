"""Targets: anything that supplies modes at the impact point (beams, plates)."""

from .base import ModalBasis, Target
from .beam import Beam
from .halfspace import HalfSpace
from .plate import Plate

__all__ = ["Beam", "HalfSpace", "ModalBasis", "Plate", "Target"]
