"""Impact on the real Beam targets through the modal solver: limits, invariants,
nonlinear contact with re-impacts, the `point` command, bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactmaps.cli import main
from impactmaps.contact import HertzContact, StrongeContact, YigitChristoforouContact, effective_modulus
from impactmaps.materials import IsotropicMaterial
from impactmaps.closed_forms.asymptotes import infinite_beam_peak
from impactmaps.solvers.modal import ModalSettings, simulate, simulate_normalised
from impactmaps.targets.beams.beam import Beam

STEEL = IsotropicMaterial(210e9, 0.3, 7850.0, 350e6)


def _beam(theory="euler", supports="ss", position=None, height=0.02):
    return Beam.rectangular(0.8, 0.04, height, STEEL, theory=theory, supports=supports, impact_position=position)


@pytest.mark.parametrize("zeta", [0.01, 0.3, 1.0])
def test_long_beam_reproduces_infinite_beam(zeta):
    """λ → 0: the SS Euler beam's F̄max equals the infinite-beam peak (eq 36) within 0.5 %."""
    result = simulate_normalised(_beam(), zeta, 1e-3, record=False)
    assert result.fmax_normalised == pytest.approx(float(infinite_beam_peak(zeta)), rel=5e-3)


@pytest.mark.parametrize("theory", ["euler", "rayleigh", "timoshenko"])
def test_heavy_impactor_is_quasi_static(theory):
    """ζ = 50, λ = 1: F̄max within 2 % of sqrt(λ/(1+λ)) for every beam theory."""
    result = simulate_normalised(_beam(theory), 50.0, 1.0, record=False)
    assert result.fmax_normalised == pytest.approx(np.sqrt(0.5), rel=0.02)


@pytest.mark.parametrize("supports", ["ss", "cc", "cs", "cf"])
def test_linear_invariants_every_support(supports):
    """0 ≤ F̄ ≤ 1, energy conserved to 1e-6 (ωΔt = 0.005), impulse = m(V0 + V_rebound)."""
    settings = ModalSettings(time_step_ratio=0.005, resolve_ratio=0.05, force_resolution=0.0)
    position = 0.6 if supports == "cf" else 0.3
    result = simulate_normalised(_beam("timoshenko", supports, position), 0.4, 0.5, settings=settings)
    force = result.normalised_history()["force_normalised"]
    assert force.min() >= 0.0 and force.max() <= 1.0
    assert result.energy_balance_error < 1e-6
    h = result.history
    impulse = np.trapezoid(h["force_N"], h["time_s"])
    assert impulse == pytest.approx(result.impactor_mass * (result.velocity + result.rebound_velocity), rel=1e-4)


@pytest.mark.parametrize("law_name", ["hertz", "yigit-christoforou", "stronge"])
def test_nonlinear_laws_multiple_impacts_energy_ledger(law_name):
    """Nonlinear laws through the same solver: a heavy sphere on a slender beam bounces
    several times; the contact dissipation from the law closes the energy balance:
    ½mV0² = ½mV_r² + E_structure + E_contact (to 1e-4 at ωΔt = 0.005)."""
    radius = 0.01
    e_star = float(effective_modulus(210e9, 0.3, 210e9, 0.3))
    law = {
        "hertz": HertzContact(4 / 3 * np.sqrt(radius) * e_star),
        "yigit-christoforou": YigitChristoforouContact.from_properties(e_star, radius, 350e6),
        "stronge": StrongeContact(e_star, radius, 350e6),
    }[law_name]
    beam = _beam("timoshenko", height=0.01)
    settings = ModalSettings(time_step_ratio=0.005, resolve_ratio=0.05, force_resolution=0.0)
    result = simulate(beam, law, 2.0, 1.0, settings=settings)
    assert result.impacts >= 2
    assert result.energy_balance_error < 1e-4
    if law_name != "hertz":
        assert result.contact_dissipation > 0 and result.permanent_indentation > 0
    else:
        assert result.contact_dissipation == 0.0


def test_point_command_for_beams(capsys):
    for theory in ("euler", "rayleigh", "timoshenko"):
        assert main(["point", "--target", "beam-ss", "--theory", theory, "--zeta", "11.3", "--lambda", "0.425",
                     "--no-check", "--json"]) == 0
        values = json.loads(capsys.readouterr().out)
        assert set(values) >= {"fmax_normalised", "impacts", "contact_time_normalised"}
        assert values["fmax_normalised"] == pytest.approx(values["quasi_static_fmax"], rel=0.1)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(impact_position=0.9), "impact_position"),
        (dict(impact_position=0.0), "impact_position"),
        (dict(supports="xx"), "supports"),
        (dict(theory="bernoulli"), "theory"),
    ],
)
def test_bad_beam_input(kwargs, name):
    options = dict(theory="euler", supports="ss", impact_position=None) | kwargs
    with pytest.raises(ValueError, match=name):
        Beam.rectangular(0.8, 0.04, 0.02, STEEL, **options)


