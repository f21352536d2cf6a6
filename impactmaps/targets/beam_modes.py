"""Natural modes and static point compliance of straight beams (PHYSICS.md 3.2).

The beam occupies ``0 ≤ x ≤ L``. Its section is described by five numbers, so that
isotropic and specially orthotropic beams share one code path:

``bending_stiffness`` bD11 (= EI) [N·m²], ``shear_stiffness`` S = k b A55 (= kGA) [N],
``mass_per_length`` ρA [kg/m], ``rotary_inertia`` ρI [kg·m].

Equations of motion (seed 001 (16)–(17)), ψ the section rotation, ``ψ + w'`` the shear
strain, bending moment ``M = bD11 ψ'``, shear force ``Q = S (ψ + w')``::

    bD11 ψ'' − S (ψ + w') = ρI ψ̈,        S (ψ' + w'') + p = ρA ẅ.

Theories: ``"euler"`` (S → ∞, ρI → 0, so ψ = −w'), ``"rayleigh"`` (S → ∞, ρI kept),
``"timoshenko"`` (both). Supports, end x = 0 first: ``"ss"``, ``"cc"``, ``"cs"``,
``"cf"`` (cantilever, free at x = L), ``"ff"``. Clamped: w = ψ = 0; simply supported:
w = 0, M = 0; free: M = 0, Q = 0.

Modes are mass-normalised, ``∫ (ρA W_i W_j + ρI Ψ_i Ψ_j) dx = δ_ij`` (ρI = 0 for Euler).
Three families of mode sets are produced here, each as an object with ascending
``frequencies`` [rad/s] and methods ``deflection(points, count)`` (W_j) and
``rotation(points, count)`` (Ψ_j):

* :func:`simply_supported_modes` — closed form, every theory, fully vectorised;
* :func:`classical_euler_modes` — Euler beams with any support: roots of the classical
  frequency equations (Blevins 1979, Table 8-1) by bisection on overflow-free forms, and
  mode shapes in the bounded basis ``cos βx, sin βx, e^{−βx}, e^{−β(L−x)}`` (accurate for
  any mode number);
* :func:`finite_element_modes` — Rayleigh and Timoshenko beams with supports other than
  SS: a hierarchical p-version finite-element model (see that function for method and
  accuracy), solved once per beam section and cached.

:func:`static_compliance` gives the exact point compliance for every support and theory.
"""

from __future__ import annotations

import math
import warnings
from collections import OrderedDict
from dataclasses import dataclass
from functools import lru_cache

import numba
import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg
from numpy.polynomial import legendre

__all__ = [
    "SUPPORTS",
    "THEORIES",
    "BeamSection",
    "ModeSet",
    "largest_wavenumber",
    "euler_roots",
    "simply_supported_modes",
    "classical_euler_modes",
    "finite_element_modes",
    "static_compliance",
    "FE_DEGREE",
    "FE_RESOLUTION",
    "FE_MAX_DOFS",
]

#: Support codes, end x = 0 first: s = simply supported, c = clamped, f = free.
SUPPORTS = ("ss", "cc", "cs", "cf", "ff")
#: Beam theories.
THEORIES = ("euler", "rayleigh", "timoshenko")

#: Polynomial degree of the deflection field in the finite-element model.
FE_DEGREE = 24
#: Largest (wavenumber × element length / degree) kept by the finite-element model.
#: Calibrated against the SS Rayleigh/Timoshenko closed forms (L/h = 5 to 300): with
#: degree 24 at 1.0 every kept eigenvalue is within 3e-10 (relative) of the exact value.
FE_RESOLUTION = 1.0
#: Cap on the finite-element unknowns (dense eigen-solution, O(n³) time, O(n²) memory).
FE_MAX_DOFS = 12000


# ---------------------------------------------------------------------------------
# Section description and dispersion
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class BeamSection:
    """The mechanical description of a uniform beam used by the mode solvers.

    Attributes
    ----------
    length : float
        L [m].
    bending_stiffness : float
        bD11 = EI [N·m²].
    shear_stiffness : float
        S = k b A55 = kGA [N]; ``math.inf`` unless ``theory == "timoshenko"``.
    mass_per_length : float
        ρA [kg/m].
    rotary_inertia : float
        ρI [kg·m]; 0 when ``theory == "euler"``.
    theory : str
        One of :data:`THEORIES`.
    supports : str
        One of :data:`SUPPORTS`.

    Build it with :meth:`effective`, which applies the theory (drops S and/or ρI).
    """

    length: float
    bending_stiffness: float
    shear_stiffness: float
    mass_per_length: float
    rotary_inertia: float
    theory: str
    supports: str

    @classmethod
    def effective(cls, length, bending_stiffness, shear_stiffness, mass_per_length,
                  rotary_inertia, theory, supports) -> "BeamSection":
        """The section as seen by ``theory``: S = ∞ unless Timoshenko, ρI = 0 for Euler."""
        return cls(
            float(length),
            float(bending_stiffness),
            float(shear_stiffness) if theory == "timoshenko" else math.inf,
            float(mass_per_length),
            float(rotary_inertia) if theory != "euler" else 0.0,
            theory,
            supports,
        )

    @property
    def shear_compliance(self) -> float:
        """1/S [1/N] (0 for Euler and Rayleigh)."""
        return 0.0 if math.isinf(self.shear_stiffness) else 1.0 / self.shear_stiffness


def largest_wavenumber(section: BeamSection, angular_frequency):
    """Largest real wavenumber k [rad/m] of free waves at ω (flexural branch) [rad/s].

    Every branch ω(k) of the dispersion relation increases with k, so all modes with
    ω_j ≤ ω have (asymptotic) wavenumbers ≤ this value. Euler: ``k⁴ = ω² ρA/EI``;
    Rayleigh: ``EI k⁴ − ρI ω² k² − ρA ω² = 0``; Timoshenko:
    ``EI S k⁴ − ω²(ρI S + ρA EI) k² + ρA ω²(ρI ω² − S) = 0`` (largest root in k²).
    """
    omega2 = np.asarray(angular_frequency, dtype=float) ** 2
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    if section.theory == "euler":
        return (omega2 * rA / EI) ** 0.25
    if section.theory == "rayleigh":
        k2 = (rI * omega2 + np.sqrt((rI * omega2) ** 2 + 4.0 * EI * rA * omega2)) / (2.0 * EI)
        return np.sqrt(k2)
    S = section.shear_stiffness
    # discriminant written without cancellation: ω⁴(ρI S − ρA EI)² + 4 EI S² ρA ω²
    root = np.sqrt(omega2**2 * (rI * S - rA * EI) ** 2 + 4.0 * EI * S**2 * rA * omega2)
    k2 = (omega2 * (rI * S + rA * EI) + root) / (2.0 * EI * S)
    return np.sqrt(k2)


