"""Which reference structure describes a target: the question the maps ask of a target.

:func:`describing_structure` returns the :class:`StructureKey` of the undamped, unit-span
reference with the target's shape and dimensionless groups (:func:`similarity_groups`), or
why there is none; :func:`reference_target` builds it. The reference is isotropic and
steel-like; for an orthotropic or laminated plate it carries the plate's stiffness ratios
(:data:`STIFFNESS_RATIOS`, the key's ``stiffness``), which no shipped map has.
See docs/map_families.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

__all__ = ["REFERENCE_SLENDERNESS", "REFERENCE_POISSON", "STRUCTURE_MATCH_RTOL", "STIFFNESS_RATIOS", "KIRCHHOFF_RATIO_COUNT", "StructureKey",
           "ReferenceMaterial", "reference_target", "similarity_groups", "describing_structure", "isotropic_refusal"]

#: Slenderness (span/thickness) of a reference whose response does not depend on it [-].
REFERENCE_SLENDERNESS = 20.0
#: Poisson ratio of a reference whose response does not depend on it [-].
REFERENCE_POISSON = 0.3
#: Relative tolerance within which a target's dimensionless group equals the reference's.
STRUCTURE_MATCH_RTOL = 1e-6
#: The dimensionless stiffness ratios of an orthotropic or laminated plate's reference, in the
#: order of :attr:`StructureKey.stiffness` (a = length_x, k the shear correction); a Kirchhoff
#: plate's key holds the first five (its response does not depend on the rest).
STIFFNESS_RATIOS = ("D22/D11", "D12/D11", "D66/D11", "D16/D11", "D26/D11", "k A44 a²/D11", "k A55 a²/D11",
                    "k A45 a²/D11", "rotary inertia/(ρh a²)")
#: How many of :data:`STIFFNESS_RATIOS` a Kirchhoff plate's key holds (the bending ones).
KIRCHHOFF_RATIO_COUNT = 5


class StructureKey(NamedTuple):
    """The reference structure of a target; ``slenderness`` [-] and ``poisson_ratio`` [-] are
    None where the normalised response does not depend on them; ``stiffness`` the plate's
    :data:`STIFFNESS_RATIOS` [-] for an orthotropic or laminated plate, None for an isotropic target."""

    kind: str
    theory: str
    supports: str
    aspect_ratio: float
    slenderness: float | None
    impact_fraction: tuple
    poisson_ratio: float | None
    stiffness: tuple | None = None


@dataclass(frozen=True)
class ReferenceMaterial:
    """Steel-like isotropic material of the reference targets (E [Pa], ν [-], ρ [kg/m³])."""

    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = 7850.0
    yield_strength: float | None = None


def reference_target(target_class, key):
    """The unit-span, steel-like reference target of ``key`` built by ``target_class``."""
    slenderness = REFERENCE_SLENDERNESS if key.slenderness is None else key.slenderness
    poisson = REFERENCE_POISSON if key.poisson_ratio is None else key.poisson_ratio
    material = ReferenceMaterial(poisson_ratio=poisson)
    span = 1.0
    thickness = span / slenderness
    if key.kind == "beam":
        return target_class.rectangular(span, thickness, thickness, material, theory=key.theory,
                                        supports=key.supports, impact_position=key.impact_fraction[0] * span)
    width = span * key.aspect_ratio
    plate = target_class.isotropic(span, width, thickness, material, theory=key.theory, edges=key.supports,
                                   impact_point=(key.impact_fraction[0] * span, key.impact_fraction[1] * width))
    stiffness = getattr(key, "stiffness", None)
    if stiffness is None:
        return plate
    d = plate.D11  # the laminate's ratios on the isotropic reference's D11, ρh and thickness
    values = dict(zip(("D22", "D12", "D66", "D16", "D26"), (r * d for r in stiffness[:KIRCHHOFF_RATIO_COUNT])))
    if len(stiffness) > KIRCHHOFF_RATIO_COUNT:
        shear = d / (plate.shear_correction * span**2)
        values.update(A44=stiffness[5] * shear, A55=stiffness[6] * shear, A45=stiffness[7] * shear,
                      rotary_inertia_per_area=stiffness[8] * plate.mass_per_area * span**2)
    return replace(plate, **values)


def similarity_groups(target, poisson: bool = False) -> dict:
    """The dimensionless ratios that, besides shape, supports and impact point, fix a target's
    normalised response."""
    groups = {"damping_ratio": float(target.damping_ratio)}
    if target.kind == "beam":
        span = target.length
        if target.theory == "timoshenko":
            groups["shear stiffness L²/EI"] = target.shear_stiffness * span**2 / target.bending_stiffness
        if target.theory != "euler":
            groups["rotary inertia/(m' L²)"] = target.rotary_inertia / (target.mass_per_length * span**2)
        return groups
    groups["D22/D11"] = target.D22 / target.D11
    groups["(D12 + 2 D66)/D11"] = (target.D12 + 2.0 * target.D66) / target.D11
    if target.theory == "mindlin" or poisson:
        groups["D12/D11"] = target.D12 / target.D11
    if target.theory == "mindlin":
        side = target.length_x
        for name in ("A44", "A55"):
            groups[f"k {name} a²/D11"] = target.shear_correction * getattr(target, name) * side**2 / target.D11
        groups["rotary inertia/(ρh a²)"] = target.rotary_inertia_per_area / (target.mass_per_area * side**2)
    # the couplings (bending–twisting, in-plane shear): none on an isotropic plate
    groups["D16/D11"] = target.D16 / target.D11
    groups["D26/D11"] = target.D26 / target.D11
    groups["k A45 a²/D11"] = target.shear_correction * target.A45 * target.length_x**2 / target.D11
    return groups


def _beam_key(beam) -> StructureKey:
    fraction = (beam.impact_position / beam.length,)
    if beam.theory == "euler":
        return StructureKey("beam", "euler", beam.supports, 1.0, None, fraction, None)
    # a rectangle: ρI/(m' L²) = 1/(12 s²) and S L²/EI = 12 k s²/(2 (1 + ν)) = 5 s²/(1 + ν), k = 5/6
    slenderness = beam.slenderness or beam.length / math.sqrt(12.0 * beam.rotary_inertia / beam.mass_per_length)
    poisson = None
    if beam.theory == "timoshenko":
        poisson = (5.0 * slenderness**2 * beam.bending_stiffness
                   / (beam.shear_stiffness * beam.length**2) - 1.0)
    return StructureKey("beam", beam.theory, beam.supports, 1.0, slenderness, fraction, poisson)


def _plate_key(plate, patch_loaded: bool) -> StructureKey:
    side = plate.length_x
    fraction = tuple(x / length for x, length in zip(plate.impact_point, (plate.length_x, plate.length_y)))
    shear = plate.theory == "mindlin"
    poisson = plate.D12 / plate.D11 if shear or plate.edges != "SSSS" else None  # Navier SSSS Kirchhoff: no ν
    slenderness = side / plate.thickness if shear or patch_loaded else None
    return StructureKey("plate", plate.theory, plate.edges, plate.length_y / side, slenderness, fraction, poisson)


def _stiffness_ratios(plate) -> tuple:
    """The plate's :data:`STIFFNESS_RATIOS` [-] (the first five for Kirchhoff)."""
    d, side = plate.D11, plate.length_x
    ratios = [getattr(plate, name) / d for name in ("D22", "D12", "D66", "D16", "D26")]
    if plate.theory == "mindlin":
        ratios += [plate.shear_correction * getattr(plate, name) * side**2 / d for name in ("A44", "A55", "A45")]
        ratios.append(plate.rotary_inertia_per_area / (plate.mass_per_area * side**2))
    return tuple(float(r) for r in ratios)


