"""Shared constants and the scalar checks of the material classes."""

from __future__ import annotations

import numpy as np

from .._checks import require_finite, require_positive

__all__ = ["DEFAULT_PLY_THICKNESS", "SPECIALLY_ORTHOTROPIC_RTOL", "optional_yield_strength", "require_scalar"]

#: Default cured ply thickness [m]: 0.125 mm, the nominal thickness of standard
#: carbon/epoxy unidirectional prepreg (used e.g. with AS4/3501-6 in Anand, Kamrin &
#: Govindjee, *Introduction to Mechanics of Solids*, OUP 2022, example 23.2, and in
#: Barbero, *Introduction to Composite Materials Design*, example 7.9). A nominal value,
#: not a property of a particular material batch: pass ``thickness`` for real laminates.
DEFAULT_PLY_THICKNESS = 0.125e-3

#: Relative tolerance of :attr:`Laminate.is_specially_orthotropic`.
SPECIALLY_ORTHOTROPIC_RTOL = 1e-9


def require_scalar(name: str, value, unit: str = "") -> float:
    """Return ``value`` as a Python float, or raise ``ValueError`` naming ``name``."""
    require_finite(name, value, unit)
    array = np.asarray(value, dtype=float)
    if array.ndim != 0:
        raise ValueError(f"{name} must be a scalar, got an array of shape {array.shape}")
    return float(array)


def optional_yield_strength(value) -> float | None:
    """``None``, or the yield strength ``value`` [Pa] as a float > 0 (``ValueError`` naming ``yield_strength``)."""
    if value is None:
        return None
    strength = require_scalar("yield_strength", value, "Pa")
    require_positive("yield_strength", strength, "Pa")
    return strength
