"""Is the plastic half-space impact quasi-static?  Time-scale estimate (no dynamic FE).

ccx 2.20 does not run implicit dynamic contact with a yielding target: the 3D attempt
(``level4_plastic_indent.py`` docstring) stalls because ccx's energy check for dynamic
contact cuts every increment in which plastic work is dissipated, and the rule has no
switch.  The axisymmetric model uses the same contact code, so the dynamic run was
not attempted again.  Instead this script compares, for the issue's example (12.7 mm
steel ball on an aluminium half-space, Y = 275 MPa) at V/V_y = 3, 30 and 300, the
contact duration t_c of the quasi-static ``epp`` impact
(:func:`impactmaps.closed_forms.halfspace.halfspace_impact`) with

* the time a longitudinal wave needs to cross the ball, 2R/c_L (Love's criterion for
  a quasi-static impact: t_c ≫ 2R/c_L);
* the time a Rayleigh wave needs to cross the final contact radius, a_m/c_R, and the
  mean speed of the contact edge during compression, a_m/t_m (t_m the time of
  the largest indentation), against c_R;
* V against the bar speed of the flat, sqrt(E/ρ).

c_L = sqrt(E(1−ν)/(ρ(1+ν)(1−2ν))); c_R from the Rayleigh equation (root by brentq).
Contact radius a² = 2Rδ (an upper estimate of the plastic contact radius).  Writes
``results/axisym_dynamic_estimate.json``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
from impactmaps.contact import ContactPair, effective_modulus  # noqa: E402
from impactmaps.contact.plastic.epp import EppContact  # noqa: E402
from impactmaps.closed_forms.halfspace import halfspace_impact  # noqa: E402

BALL = dict(E=200e9, nu=0.3, rho=7800.0, R=6.35e-3)
FLAT = dict(E=70e9, nu=0.33, rho=2700.0, Y=275e6)


def wave_speeds(E, nu, rho):
    """(c_L, c_S, c_R, c_0) [m/s] of an isotropic solid."""
    c_l = np.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))
    c_s = np.sqrt(E / (2 * (1 + nu) * rho))
    k = c_s / c_l

    def rayleigh(x):      # x = (c_R/c_S)²
        return (2 - x) ** 2 - 4 * np.sqrt(1 - x) * np.sqrt(1 - k * k * x)
    c_r = c_s * np.sqrt(brentq(rayleigh, 1e-6, 1 - 1e-12))
    return c_l, c_s, c_r, np.sqrt(E / rho)


def main():
    e_star = float(effective_modulus(BALL["E"], BALL["nu"], FLAT["E"], FLAT["nu"]))
    law = EppContact.from_contact_pair(ContactPair(e_star, BALL["R"], FLAT["Y"]))
    mass = BALL["rho"] * 4 / 3 * np.pi * BALL["R"] ** 3
    v_y = float(np.sqrt(0.8 * law.yield_force * law.yield_indentation / mass))
    c_l_ball = wave_speeds(BALL["E"], BALL["nu"], BALL["rho"])[0]
    _, _, c_r, c_0 = wave_speeds(FLAT["E"], FLAT["nu"], FLAT["rho"])
    rows = []
    for ratio in (3.0, 30.0, 300.0):
        v = ratio * v_y
        res = halfspace_impact(law, mass, v)
        h = res.history
        t, alpha = h["time_s"].to_numpy(), h["indentation_m"].to_numpy()
        t_m = float(t[np.argmax(alpha)])
        t_c = float(res.contact_intervals[0][1] - res.contact_intervals[0][0])
        a_m = float(np.sqrt(2 * BALL["R"] * res.max_indentation))
        rows.append(dict(v_over_vy=ratio, velocity_m_s=v, contact_time_s=t_c,
                         ball_transit_s=2 * BALL["R"] / c_l_ball,
                         contact_time_over_ball_transit=t_c / (2 * BALL["R"] / c_l_ball),
                         rayleigh_transit_of_contact_s=a_m / c_r,
                         contact_time_over_rayleigh_transit=t_c / (a_m / c_r),
                         mean_contact_edge_speed_over_c_R=a_m / t_m / c_r,
                         velocity_over_bar_speed=v / c_0, restitution=res.restitution))
    out = dict(example="12.7 mm steel ball on aluminium, Y = 275 MPa", v_y_m_s=v_y,
               ball_c_L_m_s=c_l_ball, flat_c_R_m_s=c_r, flat_c_0_m_s=c_0, rows=rows)
    (HERE / "results" / "axisym_dynamic_estimate.json").write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
