"""Euler beams with any support: roots of the classical frequency equations and
mode shapes in an overflow-free basis (Blevins 1979, Table 8-1)."""

from __future__ import annotations

import math

import numpy as np

from .beam_section import (
    BeamSection,
    ModeSet,
    as_points,
    cutoff_with_min_modes,
    largest_wavenumber,
)

__all__ = ["euler_roots", "classical_euler_modes"]


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


def euler_roots(supports: str, count: int, first: int = 1) -> np.ndarray:
    """Roots βL number ``first`` … ``count`` of the Euler frequency equation of ``supports``
    (elastic modes; overflow-free forms, 80 bisection steps)."""
    n = np.arange(max(int(first), 1), int(count) + 1, dtype=float)
    if n.size == 0:
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
    """Rigid-body modes followed by elastic modes in the basis cos βx, sin βx, e^{−βx}, e^{−β(L−x)}."""

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
        x = as_points(points)[:, None]
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
        x = as_points(points)[:, None]
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
    """All Euler-beam modes with ω ≤ ``max_frequency`` [rad/s] (at least ``min_modes``),
    accurate for any mode number; free–free beams get their two rigid-body modes first."""
    if section.theory != "euler":
        raise ValueError("classical_euler_modes needs theory = 'euler'")
    L, EI, rA = section.length, section.bending_stiffness, section.mass_per_length
    scale = math.sqrt(EI / (rA * L**4))
    beta_max_L = float(largest_wavenumber(section, max_frequency)) * L
    rigid = 2 if section.supports == "ff" else 0
    count = max(int(beta_max_L / math.pi) + 2, int(min_modes) - rigid, 1)
    roots = euler_roots(section.supports, count)
    frequencies = roots**2 * scale
    cutoff = cutoff_with_min_modes(np.concatenate([np.zeros(rigid), frequencies]), max_frequency, min_modes)
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

