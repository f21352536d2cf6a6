"""Contact laws: one module per law, all behind :class:`ContactLaw` and one registry."""

from .plastic import epp  # noqa: F401  (registers the FE-calibrated law "epp")
from .base import (
    ContactLaw,
    LawOption,
    available_contact_laws,
    contact_law,
    contact_law_class,
    effective_modulus,
    effective_radius,
    evaluate_kernel,
    register_contact_law,
)
from .hertz import HertzContact, hertz_stiffness
from .linear import LinearContact
from .pair import ContactPair
from .sphere import Sphere, law_for_sphere, law_options, softer_yield_strength
from .plastic.stronge import StrongeContact, stronge_continuity_coefficient
from .plastic.yigit_christoforou import YigitChristoforouContact, yield_indentation

__all__ = [
    "ContactLaw",
    "ContactPair",
    "HertzContact",
    "LawOption",
    "LinearContact",
    "Sphere",
    "StrongeContact",
    "YigitChristoforouContact",
    "available_contact_laws",
    "contact_law",
    "contact_law_class",
    "effective_modulus",
    "effective_radius",
    "evaluate_kernel",
    "hertz_stiffness",
    "law_for_sphere",
    "law_options",
    "register_contact_law",
    "softer_yield_strength",
    "stronge_continuity_coefficient",
    "yield_indentation",
]
