"""Contact laws: one module per law, all behind :class:`ContactLaw` and one registry."""

from .base import (
    ContactLaw,
    available_contact_laws,
    contact_law,
    contact_law_class,
    effective_modulus,
    effective_radius,
    evaluate_kernel,
    register_contact_law,
)
from .linear import LinearContact

__all__ = [
    "ContactLaw",
    "LinearContact",
    "available_contact_laws",
    "contact_law",
    "contact_law_class",
    "effective_modulus",
    "effective_radius",
    "evaluate_kernel",
    "register_contact_law",
]
