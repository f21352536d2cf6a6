"""``epp``: sphere on an elastic–perfectly plastic flat, calibrated on axisymmetric FE.

Normalised by the first-yield scales of docs/physics_contract.md §2 (``c_y = 1.6``):
``δ_y = R (π c_y Y / (2E*))²``, ``F_y = (4/3) E* R^{1/2} δ_y^{3/2}``. Hertz to first yield,
an FE-fitted plastic loading branch and an Etsion-type power-law unloading; coefficients
(:data:`COEFFICIENTS`), calibrated range (1 ≤ δ_m/δ_y ≤ 1000, δ_m ≤ 0.05 R, ν 0.3–0.45,
s ≤ 0.5) and errors: docs/epp_calibration.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from ..._checks import require_in_range, require_positive
from ..base import ContactLaw, law_option, register_contact_law
from .first_yield import (
    first_yield_force,
    first_yield_indentation,
    reference_impact_number,
    ReferenceYieldScales,
)

__all__ = ["COEFFICIENTS", "EppContact"]

#: Hertz peak pressure at first yield, ``p0 = c_y Y`` (docs/physics_contract.md §2).
YIELD_PRESSURE_FACTOR = 1.6

#: Fitted coefficients (validation/fe/axisym_fit.py on validation/fe/results/axisym_runs.csv).
COEFFICIENTS = {
    "q": 0.23, "c": 1.417, "r": 0.005186,  # loading: exponent deficit q L²/(c² + L²) + r L²
    "b": 0.1877, "w": 1.082, "v": 0.4343,  # recovery (δ_m − δ_r)/δ_m = (1 + b (x_m − 1)^w)^(−v/w)
    "n_inf": 0.9496, "k": 0.1236,  # unloading exponent n = n∞ + (3/2 − n∞) x_m^(−k)
    "a_nu": 0.2378, "a_r": 0.2832,  # first-yield shifts with the flat's ν (loading, unloading)
    "b_f": 0.1301, "c_s": 2.784,  # force gain with the sphere's compliance share s
    "b_s": 0.4488,  # unloading-shape shift with s
}

_ORDER = ("q", "c", "r", "b", "w", "v", "n_inf", "k", "a_nu", "a_r", "b_f", "c_s", "b_s")
#: Largest share of 1/E* the sphere may carry (the flat must be the softer body).
LARGEST_SPHERE_COMPLIANCE = 0.75
#: ln x_c beyond which the loading exponent is held at 1 (F ∝ δ: constant mean pressure):
#: the root of q L²/(c² + L²) + r L² = 1/2, x_c = 1518.5 (beyond the calibrated 1000 δ_y and
#: beyond every point of the shipped epp maps, whose values it therefore leaves unchanged).
_B = COEFFICIENTS["q"] + COEFFICIENTS["r"] * COEFFICIENTS["c"] ** 2 - 0.5
LOG_CAP = math.sqrt((math.sqrt(_B * _B + 2.0 * COEFFICIENTS["r"] * COEFFICIENTS["c"] ** 2) - _B)
                    / (2.0 * COEFFICIENTS["r"]))
#: The yield indentations δ_m/δ_y to which the law was calibrated on FE (beyond: extrapolated).
CALIBRATED_INDENTATION_RATIO = 1000.0
#: The largest δ_m/R of the calibration.
CALIBRATED_RADIUS_RATIO = 0.05


def yield_shift(poisson_ratio, a_nu=None):
    """κ(ν) = (1 + a_ν (ν − 0.3))² [-]: the law's yield indentation is κ δ_y and its yield
    force κ^{3/2} F_y (κ = 1 for ν = 0.3).
    """
    a = COEFFICIENTS["a_nu"] if a_nu is None else a_nu
    return (1.0 + a * (np.asarray(poisson_ratio, float) - 0.3)) ** 2


@numba.njit(cache=True)
def _epp_loading(x, q, c, r, gain, c_s):
    """(F/F_y, d(F/F_y)/dx) on the virgin loading curve at x = δ/δ_y > 0 (``gain`` = b_f
    ln(1/(1 − s))).
    """
    root = math.sqrt(x)
    if x <= 1.0:
        return x * root, 1.5 * root
    log_x = math.log(x)
    big_l = min(log_x, LOG_CAP)
    deficit = q * big_l * big_l / (c * c + big_l * big_l) + r * big_l * big_l
    work = q * (big_l - c * math.atan(big_l / c)) + r * big_l ** 3 / 3.0
    f = math.exp(1.5 * big_l - work)                      # F/F_y at min(x, x_c)
    exponent = 1.5 - deficit
    if log_x > big_l:                                      # exponent 1 beyond x_c
        f *= math.exp(exponent * (log_x - big_l))
    cube = c_s ** 3
    h = 1.0 + gain * big_l ** 3 / (cube + big_l ** 3)                  # held beyond x_c too
    dh = gain * 3.0 * log_x ** 2 * cube / (cube + log_x ** 3) ** 2 / x if log_x <= big_l else 0.0
    return f * h, f / x * exponent * h + f * dh


@numba.njit(cache=True)
def _epp_unloading_shape(xm, b, w, v, n_inf, k):
    """(δ_r/δ_m, exponent n) of the unloading curve from x_m = δ_m/δ_y > 1."""
    rho = 1.0 - (1.0 + b * (xm - 1.0) ** w) ** (-v / w)
    n = n_inf + (1.5 - n_inf) * xm ** (-k)
    return rho, n


@numba.njit(cache=True)
def _epp_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    yield_delta, yield_force = params[0], params[1]
    q, c, r, gain, c_s = params[2], params[3], params[4], params[10], params[11]
    x = alpha / yield_delta
    xm = alpha_max / yield_delta
    if alpha >= alpha_max or xm <= 1.0:
        f, df = _epp_loading(x, q, c, r, gain, c_s)
        return yield_force * f, yield_force / yield_delta * df
    fm, _ = _epp_loading(xm, q, c, r, gain, c_s)
    rho, n = _epp_unloading_shape(max(xm * params[12], 1.0), params[5], params[6], params[7],
                                  params[8], params[9])
    xr = rho * xm
    gap = alpha - xr * yield_delta
    if x <= xr or gap <= 0.0:
        return 0.0, 0.0
    force = yield_force * fm * ((x - xr) / (xm - xr)) ** n
    return force, n * force / gap


@register_contact_law
@dataclass(frozen=True)
class EppContact(ReferenceYieldScales, ContactLaw):
    """Elastic sphere on an elastic–perfectly plastic flat, fitted to axisymmetric FE.

    Parameters
    ----------
    effective_modulus : float or array_like
        E* [Pa] (Christoforou & Yigit 1998, eq 8).
    radius : float or array_like
        Effective radius R [m].
    yield_strength : float or array_like
        Yield stress Y of the flat (the softer body) [Pa].

    Notes
    -----
    Forms, coefficients, calibrated range and similarity: docs/epp_calibration.rst.
    """

    effective_modulus: float
    radius: float
    yield_strength: float
    poisson_ratio: float = law_option(
        0.3, "", "Poisson ratio of the yielding flat (calibrated 0.3 to 0.45)")
    sphere_compliance: float = law_option(
        0.0, "", "share of 1/E* from the elastic sphere, E*(1-nu_s^2)/E_s (0 rigid, 0.5 equal)")

    name: ClassVar[str] = "epp"
    elastic: ClassVar[bool] = False
    needs_yield_strength: ClassVar[bool] = True
    kernel = staticmethod(_epp_kernel)

    def __post_init__(self):
        require_positive("effective_modulus", self.effective_modulus, "Pa")
        require_positive("radius", self.radius, "m")
        require_positive("yield_strength", self.yield_strength, "Pa")
        require_in_range("poisson_ratio", self.poisson_ratio, 0.0, 0.5, high_inclusive=False)
        require_in_range("sphere_compliance", self.sphere_compliance, 0.0,
                         LARGEST_SPHERE_COMPLIANCE)

    @classmethod
    def from_contact_pair(cls, pair, **options) -> EppContact:
        """E*, R and Y of the pair; options ``poisson_ratio`` (the flat's ν, default 0.3)
        and ``sphere_compliance`` (E*(1 − ν_s²)/E_s, default 0: a rigid sphere)."""
        cls.check_options(options)
        return cls(pair.effective_modulus, pair.effective_radius, pair.required_yield_strength(),
                   **options)

    # -- scales ---------------------------------------------------------------------
    @property
    def effective_radius(self):
        """R [m] (the contact-patch radius scale)."""
        return np.asarray(self.radius, float)

    @property
    def yield_indentation(self):
        """``δ_y = R (π c_y Y / (2E*))²`` [m], c_y = 1.6."""
        return first_yield_indentation(self.effective_modulus, self.radius, self.yield_strength,
                                       YIELD_PRESSURE_FACTOR)

    @property
    def yield_force(self):
        """``F_y = (4/3) E* R^{1/2} δ_y^{3/2}`` [N]."""
        return first_yield_force(self.effective_modulus, self.radius, self.yield_indentation)

    def impact_number(self, impactor_mass, velocity):
        """β [-] of the Yigit–Christoforou law with the same E*, R and Y (Christoforou & Yigit
        1998, eq 11), for ``impactor_mass`` m_i [kg] at ``velocity`` V0 [m/s].
        """
        return reference_impact_number(self.effective_modulus, self.radius, self.yield_strength, impactor_mass,
                                       velocity)

    # -- ContactLaw interface ---------------------------------------------------------
    @property
    def kernel_parameters(self) -> np.ndarray:
        kappa = yield_shift(self.poisson_ratio)
        delta_y, force_y = np.broadcast_arrays(kappa * self.yield_indentation,
                                               kappa ** 1.5 * self.yield_force)
        co = COEFFICIENTS
        coefficients = [np.full(delta_y.shape, co[k], float) for k in _ORDER[:8]]
        share = np.asarray(self.sphere_compliance, float)
        gain = np.broadcast_to(co["b_f"] * np.log(1.0 / (1.0 - share)), delta_y.shape)
        c_s = np.full(delta_y.shape, co["c_s"], float)
        unload_shift = np.broadcast_to(
            1.0 / (yield_shift(self.poisson_ratio, co["a_r"]) * (1.0 + co["b_s"] * share)),
            delta_y.shape)
        return np.stack([delta_y, force_y] + coefficients + [gain, c_s, unload_shift])

    def _shape(self, max_indentation):
        """(x_m, δ_r/δ_m, n, F_m/F_y') for δ_m [m] in the law's own yield scales
        δ_y' = κ δ_y, F_y' = κ^{3/2} F_y (δ_r = 0, n = 3/2 up to first yield)."""
        params = np.asarray(self.kernel_parameters, float)
        xm = np.clip(np.asarray(max_indentation, float), 0.0, None) / params[0]
        shape = np.broadcast_shapes(xm.shape, params.shape[1:])
        xm = np.broadcast_to(xm, shape)
        pars = np.broadcast_to(params.reshape(params.shape[:1] + (1,) * (len(shape) - params.ndim + 1)
                                              + params.shape[1:]), (params.shape[0],) + shape)
        rho, n, fm = np.zeros(shape), np.full(shape, 1.5), np.zeros(shape)
        for i in np.ndindex(shape):
            pv = pars[(slice(None),) + i]
            fm[i] = _epp_loading(xm[i], pv[2], pv[3], pv[4], pv[10], pv[11])[0] if xm[i] > 0 else 0.0
            if xm[i] > 1.0:
                rho[i], n[i] = _epp_unloading_shape(max(xm[i] * pv[12], 1.0), pv[5], pv[6], pv[7],
                                                    pv[8], pv[9])
        return xm, rho, n, fm

    def calibration_note(self, max_indentation) -> str | None:
        """Why a run reaching ``max_indentation`` [m] lies beyond the FE calibration
        (δ_m/δ_y > 1000 or δ_m/R > 0.05), or ``None`` inside it. A single law only."""
        depth = float(max_indentation)
        ratio = depth / float(yield_shift(self.poisson_ratio) * self.yield_indentation)
        relative = depth / float(self.radius)
        beyond = []
        if ratio > CALIBRATED_INDENTATION_RATIO:
            beyond.append(f"{ratio:.4g} yield indentations (calibrated to {CALIBRATED_INDENTATION_RATIO:g}"
                          + ("; beyond 1518.5 the mean pressure is held at its fully plastic plateau"
                             if ratio > math.exp(LOG_CAP) else "") + ")")
        if relative > CALIBRATED_RADIUS_RATIO:
            beyond.append(f"{relative:.3g} R (calibrated to {CALIBRATED_RADIUS_RATIO:g} R)")
        if not beyond:
            return None
        return ("epp range: the largest indentation reaches " + " and ".join(beyond)
                + ": the law extrapolates its FE calibration (docs/epp_calibration.rst)")

    def permanent_indentation(self, max_indentation):
        """``δ_r = δ_m ρ∞ (1 − x_m^{−s})^t`` [m] (0 up to first yield)."""
        _xm, rho, _n, _f = self._shape(max_indentation)
        return rho * np.clip(np.asarray(max_indentation, float), 0.0, None)

    def recovered_energy(self, max_indentation, points: int = 0):
        """Work [J] returned unloading from δ_m (closed form ``F_m (δ_m − δ_r)/(n + 1)``)."""
        xm, rho, n, fm = self._shape(max_indentation)
        scale = yield_shift(self.poisson_ratio) ** 2.5 * self.yield_force * self.yield_indentation
        return scale * fm * xm * (1.0 - rho) / (n + 1.0)
