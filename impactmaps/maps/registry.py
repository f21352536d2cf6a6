"""The registered map families, the built-in ones loaded.

Importing this module registers the linear, Hertz and elastic-plastic families
(:mod:`.linear_points`, :mod:`.hertz_points`, :mod:`.plastic_points`); a family added
elsewhere registers itself with :func:`~impactmaps.maps.map_family.register_map_family`
and is then found here like the others.
"""

from __future__ import annotations

from . import linear_points  # noqa: F401, I001 (registers the built-in families, linear first)
from . import hertz_points, plastic_points  # noqa: F401
from .map_family import MapFamily, available_map_families, map_family

__all__ = ["MapFamily", "map_family", "available_map_families", "PLANE_LAWS", "CUBE_LAWS"]

#: The built-in families over (ζ, λ) alone, and those with axes before them (β).
PLANE_LAWS = tuple(name for name in available_map_families() if len(map_family(name).axes) == 2)
CUBE_LAWS = tuple(name for name in available_map_families() if len(map_family(name).axes) > 2)
