"""Reference structures for normalised (ζ, λ) maps.

A :class:`MapStructure` names a structure family (kind, theory, supports, aspect ratio,
slenderness, impact point as fractions) and builds one steel-like unit-span target that
stands for them all; :class:`BasisTable` holds its modes for many impactors.
"""

from __future__ import annotations

import hashlib
import warnings
from dataclasses import asdict, dataclass, replace

import numpy as np

from ..._checks import require_choice, require_in_range
from ...targets.base import ModalBasis, Target, dropped_compliance_sums
from ...targets.beams.beam import MIN_SLENDERNESS, Beam
from ...targets.map_structure import KIRCHHOFF_RATIO_COUNT, STIFFNESS_RATIOS, reference_target
from ...targets.options import PLATE_ASPECT_RANGE, STRUCTURE_KINDS, depends_on_slenderness, is_shear_deformable, theories
from ...targets.plates.plate import Plate
from ..._checks import ModelValidityWarning
from .builtin_families import MEMBER_SLENDERNESSES

__all__ = ["MapStructure", "BasisTable", "DEFAULT_STRUCTURES", "structure_from_name",
           "MAX_MODES", "warn_point_loaded_mindlin"]

MAX_MODES = 80_000  # cost cap on the modes (all, incl. non-participating) below the cut-off


@dataclass(frozen=True)
class MapStructure:
    """A structure family (the targets one normalised map stands for).

    Parameters
    ----------
    kind : {"beam", "plate"}
    theory, supports : str
        Beam: one of :data:`~impactmaps.targets.options.BEAM_THEORIES` and
        :data:`~impactmaps.targets.options.BEAM_SUPPORTS`; plate: one of
        :data:`~impactmaps.targets.options.PLATE_THEORIES` and an edge code, e.g. "SSSS".
    aspect_ratio : float
        Plate b/a [-] (ignored for beams).
    slenderness : float
        Span over thickness, L/h or a/h [-].
    impact_fraction : tuple of float
        Impact point as a fraction of the span(s): (x0/L,) or (x0/a, y0/b).
    poisson_ratio : float
        Poisson ratio of the reference material [-].
    stiffness : tuple of float, optional
        An orthotropic or laminated plate's stiffness ratios
        (:data:`~impactmaps.targets.map_structure.STIFFNESS_RATIOS`: 5 for Kirchhoff, 9 for
        Mindlin) [-], carried by the reference instead of the isotropic ones; None (default):
        the isotropic reference.
    """

    kind: str = "plate"
    theory: str = "kirchhoff"
    supports: str = "SSSS"
    aspect_ratio: float = 1.0
    slenderness: float = 20.0
    impact_fraction: tuple = (0.5, 0.5)
    poisson_ratio: float = 0.3
    stiffness: tuple | None = None

    def __post_init__(self):
        require_choice("kind", self.kind, STRUCTURE_KINDS)
        require_choice("theory", self.theory, theories(self.kind))
        require_in_range("aspect_ratio", self.aspect_ratio, *PLATE_ASPECT_RANGE)
        require_in_range("slenderness", self.slenderness, MIN_SLENDERNESS, np.inf)
        require_in_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5, low_inclusive=False, high_inclusive=False)
        fractions = tuple(float(f) for f in np.atleast_1d(self.impact_fraction))
        expected = 1 if self.kind == "beam" else 2
        if len(fractions) == 2 and self.kind == "beam":
            fractions = fractions[:1]
        if len(fractions) != expected:
            raise ValueError(
                f"impact_fraction = {self.impact_fraction!r} is invalid: a {self.kind} needs "
                f"{expected} fraction(s) of the span in (0, 1)"
            )
        require_in_range("impact_fraction", fractions, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
        object.__setattr__(self, "impact_fraction", fractions)
        if self.kind == "plate":
            object.__setattr__(self, "supports", self.supports.upper())
        else:
            object.__setattr__(self, "supports", self.supports.lower())
        if self.stiffness is not None:
            count = len(STIFFNESS_RATIOS) if is_shear_deformable(self.theory) else KIRCHHOFF_RATIO_COUNT
            values = tuple(float(v) for v in self.stiffness)
            if self.kind != "plate" or len(values) != count or not all(np.isfinite(values)):
                raise ValueError(f"stiffness = {self.stiffness!r} is invalid: a {self.theory} plate's "
                                 f"{count} finite ratios {STIFFNESS_RATIOS[:count]}")
            object.__setattr__(self, "stiffness", values)

    @property
    def name(self) -> str:
        """Short label, e.g. ``beam-ss-euler`` or ``plate-ssss-kirchhoff``."""
        base = f"{self.kind}-{self.supports.lower()}-{self.theory}"
        extras = []
        if self.kind == "plate" and self.aspect_ratio != 1.0:
            extras.append(f"ar{self.aspect_ratio:g}")
        if depends_on_slenderness(self.theory):
            extras.append(f"s{self.slenderness:g}")
        centre = (0.5,) if self.kind == "beam" else (0.5, 0.5)
        if self.impact_fraction != centre:
            extras.append("x" + "-".join(f"{f:g}" for f in self.impact_fraction))
        if self.stiffness is not None:  # a laminate: its ratios, shortened to a digest
            extras.append("lam" + hashlib.sha256(repr(self.stiffness).encode()).hexdigest()[:8])
        return "-".join([base, *extras])

    def as_dict(self) -> dict:
        """Plain dict of the fields (for provenance attributes; ``stiffness`` only where given,
        so that an isotropic structure's dict, and every fingerprint of it, is unchanged)."""
        fields = asdict(self)
        if self.stiffness is None:
            del fields["stiffness"]
        return fields

    def build(self) -> Target:
        """The concrete reference target: unit span, steel-like, thickness = span/slenderness,
        carrying ``stiffness`` where given (a new, equal target each call).
        """
        return reference_target(Beam if self.kind == "beam" else Plate, self)

    def model_revisions(self) -> dict:
        """The revisions of the models its points depend on beyond the solver's, for the
        fingerprints of its sweeps and tiles: ``{"plate_basis": BASIS_REVISION}`` for a plate of
        the general Ritz basis (:mod:`impactmaps.targets.plates.basis_cache`: its modes' bits
        change with that code), else empty (every other fingerprint stays what it was)."""
        if self.kind != "plate":
            return {}
        from ...targets.plates.basis_cache import BASIS_REVISION
        from ...targets.plates.plate_any_edges import uses_general_basis

        return {"plate_basis": BASIS_REVISION} if uses_general_basis(self.build()) else {}


def structure_from_name(name: str) -> MapStructure:
    """Parse the short names of the shipped maps (``beam-ss-euler`` …)."""
    for structure in DEFAULT_STRUCTURES:
        if structure.name == name:
            return structure
    for structure in MEMBER_STRUCTURES:
        if structure.name == name:
            return structure
    parts = name.split("-")
    slenderness = {}
    if len(parts) == 4 and parts[3].startswith("s"):
        try:
            slenderness = {"slenderness": float(parts[3][1:])}
        except ValueError:
            pass
        else:
            parts = parts[:3]
    if len(parts) == 3:
        kind, supports, theory = parts
        return MapStructure(kind=kind, supports=supports, theory=theory,
                            impact_fraction=(0.5,) if kind == "beam" else (0.5, 0.5), **slenderness)
    raise ValueError(
        f"structure = {name!r} is not known: use kind-supports-theory[-sSLENDERNESS], e.g. "
        "'beam-ss-euler', 'plate-ssss-kirchhoff' or 'plate-ssss-mindlin-s50'"
    )


DEFAULT_STRUCTURES = (
    MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,)),
    MapStructure(kind="beam", theory="timoshenko", supports="ss", impact_fraction=(0.5,)),
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS"),
    MapStructure(kind="plate", theory="mindlin", supports="SSSS"),
)

