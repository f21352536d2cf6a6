"""Case files: a physical impact described in TOML, built into impactmaps objects.

A case file describes one impact of a sphere on a beam, a plate or a half-space, in SI
units. It is parsed with the standard-library :mod:`tomllib` and validated key by key:
every error is a ``ValueError`` that names the key path (``target.length``), the value
and the valid range; an unknown key is an error that lists the allowed keys, so typos
cannot pass silently.

Format
------
::

    name = "steel plate, Hertz"          # optional label (default: the file name)
    description = "..."                  # optional free text

    [impactor]
    radius = 0.005                       # sphere radius R [m]
    material = "structural-steel"        # catalogue name, or an inline table
    # mass = 0.004                       # [kg]; default: solid sphere ρ (4/3) π R³
    # density = 7800.0                   # [kg/m³]; overrides the material's (not with mass)
    velocity = 2.0                       # approach velocity V0 [m/s]

    [target]
    type = "plate"                       # "beam" | "plate" | "halfspace"
    # beam:      length, width, height [m]; supports ("ss", "cc", "cs", "cf", "ff");
    #            theory ("euler", "rayleigh", "timoshenko"); impact_position x0 [m]
    # plate:     length_x, length_y, thickness [m]; edges ("SSSS", "CCCC", ...);
    #            theory ("kirchhoff", "mindlin"); impact_point [x0, y0] [m]
    # both:      shear_correction [-]; damping_ratio [-] (plates)
    material = "structural-steel"        # catalogue name or inline isotropic table, or
    # plies = [{material = "t300-934", angle_deg = 0.0, thickness = 0.000125}, ...]
    # layup = {ply = "t300-934", angles_deg = [0, 90], symmetric = true, ply_thickness = 0.000125}
    # yield_strength = 1.0e9             # laminate strength S_y [Pa] (with plies/layup only)

    [contact]
    law = "hertz"                        # a registered law: hertz, linear, yigit-christoforou, stronge
    # options: target_radius [m]; yield_strength [Pa] (not hertz); stiffness (hertz
    # K_h [N/m^1.5] or linear K [N/m], overriding the value built from the materials);
    # stronge: yield_pressure_factor, plastic_pressure_factor, plastic_indentation_ratio

    [solver]                             # optional, modal solver (ModalSettings)
    # cutoff_ratio, min_modes, residual_flexibility, time_step_ratio, resolve_ratio,
    # max_events, check_convergence, tolerance; duration [s] (time limit); time_step [s]

    [output]                             # optional
    # history_stride = 1                 # write every n-th history row
    # normalised = false                 # also write the normalised history

    [fd]                                 # optional, finite-difference beam (load_fd_case)
    # n_elements, n_half_layers, plastic, hardening_modulus [Pa],
    # damping_per_length [N s/m²], gravity, safety_factor, time_step [s],
    # history_stride, gauge_positions [m]

Inline isotropic material table: ``youngs_modulus`` [Pa], ``poisson_ratio`` [-],
``density`` [kg/m³], optional ``yield_strength`` [Pa] and ``name``. A ply table is
either a full definition (``longitudinal_modulus``, ``transverse_modulus``,
``shear_modulus``, ``poisson_ratio``, ``density`` and optional ``thickness``,
``angle_deg``, ``transverse_shear_modulus_13``, ``transverse_shear_modulus_23``,
``name``) or ``material = "<catalogue ply>"`` with any of those fields overriding it.
Plies are listed from the struck face (see :mod:`impactmaps.materials`).

Defaults of the target theory, supports and impact point are those of the target
classes (:class:`impactmaps.targets.beam.Beam`, :class:`impactmaps.targets.plate.Plate`).

Dimensionless numbers of a case (:func:`case_dimensionless`)
------------------------------------------------------------
* ``beta`` — the impact number ``β = V0/(ω_h α_y)`` (seed 001 eqs 9, 11, 12), reported
  for the elastic-plastic laws only (``yigit-christoforou``; for ``stronge`` with
  ``α_y`` from seed 001 eq 9 and the law's E*, R and yield strength — *not* Stronge's
  own yield indentation δ_y); ``None`` for ``hertz`` and ``linear``.
* ``lambda`` — ``K_st/K``. ``K`` is chosen, in this order, as: the stiffness of a
  ``linear`` law; else the linearised contact stiffness ``K_y = 1.5 K_h sqrt(α_y)``
  (seed 001 eqs 9, 10, 18) of the sphere/target pair when a yield strength is known
  (from either material or ``contact.yield_strength``); else the reference stiffness
  the modal solver uses to set the contact frequency (tangent stiffness of the law on
  its loading curve at the half-space peak indentation,
  :func:`impactmaps.solvers.modal.reference_contact_stiffness`). The summary says
  which (``lambda_basis``). ``None`` for a half-space (``K_st`` infinite).
* ``zeta`` — the target's own loss factor ``target.loss_factor(m_i, K)`` with the same
  ``K`` (plate: seed 001 eq 34; beam: the corrected eq 38, PHYSICS.md §1). ``None`` for
  a half-space.

Outputs (:func:`write_case_outputs`): ``history.csv`` (``time_s, force_N,
indentation_m, impactor_displacement_m, impactor_velocity_m_s, target_displacement_m,
target_velocity_m_s, structure_energy_J`` — displacements positive into the target,
the target deflection taken at the impact point), ``summary.json`` and a copy of the
case file ``case.toml``.
"""

