"""The registered map families, the built-in ones by name.

The built-in families (linear, Hertz, elastic-plastic: :mod:`.linear_points`,
:mod:`.hertz_points`, :mod:`.plastic_points`) are known by name from the start and imported
when first asked for (:func:`~impactmaps.maps.family.map_family.map_family`); a family added
elsewhere registers itself with :func:`~impactmaps.maps.family.map_family.register_map_family` and
is then found here like the others. What a map reader needs of a family without its point
solver: :func:`~impactmaps.maps.family.builtin_families.family_layout`.
"""

from __future__ import annotations

from .builtin_families import CUBE_LAWS, PLANE_LAWS, family_layout
from .map_family import MapFamily, available_map_families, map_family

__all__ = ["MapFamily", "map_family", "available_map_families", "family_layout", "PLANE_LAWS", "CUBE_LAWS"]
