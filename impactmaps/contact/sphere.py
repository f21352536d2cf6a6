"""Any registered contact law built from a sphere and a target material
(:func:`law_for_sphere`, :func:`law_options`).
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
        ``youngs_modulus`` [Pa] (``inf``: rigid target), ``poisson_ratio`` [-], optional
        ``yield_strength`` [Pa].
    **options
        ``target_radius`` [m] (default ``inf``, a flat), ``yield_strength`` [Pa]
        overriding the softer material's, then the law's own options
        (:func:`law_options`).

    Returns
    -------
    ContactLaw

    Raises
    ------
    ValueError
        Unknown law or option, a missing yield strength, or invalid material data.
    """
    law_class = contact_law_class(name)  # ValueError listing the known laws
    pair_options = {key: options.pop(key) for key in PAIR_OPTIONS if key in options}
    pair = ContactPair.from_sphere(sphere, target_material, **pair_options)
    law_class.check_options(options, also_valid=PAIR_OPTIONS)
    return law_class.from_contact_pair(pair, **options)


def law_options(name: str) -> dict[str, LawOption]:
    """The keyword options of ``law_for_sphere(name, ...)`` as name → LawOption (unit, default, meaning).

    Raises
    ------
    ValueError
        Unknown law.
    """
    law_class = contact_law_class(name)
    pair = {key: option for key, option in PAIR_OPTIONS.items()
            if key != "yield_strength" or law_class.needs_yield_strength}
    return pair | law_class.options()