class ModeSet:
    """Mass-normalised modes of a beam, ascending in frequency.

    Attributes
    ----------
    frequencies : ndarray, shape (n,)
        ω_j [rad/s], ascending (rigid-body modes first, ω = 0).

    Methods ``deflection(points, count=None)`` and ``rotation(points, count=None)``
    return W_j(x) [kg^-1/2] and Ψ_j(x) [kg^-1/2 m^-1] of the first ``count`` modes,
    shape (n_points, count).
    """

    frequencies: np.ndarray

    def __len__(self) -> int:
        return int(self.frequencies.size)

    def _count(self, count):
        return self.frequencies.size if count is None else int(count)

    def deflection(self, points, count=None) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def rotation(self, points, count=None) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError


def _points(points) -> np.ndarray:
    return np.atleast_1d(np.asarray(points, dtype=float)).ravel()


# ---------------------------------------------------------------------------------
# Simply supported: closed form
# ---------------------------------------------------------------------------------
class _SineModes(ModeSet):
    """W_j(x) = A_j sin(k_j x), Ψ_j(x) = B_j cos(k_j x)."""

    def __init__(self, frequencies, wavenumbers, deflection_amplitudes, rotation_amplitudes):
        order = np.argsort(frequencies, kind="stable")
        self.frequencies = np.asarray(frequencies, dtype=float)[order]
        self.wavenumbers = np.asarray(wavenumbers, dtype=float)[order]
        self.deflection_amplitudes = np.asarray(deflection_amplitudes, dtype=float)[order]
        self.rotation_amplitudes = np.asarray(rotation_amplitudes, dtype=float)[order]

    def deflection(self, points, count=None):
        n = self._count(count)
        x = _points(points)[:, None]
        return self.deflection_amplitudes[:n] * np.sin(self.wavenumbers[:n] * x)

    def rotation(self, points, count=None):
        n = self._count(count)
        x = _points(points)[:, None]
        return self.rotation_amplitudes[:n] * np.cos(self.wavenumbers[:n] * x)


def simply_supported_modes(section: BeamSection, max_frequency: float,
                           min_modes: int = 1) -> ModeSet:
    """All modes of a simply supported beam with ω ≤ ``max_frequency`` (≥ ``min_modes``).

    ``w = W sin(k_n x)``, ``ψ = Ψ cos(k_n x)``, ``k_n = nπ/L`` (PHYSICS.md 3.2).

    * Euler: ``ω_n = k_n² sqrt(EI/ρA)``, ``W = sqrt(2/(ρA L))``, ``Ψ = −k_n W``.
    * Rayleigh: ``ω_n² = EI k_n⁴/(ρA + ρI k_n²)``, ``Ψ = −k_n W``,
      ``(ρA + ρI k_n²) W² L/2 = 1``.
    * Timoshenko: per n the 2×2 problem ``(K_n − ω² M_n)[Ψ, W] = 0`` solved in closed
      form in the symmetric form ``M_n^{-1/2} K_n M_n^{-1/2}`` (rotation by the angle θ,
      ``tan 2θ = 2 a12/(a11 − a22)``), the lower eigenvalue from the determinant
      ``EI S k⁴/(ρI ρA)`` divided by the upper one (no cancellation for slender beams).
      Both branches (flexural and shear) are returned, plus the n = 0 thickness-shear
      mode ``w ≡ 0``, ``ψ = const``, ``ω² = S/ρI`` (it satisfies w = 0 and M = 0 at both
      ends; its deflection is zero everywhere, so it never takes part in an impact).

    The number of half-waves is fixed from :func:`largest_wavenumber` — no Python loop
    over modes.
    """
    L = section.length
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    k_max = float(largest_wavenumber(section, max_frequency))
    n_count = max(int(math.floor(k_max * L / math.pi * (1.0 + 1e-12))), int(min_modes), 1)
    n = np.arange(1, n_count + 1, dtype=float)
    k = n * math.pi / L
    if section.theory in ("euler", "rayleigh"):
        inertia = rA + rI * k**2
        omega = np.sqrt(EI / inertia) * k**2
        W = np.sqrt(2.0 / (L * inertia))
        modes = _SineModes(omega, k, W, -k * W)
    else:
        S = section.shear_stiffness
        a11 = (EI * k**2 + S) / rI
        a22 = S * k**2 / rA
        a12 = S * k / math.sqrt(rI * rA)
        half_difference = 0.5 * (a11 - a22)
        radius = np.hypot(half_difference, a12)
        upper = 0.5 * (a11 + a22) + radius
        lower = (EI * S * k**4 / (rI * rA)) / upper
        theta = 0.5 * np.arctan2(a12, half_difference)
        c, s = np.cos(theta), np.sin(theta)
        scale = math.sqrt(2.0 / L)
        # upper (shear) branch: v = (cos θ, sin θ); lower (flexural): v = (−sin θ, cos θ)
        frequencies = np.concatenate([np.sqrt(lower), np.sqrt(upper), [math.sqrt(S / rI)]])
        wavenumbers = np.concatenate([k, k, [0.0]])
        W = np.concatenate([c, s, [0.0]]) * scale / math.sqrt(rA)
        Psi = np.concatenate([-s, c, [math.sqrt(0.5)]]) * scale / math.sqrt(rI)
        modes = _SineModes(frequencies, wavenumbers, W, Psi)
    return _trim(modes, max_frequency, min_modes)


def _cutoff(frequencies, max_frequency, min_modes) -> float:
    """max(max_frequency, ω of the min_modes-th mode) for ascending ``frequencies``."""
    cutoff = float(max_frequency)
    if int(min_modes) >= 1 and len(frequencies):
        cutoff = max(cutoff, float(frequencies[min(int(min_modes), len(frequencies)) - 1]))
    return cutoff


