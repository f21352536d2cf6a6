"""What the points of a sweep cost, said before it starts (:func:`sweep_seconds`).

The rates are CPU seconds of one map point under the linear law, by the modal basis of the
structure: a beam or a Navier plate (SSSS, specially orthotropic) is cheap, a plate of the
Ritz basis (a clamped or free edge, D16/D26) builds and integrates a large basis. Hertz and
elastic-plastic points cost more; the estimate is for planning, not a bound.
"""

from __future__ import annotations

__all__ = ["SECONDS_PER_POINT", "SECONDS_PER_RITZ_POINT", "point_seconds", "sweep_seconds"]

#: CPU of a map point on a beam or a Navier plate [s]: the mean of the linear plane (200 × 50,
#: beam and plate: 58 CPU-s for 20 000 points, ``benchmarks/studies/RESULTS_plane.md``).
SECONDS_PER_POINT = 2.9e-3
#: CPU of a map point on a plate of the Ritz basis [s]: the largest of the means measured on
#: 12 ζ from 0.005 to 100 × λ = 0.05, 0.2, 1, 5 (2 cores at load 11, one worker): CCCC
#: Kirchhoff 0.77, CFCF Kirchhoff (b/a 0.667) 0.52, CCCC Mindlin (a/h 20) 0.44, the CCCC
#: Mindlin [45/0/−45/90]2s laminate of the drop-weight example 0.53; a beam or a Navier plate
#: 0.02–0.03 on that coarse grid.
SECONDS_PER_RITZ_POINT = 0.8


def point_seconds(structure) -> float:
    """The CPU of one linear map point of ``structure`` (a
    :class:`~impactmaps.maps.family.structures.MapStructure`) [s]."""
    if structure.kind == "plate" and not structure.build().uses_navier:
        return SECONDS_PER_RITZ_POINT
    return SECONDS_PER_POINT


def sweep_seconds(structures, points) -> float:
    """The CPU of a sweep [s] computing ``points[k]`` points of ``structures[k]``."""
    return float(sum(count * point_seconds(structure) for structure, count in zip(structures, points) if count))
