"""Elastic-plastic maps over (β, ζ, λ): the similarity they rest on, the shipped maps, their lookup.

Issue 13 item 2: for the Yigit–Christoforou and the refined Stronge law the impact number β
is the third axis (:mod:`impactmaps.maps.plastic_points`).
"""

from __future__ import annotations

import numpy as np
import pytest

from impactmaps.materials import IsotropicMaterial
from impactmaps.solvers.modal import ModalSettings, simulate
from impactmaps.targets import Beam, Plate

STEEL = IsotropicMaterial(youngs_modulus=210e9, poisson_ratio=0.3, density=7850.0)
ALUMINIUM = IsotropicMaterial(youngs_modulus=69e9, poisson_ratio=0.33, density=2700.0)


def _pair(kind):
    """Two physically different targets of one map family (sizes, materials, Poisson ratio
    of a Kirchhoff plate drop out of its normalised response only through D*, so keep ν)."""
    if kind == "beam":
        return (Beam.rectangular(0.5, 0.02, 0.01, STEEL, theory="euler"),
                Beam.rectangular(1.3, 0.05, 0.03, ALUMINIUM, theory="euler"))
    aluminium = IsotropicMaterial(youngs_modulus=69e9, poisson_ratio=0.3, density=2700.0)
    return Plate.isotropic(0.3, 0.3, 0.004, STEEL), Plate.isotropic(0.8, 0.8, 0.012, aluminium)


def _normalised(target, realised):
    from impactmaps.maps.plastic_points import plastic_summary

    result = simulate(target, realised.law, realised.mass, realised.velocity, settings=ModalSettings(),
                      record=False)
    return plastic_summary(result, realised)


@pytest.mark.parametrize("law", ["yc", "stronge"])
@pytest.mark.parametrize("kind", ["beam", "plate"])
@pytest.mark.parametrize("numbers", [(30.0, 0.3, 0.5), (400.0, 0.05, 0.03), (2.0, 2.0, 5.0)])
def test_equal_numbers_give_equal_normalised_response(kind, law, numbers):
    """Two physically different impacts (other size, material, impactor mass and speed,
    K_h and α_y) with equal (β, ζ, λ) give equal F_max/(m V0 ω_y), restitution, absorbed
    and transferred energy fractions, number of impacts and contact time to 1e-6: the
    similarity the plastic maps rest on (module docstring of plastic_points)."""
    from impactmaps.maps.plastic_points import plastic_numbers, realise_plastic

    beta, zeta, lam = numbers
    first, second = _pair(kind)
    one = realise_plastic(first, law, beta, zeta, lam, velocity=1.0)
    two = realise_plastic(second, law, beta, zeta, lam, velocity=7.3)
    assert abs(one.mass / two.mass - 1) > 0.5 and abs(float(one.numbers.force_scale) / two.numbers.force_scale - 1) > 0.5
    for realised, target in ((one, first), (two, second)):
        check = plastic_numbers(target, realised.law, realised.mass, realised.velocity)
        assert np.allclose([check.impact_number, check.loss_factor, check.relative_stiffness], numbers, rtol=1e-12)
    a, b = _normalised(first, one), _normalised(second, two)
    assert a["impacts"] == b["impacts"]
    for key in ("fmax_normalised", "restitution", "absorbed_energy_fraction", "energy_transferred_fraction",
                "contact_time_normalised", "peak_time_normalised"):
        assert a[key] == pytest.approx(b[key], rel=1e-6, abs=1e-9), key
    # the energy ledger closes: rebound + contact dissipation + structure = impact energy
    assert a["restitution"] ** 2 + a["absorbed_energy_fraction"] + a["energy_transferred_fraction"] == \
        pytest.approx(1.0, abs=1e-3)


def test_a_physical_case_is_realised_by_its_numbers():
    """A physical Yigit–Christoforou case (steel ball on a steel beam, from a case file) has
    numbers (β, ζ, λ); their realisation on the map's reference beam gives the same
    normalised answer — the route `lookup --case` takes."""
    from impactmaps.cases import parse_case
    from impactmaps.maps.plastic_points import plastic_numbers, realise_plastic
    from impactmaps.maps.structures import DEFAULT_STRUCTURES

    case = parse_case('[impactor]\nradius = 0.01\nmaterial = "structural-steel"\nvelocity = 0.05\n'
                      '[target]\ntype = "beam"\nlength = 0.6\nwidth = 0.02\nheight = 0.01\n'
                      'material = "structural-steel"\ntheory = "euler"\n[contact]\nlaw = "yigit-christoforou"\n')
    numbers = plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)
    reference = DEFAULT_STRUCTURES[0].build()
    realised = realise_plastic(reference, "yc", numbers.impact_number, numbers.loss_factor,
                               numbers.relative_stiffness)
    direct = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=ModalSettings(),
                      record=False)
    mapped = _normalised(reference, realised)
    assert direct.peak_force / numbers.force_scale == pytest.approx(mapped["fmax_normalised"], rel=1e-6)
    assert direct.restitution == pytest.approx(mapped["restitution"], rel=1e-6)


def test_numbers_refuse_other_laws():
    from impactmaps.contact.hertz import HertzContact
    from impactmaps.contact.stronge import StrongeContact
    from impactmaps.maps.plastic_points import plastic_law_of

    assert plastic_law_of(StrongeContact(1e11, 0.01, 3e8)) == "stronge"
    with pytest.raises(ValueError, match="plastic_pressure_factor"):
        plastic_law_of(StrongeContact(1e11, 0.01, 3e8, plastic_pressure_factor=3.0))
    with pytest.raises(ValueError, match="not an elastic-plastic law"):
        plastic_law_of(HertzContact(1e10))