def _trim(modes: _SineModes, max_frequency, min_modes) -> _SineModes:
    """Keep the modes with ω ≤ max(max_frequency, ω of the min_modes-th mode)."""
    cutoff = _cutoff(modes.frequencies, max_frequency, min_modes)
    keep = int(np.searchsorted(modes.frequencies, cutoff, side="right"))
    return _SineModes(modes.frequencies[:keep], modes.wavenumbers[:keep],
                      modes.deflection_amplitudes[:keep], modes.rotation_amplitudes[:keep])


# ---------------------------------------------------------------------------------
# Euler beams, any support: classical frequency equations
# ---------------------------------------------------------------------------------
def _sech(x):
    e = np.exp(-x)
    return 2.0 * e / (1.0 + e * e)


def _tanh(x):
    e = np.exp(-2.0 * x)
    return (1.0 - e) / (1.0 + e)


def _bisect(function, low, high, iterations: int = 80):
    """Vectorised bisection; ``function`` must change sign on each [low, high]."""
    low = np.array(low, dtype=float)
    high = np.array(high, dtype=float)
    f_low = function(low)
    for _ in range(iterations):
        middle = 0.5 * (low + high)
        f_middle = function(middle)
        same = np.sign(f_middle) == np.sign(f_low)
        low = np.where(same, middle, low)
        f_low = np.where(same, f_middle, f_low)
        high = np.where(same, high, middle)
    return 0.5 * (low + high)


def euler_roots(supports: str, count: int) -> np.ndarray:
    """First ``count`` roots βL of the Euler frequency equation (elastic modes).

    Frequency equations (Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979,
    Table 8-1), written overflow-free by dividing by cosh βL:

    * ss: ``sin βL = 0`` → βL = nπ;
    * cc and ff (elastic modes): ``cos βL cosh βL = 1`` → ``cos x − sech x = 0``,
      one root in each (nπ, (n+1)π), n ≥ 1;
    * cf: ``cos βL cosh βL = −1`` → ``cos x + sech x = 0``, one root in ((n−1)π, nπ);
    * cs: ``tan βL = tanh βL`` → ``sin x − cos x tanh x = 0``, one root in
      (nπ, (n+½)π).

    Each root is found by 80 bisection steps (to the last bit), so high modes (βL
    approaching (2n+1)π/2 or (4n+1)π/4 to within e^{−βL}) are exact too.
    """
    n = np.arange(1, int(count) + 1, dtype=float)
    if count <= 0:
        return np.zeros(0)
    if supports == "ss":
        return n * math.pi
    if supports in ("cc", "ff"):
        return _bisect(lambda x: np.cos(x) - _sech(x), n * math.pi, (n + 1) * math.pi)
    if supports == "cf":
        return _bisect(lambda x: np.cos(x) + _sech(x), (n - 1) * math.pi, n * math.pi)
    if supports == "cs":
        return _bisect(lambda x: np.sin(x) - np.cos(x) * _tanh(x),
                       n * math.pi, (n + 0.5) * math.pi)
    raise ValueError(f"supports = {supports!r} is not known")


# scaled derivatives f^(k)(x)/β^k of cos βx, sin βx, e^{−βx}, e^{−β(L−x)}
def _end_rows(end: str, cos_value, sin_value, e_left, e_right):
    """Rows of the boundary-condition matrix for one end; shape (N, 2, 4)."""
    c, s = cos_value, sin_value
    derivatives = [  # order k = 0..3, each an array (N, 4)
        np.stack([c, s, e_left, e_right], axis=-1),
        np.stack([-s, c, -e_left, e_right], axis=-1),
        np.stack([-c, -s, e_left, e_right], axis=-1),
        np.stack([s, -c, -e_left, e_right], axis=-1),
    ]
    orders = {"c": (0, 1), "s": (0, 2), "f": (2, 3)}[end]
    return np.stack([derivatives[k] for k in orders], axis=1)


def _gram(beta, L):
    """Gram matrix ∫0^L f_a f_b dx of (cos βx, sin βx, e^{−βx}, e^{−β(L−x)}); (N, 4, 4)."""
    b = np.asarray(beta, dtype=float)
    bl = b * L
    c, s = np.cos(bl), np.sin(bl)
    e = np.exp(-bl)
    g = np.empty(b.shape + (4, 4))
    g[..., 0, 0] = L / 2 + np.sin(2 * bl) / (4 * b)
    g[..., 1, 1] = L / 2 - np.sin(2 * bl) / (4 * b)
    g[..., 0, 1] = s**2 / (2 * b)
    g[..., 2, 2] = -np.expm1(-2 * bl) / (2 * b)
    g[..., 3, 3] = g[..., 2, 2]
    g[..., 2, 3] = L * e
    cos_left = (1.0 + e * (s - c)) / (2 * b)  # ∫ cos βx e^{−βx}
    sin_left = (1.0 - e * (s + c)) / (2 * b)  # ∫ sin βx e^{−βx}
    g[..., 0, 2] = cos_left
    g[..., 1, 2] = sin_left
    g[..., 0, 3] = c * cos_left + s * sin_left  # ∫ cos βx e^{−β(L−x)}
    g[..., 1, 3] = s * cos_left - c * sin_left  # ∫ sin βx e^{−β(L−x)}
    for i in range(4):
        for j in range(i):
            g[..., i, j] = g[..., j, i]
    return g


class _EulerModes(ModeSet):
    """Rigid-body modes (W = a + b (x − L/2)) followed by elastic modes
    W = c0 cos βx + c1 sin βx + c2 e^{−βx} + c3 e^{−β(L−x)}, Ψ = −W'."""

    def __init__(self, length, rigid_coefficients, betas, coefficients, frequencies):
        self.length = float(length)
        self.rigid_coefficients = np.asarray(rigid_coefficients, dtype=float).reshape(-1, 2)
        self.betas = np.asarray(betas, dtype=float)
        self.coefficients = np.asarray(coefficients, dtype=float).reshape(-1, 4)
        self.frequencies = np.asarray(frequencies, dtype=float)

    def _split(self, count):
        n = self._count(count)
        rigid = min(n, self.rigid_coefficients.shape[0])
        return rigid, n - rigid

    def deflection(self, points, count=None):
        rigid, elastic = self._split(count)
        x = _points(points)[:, None]
        r = self.rigid_coefficients[:rigid]
        rigid_part = r[:, 0] + r[:, 1] * (x - 0.5 * self.length)
        b = self.betas[:elastic]
        c = self.coefficients[:elastic]
        bx = b * x
        elastic_part = (c[:, 0] * np.cos(bx) + c[:, 1] * np.sin(bx)
                        + c[:, 2] * np.exp(-bx) + c[:, 3] * np.exp(-b * (self.length - x)))
        return np.concatenate([rigid_part, elastic_part], axis=1)

    def rotation(self, points, count=None):
        rigid, elastic = self._split(count)
        x = _points(points)[:, None]
        r = self.rigid_coefficients[:rigid]
        rigid_part = np.broadcast_to(-r[:, 1], (x.shape[0], rigid))
        b = self.betas[:elastic]
        c = self.coefficients[:elastic]
        bx = b * x
        slope = b * (-c[:, 0] * np.sin(bx) + c[:, 1] * np.cos(bx)
                     - c[:, 2] * np.exp(-bx) + c[:, 3] * np.exp(-b * (self.length - x)))
        return np.concatenate([rigid_part, -slope], axis=1)


