"""Every registered contact law, taken from the registry (a new law is picked up by
registering it), through the same invariants of construction and derived numbers; then
:meth:`ContactLaw.indentation_for_energy` against the three searches it replaces
(modal reference stiffness, compact energy balance, finite-difference stiffness bound)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import pytest

from impactmaps.contact import (
    ContactLaw,
    ContactPair,
    HertzContact,
    available_contact_laws,
    contact_law_class,
    effective_modulus,
    hertz_stiffness,
    law_for_sphere,
    law_options,
    yield_indentation,
)
from impactmaps.dimensionless import impact_number
from impactmaps.fd.energy import kernel_curve as _kernel_curve
from impactmaps.fd.timestep import contact_stiffness_bound as _contact_stiffness_bound
from impactmaps.closed_forms.halfspace import energy_balance_restitution
from impactmaps.solvers.modal import reference_contact_stiffness

from .test_contact_laws import ALUMINIUM, BALL, Material  # the 12.7 mm steel ball on aluminium

PAIR = ContactPair.from_sphere(BALL, ALUMINIUM)
LAWS = available_contact_laws()
#: Impact velocities [m/s] of the call-site comparisons: elastic to deep plastic indentation.
VELOCITIES = (0.05, 0.5, 3.0, 10.0)


def law_from_registry(name: str) -> ContactLaw:
    return contact_law_class(name).from_contact_pair(PAIR)


def indentation_scale(law: ContactLaw) -> float:
    """First yield for plastic laws, else the indentation storing 1 mJ [m]."""
    value = getattr(law, "yield_indentation", None)
    return float(np.asarray(value)) if value is not None else float(law.indentation_for_energy(1e-3))


def phase_boundaries(law: ContactLaw) -> list[float]:
    """Indentations [m] where a law's loading curve changes formula (from its attributes)."""
    names = ("yield_indentation", "plastic_indentation")
    return [float(np.asarray(getattr(law, n))) for n in names if getattr(law, n, None) is not None]


# -- construction -------------------------------------------------------------------------------
@pytest.mark.parametrize("name", LAWS)
def test_from_contact_pair_round_trips_with_law_for_sphere(name):
    """law_for_sphere is the registry's from_contact_pair on the pair of sphere + target
    (equal dataclasses), with and without every declared option given at its default;
    law_options lists target_radius, yield_strength exactly for laws that need one, then
    the law's own options, each with a unit string and a one-line meaning."""
    law = law_from_registry(name)
    assert type(law) is contact_law_class(name) and law.name == name
    assert law == law_for_sphere(name, BALL, ALUMINIUM)
    options = law_options(name)
    names = tuple(options)
    assert names[0] == "target_radius"
    assert ("yield_strength" in names) == contact_law_class(name).needs_yield_strength
    for key, option in options.items():
        assert option.name == key and isinstance(option.unit, str)
        assert option.meaning and "\n" not in option.meaning
    defaults = {key: o.default for key, o in options.items() if o.default is not None}
    assert law_for_sphere(name, BALL, ALUMINIUM, **defaults) == law
    own = {key: o.default for key, o in contact_law_class(name).options().items()}
    assert set(own) <= set(names)
    assert contact_law_class(name).from_contact_pair(PAIR, **own) == law
    with pytest.raises(ValueError, match="not known for law"):
        contact_law_class(name).from_contact_pair(PAIR, no_such_option=1.0)


@pytest.mark.parametrize("name", LAWS)
def test_yield_strength_needed_exactly_when_declared(name):
    """A pair with no yield strength builds the elastic laws and raises the missing-yield
    ValueError (naming yield_strength and its range) for laws that declare they need one."""
    elastic_pair = dataclasses.replace(PAIR, yield_strength=None)
    law_class = contact_law_class(name)
    if law_class.needs_yield_strength:
        with pytest.raises(ValueError, match=r"yield_strength is missing.*\(0, inf\)"):
            law_class.from_contact_pair(elastic_pair)
    else:
        assert law_class.from_contact_pair(elastic_pair) == law_from_registry(name)


