"""Asymptotes for any contact law (impactmaps.closed_forms.law_asymptotes) against exact references.

* linear contact: the closed forms of impactmaps.closed_forms.asymptotes / infinite_beam;
* Hertz contact on the infinite plate: an independent integration of Zener's model in
  the Hertz scales (one parameter μ, derived in impactmaps.closed_forms.hertz_similarity);
* the beam convolution quadrature: its convergence rate in the step, and its FFT history
  sum against the direct O(N²) sum (a Python march kept here as the reference).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import impactmaps as im
from impactmaps.contact import (
    HertzContact,
    LinearContact,
    StrongeContact,
    YigitChristoforouContact,
    effective_modulus,
)
from impactmaps.contact.plastic.epp import EppContact
from impactmaps.closed_forms.hertz_similarity import hertz_numbers, zener_parameter
from impactmaps.closed_forms.law_asymptotes import beam as beam_asymptote
from impactmaps.closed_forms.law_asymptotes import (
    asymptote,
    halfspace_asymptote,
    infinite_beam_impact_any_law,
    infinite_plate_impact,
    quasi_static_impact,
)
from impactmaps.closed_forms.asymptotes import (
    infinite_plate_contact_time,
    infinite_plate_peak,
    quasi_static_peak,
)
from impactmaps.closed_forms import infinite_beam_cq
from impactmaps.closed_forms.infinite_beam import (
    infinite_beam_contact_time,
    infinite_beam_peak,
    recontact_beam_loss_factor,
)

STEEL = im.IsotropicMaterial(210e9, 0.3, 7800.0)
PLATE = im.Plate.isotropic(0.3, 0.3, 0.004, STEEL)
BEAM = im.Beam.rectangular(1.0, 0.02, 0.02, STEEL, theory="euler")
MASS = 0.05


@pytest.mark.parametrize("stiffness", [1e6, 1e7, 1e8, 3e8, 1e9])
def test_linear_infinite_plate_matches_closed_form(stiffness):
    # DOP853 at rtol 1e-12: the peak (a turning-point event) is good to ~1e-12; 1e-6 is the brief's bar
    run = infinite_plate_impact(PLATE, LinearContact(stiffness), MASS, 2.0)
    zeta = float(im.loss_factor_plate(MASS, stiffness, PLATE.mass_per_area, PLATE.effective_bending_stiffness))
    assert run.fmax_normalised == pytest.approx(infinite_plate_peak(zeta), abs=1e-6)
    expected_time = infinite_plate_contact_time(zeta)
    if math.isinf(expected_time):
        assert math.isinf(run.contact_time) and run.restitution == 0.0
    else:
        assert run.contact_time * run.contact_frequency == pytest.approx(expected_time, rel=1e-6)
        # the plate point stops at separation: e = exp(−ζ τ_c) (impactor speed of the oscillator)
        assert run.restitution == pytest.approx(math.exp(-zeta * expected_time), rel=1e-6)


def _zener_reference(mu):
    """Zener's model in the Hertz scales: ᾱ' = ū − μ ᾱ^{3/2}, ū' = −(5/4) ᾱ^{3/2}.

    Derivation (impactmaps.closed_forms.hertz_similarity): with α_m, t* = α_m/V0, F_hs = K_h α_m^{3/2},
    m ẍ = −F gives ū' = −(K_h α_m^{5/2}/(m V0²)) F̄ = −(5/4) F̄, and ẇ = F/Z gives
    w̄' = μ F̄ with μ = F_hs t*/(α_m Z). Integrated here with Radau (implicit, a different
    family from the DOP853 of the code under test), Hertz being elastic (no history).
    Returns (F_max/F_hs, t_c/t*, e).
    """
    def rhs(_t, y):
        force = max(y[0], 0.0) ** 1.5
        return (y[1] - mu * force, -1.25 * force)

    def peak(_t, y):
        return rhs(_t, y)[0]

    def end(_t, y):
        return y[0]

    peak.terminal, end.terminal, end.direction, peak.direction = False, True, -1, -1
    run = solve_ivp(rhs, (0.0, 1e3), (0.0, 1.0), method="Radau", rtol=1e-12, atol=1e-14,
                    events=(peak, end), first_step=1e-6)
    alpha_max = run.y_events[0][0][0]
    return alpha_max**1.5, run.t_events[1][0], -run.y_events[1][0][1]


@pytest.mark.parametrize("mass", [0.004, 0.05, 0.5])
def test_hertz_infinite_plate_matches_zener(mass):
    law = HertzContact(1e10)
    numbers = hertz_numbers(PLATE, law, mass, 1.0)
    mu = 1.25**0.6 * zener_parameter(PLATE, law, mass, 1.0)
    assert mu == pytest.approx(2.5 * numbers.loss_factor, rel=1e-12)  # μ = (5/2) ζ_h exactly
    force, time, restitution = _zener_reference(mu)
    run = infinite_plate_impact(PLATE, law, mass, 1.0)
    # two rtol-1e-12 integrations with located events agree to ~1e-9; 1e-7 leaves margin
    assert run.peak_force / numbers.force_scale == pytest.approx(force, rel=1e-7)
    assert run.contact_time / numbers.time_scale == pytest.approx(time, rel=1e-7)
    assert run.restitution == pytest.approx(restitution, rel=1e-7, abs=1e-10)


def test_quasi_static_linear_and_elastic_plastic():
    stiffness = 1e8
    run = quasi_static_impact(PLATE, LinearContact(stiffness), MASS, 2.0)
    lam = 1.0 / (PLATE.static_compliance() * stiffness)
    assert run.fmax_normalised == pytest.approx(quasi_static_peak(lam), rel=1e-9)
    assert run.restitution == pytest.approx(1.0, abs=1e-9)  # spring + elastic contact: no loss
    plastic = YigitChristoforouContact(1e10, 1e-7)
    yielded = quasi_static_impact(PLATE, plastic, MASS, 2.0)
    assert 0.0 < yielded.restitution < 1.0 and yielded.permanent_indentation > 0.0


def test_halfspace_limits():
    law = YigitChristoforouContact(1e10, 1e-7)
    reference = im.halfspace_impact(law, MASS, 2.0)
    run = halfspace_asymptote(law, MASS, 2.0)
    assert run.peak_force == reference.peak_force and run.restitution == reference.restitution
    # a very stiff plate (ζ → 0) and a very stiff static spring tend to the half-space
    thick = im.Plate.isotropic(3.0, 3.0, 0.5, STEEL)
    assert infinite_plate_impact(thick, law, MASS, 2.0).restitution == pytest.approx(run.restitution, rel=2e-3)
    assert quasi_static_impact(1e15, law, MASS, 2.0).peak_force == pytest.approx(run.peak_force, rel=1e-4)


@pytest.mark.parametrize("stiffness", [1e6, 1e8])
def test_linear_infinite_beam_matches_closed_form(stiffness):
    # BDF2 CQ: error ≈ 0.2 h² in F̄max (measured), h = 0.005 → ~5e-6; 2e-5 bounds it
    run = infinite_beam_impact_any_law(BEAM, LinearContact(stiffness), MASS, 2.0, time_step=0.005)
    zeta = float(im.loss_factor_beam(MASS, stiffness, BEAM.mass_per_length, BEAM.bending_stiffness))
    assert zeta < recontact_beam_loss_factor()
    assert run.fmax_normalised == pytest.approx(infinite_beam_peak(zeta), abs=2e-5)
    assert run.contact_time * run.contact_frequency == pytest.approx(infinite_beam_contact_time(zeta), abs=1e-4)
    assert run.impacts == 1 and not run.time_limit_reached


def test_infinite_beam_reimpacts_between_recontact_and_critical_loss_factor():
    stiffness = 1e11  # ζ_b ≈ 0.35, inside (ζ_r, ζ_crit): the impactor strikes again
    run = infinite_beam_impact_any_law(BEAM, LinearContact(stiffness), MASS, 2.0, duration=60.0)
    assert run.impacts >= 2


def test_infinite_beam_hertz_converges_at_second_order():
    law = HertzContact(1e10)
    peaks = [infinite_beam_impact_any_law(BEAM, law, MASS, 2.0, time_step=h).fmax_normalised
             for h in (0.02, 0.01, 0.005)]
    ratio = (peaks[1] - peaks[0]) / (peaks[2] - peaks[1])
    assert 3.0 < ratio < 5.0  # 4 for a second-order scheme
    assert abs(peaks[2] - peaks[1]) < 1e-4


def test_asymptote_dispatch_and_summary():
    run = asymptote("infinite-plate", PLATE, HertzContact(1e10), MASS, 1.0)
    summary = run.summary()
    for key in ("peak_force_N", "contact_time_s", "restitution", "fmax_normalised", "impacts"):
        assert key in summary
    with pytest.raises(ValueError, match="kind"):
        asymptote("infinite-shell", PLATE, HertzContact(1e10), MASS, 1.0)
    with pytest.raises(ValueError, match="infinite-beam"):
        asymptote("infinite-beam", PLATE, HertzContact(1e10), MASS, 1.0)


def _direct_march(kernel, params, weights, step, speed, mass, count):
    """The reference: the O(N²) march, history summed directly step by step (plain Python)."""
    solve_step = beam_asymptote._solve_step.py_func
    force, alpha = np.zeros(count + 1), np.zeros(count + 1)
    alpha_max = impulse = 0.0
    touched = False
    for n in range(1, count + 1):
        free = speed * step * n - float(np.dot(weights[n:0:-1], force[:n]))
        alpha[n], force[n] = solve_step(kernel, params, weights[0], free, alpha_max)
        alpha_max = max(alpha_max, alpha[n])
        impulse += 0.5 * step * (force[n] + force[n - 1])
        touched = touched or force[n] > 0.0
        if touched and force[n] == 0.0 and speed - impulse / mass <= 0.0:
            return force, alpha, n
    return force, alpha, count


_E_STAR = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
FFT_LAWS = {
    "linear": LinearContact(1e8),
    "hertz": HertzContact(4.0 / 3.0 * math.sqrt(0.01) * _E_STAR),
    "yc": YigitChristoforouContact.from_properties(_E_STAR, 0.01, 350e6),
    "stronge": StrongeContact(_E_STAR, 0.01, 350e6),
    "epp": EppContact(_E_STAR, 0.01, 350e6),
}
_COMPARED = ("peak_force", "peak_time", "contact_time", "restitution", "max_indentation",
             "permanent_indentation", "max_target_displacement")


@pytest.mark.parametrize("law_name", sorted(FFT_LAWS))
@pytest.mark.parametrize("mass", [0.01, 0.2, 5.0])  # light to heavy sphere: ζ_b from small to large
def test_infinite_beam_fft_history_equals_direct_sum(monkeypatch, law_name, mass):
    # 3000 steps: the FFT blocks reach three levels above the 256-step leaves (and, with
    # 0.2 kg, re-impacts cross leaves); the runs that separate stop inside the first leaves
    law = FFT_LAWS[law_name]
    options = {"time_step": 0.01, "duration": 30.0}
    fast = infinite_beam_impact_any_law(BEAM, law, mass, 2.0, **options)
    monkeypatch.setattr(beam_asymptote, "_march", _direct_march)
    direct = infinite_beam_impact_any_law(BEAM, law, mass, 2.0, **options)
    assert fast.impacts == direct.impacts and fast.time_limit_reached == direct.time_limit_reached
    for name in _COMPARED:
        assert getattr(fast, name) == pytest.approx(getattr(direct, name), rel=1e-12, abs=0.0), name


def test_infinite_beam_small_leaves_equal_one_leaf(monkeypatch):
    # the blocked recursion on many levels (8-step leaves) against one leaf of every step
    # (the compiled direct sum), through re-impacts
    law = FFT_LAWS["yc"]
    monkeypatch.setattr(infinite_beam_cq, "LEAF_STEPS", 8)
    blocked = infinite_beam_impact_any_law(BEAM, law, 0.2, 2.0, duration=60.0)
    monkeypatch.setattr(infinite_beam_cq, "LEAF_STEPS", 10**6)
    direct = infinite_beam_impact_any_law(BEAM, law, 0.2, 2.0, duration=60.0)
    assert blocked.impacts == direct.impacts >= 2
    for name in _COMPARED:
        assert getattr(blocked, name) == pytest.approx(getattr(direct, name), rel=1e-12, abs=0.0), name
