"""Where the Timoshenko/Mindlin theories stop: the thickness-shear cut-off, the unresolved
map points beyond it, and no classical asymptote for shear-deformable targets."""

from __future__ import annotations

import math

import numpy as np
import pytest

from impactmaps.contact.linear import LinearContact
from impactmaps.dimensionless import realise
from impactmaps.maps.family.accuracy import STATUSES
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.sweep import solve_points
from impactmaps.materials import material
from impactmaps.solvers import mode_budget
from impactmaps.solvers.modal import ModalSettings
from impactmaps.targets.shear_range import (SHEAR_VALIDITY_FRACTION, beyond_shear_theory,
                                            has_classical_asymptote, thickness_shear_frequency)
from impactmaps.targets.beams.beam import Beam
from impactmaps.targets.plates.plate import Plate

STEEL = material("structural-steel")


def _isotropic_cutoff(h: float) -> float:
    """sqrt(12 k G/(ρ h²)) [rad/s], k = 5/6: the same for a plate and a rectangular beam."""
    shear_modulus = STEEL.youngs_modulus / (2.0 * (1.0 + STEEL.poisson_ratio))
    return math.sqrt(12.0 * (5.0 / 6.0) * shear_modulus / (STEEL.density * h * h))


def test_thickness_shear_frequency_of_plates_and_beams():
    h = 0.01
    plate = Plate.isotropic(0.2, 0.2, h, STEEL, theory="mindlin")
    beam = Beam.rectangular(0.2, 0.02, h, STEEL, theory="timoshenko")
    assert thickness_shear_frequency(plate) == pytest.approx(_isotropic_cutoff(h), rel=1e-12)
    assert thickness_shear_frequency(beam) == pytest.approx(_isotropic_cutoff(h), rel=1e-12)
    for classical in (Plate.isotropic(0.2, 0.2, h, STEEL, theory="kirchhoff"),
                      Beam.rectangular(0.2, 0.02, h, STEEL, theory="euler")):
        assert thickness_shear_frequency(classical) is None
        assert not beyond_shear_theory(classical, 1e12)
        assert has_classical_asymptote(classical)
    cutoff = thickness_shear_frequency(plate)
    assert not beyond_shear_theory(plate, SHEAR_VALIDITY_FRACTION * cutoff)
    assert beyond_shear_theory(plate, 1.001 * SHEAR_VALIDITY_FRACTION * cutoff)
    assert not has_classical_asymptote(plate) and not has_classical_asymptote(beam)


def test_no_classical_asymptote_for_a_mindlin_plate():
    """Past the mode cap the Kirchhoff plate takes its infinite-plate asymptote; the Mindlin
    plate of the same geometry does not (its point-load response is not the dashpot)."""
    stiffness, mass = 1e8, 1e-6
    wanted = 40.0 * math.sqrt(stiffness / mass)
    kirchhoff = Plate.isotropic(0.5, 0.5, 0.01, STEEL, theory="kirchhoff")
    mindlin = Plate.isotropic(0.5, 0.5, 0.01, STEEL, theory="mindlin")
    plan = mode_budget.plan_basis(kirchhoff, LinearContact(stiffness), mass, 1.0, wanted, max_modes=2000)
    assert plan.method == "infinite-structure-asymptote"
    try:
        plan = mode_budget.plan_basis(mindlin, LinearContact(stiffness), mass, 1.0, wanted, max_modes=2000)
    except mode_budget.ModeBudgetError as error:
        assert "no infinite-structure solution answers for a mindlin target" in str(error)
    else:
        assert plan.method == "modal+residual-capped"


@pytest.mark.parametrize("name", ["plate-ssss-mindlin-s20", "beam-ss-timoshenko-s20"])
def test_map_points_beyond_the_theory_are_unresolved(name):
    """A light-impactor point whose contact frequency passes a quarter of the
    thickness-shear cut-off has no value (every result missing: NaN in the dataset, empty
    in CSV, null in JSON) and the status `unresolved`; its neighbour inside the range is
    computed as usual."""
    structure = structure_from_name(name)
    target = structure.build()
    cutoff = thickness_shear_frequency(target)
    lam = 1.0
    # ζ at which the contact frequency is the validity limit (ω is a power of ζ at fixed λ)
    omega_1, omega_10 = (float(realise(target, zeta, lam).contact_frequency) for zeta in (1.0, 10.0))
    power = math.log10(omega_10 / omega_1)
    zeta_limit = (SHEAR_VALIDITY_FRACTION * cutoff / omega_1) ** (1.0 / power)
    beyond, inside = solve_points(structure, [(0.5 * zeta_limit, lam), (2.0 * zeta_limit, lam)], ModalSettings())
    assert STATUSES[beyond["status"]] == "unresolved"
    assert np.isnan(beyond["fmax_normalised"]) and beyond["method"] == -1 and beyond["n_modes"] == -1
    assert np.isfinite(beyond["reflection_time_normalised"])
    assert STATUSES[inside["status"]] in ("converged", "refined", "sensitive")
    assert 0.0 < inside["fmax_normalised"] <= 1.0


def test_validity_warns_when_the_contact_passes_the_shear_theory():
    """A light steel ball on a thick Mindlin plate: a contact of a few microseconds excites
    waves shorter than the thickness — the validity check says so; a heavy slow ball on the
    same plate does not trigger it."""
    import warnings

    from impactmaps.contact import Sphere, law_for_sphere
    from impactmaps.solvers.modal import simulate
    from impactmaps.validity import validity_warnings

    plate = Plate.isotropic(0.2, 0.2, 0.02, STEEL, theory="mindlin")
    messages = {}
    for radius, velocity in ((0.001, 1.0), (0.02, 0.5)):
        sphere = Sphere(radius, STEEL)
        law = law_for_sphere("hertz", sphere, STEEL)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = simulate(plate, law, sphere.mass, velocity, record=False)
        messages[radius] = [m for m in validity_warnings(sphere, STEEL, law, plate, result)
                            if m.startswith("structural theory")]
    assert messages[0.001] and "thickness-shear cut-off" in messages[0.001][0]
    assert not messages[0.02]
