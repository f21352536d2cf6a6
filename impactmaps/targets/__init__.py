"""Targets: anything that supplies modes at the impact point (beams, plates)."""

from .base import ModalBasis, Target
from .beam import Beam
from .plate import Plate

__all__ = ["Beam", "ModalBasis", "Plate", "Target"]