from __future__ import annotations

import json
import math
import tomllib
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pandas as pd

from ._checks import require_choice, require_in_range
from .contact.base import ContactLaw, available_contact_laws
from .contact.hertz import HertzContact, hertz_stiffness
from .contact.linear import LinearContact
from .contact.sphere import Sphere, law_for_sphere
from .contact.stronge import StrongeContact
from .contact.yigit_christoforou import YigitChristoforouContact, yield_indentation
from .dimensionless import impact_number
from .materials import IsotropicMaterial, Laminate, Ply, available_materials, material
from .solvers.modal import ModalSettings, reference_contact_stiffness, simulate
from .jsonio import dumps, plain
from .solvers.result import ImpactResult
from .targets.base import ModalBasis

__all__ = [
    "Case",
    "FDCase",
    "TARGET_TYPES",
    "load_case",
    "load_fd_case",
    "parse_case",
    "parse_fd_case",
    "run_case",
    "run_fd_case",
    "case_dimensionless",
    "case_summary",
    "fd_case_summary",
    "write_case_outputs",
    "read_case_outputs",
]

#: Target types a case file may describe.
TARGET_TYPES = ("beam", "plate", "halfspace")

_TOP_KEYS = ("name", "description", "impactor", "target", "contact", "solver", "output", "fd")
_IMPACTOR_KEYS = ("radius", "material", "mass", "density", "velocity")
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
_TARGET_COMMON = ("type", "material", "plies", "layup", "yield_strength")
_TARGET_KEYS = {
    "beam": _TARGET_COMMON + ("length", "width", "height", "supports", "theory",
                              "impact_position", "shear_correction", "damping_ratio"),
    "plate": _TARGET_COMMON + ("length_x", "length_y", "thickness", "edges", "theory",
                               "impact_point", "shear_correction", "damping_ratio"),
    "halfspace": _TARGET_COMMON,
}
_BEAM_THEORIES = ("euler", "rayleigh", "timoshenko")
_BEAM_SUPPORTS = ("ss", "cc", "cs", "cf", "ff")
_PLATE_THEORIES = ("kirchhoff", "mindlin")
_CONTACT_OPTIONS = {
    "hertz": ("target_radius", "stiffness"),
    "linear": ("target_radius", "yield_strength", "stiffness"),
    "yigit-christoforou": ("target_radius", "yield_strength"),
    "stronge": ("target_radius", "yield_strength", "yield_pressure_factor",
                "plastic_pressure_factor", "plastic_indentation_ratio"),
}
_SOLVER_KEYS = ("cutoff_ratio", "min_modes", "residual_flexibility", "time_step_ratio",
                "resolve_ratio", "max_events", "check_convergence", "tolerance", "duration",
                "time_step")
_OUTPUT_KEYS = ("history_stride", "normalised")
_FD_KEYS = ("n_elements", "n_half_layers", "plastic", "hardening_modulus", "damping_per_length",
            "gravity", "safety_factor", "time_step", "history_stride", "gauge_positions")
#: Beam support codes of the modal targets mapped to the (left, right) ends of FDBeam.
_FD_SUPPORTS = {"ss": ("ss", "ss"), "cc": ("cc", "cc"), "cs": ("cc", "ss"),
                "cf": ("cc", "free"), "ff": ("free", "free")}



# =====================================================================================
# Small validation helpers (all errors name the key path)
# =====================================================================================
def _table(value, path: str) -> dict:
    if not isinstance(value, dict):
        raise ValueError(f"[{path}] must be a table, got {type(value).__name__} {value!r}")
    return value


def _check_keys(table: dict, path: str, allowed, required=()) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        names = ", ".join(f"{path}.{k}" if path else k for k in unknown)
        raise ValueError(
            f"unknown key(s) {names}: valid keys {'in [' + path + ']' if path else 'at the top level'} "
            f"are {', '.join(sorted(allowed))}"
        )
    for key in required:
        if key not in table:
            raise ValueError(f"{path}.{key} is required (missing from [{path}])")


def _key(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _number(table, key, path, unit="", *, default=None, required=False, low=0.0,
            high=math.inf, low_inclusive=False, high_inclusive=True, integer=False):
    """A number from ``table[key]`` validated into a range (ValueError naming the key path)."""
    name = _key(path, key)
    if key not in table:
        if required:
            raise ValueError(f"{name} is required{_unit(unit)}")
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} = {value!r} is not a number{_unit(unit)}")
    if integer and int(value) != value:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer")
    require_in_range(name, value, low, high, low_inclusive=low_inclusive,
                     high_inclusive=high_inclusive, unit=unit)
    return int(value) if integer else float(value)


def _string(table, key, path, *, choices=None, default=None, required=False):
    name = _key(path, key)
    if key not in table:
        if required:
            raise ValueError(f"{name} is required")
        return default
    value = table[key]
    if not isinstance(value, str):
        raise ValueError(f"{name} = {value!r} is not a string")
    if choices is not None:
        require_choice(name, value, choices)
    return value