def test_contact_pair_from_sphere():
    """E* from both materials (eq 8), R from 1/R = 1/R1 + 1/R2, S_y the softer material's
    unless overridden; bad input names the parameter."""
    assert PAIR.effective_modulus == float(effective_modulus(210e9, 0.30, 70e9, 0.33))
    assert PAIR.effective_radius == 0.00635 and PAIR.yield_strength == 2.8e8
    curved = ContactPair.from_sphere(BALL, ALUMINIUM, target_radius=0.00635, yield_strength=1e8)
    assert curved.effective_radius == pytest.approx(0.00635 / 2, rel=1e-15) and curved.yield_strength == 1e8
    assert ContactPair.from_sphere(BALL, Material(70e9, 0.3, 2700.0)).yield_strength == 1.2e9
    with pytest.raises(ValueError, match="is not a Sphere"):
        ContactPair.from_sphere(object(), ALUMINIUM)
    with pytest.raises(ValueError, match=r"yield_strength = -1.0.*\(0, inf\)"):
        ContactPair.from_sphere(BALL, ALUMINIUM, yield_strength=-1.0)
    with pytest.raises(ValueError, match=r"effective_radius = 0.0.*\(0, inf\)"):
        ContactPair(1e11, 0.0)
    with pytest.raises(ValueError, match=r"target_radius = -0.1.*\(0, inf\]"):
        ContactPair.from_sphere(BALL, ALUMINIUM, target_radius=-0.1)


# -- the same invariants for every law --------------------------------------------------------
@pytest.mark.parametrize("name", LAWS)
def test_force_invariants(name):
    """F(0) = 0 whatever the history; F ≥ 0 on a grid of (α, α_max); the virgin loading
    force is strictly increasing and continuous: across every phase boundary and at
    points of a log grid, the change over ±1e-9 α is at most 1.01 × slope × step (a
    jump would be O(F))."""
    law = law_from_registry(name)
    scale = indentation_scale(law)
    history = np.array([0.0, 0.3, 1.0, 3.0, 30.0, 300.0]) * scale
    assert np.all(law.force(0.0, history) == 0.0)
    alpha = np.linspace(-0.5, 400.0, 801) * scale
    grid_alpha, grid_max = np.meshgrid(alpha, history, indexing="ij")
    assert np.all(law.force(grid_alpha, np.maximum(grid_max, grid_alpha)) >= 0.0)
    assert np.all(law.force(grid_alpha, grid_max) >= 0.0)

    loading = np.geomspace(1e-3, 1e3, 2001) * scale
    assert np.all(np.diff(law.loading_force(loading)) > 0.0)
    eps = 1e-9
    points = np.concatenate((loading[::50], phase_boundaries(law)))
    jump = np.abs(law.loading_force(points * (1 + eps)) - law.loading_force(points * (1 - eps)))
    slope = np.maximum(law.tangent_stiffness(points * (1 + eps), points * (1 + eps)),
                       law.tangent_stiffness(points * (1 - eps), points * (1 - eps)))
    assert np.all(jump <= 1.01 * 2 * eps * points * slope)


@pytest.mark.parametrize("name", LAWS)
def test_dissipation_is_nonnegative(name):
    """A load–unload cycle dissipates ≥ 0 (to 1e-12 of the stored work) from the law's
    own energies, every law (the printed refined Stronge form did not:
    test_printed_stronge_law_creates_energy_just_above_yield)."""
    law = law_from_registry(name)
    peaks = np.geomspace(1e-2, 1e3, 61) * indentation_scale(law)
    assert np.all(law.dissipated_energy(peaks) >= -1e-12 * law.loading_energy(peaks))
    if law.elastic:
        assert np.all(law.dissipated_energy(peaks) == 0.0)


