"""Which reference structure describes a target: the question the maps ask of a target.

:func:`describing_structure` returns the :class:`StructureKey` of the isotropic, undamped,
unit-span reference with the target's shape and dimensionless groups
(:func:`similarity_groups`), or why there is none; :func:`reference_target` builds it.
See docs/map_families.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

__all__ = ["REFERENCE_SLENDERNESS", "REFERENCE_POISSON", "STRUCTURE_MATCH_RTOL", "StructureKey", "ReferenceMaterial",
           "reference_target", "similarity_groups", "describing_structure"]

#: Slenderness (span/thickness) of a reference whose response does not depend on it [-].
REFERENCE_SLENDERNESS = 20.0
#: Poisson ratio of a reference whose response does not depend on it [-].
REFERENCE_POISSON = 0.3
#: Relative tolerance within which a target's dimensionless group equals the reference's.
STRUCTURE_MATCH_RTOL = 1e-6


class StructureKey(NamedTuple):
    """The reference structure of a target; ``slenderness`` [-] and ``poisson_ratio`` [-] are
    None where the normalised response does not depend on them."""

    kind: str
    theory: str
    supports: str
    aspect_ratio: float
    slenderness: float | None
    impact_fraction: tuple
    poisson_ratio: float | None


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
    return target_class.isotropic(span, width, thickness, material, theory=key.theory, edges=key.supports,
                                  impact_point=(key.impact_fraction[0] * span, key.impact_fraction[1] * width))


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


def describing_structure(target, patch_loaded: bool = False) -> tuple[StructureKey | None, str | None]:
    """The reference structure that describes ``target`` exactly, or why none does.

    ``patch_loaded``: the impact loads the target over the contact patch. Returns
    ``(StructureKey, None)`` or ``(None, reason)``.
    """
    if target.kind == "beam":
        key = _beam_key(target)
    elif target.kind == "plate":
        key = _plate_key(target, patch_loaded)
    else:
        return None, f"target type {target.kind!r} (maps: beams and plates)"
    if key.poisson_ratio is not None and not -1.0 < key.poisson_ratio < 0.5:
        return None, (f"a section whose shear stiffness implies a Poisson ratio of {key.poisson_ratio:.4g} "
                      "(no isotropic rectangle has it)")
    poisson = key.poisson_ratio is not None
    wanted = similarity_groups(reference_target(type(target), key), poisson)
    for name, value in similarity_groups(target, poisson).items():
        reference = wanted[name]
        if not (abs(value - reference) <= STRUCTURE_MATCH_RTOL * abs(reference) if reference else value == 0.0):
            name_of = f"the isotropic, undamped {key.kind} of its shape"
            return None, (f"{name} = {value:.6g} where {name_of} has {reference:.6g} (an orthotropic or laminated "
                          "plate, another beam section or structural damping is not a map structure)")
    return key, None