def _boolean(table, key, path, *, default=None):
    if key not in table:
        return default
    value = table[key]
    if not isinstance(value, bool):
        raise ValueError(f"{_key(path, key)} = {value!r} is not a boolean (true or false)")
    return value


def _number_list(table, key, path, unit="", *, length=None, low=-math.inf, high=math.inf,
                 low_inclusive=True, high_inclusive=True):
    name = _key(path, key)
    value = table[key]
    if not isinstance(value, list) or not value:
        raise ValueError(f"{name} = {value!r} is not a non-empty list of numbers{_unit(unit)}")
    if length is not None and len(value) != length:
        raise ValueError(f"{name} = {value!r} must have {length} entries{_unit(unit)}")
    out = []
    for index, item in enumerate(value):
        item_name = f"{name}[{index}]"
        if isinstance(item, bool) or not isinstance(item, (int, float)):
            raise ValueError(f"{item_name} = {item!r} is not a number{_unit(unit)}")
        require_in_range(item_name, item, low, high, low_inclusive=low_inclusive,
                         high_inclusive=high_inclusive, unit=unit)
        out.append(float(item))
    return out


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""


class _prefixed:
    """Context manager: prefix ValueErrors raised by constructors with a key path."""

    def __init__(self, path: str):
        self.path = path

    def __enter__(self):
        return self

    def __exit__(self, kind, error, traceback):
        if kind is not None and issubclass(kind, ValueError) and not getattr(error, "_case_path", False):
            wrapped = ValueError(f"{self.path}: {error}")
            wrapped._case_path = True
            raise wrapped from error
        return False


# =====================================================================================
# Materials
# =====================================================================================
def _catalogue(name, path):
    require_choice(path, name, available_materials())
    return material(name)


def _isotropic_material(value, path) -> IsotropicMaterial:
    """Catalogue name or inline isotropic table → IsotropicMaterial."""
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
    table = _table(value, path)
    _check_keys(table, path, _ISOTROPIC_KEYS, ("youngs_modulus", "poisson_ratio", "density"))
    with _prefixed(path):
        return IsotropicMaterial(
            youngs_modulus=_number(table, "youngs_modulus", path, "Pa"),
            poisson_ratio=_number(table, "poisson_ratio", path, low=-1.0, high=0.5,
                                  high_inclusive=False),
            density=_number(table, "density", path, "kg/m^3"),
            yield_strength=_number(table, "yield_strength", path, "Pa"),
            name=_string(table, "name", path, default="inline material"),
        )


def _ply(value, path) -> Ply:
    """Catalogue ply name, or a ply table (full definition or ``material`` + overrides)."""
    if isinstance(value, str):
        found = _catalogue(value, path)
        if not isinstance(found, Ply):
            raise ValueError(f"{path} = {value!r} is an isotropic material, not a ply; "
                             "catalogue plies are "
                             + ", ".join(repr(n) for n in available_materials()
                                         if isinstance(material(n), Ply)))
        return found
    table = _table(value, path)
    _check_keys(table, path, _PLY_KEYS)
    fields = {key: _number(table, key, path, unit) for key, unit in _PLY_NUMBER_KEYS.items()
              if key in table}
    if "poisson_ratio" in table:
        fields["poisson_ratio"] = _number(table, "poisson_ratio", path, low=-math.inf)
    if "angle_deg" in table:
        fields["angle_deg"] = _number(table, "angle_deg", path, "deg", low=-360.0, high=360.0,
                                      low_inclusive=True)
    if "name" in table:
        fields["name"] = _string(table, "name", path)
    with _prefixed(path):
        if "material" in table:
            base = _ply(_string(table, "material", path), _key(path, "material"))
            return replace(base, **fields)
        _check_keys(table, path, _PLY_KEYS, ("longitudinal_modulus", "transverse_modulus",
                                             "shear_modulus", "poisson_ratio", "density"))
        return Ply(**fields)


def _laminate(target: dict, path: str) -> Laminate:
    strength = _number(target, "yield_strength", path, "Pa")
    if "plies" in target:
        plies = target["plies"]
        if not isinstance(plies, list) or not plies:
            raise ValueError(f"{path}.plies = {plies!r} is not a non-empty list of ply tables")
        built = tuple(_ply(item, f"{path}.plies[{i}]") for i, item in enumerate(plies))
        with _prefixed(f"{path}.plies"):
            return Laminate(built, yield_strength=strength)
    layup_path = f"{path}.layup"
    layup = _table(target["layup"], layup_path)
    _check_keys(layup, layup_path, _LAYUP_KEYS, ("ply", "angles_deg"))
    ply = _ply(layup["ply"], f"{layup_path}.ply")
    thickness = _number(layup, "ply_thickness", layup_path, "m")
    if thickness is not None:
        ply = replace(ply, thickness=thickness)
    angles = _number_list(layup, "angles_deg", layup_path, "deg", low=-360.0, high=360.0)
    symmetric = _boolean(layup, "symmetric", layup_path, default=True)
    with _prefixed(layup_path):
        return Laminate.from_layup(ply, angles, symmetric=symmetric, yield_strength=strength)


