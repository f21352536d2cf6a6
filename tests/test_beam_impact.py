"""Impact on the real Beam targets through the modal solver: limits, invariants,
nonlinear contact with re-impacts, the `point` command, bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

from impactmaps.cli import main
from impactmaps.contact import HertzContact, StrongeContact, YigitChristoforouContact, effective_modulus
from impactmaps.materials import IsotropicMaterial
from impactmaps.solvers.asymptotes import infinite_beam_peak
from impactmaps.solvers.modal import ModalSettings, simulate, simulate_normalised
from impactmaps.targets.beam import Beam

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
