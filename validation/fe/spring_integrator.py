"""A small time integrator for the spring-coupled impact on a 3D modal model (level 3).

The struck solid is represented by its 3D modes seen from the loaded patch
(``ω_j``, mass-normalised patch participations ``p_j``) plus the quasi-static
residual ``r = C − Σ p_j²/ω_j²`` (``C`` the 3D static compliance of the patch), which
carries the truncated modes, the local deformation under the patch included.  The
sphere is a point mass joined to the patch by a tension-free spring whose law
removes the patch's own local compliance ``c`` from the Hertz approach::

    α_s(F) = (F / K_h)^(2/3) − c F          (Hertz)
    α_s(F) = F / k − c F                    (linear)

so that spring + local response of the solid reproduce the contact law.

Scheme: the force is linear over each step (first-order hold); each mode and the
sphere are then advanced exactly, and the end-of-step force solves one scalar
equation ``α_s(F) = A − B F`` (A: spring deformation with F = 0 at the end of the
step, B > 0 its sensitivity), by bracketed root finding.  Second order in the step.
This is independent of the toolkit's kernels on purpose.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


def halfspace_patch_compliance(radius, material):
    """Mean deflection per unit force of a uniform disc load on an elastic half-space.

    ``c = 16 (1 − ν²) / (3 π² a_c E)`` [m/N], ``a_c`` the disc radius [m].
    """
    nu, e = material.poisson_ratio, material.youngs_modulus
    return 16 * (1 - nu ** 2) / (3 * np.pi ** 2 * radius * e)


@dataclass
class SpringLaw:
    """Spring law α_s(F) [m] for F ≥ 0 [N]: Hertz (``stiffness`` K_h [N/m^1.5]) or linear."""

    kind: str            # "hertz" or "linear"
    stiffness: float     # K_h [N/m^1.5] or k [N/m]
    local: float         # c [m/N], the patch's own local compliance removed from the law

    def approach(self, force):
        if self.kind == "hertz":
            return (force / self.stiffness) ** (2.0 / 3.0) - self.local * force
        return force / self.stiffness - self.local * force


@dataclass
class SpringRun:
    time: np.ndarray
    force: np.ndarray
    sphere_velocity: np.ndarray
    peak_force: float
    contact_intervals: np.ndarray
    restitution: float


def integrate(omega, participation, residual, law: SpringLaw, mass, velocity,
              time_step, duration, record=True):
    """Integrate the impact; returns a :class:`SpringRun` (force history, intervals, e).

    Parameters: ``omega`` [rad/s] and ``participation`` [1/sqrt(kg)] of the retained
    modes, ``residual`` compliance [m/N] (≥ 0), sphere ``mass`` [kg] and impact
    ``velocity`` [m/s] (into the target), ``time_step`` and ``duration`` [s].
    """
    w = np.asarray(omega, float)
    p = np.asarray(participation, float)
    h = float(time_step)
    cw, sw, g0, g1, d0, d1 = step_coefficients(w, h)
    b_coef = h * h / (6 * mass) + np.dot(p * p, g1) + residual
    n_steps = int(np.ceil(duration / h))
    q = np.zeros_like(w)
    qd = np.zeros_like(w)
    z, v, f0 = 0.0, float(velocity), 0.0
    times = np.arange(n_steps + 1) * h
    forces = np.zeros(n_steps + 1)
    vels = np.zeros(n_steps + 1)
    vels[0] = v
    for k in range(n_steps):
        q_free = q * cw + qd * sw / w + p * (f0 * (g0 - g1))
        qd_free = -q * w * sw + qd * cw + p * (f0 * (d0 - d1))
        z_free = z + v * h - h * h * f0 / (3 * mass)
        a = z_free - (np.dot(p, q_free))
        if a <= 0.0:
            f1 = 0.0
        else:
            f1 = _solve(law, a, b_coef)
        q = q_free + p * (f1 * g1)
        qd = qd_free + p * (f1 * d1)
        z = z_free - h * h * f1 / (6 * mass)
        v = v - h * (f0 + f1) / (2 * mass)
        f0 = f1
        forces[k + 1] = f1
        vels[k + 1] = v
    intervals = _intervals(times, forces)
    return SpringRun(time=times, force=forces, sphere_velocity=vels,
                     peak_force=float(forces.max()), contact_intervals=intervals,
                     restitution=float(-v / velocity))


def step_coefficients(w, h):
    """Exact one-step response of ``q'' + w² q = f`` with f linear over the step.

    Returns ``cos wh, sin wh, g0, g1, d0, d1``: q and q' gain ``g0 f0 + g1 (f1 − f0)``
    and ``d0 f0 + d1 (f1 − f0)`` from the force (values f0, f1 at the step's ends).
    """
    cw, sw = np.cos(w * h), np.sin(w * h)
    return (cw, sw, (1 - cw) / w ** 2, (w * h - sw) / (w ** 3 * h), sw / w,
            (1 - cw) / (w ** 2 * h))


def _solve(law, a, b):
    """F > 0 with ``law.approach(F) = a − b F`` (a > 0)."""
    g = lambda f: law.approach(f) + b * f - a
    hi = a / b if b > 0 else 1.0
    while g(hi) < 0:
        hi *= 2
    return brentq(g, 0.0, hi, xtol=1e-14 * hi, rtol=1e-13)


def _intervals(times, forces):
    on = forces > 0
    edges = np.flatnonzero(np.diff(on.astype(int)))
    starts = [times[i] for i in edges if not on[i]]
    ends = [times[i + 1] for i in edges if on[i]]
    if on[0]:
        starts = [times[0]] + starts
    if len(ends) < len(starts):
        ends.append(times[-1])
    return np.column_stack([starts, ends]) if starts else np.zeros((0, 2))
