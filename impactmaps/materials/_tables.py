"""Materials read from TOML tables (case files and sweep files): catalogue names, inline
isotropic tables, plies and laminates.

Inline isotropic material table: ``youngs_modulus`` [Pa], ``poisson_ratio`` [-],
``density`` [kg/m³], optional ``yield_strength`` [Pa] and ``name``. A ply table is
either a full definition (``longitudinal_modulus``, ``transverse_modulus``,
``shear_modulus``, ``poisson_ratio``, ``density`` and optional ``thickness``,
``angle_deg``, ``transverse_shear_modulus_13``, ``transverse_shear_modulus_23``,
``name``) or ``material = "<catalogue ply>"`` with any of those fields overriding it.
Plies are listed from the struck face (see :mod:`impactmaps.materials`).
"""

from __future__ import annotations

import math
from dataclasses import replace

from .._checks import require_choice
from .catalogue import available_materials, material
from .isotropic import IsotropicMaterial
from .laminate import Laminate
from .ply import Ply
from .._toml import boolean, check_keys, key_path, number, number_list, string, table

__all__ = ["isotropic_material", "ply", "laminate", "target_material"]

_ISOTROPIC_KEYS = ("youngs_modulus", "poisson_ratio", "density", "yield_strength", "name")
_PLY_NUMBER_KEYS = {
    "longitudinal_modulus": "Pa",
    "transverse_modulus": "Pa",
    "shear_modulus": "Pa",
    "density": "kg/m^3",
    "thickness": "m",
    "transverse_shear_modulus_13": "Pa",
    "transverse_shear_modulus_23": "Pa",
}
_PLY_KEYS = ("material", "poisson_ratio", "angle_deg", "name", *_PLY_NUMBER_KEYS)
_LAYUP_KEYS = ("ply", "angles_deg", "symmetric", "ply_thickness")


def _catalogue(name, path):
    require_choice(path, name, available_materials())
    return material(name)


def isotropic_material(value, path) -> IsotropicMaterial:
    """Catalogue name or inline isotropic table at ``path`` → IsotropicMaterial."""
    if isinstance(value, str):
        found = _catalogue(value, path)
        if not isinstance(found, IsotropicMaterial):
            raise ValueError(
                f"{path} = {value!r} is a ply, not an isotropic material: describe a laminate "
                "with target.plies or target.layup; isotropic catalogue materials are "
                + ", ".join(repr(n) for n in available_materials()
                            if isinstance(material(n), IsotropicMaterial))
            )
        return found
    entries = table(value, path)
    check_keys(entries, path, _ISOTROPIC_KEYS, ("youngs_modulus", "poisson_ratio", "density"))
    with key_path(path):
        return IsotropicMaterial(
            youngs_modulus=number(entries, "youngs_modulus", path, "Pa"),
            poisson_ratio=number(entries, "poisson_ratio", path, low=-1.0, high=0.5,
                                  high_inclusive=False),
            density=number(entries, "density", path, "kg/m^3"),
            yield_strength=number(entries, "yield_strength", path, "Pa"),
            name=string(entries, "name", path, default="inline material"),
        )


def ply(value, path) -> Ply:
    """Catalogue ply name, or a ply table at ``path`` (full definition or ``material`` + overrides)."""
    if isinstance(value, str):
        found = _catalogue(value, path)
        if not isinstance(found, Ply):
            raise ValueError(f"{path} = {value!r} is an isotropic material, not a ply; "
                             "catalogue plies are "
                             + ", ".join(repr(n) for n in available_materials()
                                         if isinstance(material(n), Ply)))
        return found
    entries = table(value, path)
    check_keys(entries, path, _PLY_KEYS)
    fields = {key: number(entries, key, path, unit) for key, unit in _PLY_NUMBER_KEYS.items()
              if key in entries}
    if "poisson_ratio" in entries:
        fields["poisson_ratio"] = number(entries, "poisson_ratio", path, low=-math.inf)
    if "angle_deg" in entries:
        fields["angle_deg"] = number(entries, "angle_deg", path, "deg", low=-360.0, high=360.0,
                                      low_inclusive=True)
    if "name" in entries:
        fields["name"] = string(entries, "name", path)
    with key_path(path):
        if "material" in entries:
            base = ply(string(entries, "material", path), f"{path}.material")
            return replace(base, **fields)
        check_keys(entries, path, _PLY_KEYS, ("longitudinal_modulus", "transverse_modulus",
                                             "shear_modulus", "poisson_ratio", "density"))
        return Ply(**fields)


def laminate(target: dict, path: str) -> Laminate:
    """The laminate of ``target.plies`` (a list of ply tables) or ``target.layup``."""
    strength = number(target, "yield_strength", path, "Pa")
    if "plies" in target:
        plies = target["plies"]
        if not isinstance(plies, list) or not plies:
            raise ValueError(f"{path}.plies = {plies!r} is not a non-empty list of ply tables")
        built = tuple(ply(item, f"{path}.plies[{i}]") for i, item in enumerate(plies))
        with key_path(f"{path}.plies"):
            return Laminate(built, yield_strength=strength)
    layup_path = f"{path}.layup"
    layup = table(target["layup"], layup_path)
    check_keys(layup, layup_path, _LAYUP_KEYS, ("ply", "angles_deg"))
    layer = ply(layup["ply"], f"{layup_path}.ply")
    thickness = number(layup, "ply_thickness", layup_path, "m")
    if thickness is not None:
        layer = replace(layer, thickness=thickness)
    angles = number_list(layup, "angles_deg", layup_path, "deg", low=-360.0, high=360.0)
    symmetric = boolean(layup, "symmetric", layup_path, default=True)
    with key_path(layup_path):
        return Laminate.from_layup(layer, angles, symmetric=symmetric, yield_strength=strength)


def target_material(target: dict, path: str):
    """The contact material of the target: isotropic material or laminate (exactly one)."""
    given = [key for key in ("material", "plies", "layup") if key in target]
    if len(given) != 1:
        raise ValueError(
            f"[{path}] needs exactly one of {path}.material, {path}.plies, {path}.layup "
            f"(got {', '.join(given) if given else 'none'})"
        )
    if "material" in target:
        if "yield_strength" in target:
            raise ValueError(f"{path}.yield_strength is for laminates (plies/layup); give an "
                             f"isotropic material's yield strength in {path}.material")
        return isotropic_material(target["material"], f"{path}.material")
    return laminate(target, path)