@pytest.mark.parametrize("name", LAWS)
def test_indentation_for_energy_inverts_loading_energy(name):
    """indentation_for_energy(loading_energy(α)) = α and back (rel. 1e-12: a few ulps of
    the closed forms or the Newton search, amplified by at most the 5/2 power of the
    Hertz branch); the law's own inverse equals the generic Newton search of the base
    class (rel. 1e-12); energy 0 gives 0; batched laws invert member by member; a
    negative energy is a ValueError naming ``energy``."""
    law = law_from_registry(name)
    peaks = np.geomspace(1e-3, 1e3, 97) * indentation_scale(law)
    peaks = np.concatenate((peaks, phase_boundaries(law)))
    energies = law.loading_energy(peaks)
    alpha = law.indentation_for_energy(energies)
    np.testing.assert_allclose(alpha, peaks, rtol=1e-12)
    np.testing.assert_allclose(law.loading_energy(alpha), energies, rtol=1e-12)
    np.testing.assert_allclose(ContactLaw.indentation_for_energy(law, energies), alpha, rtol=1e-12)
    assert float(law.indentation_for_energy(0.0)) == 0.0

    fields = {f.name: getattr(law, f.name) for f in dataclasses.fields(law)}
    batch = type(law)(**{k: np.array([v, 1.3 * v]) for k, v in fields.items()})
    members = [type(law)(**fields), type(law)(**{k: 1.3 * v for k, v in fields.items()})]
    energy = float(energies[40])
    expected = [float(m.indentation_for_energy(energy)) for m in members]
    np.testing.assert_allclose(batch.indentation_for_energy(energy), expected, rtol=1e-14)
    np.testing.assert_allclose(ContactLaw.indentation_for_energy(batch, energy), expected, rtol=1e-12)

    with pytest.raises(ValueError, match=r"energy = -1.0 is invalid.*\[0, inf\)"):
        law.indentation_for_energy(-1.0)


@pytest.mark.parametrize("name", LAWS)
def test_linear_stiffness_and_impact_number_match_the_law_kind(name):
    """linear_stiffness is K exactly when the loading force is K α (else None);
    impact_number is None exactly for elastic laws, otherwise β ∝ V0 and, for the
    plastic laws, equals β = V0/(ω α_y) of seed 001 eq 11 with K_h and α_y of the pair
    (eqs 7, 9) — bit for bit as impactmaps.cases.case_dimensionless computes it."""
    law = law_from_registry(name)
    alpha = np.array([0.1, 1.0, 10.0]) * indentation_scale(law)
    force = law.loading_force(alpha)
    linear = law.linear_stiffness
    if linear is None:
        assert not np.allclose(force / alpha, force[0] / alpha[0], rtol=1e-6)
    else:
        assert isinstance(linear, float)
        np.testing.assert_allclose(force, linear * alpha, rtol=1e-15)
    beta = law.impact_number(BALL.mass, 2.0)
    if law.elastic:
        assert beta is None
        return
    assert float(law.impact_number(BALL.mass, 4.0)) == pytest.approx(2 * float(beta), rel=1e-14)
    modulus, radius, strength = PAIR.effective_modulus, PAIR.effective_radius, PAIR.yield_strength
    alpha_y = yield_indentation(strength, radius, modulus)
    assert float(beta) == float(impact_number(2.0, hertz_stiffness(modulus, radius), alpha_y, BALL.mass))


# -- indentation_for_energy against the searches it replaces --------------------------------------
@pytest.mark.parametrize("name", LAWS)
@pytest.mark.parametrize("velocity", VELOCITIES)
def test_modal_reference_stiffness(name, velocity):
    """solvers.modal.reference_contact_stiffness = linear_stiffness, or the loading tangent
    at indentation_for_energy(½ m V0²). Linear: exactly. Otherwise rel. 1e-9: the modal
    search is Brent with rtol 1e-10 on α, and the tangent varies at most like α¹."""
    law = law_from_registry(name)
    current = reference_contact_stiffness(law, BALL.mass, velocity)
    if law.linear_stiffness is not None:
        assert law.linear_stiffness == current
        return
    alpha = law.indentation_for_energy(0.5 * BALL.mass * velocity**2)
    assert float(law.tangent_stiffness(alpha, alpha)) == pytest.approx(current, rel=1e-9)


@pytest.mark.parametrize("name", LAWS)
@pytest.mark.parametrize("velocity", VELOCITIES)
def test_compact_energy_balance(name, velocity):
    """solvers.halfspace.energy_balance_restitution = sqrt(recovered_energy(α_m)/(½ m V0²))
    with α_m = indentation_for_energy(½ m V0²): rel. 1e-12 (its Brent search stops at
    rtol 1e-14 on α_m)."""
    law = law_from_registry(name)
    energy = 0.5 * BALL.mass * velocity**2
    alpha = law.indentation_for_energy(energy)
    restitution = math.sqrt(float(law.recovered_energy(alpha)) / energy)
    assert restitution == pytest.approx(energy_balance_restitution(law, BALL.mass, velocity), rel=1e-12)