# SHIPPED_PLANE_MAPS ((kind, theory) → the name of each of DEFAULT_STRUCTURES, checked by
# tests/maps/test_lookup_light.py) and MEMBER_SLENDERNESSES come from .builtin_families.

#: The shear-deformable slenderness members besides the default slenderness 20.
MEMBER_STRUCTURES = tuple(
    replace(structure, slenderness=slenderness)
    for structure in DEFAULT_STRUCTURES if is_shear_deformable(structure.theory)
    for slenderness in MEMBER_SLENDERNESSES if slenderness != structure.slenderness
)


class BasisTable:
    """All participating modes of a target up to some frequency, truncatable without
    recomputation: ``basis`` (the modes up to ``max_frequency`` [rad/s]) and
    ``max_frequency``.
    """

    def __init__(self, target: Target, max_frequency: float, min_modes: int = 1):
        self.basis = target.modes(max_frequency, min_modes=min_modes).participating()
        self.max_frequency = max_frequency
        # the compliance every truncation drops, summed once (the same bits as a truncation
        # summing its own dropped modes: dropped_compliance_sums)
        self._dropped_sums = dropped_compliance_sums(self.basis.frequencies, self.basis.participation)

    def truncate(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """Modes with ω ≤ ``max_frequency`` [rad/s] (at least ``min_modes``), with exact residual:
        bit for bit ``self.basis.truncate(max_frequency, min_modes)``, in O(log n).
        """
        count = self.basis.cutoff_count(max_frequency, min_modes)
        if count == self.basis.size:
            return self.basis
        return self.basis.head(count, float(self._dropped_sums[self.basis.size - 1 - count]))


def warn_point_loaded_mindlin(who: str, stacklevel: int = 2, ritz: bool = False) -> None:
    """Warn that a map of a Mindlin plate is a point load, whose answer depends on its cut-off
    (``docs/contact_patch.rst``); ``who`` is the sentence's subject; ``ritz``: some of its plates
    have the Ritz basis (edges other than SSSS, D16/D26), whose points stop at its largest basis.
    """
    cap = f"the sweep's cap of {MAX_MODES} modes" + (
        " (on a plate of the Ritz basis — edges other than SSSS, D16/D26 — no further than its largest basis "
        "resolves: method modal+residual-capped where it stops there)" if ritz else "")
    warnings.warn(f"point load: {who} the plate at a point, whose deflection diverges; the map's F̄max holds the "
                  f"shear of every mode up to {cap} and has no converged value, and "
                  "its error is that of the integration at the cap: simulate, which cuts the shear at its own "
                  "cut-off, differs by 0.07 % (median) to 5 % with one impact and by 5 % (median) to 22 % with "
                  "re-impacts (validation/mindlin_point_load.md); a sphere's Hertz impact spread over its contact "
                  "patch converges: `impactmaps lookup --case`", ModelValidityWarning, stacklevel=stacklevel + 1)
