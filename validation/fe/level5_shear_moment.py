"""Level 5, diagnosis: the elastic mid-span bending moment under the prescribed force,
Rayleigh against Timoshenko beam (modal superposition, exact for a piecewise-linear load).

The FD beam is a Rayleigh beam loaded at a point; the 3D solid deforms in shear and
spreads the load. Under short force spikes the bending moment at the load point of a
beam without shear deformation rises faster and higher than that of a shear-deformable
one; once the section there has yielded, each excess drives plastic rotation. This
script measures that excess on the elastic beams (the simply supported modes of both
theories are sin(kx) in w, so the modal sums are exact): mid-span deflection and moment
histories, their peaks, for ``--modes`` modes (odd modes only: the load is at mid-span).

Run: ``python validation/fe/level5_shear_moment.py``; adds ``shear_moment`` to
``results/level5_beam_plastic.json``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from level5_beam_plastic import (
    HEIGHT,
    LENGTH,
    STEEL,
    WIDTH,
    load,
    prescribed_force,
    save,
)
from spring_integrator import step_coefficients


def modes(n_max, shear=True):
    """(ω, modal force per unit load at mid-span, modal moment at mid-span per unit
    coordinate) of the odd simply supported modes, mass-normalised; both Timoshenko
    branches when ``shear``."""
    e, nu, rho = STEEL.youngs_modulus, STEEL.poisson_ratio, STEEL.density
    area, inertia = WIDTH * HEIGHT, WIDTH * HEIGHT**3 / 12
    kga = 10 * (1 + nu) / (12 + 11 * nu) * e / (2 * (1 + nu)) * area   # Cowper's k
    out = []
    for n in range(1, n_max + 1, 2):
        k = n * np.pi / LENGTH
        s = np.sin(n * np.pi / 2)
        if shear:   # w = W sin kx, ψ = Ψ cos kx; K [W, Ψ] = ω² M [W, Ψ]
            stiff = np.array([[kga * k**2, -kga * k], [-kga * k, e * inertia * k**2 + kga]])
            mass = np.diag([rho * area, rho * inertia]) * LENGTH / 2
            lam, vec = np.linalg.eig(np.linalg.solve(mass, stiff * LENGTH / 2))
            for j in range(2):
                v = vec[:, j] / np.sqrt(vec[:, j] @ mass @ vec[:, j])
                out.append((np.sqrt(lam[j].real), v[0] * s, e * inertia * k * v[1] * s))
        else:       # Rayleigh: ψ = w'
            m = (rho * area + rho * inertia * k**2) * LENGTH / 2
            w = 1 / np.sqrt(m)
            out.append((np.sqrt(e * inertia * k**4 / (rho * area + rho * inertia * k**2)),
                        w * s, e * inertia * k**2 * w * s))
    omega, force, moment = (np.array(c, float) for c in zip(*out))
    return omega, force, moment


def response(omega, phi, moment, times, force):
    """Mid-span deflection and sagging moment histories under the piecewise-linear load."""
    q, qd = np.zeros_like(omega), np.zeros_like(omega)
    h = times[1] - times[0]
    c, s, g0, g1, d0, d1 = step_coefficients(omega, h)
    w_out, m_out = [0.0], [0.0]
    for f0, f1 in zip(force[:-1], force[1:]):
        q, qd = (q * c + qd * s / omega + phi * (f0 * (g0 - g1) + f1 * g1),
                 -q * omega * s + qd * c + phi * (f0 * (d0 - d1) + f1 * d1))
        w_out.append(float(phi @ q))
        m_out.append(float(moment @ q))
    return np.array(w_out), np.array(m_out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--modes", type=int, default=401, help="highest mode number n")
    p.add_argument("--end", type=float, default=7.5e-3, help="end time [s]")
    a = p.parse_args(argv)
    times, force = prescribed_force(a.end)
    m_y = STEEL.yield_strength * WIDTH * HEIGHT**2 / 6
    result = {}
    for name, shear in (("rayleigh", False), ("timoshenko", True)):
        w, m = response(*modes(a.modes, shear), times, force)
        result[name] = {"peak_deflection_m": float(w.max()), "peak_moment_Nm": float(m.max()),
                        "peak_moment_over_My": float(m.max() / m_y),
                        "time_above_Mp_s": float(np.count_nonzero(m > 1.5 * m_y)
                                                 * (times[1] - times[0]))}
        print(name, result[name])
    w_r, m_r = response(*modes(a.modes, False), times, force)
    w_t, m_t = response(*modes(a.modes, True), times, force)
    result["max_moment_difference_over_My"] = float(np.abs(m_r - m_t).max() / m_y)
    result["modes"], result["end_s"] = a.modes, a.end
    data = load()
    data["shear_moment"] = result
    save(data)
    print(result)


if __name__ == "__main__":
    main()