def classical_euler_modes(section: BeamSection, max_frequency: float,
                          min_modes: int = 1) -> ModeSet:
    """All Euler-beam modes with ω ≤ ``max_frequency`` (at least ``min_modes``).

    ``ω_n = (β_n L)² sqrt(EI/(ρA L⁴))`` with β_n L from :func:`euler_roots`. The mode
    shape is the null vector (SVD) of the 4×4 boundary-condition matrix in the basis
    ``cos βx, sin βx, e^{−βx}, e^{−β(L−x)}``, whose entries are all O(1) for any β, so the
    shapes stay accurate to round-off for any mode number (the textbook form
    ``cosh βx − σ sinh βx`` loses all digits beyond n ≈ 12). Mass normalisation uses the
    exact Gram integrals of that basis. Free–free beams also get the two rigid-body modes
    (ω = 0): translation ``W = 1/sqrt(ρA L)`` and rotation
    ``W = sqrt(12/(ρA L³)) (x − L/2)``.
    """
    if section.theory != "euler":
        raise ValueError("classical_euler_modes needs theory = 'euler'")
    L, EI, rA = section.length, section.bending_stiffness, section.mass_per_length
    scale = math.sqrt(EI / (rA * L**4))
    beta_max_L = float(largest_wavenumber(section, max_frequency)) * L
    rigid = 2 if section.supports == "ff" else 0
    count = max(int(beta_max_L / math.pi) + 2, int(min_modes) - rigid, 1)
    roots = euler_roots(section.supports, count)
    frequencies = roots**2 * scale
    cutoff = _cutoff(np.concatenate([np.zeros(rigid), frequencies]), max_frequency, min_modes)
    keep = int(np.searchsorted(frequencies, cutoff, side="right"))
    roots, frequencies = roots[:keep], frequencies[:keep]
    beta = roots / L
    cos_l, sin_l, exp_l = np.cos(roots), np.sin(roots), np.exp(-roots)
    ones, zeros = np.ones_like(roots), np.zeros_like(roots)
    left, right = section.supports[0], section.supports[1]
    rows = np.concatenate([
        _end_rows(left, ones, zeros, ones, exp_l),
        _end_rows(right, cos_l, sin_l, exp_l, ones),
    ], axis=1)
    _, _, vt = np.linalg.svd(rows)
    coefficients = vt[:, -1, :]
    # sign convention: the largest coefficient is positive
    largest = np.take_along_axis(coefficients, np.argmax(np.abs(coefficients), axis=1)[:, None], 1)
    coefficients = coefficients * np.sign(largest)
    norm2 = rA * np.einsum("ni,nij,nj->n", coefficients, _gram(beta, L), coefficients)
    coefficients = coefficients / np.sqrt(norm2)[:, None]
    rigid_coefficients = np.zeros((rigid, 2))
    if rigid:
        rigid_coefficients[0, 0] = 1.0 / math.sqrt(rA * L)
        rigid_coefficients[1, 1] = math.sqrt(12.0 / (rA * L**3))
    return _EulerModes(L, rigid_coefficients, beta, coefficients,
                       np.concatenate([np.zeros(rigid), frequencies]))


# ---------------------------------------------------------------------------------
# Rayleigh and Timoshenko beams, any support: p-version finite elements
# ---------------------------------------------------------------------------------
@lru_cache(maxsize=8)
def _c0_basis(degree: int) -> np.ndarray:
    """Legendre coefficients (rows) of the hierarchical C0 basis of ``degree`` on [−1, 1].

    Order: (1 − ξ)/2, (1 + ξ)/2, then the integrated Legendre bubbles
    ``(P_j − P_{j−2})/sqrt(2(2j − 1))``, j = 2..degree (zero at both ends).
    """
    rows = np.zeros((degree + 1, degree + 1))
    rows[0, :2] = [0.5, -0.5]
    rows[1, :2] = [0.5, 0.5]
    for j in range(2, degree + 1):
        rows[j, j] = 1.0 / math.sqrt(2.0 * (2 * j - 1))
        rows[j, j - 2] = -rows[j, j]
    return rows


@lru_cache(maxsize=8)
def _c1_basis(degree: int) -> np.ndarray:
    """Legendre coefficients (rows) of the hierarchical C1 basis of ``degree`` on [−1, 1].

    Order: the Hermite cubics for w(−1), w'(−1), w(1), w'(1) (derivatives in ξ), then the
    bubbles ``B_m`` with ``B_m'' = sqrt((2m+1)/2) P_m`` and zero value and slope at both
    ends, m = 2..degree−2.
    """
    hermite = [
        [0.5, -0.75, 0.0, 0.25],
        [0.25, -0.25, -0.25, 0.25],
        [0.5, 0.75, 0.0, -0.25],
        [-0.25, -0.25, 0.25, 0.25],
    ]
    rows = np.zeros((degree + 1, degree + 1))
    for i, power in enumerate(hermite):
        coefficients = legendre.poly2leg(power)
        rows[i, : coefficients.size] = coefficients
    for m in range(2, degree - 1):
        unit = np.zeros(m + 1)
        unit[m] = math.sqrt((2 * m + 1) / 2.0)
        coefficients = legendre.legint(unit, m=2, lbnd=-1.0)
        rows[2 + m, : coefficients.size] = coefficients
    return rows


def _evaluate(rows: np.ndarray, xi, derivative: int = 0) -> np.ndarray:
    """Basis values (n_basis, n_xi) from Legendre coefficient rows."""
    coefficients = rows.T
    if derivative:
        coefficients = legendre.legder(coefficients, m=derivative, axis=0)
    return legendre.legval(np.asarray(xi, dtype=float), coefficients).reshape(rows.shape[0], -1)