# =====================================================================================
# Sections
# =====================================================================================
def _impactor(data) -> tuple[Sphere, float]:
    path = "impactor"
    table = _table(data.get(path), path) if path in data else None
    if table is None:
        raise ValueError("[impactor] is required (radius, material, velocity)")
    _check_keys(table, path, _IMPACTOR_KEYS, ("radius", "material", "velocity"))
    radius = _number(table, "radius", path, "m")
    velocity = _number(table, "velocity", path, "m/s")
    mat = _isotropic_material(table["material"], f"{path}.material")
    mass = _number(table, "mass", path, "kg")
    density = _number(table, "density", path, "kg/m^3")
    if mass is not None and density is not None:
        raise ValueError("impactor.mass and impactor.density are exclusive: give one of them "
                         "(density sets the mass of a solid sphere)")
    if density is not None:
        mat = replace(mat, density=density)
    with _prefixed(path):
        sphere = Sphere(radius, mat, mass)
    return sphere, velocity


def _target_material(target: dict, path: str):
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
        return _isotropic_material(target["material"], f"{path}.material")
    return _laminate(target, path)


def _target(data):
    path = "target"
    if path not in data:
        raise ValueError("[target] is required (type = 'beam', 'plate' or 'halfspace')")
    table = _table(data[path], path)
    kind = _string(table, "type", path, choices=TARGET_TYPES, required=True)
    _check_keys(table, path, _TARGET_KEYS[kind])
    contact_material = _target_material(table, path)
    if kind == "halfspace":
        return ModalBasis(np.empty(0), np.empty(0), 0.0), kind, contact_material
    if kind == "beam":
        return _beam(table, path, contact_material), kind, contact_material
    return _plate(table, path, contact_material), kind, contact_material


def _beam(table, path, contact_material):
    from .targets.beam import Beam  # imported late: the beam module is optional at import time

    length = _number(table, "length", path, "m", required=True)
    width = _number(table, "width", path, "m", required=True)
    options = {}
    if "theory" in table:
        options["theory"] = _string(table, "theory", path, choices=_BEAM_THEORIES)
    if "supports" in table:
        options["supports"] = _string(table, "supports", path, choices=_BEAM_SUPPORTS)
    if "impact_position" in table:
        options["impact_position"] = _number(table, "impact_position", path, "m", high=length,
                                             high_inclusive=False)
    if "shear_correction" in table:
        options["shear_correction"] = _number(table, "shear_correction", path)
    if "damping_ratio" in table:
        options["damping_ratio"] = _number(table, "damping_ratio", path, low=0.0, high=1.0,
                                           low_inclusive=True, high_inclusive=False)
    with _prefixed(path):
        if isinstance(contact_material, Laminate):
            if "height" in table:
                raise ValueError(f"{path}.height is the laminate thickness for a laminated beam; "
                                 "remove it (the plies define it)")
            build, arguments = Beam.from_laminate, (length, width, contact_material)
        else:
            height = _number(table, "height", path, "m", required=True)
            build, arguments = Beam.rectangular, (length, width, height, contact_material)
        try:
            return build(*arguments, **options)
        except TypeError as error:  # an option this Beam does not take
            raise ValueError(f"{sorted(options)} not all accepted by the beam target: {error}") from None


def _plate(table, path, contact_material):
    from .targets.plate import Plate

    length_x = _number(table, "length_x", path, "m", required=True)
    length_y = _number(table, "length_y", path, "m", required=True)
    options = {}
    if "theory" in table:
        options["theory"] = _string(table, "theory", path, choices=_PLATE_THEORIES)
    if "edges" in table:
        options["edges"] = _string(table, "edges", path)
    if "impact_point" in table:
        x0, y0 = _number_list(table, "impact_point", path, "m", length=2)
        require_in_range(f"{path}.impact_point[0]", x0, 0.0, length_x, low_inclusive=False,
                         high_inclusive=False, unit="m")
        require_in_range(f"{path}.impact_point[1]", y0, 0.0, length_y, low_inclusive=False,
                         high_inclusive=False, unit="m")
        options["impact_point"] = (x0, y0)
    if "shear_correction" in table:
        options["shear_correction"] = _number(table, "shear_correction", path)
    if "damping_ratio" in table:
        options["damping_ratio"] = _number(table, "damping_ratio", path, low=0.0, high=1.0,
                                           low_inclusive=True, high_inclusive=False)
    with _prefixed(path):
        if isinstance(contact_material, Laminate):
            if "thickness" in table:
                raise ValueError(f"{path}.thickness is derived from the plies for a laminated "
                                 "plate; remove it")
            return Plate.from_laminate(length_x, length_y, contact_material, **options)
        thickness = _number(table, "thickness", path, "m", required=True)
        return Plate.isotropic(length_x, length_y, thickness, contact_material, **options)


