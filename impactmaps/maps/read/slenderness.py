"""Slenderness members of the shear-deformable maps: a lookup at any slenderness by interpolation in 1/s.

The maps of Timoshenko beams and Mindlin plates depend on the slenderness s = span /
thickness; those of Euler beams and Kirchhoff plates do not. ζ and λ are defined with the
classical quantities (static stiffness, infinite-structure impedance), so as s grows a
shear-deformable map tends to the classical one. The package ships the slenderness members at
s = 10, 20 and 50 (:data:`~impactmaps.maps.family.builtin_families.MEMBER_SLENDERNESSES`; Timoshenko
beams for the linear and the Hertz law, Mindlin plates for the linear law) and the
classical map is its thin limit, 1/s = 0.

:func:`read_slenderness` (:func:`impactmaps.lookup` with a ``slenderness``) reads the two
members whose 1/s bracket the requested one at (ζ, λ) (each its own band and status) and
interpolates linearly in 1/s. Its band adds to the larger member band the slenderness
interpolation error, estimated per grid point by leaving a member out
(:func:`slenderness_error_grid`): s = 20 predicted from s = 10 and 50, and s = 50 from
the classical map and s = 20. Those brackets are wider than any a lookup uses, so the
estimate bounds the error at the nearest grid point; ``validation/slenderness_interpolation.py``
measures it and checks the band against direct simulations at other slendernesses.
Slendernesses below 10 are refused (no member brackets them).
"""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np

from ..._checks import require_in_range
from ...targets.options import classical_theory, is_shear_deformable, point_load_diverges
from ..family.builtin_families import MEMBER_SLENDERNESSES, PLANE_LAWS
from ..family.map_family import map_family
from ..files.shipped import load_shipped_map
from ..family.accuracy import SEVERITY, answer_status
from .reader import first_structure

__all__ = ["slenderness_members", "read_slenderness", "slenderness_error_grid", "shipped_for"]


def shipped_for(kind: str, theory: str, law: str) -> bool:
    """Whether slenderness members are shipped for a (kind, theory) with the map law ``law``.

    A shear-deformable theory (:func:`~impactmaps.targets.options.is_shear_deformable`) of a
    shipped (ζ, λ) map of the law, struck by a point load: a law whose family loads the
    contact patch (Hertz) on a target whose point load diverges (Mindlin) has the patch
    radius as a third number, so no members are shipped for it.
    """
    if law not in PLANE_LAWS or not is_shear_deformable(theory):
        return False
    family = map_family(law)
    return (kind, theory) in family.shipped and not (family.patch_loadable and point_load_diverges(theory))


def slenderness_members(kind: str, theory: str, law: str = "linear") -> tuple[tuple[float, float | None], ...]:
    """The slenderness members of (kind, theory, law) as ``(1/s, s)`` pairs, ascending in 1/s; s None is the thin limit.

    Raises
    ------
    ValueError
        When no slenderness members are shipped for (kind, theory, law).
    """
    if not shipped_for(kind, theory, law):
        raise ValueError(f"no slenderness members are shipped for a {theory} {kind} with the {law} law "
                         f"(shipped: Timoshenko beams, linear and Hertz; Mindlin plates, linear)")
    return ((0.0, None), *((1.0 / s, s) for s in sorted(MEMBER_SLENDERNESSES, reverse=True)))


def _member_values(kind: str, theory: str, slenderness: float | None, law: str):
    """(log λ grid, log ζ grid, F̄max values) of one member map."""
    if slenderness is None:
        dataset = load_shipped_map(kind, classical_theory(theory), law)
    else:
        dataset = load_shipped_map(kind, theory, law, slenderness=slenderness)
    return (np.log(dataset["lambda_"].values), np.log(dataset["zeta"].values),
            first_structure(dataset, "fmax_normalised"))


def _on_grid(member, grid) -> np.ndarray:
    """A member's F̄max on another member's grid (bilinear in log λ, log ζ; NaN outside)."""
    lam, zeta, values = member
    if np.array_equal(lam, grid[0]) and np.array_equal(zeta, grid[1]):
        return values
    from scipy.interpolate import RegularGridInterpolator  # only where two members' grids differ

    interpolate = RegularGridInterpolator((lam, zeta), values, bounds_error=False, fill_value=np.nan)
    mesh = np.stack(np.meshgrid(grid[0], grid[1], indexing="ij"), axis=-1)
    return interpolate(mesh)


