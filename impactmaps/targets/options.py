"""The named choices of the targets, written once: structure kinds, theories, supports."""

from __future__ import annotations

__all__ = ["MIN_SUPPORT_DISTANCE", "PLATE_ASPECT_RANGE", "STRUCTURE_KINDS", "BEAM_THEORIES", "BEAM_SUPPORTS", "PLATE_THEORIES", "CLASSICAL_THEORIES",
           "DIVERGENT_POINT_LOAD_THEORIES", "SLENDERNESS_THEORIES", "SHEAR_THEORIES", "FD_BEAM_THEORY",
           "theories", "default_theory", "classical_theory", "depends_on_slenderness", "is_shear_deformable",
           "point_load_diverges"]

#: Kinds of finite structure with modes and an infinite-structure asymptote.
STRUCTURE_KINDS = ("beam", "plate")
#: Beam theories: Euler–Bernoulli, Rayleigh (rotary inertia), Timoshenko (and shear).
BEAM_THEORIES = ("euler", "rayleigh", "timoshenko")
#: Beam support codes, end x = 0 first: s = simply supported, c = clamped, f = free.
BEAM_SUPPORTS = ("ss", "cc", "cs", "cf", "ff")
#: Plate theories: classical (shear-rigid, no rotary inertia) and Mindlin (first-order shear).
PLATE_THEORIES = ("kirchhoff", "mindlin")
#: Theories whose infinite-structure closed forms are the toolkit's asymptotes (the Euler
#: beam's t^(-1/2) kernel, the Kirchhoff plate's dashpot 8 sqrt(D ρh)).
CLASSICAL_THEORIES = ("euler", "kirchhoff")
#: Theories under which the deflection under a point load is unbounded (a Mindlin plate:
#: logarithmic, from transverse shear), so a point-load peak force never converges.
DIVERGENT_POINT_LOAD_THEORIES = ("mindlin",)
#: Theories whose normalised response depends on the slenderness (span/thickness), through
#: rotary inertia (Rayleigh) or shear and rotary inertia (Timoshenko, Mindlin).
SLENDERNESS_THEORIES = ("rayleigh", "timoshenko", "mindlin")
#: Shear-deformable theories, each with its classical (shear-rigid) thin limit.
SHEAR_THEORIES = {"timoshenko": "euler", "mindlin": "kirchhoff"}
#: The theory of the finite-difference beam (:mod:`impactmaps.fd`): rotary inertia, no shear.
FD_BEAM_THEORY = "rayleigh"


def theories(kind: str) -> tuple[str, ...]:
    """The theories of a structure kind: :data:`BEAM_THEORIES` or :data:`PLATE_THEORIES`."""
    return BEAM_THEORIES if kind == "beam" else PLATE_THEORIES


def default_theory(kind: str) -> str:
    """The classical theory of ``kind`` (``"beam"`` → Euler–Bernoulli, ``"plate"`` → Kirchhoff)."""
    return next(theory for theory in theories(kind) if theory in CLASSICAL_THEORIES)


def classical_theory(theory: str) -> str:
    """The classical thin limit of ``theory`` (Timoshenko → Euler, Mindlin → Kirchhoff);
    a classical theory is its own."""
    return SHEAR_THEORIES.get(theory, theory)


def depends_on_slenderness(theory: str) -> bool:
    """Whether the normalised response under ``theory`` depends on the slenderness."""
    return theory in SLENDERNESS_THEORIES


def is_shear_deformable(theory: str) -> bool:
    """Whether ``theory`` has transverse shear deformation (:data:`SHEAR_THEORIES`)."""
    return theory in SHEAR_THEORIES


def point_load_diverges(theory: str) -> bool:
    """Whether the point-load deflection is unbounded under ``theory``."""
    return theory in DIVERGENT_POINT_LOAD_THEORIES


#: Closest an impact point may lie to a supported (clamped or simply supported) end or edge,
#: as a fraction of that span [-]. Closer, the point load and the support coincide for the
#: model (the static compliance underflows to zero at 1e-300 m); the model stops describing
#: the impact well before, within a section depth (:func:`impactmaps.validity.validity_warnings`).
MIN_SUPPORT_DISTANCE = 1e-6


def impact_coordinate_range(span: float, low_supported: bool, high_supported: bool) -> tuple:
    """The closed range ``(low, high)`` [m] of an impact coordinate on a span [m]
    (:data:`MIN_SUPPORT_DISTANCE` × span from a supported end; a free end itself)."""
    margin = MIN_SUPPORT_DISTANCE * span
    return (margin if low_supported else 0.0, span - margin if high_supported else span)


#: Plate aspect ratios b/a a normalised map structure takes: beyond 1000 (or below 1e-3) the
#: plate is a strip whose modes its Navier/Ritz series reach only with an overflowing count
#: (``point --aspect 1e300`` overflowed).
PLATE_ASPECT_RANGE = (1.0e-3, 1.0e3)
