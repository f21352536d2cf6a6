"""Reading an elastic-plastic map: F̄max, restitution and absorbed energy at (β, ζ, λ).

The maps (``impactmaps/maps/data/NAME-yc.npz``, ``NAME-stronge.npz`` and ``NAME-epp.npz``, built by
``data_build/build_plastic_maps.py``; numbers and scales in
:mod:`impactmaps.maps.compute.plastic_points`) are interpolated linearly in (log β, log λ, log ζ)
(:func:`impactmaps.lookup` with the law ``"yc"``, ``"stronge"`` or ``"epp"``).
Each answer carries a band: over the eight map points around it, the largest of their own
error (refinement, or half the spread of a sensitive point) plus the local interpolation
error estimated from the map's second differences
(:func:`impactmaps.maps.read.bands.interpolation_error` along the three axes), times
:data:`BAND_SAFETY`; its coverage is measured by ``validation/lookup_error.py --law yc`` (``stronge``, ``epp``).
A map may ship with a refinement of each β slice (``data/refinements/NAME-LAW``,
:mod:`impactmaps.maps.family.slice_refinement`): F̄max is then read in the slices' refined leaves.
Next to a point the map holds no value for (``unresolved``: beyond what a Timoshenko
theory holds, or no model within the mode cap) a lookup is refused — never a number
without its band.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..family.builtin_families import LAYOUTS, family_layout
from .reader import read_values

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["PLASTIC_MAPS", "BAND_SAFETY", "PlasticLookup", "read_plastic"]

#: (kind, theory) → structure name of the shipped plastic maps (no Mindlin plate: its pressure
#: patch depends on the sphere radius, a fourth number).
PLASTIC_MAPS = LAYOUTS["yc"].shipped
#: The interpolation estimate of the plastic maps (:func:`~impactmaps.maps.read.bands.interpolation_error`):
#: second differences over one neighbour a side, safety factor 4, and the factor on the
#: whole band (:class:`~impactmaps.maps.family.map_family.Interpolation` of the plastic families).
_YC = LAYOUTS["yc"]
PLASTIC_REACH, PLASTIC_SAFETY, BAND_SAFETY = _YC.interpolation.reach, _YC.interpolation.safety, _YC.interpolation.band_safety


@dataclass(frozen=True)
class PlasticLookup:
    """Outcome of a lookup in a plastic map (scalars or arrays, all [-]).

    Attributes
    ----------
    fmax_normalised, fmax_error : F_max/(m V0 ω_y) and its band half-width.
    restitution, restitution_error : rebound speed / V0 and its band half-width.
    absorbed_energy_fraction, absorbed_energy_error : contact dissipation / ½ m V0² and its band.
    status : str or ndarray of str
        Worst status of the eight map points around the answer (``sensitive`` >
        ``refined`` > ``converged``/``asymptotic``; an ``unresolved`` one is refused), and
        ``interpolated`` where they converged but the F̄max band is wider than the points'
        tolerance (:func:`impactmaps.maps.read.bands.answer_status`).
    map_name : str
    law : str
        ``"yc"``, ``"stronge"`` or ``"epp"``.
    """

    fmax_normalised: object
    fmax_error: object
    restitution: object
    restitution_error: object
    absorbed_energy_fraction: object
    absorbed_energy_error: object
    status: object
    map_name: str
    law: str


def read_plastic(dataset: xr.Dataset | None, law: str, numbers, *, name: str, where: str,
                 band_grids: dict | None = None, prepared=None, refinement=None) -> PlasticLookup:
    """A plastic map (shipped, or an on-demand tile) read at ``numbers`` = (β, ζ, λ) [-].

    Parameters
    ----------
    dataset : xarray.Dataset or None
        A map of the plastic family ``law`` over (β, λ, ζ) (None when ``prepared`` is given).
    law : {"yc", "stronge", "epp"}
    numbers : (β, ζ, λ)
        Floats or arrays [-].
    name, where : str
        The map's name (the answer's ``map_name``) and how a refusal names it.
    band_grids : dict, optional
        :func:`~impactmaps.maps.read.reader.band_grid` of each interpolated quantity, when known.
    prepared : PreparedMap, optional
        The map already prepared (:func:`~impactmaps.maps.read.reader.prepare_map`).
    refinement : SlicedRefinement, optional
        The refinement of each β slice of ``dataset``
        (:mod:`impactmaps.maps.family.slice_refinement`): F̄max is read in the slices' refined leaves.

    Returns
    -------
    PlasticLookup

    Raises
    ------
    ValueError
        Outside the map's range (naming the number and the range), or where a map point
        around the answer is ``unresolved`` (holds no value).
    """
    reading = read_values(dataset, family_layout(law), numbers, ("beta", "loss_factor", "relative_stiffness"),
                          where=where, hints=(" (impactmaps simulate)",) * 2, band_grids=band_grids,
                          prepared=prepared, refinement=refinement)
    values = reading.values | reading.errors
    status = reading.status
    if not reading.shape:
        values = {key: float(value) for key, value in values.items()}
        status = str(status)
    return PlasticLookup(status=status, map_name=name, law=law, **values)