class _FiniteElementModes(ModeSet):
    """Modes stored as finite-element coefficient vectors on a uniform mesh."""

    def __init__(self, section, elements, degree, connectivity, vectors, frequencies,
                 resolved_frequency):
        self.section = section
        self.elements = int(elements)
        self.degree = int(degree)
        self.connectivity = connectivity
        self.vectors = vectors  # (n_dof_all, n_modes), constrained unknowns are zero
        self.frequencies = frequencies
        #: every mode up to this frequency [rad/s] is present and resolved
        self.resolved_frequency = float(resolved_frequency)

    def _locate(self, points):
        x = _points(points)
        h = self.section.length / self.elements
        element = np.clip(np.floor(x / h).astype(int), 0, self.elements - 1)
        xi = 2.0 * (x - element * h) / h - 1.0
        return element, np.clip(xi, -1.0, 1.0), h

    def _field(self, points, count, which):
        n = self._count(count)
        element, xi, h = self._locate(points)
        out = np.empty((xi.size, n))
        timoshenko = self.section.theory == "timoshenko"
        p = self.degree
        if timoshenko:
            if which == "w":
                values = _evaluate(_c0_basis(p), xi)
                local = slice(0, p + 1)
            else:
                values = _evaluate(_c0_basis(p - 1), xi)
                local = slice(p + 1, 2 * p + 1)
            sign = 1.0
        else:
            rows = _c1_basis(p)
            if which == "w":
                values = _evaluate(rows, xi)
                sign = 1.0
            else:  # Ψ = −w' = −(2/h) dw/dξ
                values = _evaluate(rows, xi, 1) * (2.0 / h)
                sign = -1.0
            values = values * _c1_slope_scale(p, h)[:, None]
            local = slice(0, p + 1)
        for e in np.unique(element):
            here = element == e
            dofs = self.connectivity[e, local]
            out[here] = sign * values[:, here].T @ self.vectors[dofs, :n]
        return out

    def deflection(self, points, count=None):
        return self._field(points, count, "w")

    def rotation(self, points, count=None):
        return self._field(points, count, "psi")


def _c1_slope_scale(degree, h):
    """Physical slope unknowns: the ξ-slope Hermite functions are multiplied by h/2."""
    scale = np.ones(degree + 1)
    scale[1] = scale[3] = 0.5 * h
    return scale


def _bubbles_per_element(theory: str, degree: int) -> int:
    return 2 * degree - 3 if theory == "timoshenko" else degree - 3


def _layout(theory: str, elements: int, degree: int):
    """Banded numbering: node e (2 unknowns), bubbles of element e, node e + 1, …

    Returns the element connectivity (local order as in :func:`_assemble`), the global
    numbers of the two nodal unknowns of every node (w and ψ, or w and w' for C1),
    the number of unknowns and the half-bandwidth.
    """
    bubbles = _bubbles_per_element(theory, degree)
    stride = 2 + bubbles
    e = np.arange(elements)
    base = e * stride
    node_dofs = np.arange(elements + 1)[:, None] * stride + np.arange(2)
    if theory == "timoshenko":
        bubbles_w = degree - 1
        connectivity = np.empty((elements, 2 * degree + 1), dtype=int)
        connectivity[:, 0], connectivity[:, 1] = base, base + stride
        connectivity[:, 2:degree + 1] = base[:, None] + 2 + np.arange(bubbles_w)
        connectivity[:, degree + 1], connectivity[:, degree + 2] = base + 1, base + stride + 1
        connectivity[:, degree + 3:] = base[:, None] + 2 + bubbles_w + np.arange(bubbles - bubbles_w)
    else:
        connectivity = np.empty((elements, degree + 1), dtype=int)
        connectivity[:, 0], connectivity[:, 1] = base, base + 1
        connectivity[:, 2], connectivity[:, 3] = base + stride, base + stride + 1
        connectivity[:, 4:] = base[:, None] + 2 + np.arange(bubbles)
    total = 2 * (elements + 1) + elements * bubbles
    return connectivity, node_dofs, total, bubbles + 3


def _element_matrices(section: BeamSection, h: float, degree: int):
    """Element stiffness and mass matrices [SI] in the local order of :func:`_layout`."""
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    jac = 0.5 * h
    xi, weights = legendre.leggauss(degree + 2)
    if section.theory == "timoshenko":
        S = section.shear_stiffness
        rows_w, rows_p = _c0_basis(degree), _c0_basis(degree - 1)
        Nw, dNw = _evaluate(rows_w, xi), _evaluate(rows_w, xi, 1) / jac
        Np, dNp = _evaluate(rows_p, xi), _evaluate(rows_p, xi, 1) / jac
        zw, zp = np.zeros_like(Nw), np.zeros_like(Np)
        shear = np.concatenate([dNw, Np])  # ψ + w'
        bending = np.concatenate([zw, dNp])  # ψ'
        deflection = np.concatenate([Nw, zp])
        rotation = np.concatenate([zw, Np])
        Ke = (EI * (bending * weights) @ bending.T + S * (shear * weights) @ shear.T) * jac
        Me = (rA * (deflection * weights) @ deflection.T
              + rI * (rotation * weights) @ rotation.T) * jac
    else:
        rows = _c1_basis(degree)
        scale = _c1_slope_scale(degree, h)[:, None]
        N = _evaluate(rows, xi) * scale
        dN = _evaluate(rows, xi, 1) * scale / jac
        ddN = _evaluate(rows, xi, 2) * scale / jac**2
        Ke = EI * (ddN * weights) @ ddN.T * jac
        Me = (rA * (N * weights) @ N.T + rI * (dN * weights) @ dN.T) * jac
    return Ke, Me


