"""The elastic-plastic contact laws on clamped Mindlin plates, laminated and isotropic, as a
user runs them (``simulate`` on a case file): the energy ledger, the peak force and the
restitution against the elastic Hertz law of the same pair, the elastic limit (an infinite
yield strength gives the Hertz run), convergence in the time step and the modes; and
``lookup --case``, which refuses a plastic case on a Mindlin plate with its reason.
Figures: docs/plastic_maps.rst, "Plastic laws on clamped and laminated Mindlin plates"."""

from __future__ import annotations

import warnings
from dataclasses import replace

import pytest

from impactmaps.cases import parse_case
from impactmaps.solvers.modal import simulate

from ..helpers import ROOT

PLASTIC_LAWS = ("yigit-christoforou", "stronge", "epp")
DROP_WEIGHT = (ROOT / "examples" / "drop_weight_quasi_isotropic.toml").read_text()
#: A clamped 6061-T6 Mindlin plate struck by a 12.7 mm 52100 ball (the plate yields first).
CLAMPED_ALUMINIUM = """
[impactor]
radius = 0.00635
material = "bearing-steel-52100"
velocity = 5.0
[target]
type = "plate"
length_x = 0.2
length_y = 0.15
thickness = 0.01
material = "aluminium-6061-t6"
theory = "mindlin"
edges = "CCCC"
[contact]
law = "hertz"
"""


def case_of(text: str, law: str, contact: str = ""):
    return parse_case(text.replace('law = "hertz"', f'law = "{law}"\n{contact}'))


def run(case, **settings):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the cases' validity warnings (large deflection …) are not tested here
        return simulate(case.target, case.law, case.impactor_mass, case.velocity,
                        settings=replace(case.settings, **settings))


def ledger(result) -> float:
    """(kinetic energy in − out − energy left in the plate − contact dissipation)/energy in, from
    the solver's independent terms (the plate's modal energy; the law's closed-form dissipation)."""
    out = 0.5 * result.impactor_mass * result.rebound_velocity**2
    return (result.impact_energy - out - result.energy_transferred - result.contact_dissipation) / result.impact_energy


def test_a_plastic_case_on_a_mindlin_plate_is_refused_with_its_reason():
    """No plastic tile of a Mindlin plate: its contact patch makes the sphere radius a fourth number."""
    import impactmaps

    case = case_of(DROP_WEIGHT, "yigit-christoforou")
    with pytest.raises(ValueError, match="elastic-plastic impact on a target that simulate loads over the contact "
                                         "patch.*run `impactmaps simulate"):
        impactmaps.lookup(case=case)


@pytest.mark.parametrize("law, target_strength, contact, warned", [
    ("yigit-christoforou", "", "", True),
    ("epp", "", "", True),
    ("yigit-christoforou", "yield_strength = 4e8\n", "", False),
    ("stronge", "", "yield_strength = 4e8", False),
    ("hertz", "", "", False),
])
def test_a_laminate_without_strength_says_whose_yield_strength_the_law_takes(law, target_strength, contact, warned):
    """The drop-weight laminate has no yield strength: a plastic law then yields at the S235
    tup's (β = 65 at 10 J), which nothing said; every command now warns and names the keys."""
    from impactmaps.validity import case_warnings

    text = DROP_WEIGHT.replace(
        'layup = {', target_strength + 'layup = {', 1)
    messages = [m for m in case_warnings(case_of(text, law, contact)) if m.startswith("yield strength")]
    assert bool(messages) == warned
    if warned:
        assert "S_y = 2.35e+08 Pa" in messages[0] and "target.yield_strength" in messages[0]


@pytest.mark.slow
@pytest.mark.parametrize("text, strong, fine", [
    # the drop-weight example: CCCC Mindlin [45/0/−45/90]2s, 5.5 kg at 10 J (yield: the S235 tup's)
    (DROP_WEIGHT, "yield_strength = 1e12", {"cutoff_ratio": 320.0, "patch_cutoff_ratio": 160.0}),
    # the clamped 10 mm aluminium plate at 5 m/s: its basis is capped (186 modes) at the default
    (CLAMPED_ALUMINIUM, "yield_strength = 1e13", {"cutoff_ratio": 160.0, "patch_cutoff_ratio": 80.0}),
], ids=["cccc-mindlin-laminate", "cccc-mindlin-aluminium"])
def test_plastic_laws_on_clamped_mindlin_plates(text, strong, fine):
    """Measured (docs/plastic_maps.rst): ledgers ≤ 2e-5 (the plate's energy left at separation
    is integrated, hence not exact); plastic peaks 0.42–0.9975 of the Hertz peak, restitution
    0.007–0.51 below it; an infinite yield strength reproduces the Hertz run to 1e-9; a quarter
    time step moves the peak by ≤ 7.2e-4, the finer cut-off by ≤ 5.9e-3 (the laminate's epp;
    the Hertz run itself moves 1.2 % there)."""
    hertz = run(case_of(text, "hertz"))
    hertz_fine = run(case_of(text, "hertz"), **fine)
    for law in PLASTIC_LAWS:
        case = case_of(text, law)
        result = run(case)
        assert abs(ledger(result)) <= 1e-4, law
        assert result.contact_dissipation > 0.0 and result.permanent_indentation > 0.0
        assert result.peak_force <= hertz.peak_force, law
        assert result.restitution < hertz.restitution, law
        elastic = run(case_of(text, law, strong))
        assert elastic.peak_force == pytest.approx(hertz.peak_force, rel=1e-9), law
        assert elastic.restitution == pytest.approx(hertz.restitution, rel=1e-9), law
        assert abs(elastic.contact_dissipation) <= 1e-9 * hertz.impact_energy
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            stepped = simulate(case.target, case.law, case.impactor_mass, case.velocity, settings=case.settings,
                               time_step=0.25 * result.time_step)
        assert stepped.peak_force == pytest.approx(result.peak_force, rel=2e-3), law
        refined = run(case, **fine)
        assert refined.peak_force == pytest.approx(result.peak_force, rel=1e-2), law
        assert refined.peak_force <= hertz_fine.peak_force and refined.restitution < hertz_fine.restitution, law
        assert abs(ledger(refined)) <= 1e-4, law