@functools.lru_cache(maxsize=8)
def slenderness_error_grid(kind: str, theory: str, law: str = "linear") -> tuple:
    """Leave-one-out error of interpolation in 1/s, per grid point of the s = 20 member.

    Returns
    -------
    tuple
        ``(log λ grid, log ζ grid, error)``: ``error`` is the larger of
        |s20 − interp(s10, s50) at 1/20| and |s50 − interp(thin limit, s20) at 1/50|
        (the latter taken on the s = 20 grid), NaN where a member has no value. A pure
        function of the shipped maps (cached).
    """
    members = {s: _member_values(kind, theory, s, law) for _, s in slenderness_members(kind, theory, law)}
    grid = members[20.0][:2]
    on = {s: _on_grid(values, grid) for s, values in members.items()}

    def predicted(low, high, target):
        (x0, s0), (x1, s1) = low, high
        weight = (1.0 / target - x0) / (x1 - x0)
        return (1.0 - weight) * on[s0] + weight * on[s1]

    leave_20 = np.abs(on[20.0] - predicted((1 / 50, 50.0), (1 / 10, 10.0), 20.0))
    leave_50 = np.abs(on[50.0] - predicted((0.0, None), (1 / 20, 20.0), 50.0))
    return grid[0], grid[1], np.fmax(leave_20, leave_50)


def read_slenderness(read_member, loss_factor: float, relative_stiffness: float, *, kind: str, theory: str,
                     slenderness: float, law: str = "linear"):
    """F̄max at (ζ, λ) of a shear-deformable target of any slenderness ≥ 10, with its band.

    Parameters
    ----------
    read_member : callable
        ``read_member(theory, slenderness) -> LookupResult``: a member map read at (ζ, λ)
        (slenderness None: the classical theory's map, the thin limit).
    loss_factor, relative_stiffness : float
        ζ and λ [-] (ζ_h, λ_h for the Hertz law).
    kind, theory : str
        ``("beam", "timoshenko")`` or ``("plate", "mindlin")``.
    slenderness : float
        span / thickness [-], ≥ 10 (the thickest member).
    law : {"linear", "hertz"}

    Returns
    -------
    LookupResult
        A member's, ``fmax_error`` the larger member band plus
        the slenderness interpolation error at the nearest grid point, ``status`` the worse
        member status, ``map_name`` naming both members and the weight.

    Raises
    ------
    ValueError
        Slenderness below 10, no slenderness members for the law, or a member refusing (outside its
        range or next to an ``unresolved`` point).
    """
    members = slenderness_members(kind, theory, law)
    require_in_range("slenderness", slenderness, min(MEMBER_SLENDERNESSES), np.inf)
    inverse = 1.0 / float(slenderness)
    for (x0, s0), (x1, s1) in zip(members, members[1:]):
        if x0 <= inverse <= x1:
            break
    weight = (inverse - x0) / (x1 - x0)
    if weight in (0.0, 1.0):  # a member itself
        return _member(read_member, theory, s1 if weight else s0)
    low = _member(read_member, theory, s0)
    high = _member(read_member, theory, s1)
    fmax = (1.0 - weight) * low.fmax_normalised + weight * high.fmax_normalised
    lam_grid, zeta_grid, errors = slenderness_error_grid(kind, theory, law)
    row = int(np.argmin(np.abs(lam_grid - np.log(relative_stiffness))))
    column = int(np.argmin(np.abs(zeta_grid - np.log(loss_factor))))
    slender_error = float(errors[row, column])
    if not np.isfinite(slender_error):
        raise ValueError(f"slenderness = {slenderness:g} at (loss_factor, relative_stiffness) = "
                         f"({loss_factor:g}, {relative_stiffness:g}): a slenderness member holds no value next to it "
                         "(unresolved); run a simulation instead")
    band = float(max(low.fmax_error, high.fmax_error) + slender_error)
    # the worse member status, interpolated if the slenderness error widens the band past the tolerance
    status = answer_status(max(low.status, high.status, key=SEVERITY.__getitem__), band)
    name = f"{low.map_name} ×{1.0 - weight:.3g} + {high.map_name} ×{weight:.3g} (1/s)"
    return replace(low, fmax_normalised=float(fmax), fmax_error=band, status=status, map_name=name, theory=theory)


def _member(read_member, theory: str, slenderness: float | None):
    """One member read at the point: the classical theory's map for the thin limit (None)."""
    return read_member(classical_theory(theory), None) if slenderness is None else read_member(theory, slenderness)
