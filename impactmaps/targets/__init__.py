"""Targets: anything that supplies modes at the impact point (half-space, beams, plates)."""

from .base import ModalBasis, Target

__all__ = ["ModalBasis", "Target"]