def _contact(data, sphere, target_material, default_law=None) -> tuple[ContactLaw, str, dict]:
    """The contact law of a case; ``default_law`` (a registry name) when none is given."""
    path = "contact"
    if path not in data and default_law is None:
        raise ValueError("[contact] is required (law = one of "
                         + ", ".join(repr(n) for n in available_contact_laws()) + ")")
    table = _table(data.get(path, {}), path)
    name = _string(table, "law", path, choices=available_contact_laws(),
                   default=default_law, required=default_law is None)
    allowed = _CONTACT_OPTIONS.get(name)
    if allowed is None:
        raise ValueError(f"contact.law = {name!r} cannot be built from a case file: valid values "
                         f"are {', '.join(repr(n) for n in _CONTACT_OPTIONS)}")
    _check_keys(table, path, ("law",) + allowed)
    options = {}
    for key in allowed:
        if key == "stiffness" or key not in table:
            continue
        if key == "target_radius":
            options[key] = _number(table, key, path, "m", high=math.inf)
        elif key == "yield_strength":
            options[key] = _number(table, key, path, "Pa")
        else:
            options[key] = _number(table, key, path)
    stiffness = _number(table, "stiffness", path, "N/m^1.5" if name == "hertz" else "N/m")
    with _prefixed(path):
        if stiffness is not None:
            law = HertzContact(stiffness) if name == "hertz" else LinearContact(stiffness)
        else:
            law = law_for_sphere(name, sphere, target_material, **options)
    return law, name, options


def _solver(data, law, sphere, velocity):
    path = "solver"
    table = _table(data.get(path, {}), path)
    _check_keys(table, path, _SOLVER_KEYS)
    fields = {}
    for key in ("cutoff_ratio", "time_step_ratio", "resolve_ratio", "tolerance"):
        if key in table:
            fields[key] = _number(table, key, path)
    for key in ("min_modes", "max_events"):
        if key in table:
            fields[key] = _number(table, key, path, low=0 if key == "min_modes" else 1,
                                  low_inclusive=True, integer=True)
    for key in ("residual_flexibility", "check_convergence"):
        if key in table:
            fields[key] = _boolean(table, key, path)
    duration = _number(table, "duration", path, "s")
    time_step = _number(table, "time_step", path, "s")
    if duration is not None:
        omega = math.sqrt(reference_contact_stiffness(law, sphere.mass, velocity) / sphere.mass)
        fields["max_time_ratio"] = duration * omega
    with _prefixed(path):
        settings = ModalSettings(**fields)
    return settings, duration, time_step


def _output(data):
    path = "output"
    table = _table(data.get(path, {}), path)
    _check_keys(table, path, _OUTPUT_KEYS)
    return {
        "history_stride": _number(table, "history_stride", path, default=1, low=1,
                                  low_inclusive=True, integer=True),
        "normalised": _boolean(table, "normalised", path, default=False),
    }


def _read(path) -> tuple[str, Path]:
    source = Path(path)
    try:
        text = source.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ValueError(f"case file {str(source)!r} does not exist") from None
    return text, source


def _parse_toml(text: str, label: str) -> dict:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{label}: not valid TOML: {error}") from None
    _check_keys(data, "", _TOP_KEYS)
    for key in ("name", "description"):
        _string(data, key, "")
    return data


# =====================================================================================
# Modal case
# =====================================================================================
@dataclass(frozen=True)
class Case:
    """A physical impact case built from a case file (SI units).

    Attributes
    ----------
    name : str
        Label (``name`` key, default the file stem).
    sphere : Sphere
        The impactor (radius [m], material, mass [kg]).
    velocity : float
        Approach velocity V0 [m/s].
    target : Target or ModalBasis
        The struck structure; a half-space is an empty :class:`ModalBasis`.
    target_type : str
        ``"beam"``, ``"plate"`` or ``"halfspace"``.
    target_material : IsotropicMaterial or Laminate
        The target's material as seen by the contact law.
    law : ContactLaw
        The contact law (built by :func:`impactmaps.contact.law_for_sphere` unless a
        stiffness was given).
    law_name : str
        Registered name of the law.
    contact_options : dict
        Options passed to the law builder (``target_radius`` [m], ``yield_strength``
        [Pa], Stronge constants).
    settings : ModalSettings
        Modal solver settings (``solver.duration`` already converted to
        ``max_time_ratio``).
    duration : float or None
        Requested time limit [s] (``None``: the solver default).
    time_step : float or None
        Forced time step [s] (``None``: automatic).
    output : dict
        ``history_stride`` (int), ``normalised`` (bool).
    description : str
        Free text from the file.
    source : Path or None
        The case file.
    source_text : str
        The case file's text (copied to the outputs).
    """

    name: str
    sphere: Sphere
    velocity: float
    target: object
    target_type: str
    target_material: object
    law: ContactLaw
    law_name: str
    contact_options: dict = field(default_factory=dict)
    settings: ModalSettings = field(default_factory=ModalSettings)
    duration: float | None = None
    time_step: float | None = None
    output: dict = field(default_factory=lambda: {"history_stride": 1, "normalised": False})
    description: str = ""
    source: Path | None = None
    source_text: str = ""

    @property
    def impactor_mass(self) -> float:
        """Impactor mass m_i [kg]."""
        return float(self.sphere.mass)


def parse_case(text: str, *, name: str = "case", source: Path | None = None) -> Case:
    """Build a :class:`Case` from the text of a case file (see the module docstring).

    Parameters
    ----------
    text : str
        TOML text.
    name : str, optional
        Default label when the file has no ``name`` key.
    source : Path, optional
        Where the text came from (provenance only).

    Raises
    ------
    ValueError
        Invalid TOML, an unknown key, or a missing/invalid value; the message names the
        key path, the value and the valid range.
    """
    data = _parse_toml(text, str(source) if source else name)
    sphere, velocity = _impactor(data)
    target, kind, target_material = _target(data)
    law, law_name, options = _contact(data, sphere, target_material)
    settings, duration, time_step = _solver(data, law, sphere, velocity)
    output = _output(data)
    if "fd" in data:
        _fd_options(data)  # validate it even when the modal solver will ignore it
    return Case(
        name=data.get("name", name), sphere=sphere, velocity=velocity, target=target,
        target_type=kind, target_material=target_material, law=law, law_name=law_name,
        contact_options=options, settings=settings, duration=duration, time_step=time_step,
        output=output, description=data.get("description", ""), source=source, source_text=text,
    )