def _assemble(section: BeamSection, elements: int, degree: int):
    """Sparse global K, M [SI] (banded numbering), connectivity, free unknowns, nodes."""
    connectivity, node_dofs, total, bandwidth = _layout(section.theory, elements, degree)
    Ke, Me = _element_matrices(section, section.length / elements, degree)
    local = connectivity.shape[1]
    rows = np.repeat(connectivity, local, axis=1).ravel()
    cols = np.tile(connectivity, (1, local)).ravel()
    K = scipy.sparse.coo_matrix((np.tile(Ke.ravel(), elements), (rows, cols)),
                                shape=(total, total)).tocsc()
    M = scipy.sparse.coo_matrix((np.tile(Me.ravel(), elements), (rows, cols)),
                                shape=(total, total)).tocsc()
    fixed = []
    for end, node in ((section.supports[0], 0), (section.supports[1], elements)):
        if end in "cs":
            fixed.append(node_dofs[node, 0])  # w = 0
        if end == "c":
            fixed.append(node_dofs[node, 1])  # ψ = 0 (Timoshenko) or w' = 0 (C1)
    free = np.setdiff1d(np.arange(total), fixed)
    return K, M, connectivity, free, node_dofs, bandwidth


def _rigid_vectors(section: BeamSection, elements: int, total: int, node_dofs) -> np.ndarray:
    """FE coefficient vectors of translation (w = 1) and rotation (w = x − L/2, ψ = −1)."""
    L = section.length
    x = np.linspace(0.0, L, elements + 1)
    vectors = np.zeros((total, 2))
    vectors[node_dofs[:, 0], 0] = 1.0
    vectors[node_dofs[:, 0], 1] = x - 0.5 * L
    # ψ = −1 (Timoshenko) or w' = +1 (C1 slope unknowns)
    vectors[node_dofs[:, 1], 1] = -1.0 if section.theory == "timoshenko" else 1.0
    return vectors


@numba.njit(cache=True)
def _count_below(stiffness_band, mass_band, shift):  # pragma: no cover - numba
    """Number of eigenvalues of ``K x = λ M x`` below ``shift`` (Sylvester's inertia).

    LDLᵀ factorisation without pivoting of the banded ``K − shift·M`` (lower band
    storage, ``band[d, j] = A[j + d, j]``); the count is the number of negative pivots
    (Sturm-sequence property, as used by Wittrick–Williams and subspace-iteration codes).
    """
    width = stiffness_band.shape[0] - 1
    n = stiffness_band.shape[1]
    lower = np.zeros((width + 1, n))
    pivots = np.zeros(n)
    negatives = 0
    tiny = 1e-300
    for j in range(n):
        value = stiffness_band[0, j] - shift * mass_band[0, j]
        for k in range(max(0, j - width), j):
            value -= lower[j - k, k] ** 2 * pivots[k]
        if value == 0.0:
            value = tiny
        pivots[j] = value
        if value < 0.0:
            negatives += 1
        for i in range(j + 1, min(n, j + width + 1)):
            entry = stiffness_band[i - j, j] - shift * mass_band[i - j, j]
            for k in range(max(0, i - width), j):
                entry -= lower[i - k, k] * lower[j - k, k] * pivots[k]
            lower[i - j, j] = entry / value
    return negatives


def _lower_band(matrix, width: int) -> np.ndarray:
    n = matrix.shape[0]
    band = np.zeros((width + 1, n))
    for d in range(width + 1):
        band[d, : n - d] = matrix.diagonal(-d)
    return band


#: FE models with at most this many unknowns are solved densely, larger ones by
#: spectrum slicing (shift-invert Lanczos with Sturm-sequence checks).
_DENSE_LIMIT = 1500
#: Target number of eigenvalues per spectrum slice.
_SLICE_SIZE = 48


def _solve_dense(K, M, upper, shift):
    """All eigenpairs with λ < ``upper`` in flexibility form (relative accuracy kept)."""
    Kd, Md = K.toarray(), M.toarray()
    factor = scipy.linalg.cholesky(Kd + shift * Md, lower=True)
    half = scipy.linalg.solve_triangular(factor, Md, lower=True)
    flexibility = scipy.linalg.solve_triangular(factor, half.T, lower=True)
    flexibility = 0.5 * (flexibility + flexibility.T)
    lowest = 1.0 / (upper + shift)
    mu, y = scipy.linalg.eigh(flexibility, subset_by_value=(lowest, np.inf), driver="evr")
    mu, y = mu[::-1], y[:, ::-1]
    vectors = scipy.linalg.solve_triangular(factor, y, lower=True, trans="T") / np.sqrt(mu)
    return 1.0 / mu - shift, vectors


def _solve_sliced(K, M, upper, start, width):
    """All eigenpairs with ``start`` < λ < ``upper`` by spectrum slicing.

    The interval is cut into slices of about :data:`_SLICE_SIZE` eigenvalues using
    Sylvester inertia counts; each slice is solved by shift-invert Lanczos (ARPACK,
    ``tol = 0``) at its centre; slice boundaries are moved into the gap between computed
    eigenvalues and the count of every slice is checked against the inertia, so no
    eigenvalue is missed or repeated (a failed check retries the slice with more vectors).
    """
    kband, mband = _lower_band(K, width), _lower_band(M, width)
    n = K.shape[0]

    def below(value):
        return _count_below(kband, mband, value)

    low = start
    below_low = below(low)
    remaining = below(upper) - below_low
    span = (upper - start) * min(1.0, _SLICE_SIZE / max(remaining, 1))
    values, vectors = [], []
    while remaining > 0:
        high = min(upper, low + span)
        count = below(high) - below_low
        while count > 2 * _SLICE_SIZE:
            span *= 0.5
            high = low + span
            count = below(high) - below_low
        while count == 0:
            span *= 2.0
            high = min(upper, low + span)
            count = below(high) - below_low
        extra = 8
        for _attempt in range(5):
            k = min(count + extra, n - 2)
            lam, vec = scipy.sparse.linalg.eigsh(
                K, k=k, M=M, sigma=0.5 * (low + high), which="LM", tol=0.0,
                ncv=min(n - 1, max(2 * k + 1, 40)))
            order = np.argsort(lam)
            above = lam[order] > low
            lam, vec = lam[order][above], vec[:, order][:, above]
            boundary = 0.5 * (lam[count - 1] + lam[count]) if lam.size > count else high
            if lam.size >= count and below(boundary) - below_low == count:
                break
            extra *= 2
        else:
            raise RuntimeError("spectrum slicing of the beam FE model failed: an eigenvalue "
                               "count did not match the Sturm sequence")
        values.append(lam[:count])
        vectors.append(vec[:, :count])
        low, below_low, remaining = boundary, below_low + count, remaining - count
        span *= min(2.0, max(0.5, _SLICE_SIZE / count))
    lam = np.concatenate(values) if values else np.zeros(0)
    vec = np.concatenate(vectors, axis=1) if vectors else np.zeros((n, 0))
    norms = np.sqrt(np.einsum("ij,ij->j", vec, M @ vec))
    return lam, vec / norms


