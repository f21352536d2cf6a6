"""The refined Stronge law exactly as docs/physics_contract.md §2 printed it — a test fixture, never run by the package.

Its elastic-plastic branch takes the fully plastic contact area from first yield on,
``a² = R(2δ − δ_y)``, with ``F = F_y L [1 + ln L/κ]``, ``L = 2δ/δ_y − 1``: the loading
curve rises above the elastic Hertz curve for δ_y < δ < 16.65 δ_y, the elastic recovery
``3F_m/(4E* a_m)`` exceeds δ_m below 5.396 δ_y (δ_r < 0, cut to 0 by the no-tension
rule) and a load–unload cycle below 4.897 δ_y returns more work than it absorbed.
:mod:`impactmaps.contact.plastic.stronge` replaces that area law; this copy exists so that
``tests/contact/test_contact_laws.py`` can prove the flaw and ``tests/contact/test_contact_contract.py``
can show that the contract catches it. It is a subclass of the package's law (same
yield point, κ, fully plastic phase and unloading rule) and is not registered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from impactmaps.contact import ContactLaw, StrongeContact
from impactmaps.contact.plastic.stronge import hertz_unloading


@numba.njit(cache=False)
def _printed_loading(delta, params):
    """(force, stiffness, contact radius) of the printed virgin loading curve, δ > 0."""
    modulus, radius, yield_delta, yield_force = params[0], params[1], params[2], params[3]
    plastic_delta, kappa, plastic_pressure = params[4], params[5], params[6]
    if delta <= yield_delta:
        root = math.sqrt(delta)
        factor = modulus * math.sqrt(radius)
        return 4.0 / 3.0 * factor * delta * root, 2.0 * factor * root, math.sqrt(radius * delta)
    ratio = 2.0 * delta / yield_delta - 1.0
    contact_radius = math.sqrt(radius * (2.0 * delta - yield_delta))
    if delta <= plastic_delta:
        log_ratio = math.log(ratio)
        force = yield_force * ratio * (1.0 + log_ratio / kappa)
        stiffness = 2.0 * yield_force / yield_delta * (1.0 + (1.0 + log_ratio) / kappa)
        return force, stiffness, contact_radius
    return (math.pi * contact_radius * contact_radius * plastic_pressure,
            2.0 * math.pi * radius * plastic_pressure, contact_radius)


@numba.njit(cache=False)
def _printed_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    if alpha >= alpha_max or alpha_max <= params[2]:
        force, stiffness, _a = _printed_loading(alpha, params)
        return force, stiffness
    peak_force, _k, peak_radius = _printed_loading(alpha_max, params)
    recovery = 3.0 * peak_force / (4.0 * params[0] * peak_radius)  # may exceed δ_m: δ_r < 0
    return hertz_unloading(alpha, alpha_max, peak_force, recovery)


@dataclass(frozen=True)
class PrintedStrongeContact(StrongeContact):
    """The printed (energy-creating) refined Stronge law; same constructor as :class:`StrongeContact`."""

    name: ClassVar[str] = "stronge-printed"
    kernel = staticmethod(_printed_kernel)

    @property
    def kernel_parameters(self) -> np.ndarray:
        return StrongeContact.kernel_parameters.fget(self)[:7]

    def loading_contact_radius(self, indentation):
        """Printed contact radius: ``a² = R δ`` to δ_y, ``R(2δ − δ_y)`` beyond [m]."""
        delta = np.clip(np.asarray(indentation, dtype=float), 0.0, None)
        radius = np.asarray(self.radius, float)
        yield_delta = self.yield_indentation
        return np.where(delta <= yield_delta, np.sqrt(radius * delta),
                        np.sqrt(radius * np.clip(2.0 * delta - yield_delta, 0.0, None)))

    def signed_permanent_indentation(self, max_indentation):
        """``δ_r = δ_m − 3F_m/(4E* a_m)`` [m] as printed — negative near yield."""
        alpha_max = np.clip(np.asarray(max_indentation, float), 0.0, None)
        force = self.loading_force(alpha_max)
        with np.errstate(invalid="ignore", divide="ignore"):
            recovery = 3.0 * force / (4.0 * np.asarray(self.effective_modulus, float)
                                      * self.loading_contact_radius(alpha_max))
        return np.where(alpha_max <= self.yield_indentation, 0.0, alpha_max - recovery)

    def permanent_indentation(self, max_indentation):
        """``max(δ_r, 0)`` [m]: where the printed unloading curve is cut by the no-tension rule."""
        return np.clip(self.signed_permanent_indentation(max_indentation), 0.0, None)

    # energies by the base class's quadrature of the kernel (no closed form kept)
    loading_energy = ContactLaw.loading_energy
    recovered_energy = ContactLaw.recovered_energy
    indentation_for_energy = ContactLaw.indentation_for_energy