def load_case(path) -> Case:
    """Read and validate a case file for the modal solver.

    Parameters
    ----------
    path : str or Path
        The TOML case file.

    Returns
    -------
    Case

    Raises
    ------
    ValueError
        Missing file, invalid TOML, unknown keys or invalid values; the message starts
        with the file name and names the key path.
    """
    text, source = _read(path)
    try:
        return parse_case(text, name=source.stem, source=source)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from error


def case_dimensionless(case: Case) -> dict:
    """The dimensionless numbers of a case (module docstring: which K is used).

    Returns
    -------
    dict
        ``beta`` [-] or ``None``; ``lambda`` [-] or ``None``; ``zeta`` [-] or ``None``;
        ``lambda_basis`` (which contact stiffness); ``contact_stiffness_N_m`` (that K);
        ``reference_contact_stiffness_N_m`` (the solver's); ``static_stiffness_N_m``
        (``None`` for a half-space); ``impactor_mass_kg``; ``velocity_m_s``.
    """
    mass, velocity, law = case.impactor_mass, case.velocity, case.law
    reference = float(reference_contact_stiffness(law, mass, velocity))
    if isinstance(law, LinearContact):
        stiffness, basis = float(law.stiffness), "linear law stiffness K"
    else:
        stiffness, basis = reference, "solver reference stiffness (loading tangent at the half-space peak indentation)"
        linear_options = {k: v for k, v in case.contact_options.items()
                          if k in ("target_radius", "yield_strength")}
        try:
            linear = law_for_sphere("linear", case.sphere, case.target_material, **linear_options)
        except ValueError:
            pass  # no yield strength known: keep the reference stiffness
        else:
            stiffness, basis = float(linear.stiffness), "linearised contact stiffness K_y (seed 001 eqs 9, 10)"
    beta = None
    if isinstance(law, YigitChristoforouContact):
        beta = float(law.impact_number(mass, velocity))
    elif isinstance(law, StrongeContact):
        alpha_y = yield_indentation(law.yield_strength, law.radius, law.effective_modulus)
        beta = float(impact_number(velocity, hertz_stiffness(law.effective_modulus, law.radius),
                                   alpha_y, mass))
    if case.target_type == "halfspace":
        static = lam = zeta = None
    else:
        static = float(case.target.static_stiffness())
        lam = static / stiffness
        zeta = float(case.target.loss_factor(mass, stiffness))
    return {
        "beta": beta,
        "lambda": lam,
        "zeta": zeta,
        "lambda_basis": basis,
        "contact_stiffness_N_m": stiffness,
        "reference_contact_stiffness_N_m": reference,
        "static_stiffness_N_m": static,
        "impactor_mass_kg": mass,
        "velocity_m_s": velocity,
    }


def case_summary(case: Case, result: ImpactResult) -> dict:
    """The JSON-ready summary of a modal run of ``case`` (keys carry their units).

    ``result.summary()`` (``peak_force_N``, ``contact_intervals_s``, ``first_contact_duration_s``, ``total_contact_time_s``,
    ``impacts``, ``restitution``, ``energy_transferred_J``, …) plus
    ``max_deflection_m`` (largest |target deflection| at the impact point [m]), the
    dimensionless numbers of :func:`case_dimensionless` and the case identity.
    """
    summary = dict(result.summary())
    if result.history is not None and len(result.history):
        deflection = result.history["target_displacement_m"].to_numpy()
        summary["max_deflection_m"] = float(np.max(np.abs(deflection)))
    else:
        summary["max_deflection_m"] = None
    summary.update(case_dimensionless(case))
    summary.update({
        "case": case.name,
        "target_type": case.target_type,
        "law": case.law_name,
        "end_time_s": float(result.end_time),
        "time_step_s": float(result.time_step),
    })
    return plain(summary)


def run_case(case: Case) -> tuple[ImpactResult, dict]:
    """Run the modal solver on a case.

    Returns
    -------
    result : ImpactResult
        Full result with histories.
    summary : dict
        :func:`case_summary` of the run (JSON-ready).
    """
    if not isinstance(case, Case):
        raise ValueError(f"case = {case!r} is not a Case (use load_fd_case/run_fd_case for FD cases)")
    result = simulate(case.target, case.law, case.impactor_mass, case.velocity,
                      settings=case.settings, record=True, time_step=case.time_step)
    return result, case_summary(case, result)