def _fe_solve(section: BeamSection, elements: int, degree: int) -> _FiniteElementModes:
    """Eigen-solution of the FE model: all modes up to its resolved frequency."""
    K, M, connectivity, free, node_dofs, width = _assemble(section, elements, degree)
    Kf, Mf = K[free][:, free], M[free][:, free]
    L, EI, rA = section.length, section.bending_stiffness, section.mass_per_length
    resolved = _frequency_at_wavenumber(section, FE_RESOLUTION * degree * elements / L)
    upper = resolved**2 * (1.0 + 1e-9)
    reference = EI * (math.pi / L) ** 4 / rA
    free_free = section.supports == "ff"
    if Kf.shape[0] <= _DENSE_LIMIT:
        # Flexibility form (K + σM)^{-1} M: the low modes are its largest eigenvalues and
        # keep full relative accuracy (K x = ω² M x directly loses about eps·ω_max²/ω_1²
        # in the fundamental: 1e-5 and worse on fine meshes).
        eigenvalues, vectors_free = _solve_dense(Kf, Mf, upper, reference if free_free else 0.0)
    else:
        eigenvalues, vectors_free = _solve_sliced(
            Kf.tocsc(), Mf.tocsc(), upper, -1e-3 * reference if free_free else 0.0, width)
    vectors = np.zeros((K.shape[0], eigenvalues.size))
    vectors[free] = vectors_free
    if free_free:
        # the two rigid-body modes are exact in the FE space: replace the computed
        # (degenerate, round-off-rotated) pair by translation and rotation, M-normalised
        if eigenvalues.size < 3 or not abs(eigenvalues[1]) < 1e-6 * eigenvalues[2]:
            raise RuntimeError("free-free FE model does not show exactly two rigid-body modes")
        rigid = _rigid_vectors(section, elements, K.shape[0], node_dofs)
        rigid = rigid / np.sqrt(np.einsum("ij,ij->j", rigid, M @ rigid))
        elastic = vectors[:, 2:]
        elastic -= rigid @ (rigid.T @ (M @ elastic))  # round-off rigid content
        vectors[:, :2] = rigid
        eigenvalues[:2] = 0.0
    eigenvalues = np.maximum(eigenvalues, 0.0)
    return _FiniteElementModes(section, elements, degree, connectivity, vectors,
                               np.sqrt(eigenvalues), resolved)


def _frequency_at_wavenumber(section: BeamSection, wavenumber: float) -> float:
    """Lowest-branch frequency ω(k) [rad/s] of free waves of the infinite beam."""
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    k = float(wavenumber)
    if section.theory in ("euler", "rayleigh"):
        return math.sqrt(EI * k**4 / (rA + rI * k**2))
    S = section.shear_stiffness
    a11, a22, a12 = (EI * k**2 + S) / rI, S * k**2 / rA, S * k / math.sqrt(rI * rA)
    upper = 0.5 * (a11 + a22) + math.hypot(0.5 * (a11 - a22), a12)
    return math.sqrt(EI * S * k**4 / (rI * rA) / upper)


#: FE eigen-solutions, keyed by section; each entry the finest solution computed so far.
_FE_CACHE: "OrderedDict[BeamSection, _FiniteElementModes]" = OrderedDict()
_FE_CACHE_SIZE = 8


def _elements_needed(section: BeamSection, max_frequency: float, min_modes: int,
                     degree: int) -> int:
    L = section.length
    k_needed = max(float(largest_wavenumber(section, max_frequency)),
                   (int(min_modes) + 2) * math.pi / L)
    needed = max(2, math.ceil(k_needed * L / (FE_RESOLUTION * degree)))
    # round up on a ~×1.25 grid so that nearby requests share one cached solution
    grid = 2
    while grid < needed:
        grid = max(grid + 1, int(math.ceil(grid * 1.25)))
    return grid


def _dofs(section: BeamSection, elements: int, degree: int) -> int:
    return 2 * (elements + 1) + elements * _bubbles_per_element(section.theory, degree)


def finite_element_modes(section: BeamSection, max_frequency: float, min_modes: int = 1,
                         *, degree: int = FE_DEGREE) -> ModeSet:
    """Rayleigh/Timoshenko (or, for verification, Euler) modes by p-version finite elements.

    Method. Uniform mesh of ``n_e`` elements of degree ``p = degree`` (24).
    Timoshenko: w and ψ continuous (C0), w of degree p and ψ of degree p − 1
    (hierarchical integrated-Legendre bases; the lower degree of ψ lets the Kirchhoff
    constraint ψ = −w' be met exactly, so there is no shear locking).
    Rayleigh and Euler: w alone, C1 (Hermite cubics plus twice-integrated Legendre
    bubbles), ψ = −w', consistent rotary inertia ``∫ ρI w'δw'``. Exact Gauss quadrature,
    consistent mass. Boundary conditions: clamped w = ψ = 0 (C1: w = w' = 0), SS w = 0,
    free nothing (M = Q = 0 are natural). Unknowns numbered element by element, so K and
    M are banded. Eigen-solution: up to 1500 unknowns dense, in flexibility form
    ``(K + σM)^{-1}M`` (σ > 0 only for free–free; K x = ω² M x directly would lose about
    eps·ω_max²/ω_1² in the fundamental); above that by spectrum slicing — slices of ~48
    eigenvalues found by Sylvester-inertia (Sturm) counts of the banded ``K − σM``, each
    solved by shift-invert Lanczos (ARPACK, tol = 0) and its eigenvalue count checked
    against the inertia. The two free–free rigid-body modes are put in exactly.

    Accuracy. Only modes with wavenumber ``k ≤ 1.0 p/h_e`` are kept (the mesh is chosen
    from :func:`largest_wavenumber` of ``max_frequency``). Relative frequency error
    ≤ 3e-10 against the SS Rayleigh/Timoshenko closed forms for 5 ≤ L/h ≤ 300 and
    ~1e-12 against the exact Timoshenko frequency equation (CC, CF, CS, FF) at L/h ≤ 100;
    round-off in the very stiff shear term raises this to ~1e-6 for the highest modes at
    L/h = 1000. Conforming elements: FE frequencies are upper bounds and FE partial
    static compliances lower bounds (so the residual compliance is never negative).

    Cost. About 3 (Rayleigh) or 6–8 (Timoshenko) unknowns per mode; ~0.1 s for 50 modes,
    a few seconds for 300 and ~20 s for 1000 Timoshenko modes (single core). Results are
    cached per section (the largest solution is kept and sliced for later requests). At
    most :data:`FE_MAX_DOFS` unknowns: beyond that a warning is issued and only the modes
    the capped mesh resolves are returned (the rest is carried by the residual
    compliance).
    """
    cached = _FE_CACHE.get(section)
    elements = _elements_needed(section, max_frequency, min_modes, degree)
    while True:
        capped = _dofs(section, elements, degree) > FE_MAX_DOFS
        if capped:
            while elements > 2 and _dofs(section, elements, degree) > FE_MAX_DOFS:
                elements -= 1
        if cached is None or cached.degree != degree or cached.elements < elements:
            cached = _fe_solve(section, elements, degree)
            _FE_CACHE[section] = cached
            while len(_FE_CACHE) > _FE_CACHE_SIZE:
                _FE_CACHE.popitem(last=False)
        if len(cached) >= min_modes or capped:
            break
        elements = _elements_needed(section, 0.0, 2 * max(int(min_modes), len(cached)), degree)
    _FE_CACHE.move_to_end(section)
    if capped and (cached.resolved_frequency < max_frequency or len(cached) < min_modes):
        warnings.warn(
            f"beam finite-element model capped at FE_MAX_DOFS = {FE_MAX_DOFS} unknowns: "
            f"modes above {cached.resolved_frequency:.6g} rad/s are not resolved and are "
            f"left to the residual compliance (requested max_frequency = "
            f"{float(max_frequency):.6g} rad/s, min_modes = {int(min_modes)})",
            stacklevel=3,
        )
    cutoff = _cutoff(cached.frequencies, max_frequency, min_modes)
    keep = int(np.searchsorted(cached.frequencies, cutoff, side="right"))
    return _FiniteElementModes(section, cached.elements, cached.degree, cached.connectivity,
                               cached.vectors[:, :keep], cached.frequencies[:keep],
                               cached.resolved_frequency)