def describing_structure(target, patch_loaded: bool = False) -> tuple[StructureKey | None, str | None]:
    """The reference structure that describes ``target`` exactly, or why none does.

    ``patch_loaded``: the impact loads the target over the contact patch. Returns
    ``(StructureKey, None)`` or ``(None, reason)``. An undamped plate that no isotropic
    reference describes (orthotropic, laminated) gets the key of the reference carrying its
    stiffness ratios (``stiffness``; :func:`isotropic_refusal` says why it is not isotropic).
    """
    key, reason = _isotropic_structure(target, patch_loaded)
    if reason is None:
        return key, None
    if key is None or target.kind != "plate":
        return None, reason
    if target.damping_ratio != 0.0:
        return None, (f"damping_ratio = {target.damping_ratio:.6g} where the undamped plate of its shape has 0 "
                      "(structural damping is not a map structure)")
    key = key._replace(poisson_ratio=None, stiffness=_stiffness_ratios(target))
    carried = _stiffness_ratios(reference_target(type(target), key))
    for name, wanted, value in zip(STIFFNESS_RATIOS, key.stiffness, carried):  # the reference is the plate's twin
        if abs(value - wanted) > STRUCTURE_MATCH_RTOL * abs(wanted):
            return None, f"{name} = {wanted:.6g}, which its reference plate cannot carry ({value:.6g})"
    return key, None


def isotropic_refusal(target, patch_loaded: bool = False) -> str | None:
    """Why no isotropic, undamped reference describes ``target`` (None when one does): an
    orthotropic or laminated plate is answered from its own on-demand tile, never from a
    shipped map."""
    return _isotropic_structure(target, patch_loaded)[1]


def _isotropic_structure(target, patch_loaded: bool) -> tuple[StructureKey | None, str | None]:
    """The isotropic reference's key and None, or the key of the target's shape and why no
    isotropic reference describes it (None and the reason for a target that is no beam or plate)."""
    if target.kind == "beam":
        key = _beam_key(target)
    elif target.kind == "plate":
        key = _plate_key(target, patch_loaded)
    else:
        return None, f"target type {target.kind!r} (maps: beams and plates)"
    if key.poisson_ratio is not None and not -1.0 < key.poisson_ratio < 0.5:
        return (None if target.kind == "beam" else key), (
            f"a section whose shear stiffness implies a Poisson ratio of {key.poisson_ratio:.4g} "
            "(no isotropic rectangle has it)")
    poisson = key.poisson_ratio is not None
    wanted = similarity_groups(reference_target(type(target), key), poisson)
    for name, value in similarity_groups(target, poisson).items():
        reference = wanted[name]
        if not (abs(value - reference) <= STRUCTURE_MATCH_RTOL * abs(reference) if reference else value == 0.0):
            name_of = f"the isotropic, undamped {key.kind} of its shape"
            if target.kind == "plate" and name != "damping_ratio":
                return key, (f"{name} = {value:.6g} where {name_of} has {reference:.6g} (an orthotropic or laminated "
                             "plate: the shipped maps are of isotropic plates; its own on-demand tile describes it)")
            return None, (f"{name} = {value:.6g} where {name_of} has {reference:.6g} (an orthotropic or laminated "
                          "plate, another beam section or structural damping is not a map structure)")
    return key, None
