"""What the points of a sweep cost, said before it starts (:func:`sweep_seconds`).

The rates are CPU seconds of the linear law, by the modal basis of the structure: a point of
a beam or a Navier plate (SSSS, specially orthotropic) is cheap; a plate of the Ritz basis (a
clamped or free edge, D16/D26) first builds its basis (a dense eigenproblem, kept on disk
afterwards: :mod:`impactmaps.targets.plates.basis_cache`), then integrates more modes a point.
Hertz and elastic-plastic points cost more. The estimate is for planning, not a bound: it
counts the basis as not yet cached.
"""

from __future__ import annotations

__all__ = ["SECONDS_PER_POINT", "SECONDS_PER_RITZ_POINT", "RITZ_BASIS_SECONDS", "point_seconds", "sweep_seconds"]

#: CPU of a map point on a beam or a Navier plate [s]: the mean of the linear plane (200 × 50,
#: beam and plate: 58 CPU-s for 20 000 points, ``benchmarks/studies/RESULTS_plane.md``).
SECONDS_PER_POINT = 2.9e-3
#: CPU of a map point on a plate of the Ritz basis, its basis built [s]: the largest mean measured
#: on 20 ζ from 0.005 to 100 × λ = 0.05, 0.2, 1, 5 (one process, 2 cores at load 7–8): CCCC
#: Kirchhoff 0.14–0.20, CFCF Kirchhoff (b/a 0.667) 0.07, CCCC Mindlin (a/h 20) and the CCCC
#: Mindlin [45/0/−45/90]2s laminate of the drop-weight example 0.002–0.003 (their points stop
#: at the modes the basis resolves); a beam or a Navier plate 0.01 on that grid.
SECONDS_PER_RITZ_POINT = 0.2
#: CPU of building a Ritz basis, once per structure while it is not cached [s]: the largest
#: measured, the drop-weight laminate's (about 33 s; CCCC Mindlin 16, CFCF Kirchhoff 11).
RITZ_BASIS_SECONDS = 30.0


def point_seconds(structure) -> float:
    """The CPU of one linear map point of ``structure`` (a
    :class:`~impactmaps.maps.family.structures.MapStructure`) [s]."""
    return SECONDS_PER_RITZ_POINT if _ritz(structure) else SECONDS_PER_POINT


def sweep_seconds(structures, points) -> float:
    """The CPU of a sweep computing ``points[k]`` points of ``structures[k]`` [s], with the
    build of each Ritz basis (:data:`RITZ_BASIS_SECONDS`)."""
    return float(sum(count * point_seconds(structure) + (RITZ_BASIS_SECONDS if _ritz(structure) else 0.0)
                     for structure, count in zip(structures, points) if count))


def _ritz(structure) -> bool:
    return structure.kind == "plate" and not structure.build().uses_navier