def test_slenderness_below_two_is_rejected():
    with pytest.raises(ValueError, match="slenderness"):
        Beam.rectangular(0.03, 0.04, 0.02, STEEL)


# -- the contact patch and Timoshenko beams (issue 14) ---------------------------------
def _fe_beam(length=0.5):
    """The steel beam of validation/fe level 3 (20 × 20 mm, SS) and its solid 10 mm-radius
    steel sphere with the Hertz law of the pair."""
    from impactmaps.contact import Sphere, law_for_sphere
    from impactmaps.materials import material

    steel = material("structural-steel")
    sphere = Sphere(0.01, steel)
    return (Beam.rectangular(length, 0.02, 0.02, steel, theory="timoshenko"), sphere,
            law_for_sphere("hertz", sphere, steel))


@pytest.mark.parametrize("length", [0.5, 0.2])
def test_timoshenko_hertz_peak_converges_in_the_cutoff(length):
    """The point-loaded Timoshenko beam converges in the cut-off, unlike the Mindlin plate:
    its shear deflection under a point load is finite (static compliance
    L³/(48 EI) + L/(4 kGA) at mid-span, the modal series converging like Σ 1/n²), so the
    dropped modes are carried exactly by the residual. Solid sphere at 1 m/s on the FE
    beam (span/height 25 and 10): the peak force moves < 2e-5 over cut-offs 20–160 ω
    (measured 1.6e-6), and the default "auto" keeps the point load on beams."""
    beam, sphere, law = _fe_beam(length)
    forces = [simulate(beam, law, sphere.mass, 1.0, settings=ModalSettings(cutoff_ratio=c), record=False)
              for c in (20, 40, 80, 160)]
    peaks = [r.peak_force for r in forces]
    assert max(peaks) - min(peaks) < 2e-5 * peaks[0]
    assert all("contact_radius_m" not in r.settings for r in forces)
    basis = beam.modes(40 * forces[1].contact_frequency)
    retained = float(np.sum(basis.participation**2 / basis.frequencies**2))
    closed = length**3 / (48 * beam.bending_stiffness) + length / (4 * beam.shear_stiffness)
    assert retained + basis.residual_compliance == pytest.approx(closed, rel=1e-12)


def test_a_strip_patch_would_not_change_the_timoshenko_beam():
    """Why beams need no patch. The Hertz pressure p ∝ sqrt(1 − r²/a²) on a disc inside the
    width, integrated across it, is the line load ∝ (1 − x²/a²) on |x| < a, whose
    modal transform for sin(kx) is the same 3(sin x − x cos x)/x³ (quadrature, 1e-12). The
    SS beam's static compliance under that strip load, summed mode by mode (2e6 modes,
    bending + shear), differs from the point value by −6.3e-12 m/N at the peak Hertz radius
    of the solid-sphere case (a = 0.46 mm; shear part −4.4e-12 ≈ −0.26 a/(kGA)): 7e-6 of the
    static compliance and 0.35 % of the 1.8e-9 m/N excess compliance the 3D FE model finds
    (validation/fe, levels 2–3). The beam's excess over 3D is a near-field effect on the
    scale of the depth h, not of the contact radius a, so a patch load does not close it."""
    from impactmaps.targets.patch import hertz_transform

    beam, _, _ = _fe_beam()
    radius, length = 0.46e-3, beam.length
    nodes, weights = np.polynomial.legendre.leggauss(200)
    for k in (3.0, 1e3, 2e4):
        line = np.sum(weights * (1 - nodes**2) * np.cos(k * radius * nodes)) / np.sum(weights * (1 - nodes**2))
        assert line == pytest.approx(float(hertz_transform(k * radius)), abs=1e-12)
    n = np.arange(1, 2_000_002, 2, dtype=float)  # the even modes have no motion at mid-span
    k = n * np.pi / length
    bending = 2 / (length * beam.bending_stiffness * k**4)
    shear = 2 / (length * beam.shear_stiffness * k**2)
    change_squared = hertz_transform(k * radius) ** 2 - 1.0
    total_change = float(np.sum((bending + shear) * change_squared))
    shear_change = float(np.sum(shear * change_squared))
    assert float(np.sum(bending + shear)) == pytest.approx(beam.static_compliance(), rel=1e-8)
    assert -1e-11 < total_change < 0 and abs(total_change) < 1e-5 * beam.static_compliance()
    assert shear_change == pytest.approx(-0.257 * radius / beam.shear_stiffness, rel=0.02)
    assert abs(total_change) < 5e-3 * 1.8e-9