# =====================================================================================
# Finite-difference case
# =====================================================================================
@dataclass(frozen=True)
class FDCase:
    """A beam impact case for the finite-difference solver :func:`impactmaps.fd.simulate_fd`.

    Attributes
    ----------
    name, description, source, source_text
        As in :class:`Case`.
    sphere : Sphere
        The impactor.
    velocity : float
        V0 [m/s].
    beam : FDBeam
        Grid, layered section, supports and damping (from ``[target]`` and ``[fd]``).
    target_material : IsotropicMaterial
        The beam material (contact).
    law : ContactLaw
        Contact law; ``law_name`` its registered name.
    impact_position : float or None
        x0 [m] (``None``: mid-span).
    duration : float
        Simulated time [s] (``solver.duration``, required).
    time_step : float or None
        Forced Δt [s].
    safety_factor : float
        Fraction of the stability limit used by the automatic step.
    gravity : bool
        Gravity on the sphere.
    history_stride : int
        Record every n-th step.
    gauge_positions : tuple of float
        Gauge positions [m].
    """

    name: str
    sphere: Sphere
    velocity: float
    beam: object
    target_material: object
    law: ContactLaw
    law_name: str
    impact_position: float | None
    duration: float
    time_step: float | None = None
    safety_factor: float = 0.8
    gravity: bool = False
    history_stride: int = 1
    gauge_positions: tuple = ()
    description: str = ""
    source: Path | None = None
    source_text: str = ""

    @property
    def impactor_mass(self) -> float:
        """Impactor mass m_i [kg]."""
        return float(self.sphere.mass)


def _fd_options(data) -> dict:
    path = "fd"
    table = _table(data.get(path, {}), path)
    _check_keys(table, path, _FD_KEYS)
    beam = {}
    for key in ("n_elements", "n_half_layers"):
        if key in table:
            beam[key] = _number(table, key, path, low=4 if key == "n_elements" else 2,
                                low_inclusive=True, integer=True)
    if "plastic" in table:
        beam["plastic"] = _boolean(table, "plastic", path)
    for key, unit in (("hardening_modulus", "Pa"), ("damping_per_length", "N s/m^2")):
        if key in table:
            beam[key] = _number(table, key, path, unit, low=0.0, low_inclusive=True)
    run = {
        "gravity": _boolean(table, "gravity", path, default=False),
        "safety_factor": _number(table, "safety_factor", path, default=0.8, high=1.0),
        "time_step": _number(table, "time_step", path, "s"),
        "history_stride": _number(table, "history_stride", path, default=1, low=1,
                                  low_inclusive=True, integer=True),
        "gauge_positions": tuple(_number_list(table, "gauge_positions", path, "m", low=0.0))
        if "gauge_positions" in table else (),
    }
    return {"beam": beam, "run": run}


def parse_fd_case(text: str, *, name: str = "case", source: Path | None = None) -> FDCase:
    """Build an :class:`FDCase` from case-file text (same format; target must be a beam).

    The beam must be isotropic with a yield strength (the layered section needs σ_y even
    when ``fd.plastic = false``); ``solver.duration`` [s] is required. The modal
    ``[solver]`` keys are accepted (so that one file serves both solvers) but only
    ``duration`` is used; ``fd.time_step`` forces the step. The finite-difference beam
    is a Rayleigh beam whatever ``target.theory`` says (a warning is issued if it says
    otherwise). Without a ``[contact]`` table (or without ``contact.law``) the contact
    is seed 000's refined Stronge law (``law = "stronge"``).
    """
    from .fd import FDBeam

    data = _parse_toml(text, str(source) if source else name)
    sphere, velocity = _impactor(data)
    path = "target"
    if path not in data:
        raise ValueError("[target] is required (type = 'beam' for the finite-difference solver)")
    table = _table(data[path], path)
    kind = _string(table, "type", path, choices=TARGET_TYPES, required=True)
    if kind != "beam":
        raise ValueError(f"target.type = {kind!r} is invalid for the finite-difference solver: "
                         "valid values are 'beam'")
    _check_keys(table, path, _TARGET_KEYS["beam"])
    if "plies" in table or "layup" in table:
        raise ValueError("target.plies/target.layup are not supported by the finite-difference "
                         "beam: give an isotropic target.material")
    _check_keys(table, path, _TARGET_KEYS["beam"], ("length", "width", "height", "material"))
    target_material = _isotropic_material(table["material"], "target.material")
    if target_material.yield_strength is None:
        raise ValueError("target.material.yield_strength is required by the finite-difference "
                         "beam (valid range (0, inf) [Pa]); with fd.plastic = false any positive "
                         "value gives the elastic beam")
    length = _number(table, "length", path, "m")
    width = _number(table, "width", path, "m")
    height = _number(table, "height", path, "m")
    supports = _string(table, "supports", path, choices=_BEAM_SUPPORTS, default="ss")
    theory = _string(table, "theory", path, choices=_BEAM_THEORIES)
    if theory is not None and theory != "rayleigh":
        warnings.warn(f"target.theory = {theory!r}: the finite-difference beam is a Rayleigh beam "
                      "(no shear deformation); the key is ignored", UserWarning, stacklevel=3)
    for key in ("shear_correction", "damping_ratio"):
        if key in table:
            warnings.warn(f"target.{key} is not used by the finite-difference beam (use "
                          "fd.damping_per_length for damping)", UserWarning, stacklevel=3)
    impact_position = None
    if "impact_position" in table:
        impact_position = _number(table, "impact_position", path, "m", high=length,
                                  high_inclusive=False)
    law, law_name, _ = _contact(data, sphere, target_material, default_law="stronge")
    solver = _table(data.get("solver", {}), "solver")
    _check_keys(solver, "solver", _SOLVER_KEYS)
    duration = _number(solver, "duration", "solver", "s", required=True)
    _output(data)
    options = _fd_options(data)
    with _prefixed("fd"):
        beam = FDBeam.from_material(length, width, height, target_material,
                                    supports=_FD_SUPPORTS[supports], **options["beam"])
    run = options["run"]
    return FDCase(
        name=data.get("name", name), sphere=sphere, velocity=velocity, beam=beam,
        target_material=target_material, law=law, law_name=law_name,
        impact_position=impact_position, duration=duration, time_step=run["time_step"],
        safety_factor=run["safety_factor"], gravity=run["gravity"],
        history_stride=run["history_stride"], gauge_positions=run["gauge_positions"],
        description=data.get("description", ""), source=source, source_text=text,
    )