# ---------------------------------------------------------------------------------
# Static point compliance
# ---------------------------------------------------------------------------------
def static_compliance(section: BeamSection, position: float) -> float:
    """Exact static deflection [m/N] at x0 = ``position`` under a unit force at x0.

    Closed forms (a = x0, b = L − x0, s = 1/S the shear compliance, zero for Euler and
    Rayleigh, Φ = 12 EI s/L²), all derived from the static equations of PHYSICS.md 3.2
    with a point load (unit-load method) and checked symbolically:

    * ss: ``a²b²/(3EIL) + s a b/L`` (PHYSICS.md 3.2);
    * cc: ``a b [a²b² + (Φ L²/4)(L² + ab) + Φ² L⁴/4] / (3 EI L³ (1 + Φ))``; Φ = 0 gives
      ``a³b³/(3EIL³)``, the centre gives ``L³/(192EI) + L/(4S)``;
    * cs (clamped at x = 0): ``a b [a²b(3L + b) + Φ L²(L² + ab) + Φ² L⁴/4] / (3 EI L³ (4 + Φ))``;
      Φ = 0 gives ``a³b²(3L + b)/(12EIL³)``;
    * cf (clamped at x = 0, free at L): ``a³/(3EI) + s a``;
    * ff: the beam is unrestrained, so the static compliance is defined by inertia
      relief — the compliance of the *elastic* modes only, ``Σ_elastic W_j(x0)²/ω_j²``
      (the rigid-body modes are excluded): the deflection, made mass-orthogonal to the
      rigid-body modes, under the unit force balanced by the d'Alembert loads of the
      rigid-body acceleration. With t = x0/L − ½, r = ρI/(ρA L²), σ = EI s/L²::

          (EI/L³)·C = [P00 + r P01 + r² P02 + σ (P10 + r P11 + r² P12)] / (6720 (1 + 12r)²)
          P00 = −1344t⁶ + 2800t⁴ − 444t² + 21,   P01 = −168(96t⁶ − 320t⁴ + 54t² − 3),
          P02 = 1008(240t⁴ − 40t² + 3),          P10 = 112(240t⁴ − 48t² + 5),
          P11 = 13440(24t⁴ − 6t² + 1),           P12 = 80640(12t² + 1);

      e.g. Euler: L³/(320EI) at the centre and L³/(105EI) at an end. ρI enters through
      the rigid-body rotation mode (Rayleigh and Timoshenko).
    """
    L, EI = section.length, section.bending_stiffness
    s = section.shear_compliance
    a = float(position)
    b = L - a
    supports = section.supports
    if supports == "ss":
        return a * a * b * b / (3.0 * EI * L) + s * a * b / L
    if supports == "cf":
        return a**3 / (3.0 * EI) + s * a
    phi = 12.0 * EI * s / L**2
    if supports == "cc":
        numerator = a * a * b * b + 0.25 * phi * L * L * (L * L + a * b) + 0.25 * phi**2 * L**4
        return a * b * numerator / (3.0 * EI * L**3 * (1.0 + phi))
    if supports == "cs":
        numerator = (a * a * b * (3.0 * L + b) + phi * L * L * (L * L + a * b)
                     + 0.25 * phi**2 * L**4)
        return a * b * numerator / (3.0 * EI * L**3 * (4.0 + phi))
    if supports == "ff":
        t2 = (a / L - 0.5) ** 2
        r = section.rotary_inertia / (section.mass_per_length * L * L)
        sigma = EI * s / (L * L)
        p00 = ((-1344.0 * t2 + 2800.0) * t2 - 444.0) * t2 + 21.0
        p01 = -168.0 * (((96.0 * t2 - 320.0) * t2 + 54.0) * t2 - 3.0)
        p02 = 1008.0 * ((240.0 * t2 - 40.0) * t2 + 3.0)
        p10 = 112.0 * ((240.0 * t2 - 48.0) * t2 + 5.0)
        p11 = 13440.0 * ((24.0 * t2 - 6.0) * t2 + 1.0)
        p12 = 80640.0 * (12.0 * t2 + 1.0)
        value = (p00 + r * (p01 + r * p02) + sigma * (p10 + r * (p11 + r * p12))) / (
            6720.0 * (1.0 + 12.0 * r) ** 2)
        return L**3 / EI * value
    raise ValueError(f"supports = {supports!r} is not known")
