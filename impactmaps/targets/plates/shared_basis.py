"""One general Ritz basis for every run on a plate: the map points' shared basis.

A plate of the general basis (:func:`~impactmaps.targets.plates.plate_any_edges.uses_general_basis`)
grows its basis with the cut-off a run asks for (:func:`~impactmaps.targets.plates.plate_any_edges.grown_solution`),
so the points of a map tile — which differ in (ζ, λ), i.e. impactor mass and contact
stiffness, and so in cut-off — each built a basis of their own (16 points, 12 dense
eigen-solutions of up to 3468 unknowns). :func:`shared_basis` gives the plate whose basis
is pinned at the size resolving a frequency the caller fixes (a map's cap,
:func:`~impactmaps.solvers.mode_budget.frequency_cap`, above every point's cut-off): every
run on it truncates the modes of that one basis at its own cut-off (with the residual
compliance of the rest, as before). Pure: the size depends on the plate and the
frequency only, never on which points were computed first.

Truncating a larger basis is not the smaller basis: the modes below a cut-off come out
lower (Ritz frequencies fall monotonically as the basis grows) and the residual
compliance is solved in the larger static basis, so a point's bits differ from those of a
run that grew its own basis, by the basis's convergence error (measured on the clamped
Mindlin plate of benchmarks/bench_plates_any_edges.py: docs/plates_any_edges.rst, "Speed").
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from .plate import Plate
from .plate_any_edges import basis_size, class_groups, uses_general_basis

__all__ = ["PinnedBasisPlate", "shared_basis"]


@dataclass(frozen=True)
class PinnedBasisPlate(Plate):
    """A :class:`~impactmaps.targets.plates.plate.Plate` whose general Ritz basis has at least
    ``basis_functions`` functions per direction and field, whatever the cut-off (its modes
    are truncated from it; the largest basis still caps it)."""

    basis_functions: int = 0


def shared_basis(target, frequency: float):
    """``target`` with its general basis pinned at the size resolving ``frequency`` [rad/s]
    (:class:`PinnedBasisPlate`), or ``target`` itself when it has no such basis (Navier and
    Kirchhoff Ritz plates, beams …: their modes do not depend on the cut-off beyond
    truncation) or is pinned already."""
    if not isinstance(target, Plate) or isinstance(target, PinnedBasisPlate) or not uses_general_basis(target):
        return target
    n, _ = basis_size(target, float(frequency), class_groups(target)[0])
    return PinnedBasisPlate(**{f.name: getattr(target, f.name) for f in fields(target) if f.init},
                            basis_functions=int(n))