def load_fd_case(path) -> FDCase:
    """Read and validate a case file for the finite-difference beam solver.

    Parameters
    ----------
    path : str or Path
        The TOML case file (``target.type = "beam"``, ``solver.duration`` given).

    Returns
    -------
    FDCase

    Raises
    ------
    ValueError
        As :func:`load_case`, plus FD-specific requirements (beam target, isotropic
        material with a yield strength, duration).
    """
    text, source = _read(path)
    try:
        return parse_fd_case(text, name=source.stem, source=source)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from error


def run_fd_case(case: FDCase):
    """Run the finite-difference solver on an :class:`FDCase`.

    Returns
    -------
    result : ImpactResult
    summary : dict
        ``result.summary()`` (``peak_force_N``, ``contact_intervals_s``, ``restitution``,
        ``energy_loss_J``, ``permanent_indentation_m``, ``beam_plastic_work_J``,
        ``energy_balance_error``, …), plus ``max_deflection_m`` (largest |deflection| at
        the impact node [m]) and the case identity; NaN (e.g. a record that ends in
        contact) becomes ``None``.
    """
    from .fd import simulate_fd

    if not isinstance(case, FDCase):
        raise ValueError(f"case = {case!r} is not an FDCase (use load_case/run_case for modal cases)")
    result = simulate_fd(case.beam, case.law, case.impactor_mass, case.velocity,
                         case.impact_position, duration=case.duration, time_step=case.time_step,
                         safety_factor=case.safety_factor, gauge_positions=case.gauge_positions,
                         gravity=case.gravity, history_stride=case.history_stride)
    return result, fd_case_summary(case, result)


# =====================================================================================
# Outputs
# =====================================================================================
def write_case_outputs(case, result, out_dir) -> dict:
    """Write the histories, the summary and a copy of the case file to ``out_dir``.

    Parameters
    ----------
    case : Case or FDCase
        The case that was run.
    result : ImpactResult
        Its result (with histories).
    out_dir : str or Path
        Output directory (created if needed).

    Returns
    -------
    dict
        ``{"history": Path, "summary": Path, "case": Path}`` and, for a modal case with
        ``output.normalised = true``, ``"history_normalised": Path``.

    Notes
    -----
    ``history.csv``: modal — ``time_s, force_N, indentation_m, impactor_displacement_m,
    impactor_velocity_m_s, target_displacement_m, target_velocity_m_s,
    structure_energy_J``; finite difference — the columns of
    :class:`impactmaps.fd.FDDetails`. ``summary.json``: :func:`case_summary` /
    :func:`run_fd_case` summary.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = {"history": out / "history.csv", "summary": out / "summary.json",
             "case": out / "case.toml"}
    if isinstance(case, FDCase):
        history = result.history
        summary = fd_case_summary(case, result)
    elif isinstance(case, Case):
        if result.history is None:
            raise ValueError("result has no history (run with record=True)")
        stride = int(case.output.get("history_stride", 1))
        history = result.history.iloc[::stride]
        summary = case_summary(case, result)
        if case.output.get("normalised"):
            paths["history_normalised"] = out / "history_normalised.csv"
            result.normalised_history().iloc[::stride].to_csv(paths["history_normalised"],
                                                              index=False)
    else:
        raise ValueError(f"case = {case!r} is not a Case or an FDCase")
    history.to_csv(paths["history"], index=False)
    paths["summary"].write_text(dumps(summary, indent=2) + "\n",
                                encoding="utf-8")
    paths["case"].write_text(case.source_text, encoding="utf-8")
    return paths


def fd_case_summary(case: FDCase, result) -> dict:
    """Summary dict of an existing finite-difference result (as :func:`run_fd_case`)."""
    summary = dict(result.summary())
    deflection = result.history["target_displacement_m"].to_numpy()
    summary["max_deflection_m"] = float(np.max(np.abs(deflection))) if deflection.size else None
    summary.update({
        "case": case.name,
        "target_type": "beam",
        "law": case.law_name,
        "impactor_mass_kg": case.impactor_mass,
        "velocity_m_s": case.velocity,
        "method": result.method,
    })
    return plain(summary)


def read_case_outputs(out_dir) -> tuple[pd.DataFrame, dict]:
    """Read back ``history.csv`` and ``summary.json`` written by :func:`write_case_outputs`."""
    out = Path(out_dir)
    history = pd.read_csv(out / "history.csv")
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    return history, summary
