"""Any registered contact law built from a sphere and a target material.

The :class:`Sphere` itself lives in :mod:`impactmaps.contact.pair` with the checks of
the materials (it is re-exported here).

Materials are duck-typed: an object with ``youngs_modulus`` [Pa], ``poisson_ratio``
[-], ``density`` [kg/m³] and optionally ``yield_strength`` [Pa] (``None`` or missing:
the body is taken not to yield), for example
:class:`impactmaps.materials.IsotropicMaterial`. The checks of the materials and the
contact geometry are in :mod:`impactmaps.contact.pair`.
"""

from __future__ import annotations

from .base import ContactLaw, LawOption, contact_law_class
from .pair import PAIR_OPTIONS, ContactPair, Sphere, softer_yield_strength

__all__ = ["Sphere", "law_for_sphere", "law_options", "softer_yield_strength"]


def law_for_sphere(name: str, sphere: Sphere, target_material, **options) -> ContactLaw:
    """Build the registered contact law ``name`` for ``sphere`` striking a target.

    Parameters
    ----------
    name : str
        A registered law (``impactmaps.contact.available_contact_laws()``).
    sphere : Sphere
        The impactor.
    target_material : material-like
        Target material (``youngs_modulus`` [Pa], ``poisson_ratio`` [-], optional
        ``yield_strength`` [Pa]); ``youngs_modulus = inf`` is a rigid target.
    **options
        ``target_radius`` [m] (default ``inf``, a flat: the target's curvature at the
        impact point, ``1/R = 1/R_sphere + 1/R_target``); ``yield_strength`` [Pa]
        overriding the softer material's (e.g. ``2 S_u`` for composites, seed 001);
        then the law's own options, e.g. for ``"stronge"`` ``yield_pressure_factor``,
        ``plastic_pressure_factor``, ``plastic_indentation_ratio``
        (:func:`law_options` lists them with units, defaults and meanings).

    Returns
    -------
    ContactLaw
        ``"hertz"``: ``K_h = (4/3) sqrt(R) E*`` (eqs 7–8). ``"yigit-christoforou"``:
        K_h and ``α_y = 0.68 π² S_y² R/E*²`` (eq 9) with S_y the smaller yield
        strength of the two bodies. ``"linear"``: ``K = K_y = 1.5 K_h sqrt(α_y)`` (eqs
        10, 18), which needs a yield strength. ``"stronge"``: E*, R, S_y and the
        constants.

    Raises
    ------
    ValueError
        Unknown law, a law with no contact-pair builder, an unknown option, a
        missing yield strength, or invalid material data.
    """
    law_class = contact_law_class(name)  # ValueError listing the known laws
    pair_options = {key: options.pop(key) for key in PAIR_OPTIONS if key in options}
    pair = ContactPair.from_sphere(sphere, target_material, **pair_options)
    law_class.check_options(options, also_valid=PAIR_OPTIONS)
    return law_class.from_contact_pair(pair, **options)


def law_options(name: str) -> dict[str, LawOption]:
    """The keyword options that matter to ``law_for_sphere(name, ...)``, each declared once.

    ``target_radius`` (every law), ``yield_strength`` (laws that need a yield strength),
    then the law's own options (:meth:`ContactLaw.options`).

    Parameters
    ----------
    name : str
        A registered law (``impactmaps.contact.available_contact_laws()``).

    Returns
    -------
    dict of str to LawOption
        In that order; iterating gives the names. Each LawOption has the unit (``""``:
        dimensionless), the default and a one-line meaning.

    Raises
    ------
    ValueError
        Unknown law.
    """
    law_class = contact_law_class(name)
    pair = {key: option for key, option in PAIR_OPTIONS.items()
            if key != "yield_strength" or law_class.needs_yield_strength}
    return pair | law_class.options()
