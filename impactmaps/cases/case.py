"""One case: a physical impact read from a case file and built into impactmaps objects.

Each section maps onto a constructor whose options are its valid keys and which checks
the ranges: ``[solver]`` onto :class:`~impactmaps.solvers.modal_settings.ModalSettings`
or the finite-difference settings, ``[target]`` onto the target's, ``[contact]`` onto
the law's, ``[output]`` onto :class:`OutputSettings` (the format: docs/cases.rst).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from .._checks import read_text_input, require_in_range, require_plate_proportions, warn_if_unusual
from ..contact import law_options
from ..contact.base import ContactLaw, available_contact_laws, contact_law, contact_law_class
from ..contact.pair import Sphere
from ..contact.sphere import law_for_sphere
from ..materials import Laminate
from ..solvers.modal_settings import ModalSettings
from ..contact.contact_scale import reference_contact_stiffness
from ..targets.halfspace import HalfSpace
from ..materials._tables import isotropic_material, target_material
from .._toml import (
    check_keys,
    key_path,
    keyword_options,
    number,
    read_options,
    string,
    table,
)

if TYPE_CHECKING:
    from ..fd import FDSettings

__all__ = ["Case", "OutputSettings", "SOLVER_KINDS", "TARGET_TYPES", "parse_case", "load_case"]

#: Target types a case file may describe.
TARGET_TYPES = ("beam", "plate", "halfspace")
#: Solvers a case may ask for (``[solver] kind``).
SOLVER_KINDS = ("modal", "fd")
#: Range of ``contact.stiffness`` (K_h [N/m^1.5] or K [N/m]): a diamond sphere of radius
#: 10 m on diamond has K_h = (4/3) sqrt(R) E* ≈ 2.5e12 N/m^1.5, a soft foam contact
#: ~1e2; values beyond the range are typing errors (1e300 overflowed later).
STIFFNESS_RANGE = (1.0e-3, 1.0e15)
#: Upper bounds of the impactor keys [SI] (all must be > 0): a 10 m sphere, 1e9 kg, 10 km/s;
#: beyond them the contact scales overflow (a velocity or radius of 1e300 raised
#: OverflowError). No lower bound: realisations of map points use speeds down to 1e-13 m/s.
IMPACTOR_RANGES = {"radius": (0.0, 10.0), "mass": (0.0, 1.0e9), "velocity": (0.0, 1.0e4)}

_TOP_KEYS = ("name", "description", "impactor", "target", "contact", "solver", "output", "fd")
_IMPACTOR_KEYS = ("radius", "material", "mass", "density", "velocity")
_TARGET_COMMON = ("type", "material", "plies", "layup", "yield_strength")
_BEAM_SIZE = ("length", "width", "height")
_PLATE_SIZE = ("length_x", "length_y", "thickness")
_TARGET_UNITS = {"impact_position": "m", "impact_point": "m"}
#: ``[solver]`` keys that are not ModalSettings fields.
_SOLVER_EXTRA = ("kind", "duration", "time_step")


@dataclass(frozen=True)
class OutputSettings:
    """What ``impactmaps simulate`` writes besides the summary.

    Attributes
    ----------
    history_stride : int
        Write every n-th history row (≥ 1).
    normalised : bool
        Also write the history in normalised variables (``history_normalised.csv``).
    """

    history_stride: int = 1
    normalised: bool = False

    def __post_init__(self):
        require_in_range("history_stride", self.history_stride, 1, math.inf)


@dataclass(frozen=True)
class Case:
    """A physical impact case built from a case file (SI units).

    Attributes
    ----------
    name, description : str
        Label (default the file stem) and free text.
    sphere : Sphere
        The impactor (radius [m], material, mass [kg]).
    velocity : float
        Approach velocity V0 [m/s].
    target, target_type : Target, str
        The struck structure and its type (``"beam"``, ``"plate"``, ``"halfspace"``).
    target_material : IsotropicMaterial or Laminate
        The target's material as seen by the contact law.
    law, law_name : ContactLaw, str
        The contact law and its registered name.
    contact_options : dict
        Options passed to the law builder (``target_radius`` [m], ``yield_strength`` [Pa], …).
    solver_kind : str
        ``"modal"`` or ``"fd"`` (finite-difference Rayleigh beam).
    settings, fd_settings : ModalSettings, FDSettings or None
        The solvers' settings.
    duration, time_step : float or None
        Time limit and forced time step [s] (``None``: the solver's choice).
    output : OutputSettings
        What to write besides the summary.
    source, source_text : Path or None, str
        The case file and its text.
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
    solver_kind: str = "modal"
    settings: ModalSettings = field(default_factory=ModalSettings)
    fd_settings: FDSettings | None = None
    duration: float | None = None
    time_step: float | None = None
    output: OutputSettings = field(default_factory=OutputSettings)
    description: str = ""
    source: Path | None = None
    source_text: str = ""

    @property
    def impactor_mass(self) -> float:
        """Impactor mass m_i [kg]."""
        return float(self.sphere.mass)

    @property
    def fd_beam(self):
        """The finite-difference beam of a ``kind = "fd"`` case (``None`` otherwise)."""
        if self.solver_kind != "fd":
            return None
        from ..fd import FDBeam

        return FDBeam.from_beam(self.target, self.target_material, self.fd_settings)


# -- sections ---------------------------------------------------------------------------
def _impactor(data) -> tuple[Sphere, float]:
    path = "impactor"
    if path not in data:
        raise ValueError("[impactor] is required (radius, material, velocity)")
    entries = table(data[path], path)
    check_keys(entries, path, _IMPACTOR_KEYS, ("radius", "material", "velocity"))
    radius = number(entries, "radius", path, "m", low=IMPACTOR_RANGES["radius"][0],
                    high=IMPACTOR_RANGES["radius"][1])
    velocity = number(entries, "velocity", path, "m/s", low=IMPACTOR_RANGES["velocity"][0],
                      high=IMPACTOR_RANGES["velocity"][1])
    material = isotropic_material(entries["material"], f"{path}.material")
    mass = number(entries, "mass", path, "kg", low=IMPACTOR_RANGES["mass"][0],
                  high=IMPACTOR_RANGES["mass"][1])
    density = number(entries, "density", path, "kg/m^3")
    if mass is not None and density is not None:
        raise ValueError("impactor.mass and impactor.density are exclusive: give one of them "
                         "(density sets the mass of a solid sphere)")
    if density is not None:
        material = replace(material, density=density)
    with key_path(path, ("radius", "mass", "material")):
        sphere = Sphere(radius, material, mass)
    warn_if_unusual(f"{path}.radius", radius, "radius", f"a sphere of {float(sphere.mass):.3g} kg", stacklevel=4)
    return sphere, velocity


def _target_builder(kind: str, laminated: bool):
    """The constructor a target table maps onto, and its positional size keys."""
    from ..targets.beams.beam import Beam
    from ..targets.plates.plate import Plate

    if kind == "beam":
        if laminated:
            return Beam.from_laminate, ("length", "width")
        return Beam.rectangular, _BEAM_SIZE
    if laminated:
        return Plate.from_laminate, ("length_x", "length_y")
    return Plate.isotropic, _PLATE_SIZE


def target_keys(kind: str) -> tuple[str, ...]:
    """Every key ``[target]`` accepts for a target type (derived from the constructors)."""
    if kind == "halfspace":
        return _TARGET_COMMON
    build, sizes = _target_builder(kind, laminated=False)
    return _TARGET_COMMON + sizes + tuple(keyword_options(build))


def _target(data):
    path = "target"
    if path not in data:
        raise ValueError("[target] is required (type = 'beam', 'plate' or 'halfspace')")
    entries = table(data[path], path)
    kind = string(entries, "type", path, choices=TARGET_TYPES, required=True)
    check_keys(entries, path, target_keys(kind))
    contact_material = target_material(entries, path)
    if kind == "halfspace":
        return HalfSpace(), kind, contact_material
    build, size = _target_builder(kind, isinstance(contact_material, Laminate))
    for key in (_BEAM_SIZE if kind == "beam" else _PLATE_SIZE):
        if key not in size and key in entries:
            raise ValueError(f"{path}.{key} is derived from the plies for a laminated {kind}; "
                             "remove it")
    sizes = [number(entries, key, path, "m", required=True) for key in size]
    given = dict(zip(size, sizes))
    if kind == "plate" and "thickness" in given:  # a laminate's thickness comes from its plies (checked below)
        require_plate_proportions(f"{path}.thickness", given["thickness"], min(given["length_x"], given["length_y"]))
    options = read_options(entries, path, keyword_options(build), _TARGET_UNITS)
    with key_path(path, tuple(entries) + ("material",)):
        target = build(*sizes, contact_material, **options)
    depth_key = "thickness" if kind == "plate" else "height"
    depth = getattr(target, depth_key, None)
    if depth is not None:
        name = f"{path}.{depth_key}" + ("" if depth_key in given else " (the plies' total)")
        if kind == "plate" and depth_key not in given:
            require_plate_proportions(name, float(depth), min(float(target.length_x), float(target.length_y)))
        warn_if_unusual(name, float(depth), depth_key, stacklevel=4)
    return target, kind, contact_material


def _contact(data, sphere, contact_material, default_law=None) -> tuple[ContactLaw, str, dict]:
    """The contact law of a case; ``default_law`` (a registry name) when none is given."""
    path = "contact"
    if path not in data and default_law is None:
        raise ValueError("[contact] is required (law = one of "
                         + ", ".join(repr(n) for n in available_contact_laws()) + ")")
    entries = table(data.get(path, {}), path)
    name = string(entries, "law", path, choices=available_contact_laws(),
                  default=default_law, required=default_law is None)
    allowed = tuple(law_options(name))
    stiffness_unit = contact_law_class(name).stiffness_unit
    check_keys(entries, path, ("law",) + allowed + (("stiffness",) if stiffness_unit else ()))
    units = {key: option.unit for key, option in law_options(name).items()}
    options = read_options(entries, path, dict.fromkeys(allowed, "number"), units)
    stiffness = number(entries, "stiffness", path, stiffness_unit or "", low=STIFFNESS_RANGE[0],
                       high=STIFFNESS_RANGE[1])
    with key_path(path, allowed + ("stiffness",)):
        if stiffness is not None:
            law = contact_law(name, stiffness=stiffness)
        else:
            law = law_for_sphere(name, sphere, contact_material, **options)
    return law, name, options


def _solver(data, law, sphere, velocity, kind):
    path = "solver"
    entries = table(data.get(path, {}), path)
    modal_options = keyword_options(ModalSettings)
    check_keys(entries, path, _SOLVER_EXTRA + tuple(modal_options))
    duration = number(entries, "duration", path, "s", required=kind == "fd")
    time_step = number(entries, "time_step", path, "s")
    fields = read_options(entries, path, modal_options)
    if duration is not None:
        if "max_time_ratio" in fields:
            raise ValueError("solver.duration and solver.max_time_ratio are exclusive: give one")
        omega = math.sqrt(reference_contact_stiffness(law, sphere.mass, velocity) / sphere.mass)
        fields["max_time_ratio"] = duration * omega
        if not math.isfinite(fields["max_time_ratio"]):
            raise ValueError(f"solver.duration = {duration:g} s is invalid: valid range is up to about "
                             f"{1e300 / omega:.3g} s (times the contact frequency {omega:.4g} rad/s it must stay finite)")
    with key_path(path, tuple(modal_options)):
        settings = ModalSettings(**fields)
    return settings, duration, time_step


def _output(data) -> OutputSettings:
    path = "output"
    entries = table(data.get(path, {}), path)
    options = keyword_options(OutputSettings)
    check_keys(entries, path, tuple(options))
    with key_path(path, tuple(options)):
        return OutputSettings(**read_options(entries, path, options))


def _solver_kind(data, override):
    if override is not None:
        return override
    entries = table(data.get("solver", {}), "solver")
    return string(entries, "kind", "solver", choices=SOLVER_KINDS, default="modal")


def _parse_toml(text: str) -> dict:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:  # load_case names the file, as for every other error
        raise ValueError(f"not valid TOML: {error}") from None
    check_keys(data, "", _TOP_KEYS)
    for key in ("name", "description"):
        string(data, key, "")
    return data


def parse_case(text: str, *, name: str = "case", source: Path | None = None,
               solver: str | None = None) -> Case:
    """Build a :class:`Case` from the TOML ``text`` of a case file (``name``: default label;
    ``source``: provenance; ``solver``: override ``[solver] kind``).

    Raises
    ------
    ValueError
        Invalid TOML, an unknown key, or a missing/invalid value, naming the key path, the
        value and the valid range.
    """
    from ._fd import check_fd_target, fd_settings

    data = _parse_toml(text)
    kind = _solver_kind(data, solver)
    sphere, velocity = _impactor(data)
    if kind == "fd":
        check_fd_target(data)
    target, target_type, contact_material = _target(data)
    law, law_name, options = _contact(data, sphere, contact_material,
                                      default_law="stronge" if kind == "fd" else None)
    settings, duration, time_step = _solver(data, law, sphere, velocity, kind)
    output = _output(data)
    fd = fd_settings(data, contact_material, required=kind == "fd") if kind == "fd" or "fd" in data else None
    if kind == "fd":
        time_step = fd.time_step
    return Case(
        name=data.get("name", name), sphere=sphere, velocity=velocity, target=target,
        target_type=target_type, target_material=contact_material, law=law, law_name=law_name,
        contact_options=options, solver_kind=kind, settings=settings, fd_settings=fd,
        duration=duration, time_step=time_step, output=output,
        description=data.get("description", ""), source=source, source_text=text,
    )


def load_case(path, *, solver: str | None = None) -> Case:
    """Read and validate the case file at ``path`` (``solver``: override ``[solver] kind``).

    Raises
    ------
    ValueError
        Missing file, invalid TOML, unknown keys or invalid values, starting with the file
        name and naming the key path.
    """
    source, text = read_text_input("case file", path)
    try:
        return parse_case(text, name=source.stem, source=source, solver=solver)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from error
