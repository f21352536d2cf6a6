"""Laminates have no 3D-consistent near field under the contact patch; its size is estimated
with the isotropic kernel and a run says so when it is large (issue 39; docs/contact_patch.rst,
"Laminates: the near field estimated").
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pytest

from impactmaps._checks import ModelValidityWarning
from impactmaps.cases import parse_case
from impactmaps.contact import Sphere, law_for_sphere
from impactmaps.materials import material
from impactmaps.solvers.modal import simulate
from impactmaps.solvers.modal_settings import ModalSettings
from impactmaps.targets.plates import near_field
from impactmaps.targets.plates.plate import Plate
from impactmaps.validity import NEAR_FIELD_SHARE_LIMIT

from ..helpers import case_text

ALUMINIUM = material("aluminium-6061-t6")

#: The [target] lines of a 150 × 100 mm SSSS Mindlin [0/90]4s AS4/3501-6 plate of ply thickness {ply}.
_LAMINATE_TARGET = """
    type = "plate"
    length_x = 0.15
    length_y = 0.10
    theory = "mindlin"
    edges = "SSSS"
    layup = {{ ply = "as4-3501-6", angles_deg = [0, 90, 0, 90, 0, 90, 0, 90], symmetric = true, ply_thickness = {ply} }}
"""


def test_the_isotropic_weight_is_the_near_field_of_an_isotropic_plate():
    """:func:`isotropic_factor` (E cancels) equals the plate's own :func:`near_field_factor`."""
    plate = Plate.isotropic(0.3, 0.3, 0.004, ALUMINIUM, theory="mindlin")
    k = np.geomspace(10.0, 2e4, 9)
    expected = near_field.near_field_factor(plate, k)
    assert near_field.isotropic_factor(k, 0.004, ALUMINIUM.poisson_ratio, plate.shear_correction) == pytest.approx(
        expected, rel=1e-12)


def test_the_estimate_on_an_isotropic_plate_is_its_near_field():
    """On an isotropic SSSS plate the estimate (its own ν) is what the near field takes from the
    static compliance under the patch: the modes' Σ φ²/ω² plus the residual with the near field
    against the same plate made (to 1e-9) non-isotropic, which has none."""
    plate = Plate.isotropic(0.3, 0.3, 0.004, ALUMINIUM, theory="mindlin")
    without = replace(plate, D22=plate.D22 * (1.0 + 1e-9))
    assert near_field.isotropic_constants(without) is None
    radius = 4e-4

    def static(target):
        basis = target.modes(2e5, contact_radius=radius)
        return basis.retained_compliance + basis.residual_compliance

    removed = static(without) - static(plate)
    assert near_field.near_field_estimate(plate, radius, ALUMINIUM.poisson_ratio) == pytest.approx(removed, rel=1e-5)


def test_a_laminate_under_the_patch_warns_with_its_estimated_share():
    """A thin cross-ply plate struck by a light ball: the estimated near field is ≈ 20 % of the
    contact's compliance at the peak force, above the limit: one ModelValidityWarning naming the
    share. The isotropic plate of the same size (near field built) and a point load do not."""
    case = parse_case(case_text(_LAMINATE_TARGET.format(ply=0.000125), radius=0.00635, mass=0.01, velocity=2.0,
                                   name="cross-ply"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate(case.target, case.law, case.impactor_mass, case.velocity, record=False)
    said = [str(w.message) for w in caught if w.category is ModelValidityWarning and "near field" in str(w.message)]
    assert len(said) == 1
    share = near_field.near_field_estimate(case.target, result.settings["contact_radius_m"]) \
        * result.peak_force / result.max_indentation
    assert NEAR_FIELD_SHARE_LIMIT < share < 0.5
    assert f"{share:.0%} of the contact's own compliance" in said[0]
    isotropic = Plate.isotropic(0.15, 0.10, 0.002, ALUMINIUM, theory="mindlin")
    law = law_for_sphere("hertz", Sphere(0.00635, material("structural-steel")), ALUMINIUM)
    for target, settings in ((isotropic, None), (case.target, ModalSettings(contact_patch="point"))):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            simulate(target, law, 0.01, 2.0, record=False, settings=settings)
        assert not [w for w in caught if "near field" in str(w.message)]
