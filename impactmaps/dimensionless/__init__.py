"""The dimensionless framework of seed 001 (docs/physics_contract.md §1 and §4).

The groups (contact frequency, force scale, relative stiffness λ, loss factors ζ with
the corrected beam ζ_b) in :mod:`~impactmaps.dimensionless.groups`, and the way back from
(ζ, λ) to SI (:func:`realise`). Inputs are validated (``ValueError`` naming the
parameter). The framework and the beam correction: docs/physics.rst.
"""

from __future__ import annotations

from . import groups, realisation

from .groups import *  # noqa: F403 (the names of groups.__all__)
from .realisation import *  # noqa: F403 (the names of realisation.__all__)

__all__ = groups.__all__ + realisation.__all__