def _fd_bracket(law: ContactLaw, energy: float) -> float:
    """The indentation fd.timestep.contact_stiffness_bound doubles up to (1e-12 m × 2^k, the
    first whose loading work reaches ``energy``), from indentation_for_energy."""
    return 1e-12 * 2.0 ** max(0, math.ceil(math.log2(float(law.indentation_for_energy(energy)) / 1e-12)))


@pytest.mark.parametrize("name", LAWS)
@pytest.mark.parametrize("velocity", VELOCITIES)
def test_fd_stiffness_bound(name, velocity):
    """fd.timestep.contact_stiffness_bound is unchanged, bit for bit, when its doubling loop
    (trapezoid work on 4096 points, α = 1e-12 m × 2^k) is replaced by rounding
    indentation_for_energy(2 × ½ m V0²) up to the next 1e-12 m × 2^k: at that α the
    trapezoid work reaches the target and at α/2 it does not (the loop's stopping rule),
    and the bound computed from that α equals the function's."""
    law = law_from_registry(name)
    params = np.ascontiguousarray(law.kernel_parameters.reshape(-1))
    target = 2.0 * 0.5 * BALL.mass * velocity**2
    alpha = _fd_bracket(law, target)
    fraction = np.linspace(0.0, 1.0, 4097)[1:]

    def trapezoid_work(upper):
        grid = upper * fraction
        force = law.loading_force(grid)
        return np.trapezoid(np.concatenate(([0.0], force)), np.concatenate(([0.0], grid)))

    assert trapezoid_work(alpha) >= target > trapezoid_work(alpha / 2)
    grid = alpha * fraction
    _f, loading = _kernel_curve(law.kernel, params, grid, grid)
    _f, unloading = _kernel_curve(law.kernel, params, grid * (1.0 - 1e-12), np.full(grid.size, alpha))
    bound = float(max(np.max(loading), np.max(unloading)))
    assert bound == _contact_stiffness_bound(law, params, BALL.mass, velocity)


@dataclass(frozen=True)
class QuadratureHertz(HertzContact):
    """Hertz without its closed forms (not registered): the base class's quadrature
    energies and generic inversion, as a new law without closed forms would have."""

    loading_energy = ContactLaw.loading_energy
    recovered_energy = ContactLaw.recovered_energy
    indentation_for_energy = ContactLaw.indentation_for_energy


def test_generic_inversion_of_a_quadrature_law():
    """With Simpson loading work (2001 graded points), the generic Newton search still
    lands on the closed-form Hertz inverse (rel. 1e-9, the quadrature's accuracy on
    α^{3/2}); energies from µJ to kJ; an energy the law cannot absorb within 1000 m of
    indentation is a ValueError naming the energy."""
    closed = law_from_registry("hertz")
    quadrature = QuadratureHertz(closed.stiffness)
    energies = np.geomspace(1e-6, 1e3, 7)
    np.testing.assert_allclose(quadrature.indentation_for_energy(energies),
                               closed.indentation_for_energy(energies), rtol=1e-9)
    with pytest.raises(ValueError, match=r"energy = 1.0 J is not absorbed within 1000 m"):
        ContactLaw.indentation_for_energy(HertzContact(1e-30), 1.0)


def test_hertz_law_from_a_pair_knows_its_radius():
    """The Hertz law built from a sphere and a target carries the pair's effective radius
    (the contact patch radius is sqrt(R α)); a law given by its stiffness alone does not,
    and the radius is not part of the force law (same kernel parameters)."""
    from impactmaps.contact import HertzContact, Sphere, law_for_sphere
    from impactmaps.materials import material

    steel = material("structural-steel")
    law = law_for_sphere("hertz", Sphere(0.01, steel), steel, target_radius=0.03)
    assert law.contact_radius_scale == pytest.approx(1.0 / (1.0 / 0.01 + 1.0 / 0.03), rel=1e-15)
    bare = HertzContact(law.stiffness)
    assert bare.contact_radius_scale is None
    np.testing.assert_array_equal(bare.kernel_parameters, law.kernel_parameters)
