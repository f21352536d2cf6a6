"""The contract every registered contact law keeps (docs/physics_contract.md §2, issue 28 step 1).

Property-based over random contact pairs: both bodies elastic or one rigid (E from 1 to
1000 GPa, ν 0.2–0.45), Y/E* from 1e-4 to 3e-2, R from 0.1 mm to 1 m, maximum
indentations δ_m from 0 to 10⁴ δ_y, where ``δ_y = R (π 1.6 Y/(2E*))²`` is the Hertz
first-yield indentation of the pair (p0 = 1.6 Y) — one scale for every law. For each law
of the registry (a new registered law is covered without editing this file):

* loading force never above the elastic reference at the same indentation;
* unloading starts at (δ_m, F_m): the unloading curve meets the loading curve there;
* unloading returns no more work than loading absorbed (quadrature of the kernel);
* permanent indentation δ_f: 0 ≤ δ_f ≤ δ_m, the kernel's force is zero at δ_f and
  positive above it, and δ_f never decreases when δ_m grows;
* force continuous along loading and unloading (no jump between grid points: the force
  step equals the trapezoid integral of the kernel's tangent stiffness to within half
  the change of that stiffness, which a kink can reach and a jump exceeds);
* reloading below δ_m follows the unloading curve, and beyond δ_m the loading curve
  (driven step by step as the solvers drive a law, updating α_max);
* on a half-space (``halfspace_impact``): e ≤ 1 and peak force ≤ the elastic peak.

The elastic reference of a plastic law is Hertz, ``(4/3) E* R^{1/2} δ^{3/2}``, of the
same pair. An elastic law (``law.elastic``) is its own reference: for the ``linear`` law
``F = K_y α`` (seed 001 eq 18), a contact stiffness rather than a sphere, "never above
the elastic force" has no Hertz meaning (K_y α exceeds Hertz below 2.25 α_y by design);
what the contract demands of it, and of ``hertz``, is reversibility — unloading retraces
loading exactly, δ_f = 0, no work lost, e = 1 and the peak force of its own energy
balance on the half-space.

Each law sees ≥ 2000 random cases per run (8 hypothesis examples × 256 cases drawn from
a hypothesis-chosen seed, plus up to 16 hypothesis-shrinkable cases each), vectorised
through the law's numba kernel; ``derandomize=True`` makes CI deterministic. The last
tests run the same checks on the refined Stronge law as printed (tests/printed_stronge.py)
and on a law with a force jump and a shrinking dent, and show that the contract catches them.
"""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numba
import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st
from scipy.integrate import simpson

from impactmaps.contact import (
    ContactPair,
    available_contact_laws,
    contact_law_class,
    effective_modulus,
)
from impactmaps.contact.base import evaluate_kernel
from impactmaps.contact.hertz import HertzContact
from impactmaps.closed_forms.halfspace import halfspace_impact, hertz_peak_force

from ..printed_stronge import PrintedStrongeContact

LAWS = available_contact_laws()
# no shrinking: a failure report already names the case; shrinking 256-case batches takes minutes
CONTRACT = settings(derandomize=True, database=None, deadline=None, max_examples=8,
                    phases=(Phase.explicit, Phase.generate))
HALFSPACE = settings(derandomize=True, database=None, deadline=None, max_examples=25,
                     phases=(Phase.explicit, Phase.generate))
BATCH = 256
UNITS = 10  # unit-interval numbers per case (see cases_from_units)
QUADRATURE_POINTS = 401
EPS = 1e-9

unit = st.floats(0.0, 1.0, allow_nan=False)
explicit_cases = st.lists(st.tuples(*[unit] * UNITS), max_size=16)


# -- random contact pairs --------------------------------------------------------------------------
def _log_uniform(u, low, high):
    return np.exp(np.log(low) + u * (np.log(high) - np.log(low)))


def cases_from_units(u: np.ndarray) -> dict:
    """Map unit numbers, shape (n, UNITS), onto contact pairs and load histories (SI).

    Columns: body kind (both elastic / sphere rigid / target rigid), E of sphere and
    target (log-uniform 1–1000 GPa), their ν (0.2–0.45), Y/E* (log-uniform 1e-4–3e-2),
    R (log-uniform 1e-4–1 m), δ_m/δ_y (0 in 3 % of cases, else log-uniform 1e-3–1e4), a
    growth factor q of δ_m (log-uniform 1e-9–1) and a valley fraction r (0–1).
    """
    u = np.atleast_2d(np.asarray(u, float))
    kind = np.minimum((3 * u[:, 0]).astype(int), 2)
    e_sphere, e_target = _log_uniform(u[:, 1], 1e9, 1e12), _log_uniform(u[:, 2], 1e9, 1e12)
    nu_sphere, nu_target = 0.2 + 0.25 * u[:, 3], 0.2 + 0.25 * u[:, 4]
    modulus = np.where(kind == 0, effective_modulus(e_sphere, nu_sphere, e_target, nu_target),
                       np.where(kind == 1, effective_modulus(e_target, nu_target),  # rigid sphere
                                effective_modulus(e_sphere, nu_sphere)))  # rigid target
    strength = _log_uniform(u[:, 5], 1e-4, 3e-2) * modulus
    radius = _log_uniform(u[:, 6], 1e-4, 1.0)
    yield_delta = radius * (math.pi * 1.6 * strength / (2.0 * modulus)) ** 2
    ratio = np.where(u[:, 7] < 0.03, 0.0, _log_uniform(np.clip((u[:, 7] - 0.03) / 0.97, 0, 1), 1e-3, 1e4))
    sphere_modulus = np.where(kind == 1, np.inf, e_sphere)  # the bodies, for a law that needs more than E*
    target_modulus = np.where(kind == 2, np.inf, e_target)
    return {"modulus": modulus, "radius": radius, "strength": strength, "yield_delta": yield_delta,
            "sphere_modulus": sphere_modulus, "sphere_poisson": nu_sphere,
            "target_modulus": target_modulus, "target_poisson": nu_target,
            "peak": ratio * yield_delta, "growth": _log_uniform(u[:, 8], 1e-9, 1.0), "valley": u[:, 9]}


def draw_cases(seed: int, explicit) -> dict:
    rng = np.random.default_rng(seed)
    units = rng.random((BATCH, UNITS))
    if explicit:
        units = np.vstack([units, np.asarray(explicit, float)])
    return cases_from_units(units)


def batched_law(cls, cases):
    """One law object holding every case (its fields as arrays), built pair by pair.

    The laws are built from ``ContactPair(E*, R, Y)`` with their default options; a law
    that needs more of the bodies finds their moduli and Poisson ratios in ``cases``."""
    laws = [cls.from_contact_pair(ContactPair(float(m), float(r), float(y)))
            for m, r, y in zip(cases["modulus"], cases["radius"], cases["strength"])]
    values = {}
    for field in dataclasses.fields(laws[0]):
        column = [getattr(law, field.name) for law in laws]
        values[field.name] = None if all(v is None for v in column) else np.array(column, float)
    return cls(**values)


def hertz_force(cases, delta):
    """Elastic reference (4/3) E* R^{1/2} δ^{3/2} [N]; ``delta`` has the cases on axis 0."""
    modulus = cases["modulus"].reshape((-1,) + (1,) * (np.ndim(delta) - 1))
    radius = cases["radius"].reshape(modulus.shape)
    return 4.0 / 3.0 * modulus * np.sqrt(radius) * np.clip(delta, 0.0, None) ** 1.5


# -- the contract --------------------------------------------------------------------------------
def _kernel(law, alpha, alpha_max):
    """Force and stiffness of a batched law; cases on axis 0 of ``alpha``/``alpha_max``."""
    params = np.asarray(law.kernel_parameters, float)
    params = params.reshape(params.shape + (1,) * (np.ndim(alpha) - 1))
    return evaluate_kernel(law.kernel, params, alpha, alpha_max)


def _jumps(law, delta, history, force, stiffness):
    """True for the rows (cases) where the force jumps between neighbouring grid points.

    Over an interval of length h where the stiffness k is monotone, ΔF = ∫k dδ lies
    within ½|Δk| h of the trapezoid ½(k_i + k_{i+1}) h; a jump adds to ΔF. Intervals that
    break this bound (a jump, or a kink with an interior stiffness extremum) are bisected
    60 times into the half that breaks it more: a jump J stays in ΔF while ½|Δk| h and
    max(k) h shrink with h, so a jump above 1e-9 of the force is told from a kink.
    ``history`` is α_max for each point (the loading curve: ``delta`` itself).
    """
    h = np.diff(delta, axis=-1)
    trapezoid = 0.5 * (stiffness[..., 1:] + stiffness[..., :-1]) * h
    mismatch = np.abs(np.diff(force, axis=-1) - trapezoid)
    scale = np.max(np.abs(force), axis=-1, keepdims=True) + 1e-300
    flagged = mismatch > 0.5 * np.abs(np.diff(stiffness, axis=-1)) * h * (1 + 1e-9) + 1e-12 * scale
    rows, cols = np.nonzero(flagged)
    if rows.size == 0:
        return np.zeros(delta.shape[0], bool)
    params = np.asarray(law.kernel_parameters, float)
    params = np.ascontiguousarray(params.reshape(params.shape[0], -1)[:, rows] if params.ndim > 1 else params)
    low, high = delta[rows, cols], delta[rows, cols + 1]
    past = history[rows, cols + 1] if np.ndim(history) else history
    fixed = not np.array_equal(history, delta)  # unloading: α_max fixed; loading: α_max = α

    def evaluate(alpha):
        return evaluate_kernel(law.kernel, params, alpha, past if fixed else alpha)

    f_low, k_low = evaluate(low)
    f_high, k_high = evaluate(high)
    for _ in range(60):
        mid = 0.5 * (low + high)
        f_mid, k_mid = evaluate(mid)
        left = np.abs(f_mid - f_low - 0.5 * (k_mid + k_low) * (mid - low))
        right = np.abs(f_high - f_mid - 0.5 * (k_high + k_mid) * (high - mid))
        go_left = left >= right
        high, f_high, k_high = np.where(go_left, mid, high), np.where(go_left, f_mid, f_high), np.where(go_left, k_mid, k_high)
        low, f_low, k_low = np.where(go_left, low, mid), np.where(go_left, f_low, f_mid), np.where(go_left, k_low, k_mid)
    jump = np.abs(f_high - f_low) > 1e-9 * scale[rows, 0] + 2.0 * np.maximum(np.abs(k_low), np.abs(k_high)) * (high - low)
    found = np.zeros(delta.shape[0], bool)
    found[rows[jump]] = True
    return found


def violations(cls, cases) -> dict[str, np.ndarray]:
    """Per contract clause, a boolean array: True for the cases that break it."""
    law = batched_law(cls, cases)
    peak = cases["peak"]
    yielded = peak > 0.0
    s = np.concatenate((np.geomspace(1e-4, 1.0, 32), np.linspace(0.02, 0.98, 49)))
    s = np.sort(np.concatenate((s, 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, QUADRATURE_POINTS))))))
    delta = peak[:, None] * s[None, :]
    load, load_k = _kernel(law, delta, delta)
    unload, _ = _kernel(law, delta, np.broadcast_to(peak[:, None], delta.shape))
    peak_force, peak_k = _kernel(law, peak, peak)
    out = {}

    # loading never above the elastic reference (plastic laws: Hertz; elastic laws: reversible)
    if law.elastic:
        out["elastic law not reversible"] = np.any(unload != load, axis=1)
    else:
        reference = hertz_force(cases, delta)
        out["loading above Hertz"] = np.any(load > reference * (1 + 1e-12), axis=1)
    out["negative or non-finite force"] = np.any(~np.isfinite(load) | (load < 0) | (unload < 0), axis=1)

    # unloading starts at (δ_m, F_m)
    just_below, below_k = _kernel(law, peak * (1 - EPS), peak)
    allowed = 1.01 * EPS * peak * np.maximum(below_k, peak_k) + 1e-14 * peak_force
    out["unloading does not start at (δ_m, F_m)"] = yielded & (np.abs(just_below - peak_force) > allowed)

    # work: returned ≤ absorbed (same nodes; Simpson error ≪ 1e-6 of the work)
    absorbed = simpson(load, x=delta, axis=1)
    returned = simpson(unload, x=delta, axis=1)
    out["returns more work than loading absorbed"] = returned > absorbed * (1 + 1e-6) + 1e-300

    # permanent indentation
    final = np.asarray(law.permanent_indentation(peak), float)
    at_final, _ = _kernel(law, final, peak)
    above_final, _ = _kernel(law, final + 1e-6 * (peak - final), peak)
    out["permanent indentation outside [0, δ_m]"] = ~((final >= 0.0) & (final <= peak))
    out["kernel force not zero at the permanent indentation"] = at_final > 1e-9 * peak_force
    out["kernel force not positive above the permanent indentation"] = yielded & (above_final <= 0.0)
    grown = peak * (1.0 + cases["growth"])
    out["permanent indentation decreases as δ_m grows"] = (
        np.asarray(law.permanent_indentation(grown), float) < final - 1e-12 * grown)
    history = cases["yield_delta"][None, :] * np.geomspace(1e-3, 1e4, 48)[:, None]  # (48, cases)
    scan = np.asarray(law.permanent_indentation(history), float)
    out["permanent indentation decreases as δ_m grows"] |= np.any(np.diff(scan, axis=0) < -1e-12 * history[1:], axis=0)

    # continuity along loading and along unloading (from δ_f to δ_m)
    out["force jumps on the loading curve"] = yielded & _jumps(law, delta, delta, load, load_k)
    span = final[:, None] + (peak - final)[:, None] * s[None, :]
    span_history = np.broadcast_to(peak[:, None], span.shape)
    back, back_k = _kernel(law, span, span_history)
    out["force jumps on the unloading curve"] = yielded & _jumps(law, span, span_history, back, back_k)

    # reloading below δ_m follows unloading, driven as a solver drives it
    valley = cases["valley"] * peak
    down = np.linspace(peak, valley, 17)  # (17, cases); back up through the same indentations
    state = peak.copy()
    forces = []
    for row in np.concatenate((down, down[::-1], grown[None, :])):
        forces.append(_kernel(law, row, state)[0])
        state = np.maximum(state, row)
    forces = np.array(forces)
    out["reloading leaves the unloading curve"] = np.any(forces[:17] != forces[17:34][::-1], axis=0)
    out["loading past δ_m is not the virgin curve"] = forces[34] != _kernel(law, grown, grown)[0]
    return out


def assert_keeps_contract(name, cases):
    failed = {clause: mask for clause, mask in violations(contact_law_class(name), cases).items() if np.any(mask)}
    report = []
    for clause, mask in failed.items():
        i = int(np.flatnonzero(mask)[0])
        report.append(f"{clause}: {int(mask.sum())} case(s), e.g. E* = {cases['modulus'][i]:.6g} Pa, "
                      f"R = {cases['radius'][i]:.6g} m, Y = {cases['strength'][i]:.6g} Pa, "
                      f"δ_m/δ_y = {cases['peak'][i] / cases['yield_delta'][i]:.6g}")
    assert not failed, f"law {name!r} breaks the contract:\n" + "\n".join(report)


@pytest.mark.parametrize("name", LAWS)
@CONTRACT
@given(seed=st.integers(0, 2**32 - 1), explicit=explicit_cases)
def test_contract(name, seed, explicit):
    """Every registered law keeps the force–indentation contract on 256+ random cases per example."""
    assert_keeps_contract(name, draw_cases(seed, explicit))


@pytest.mark.parametrize("name", LAWS)
def test_contract_at_the_corners(name):
    """The corners of the case box (every unit number 0 or 1 in turn, δ_m exactly 0, δ_y,
    10⁴ δ_y), where a random draw rarely lands."""
    corners = np.array([[a, b, c, a, b, c, a, b, c, b] for a in (0.0, 1.0) for b in (0.0, 1.0) for c in (0.0, 1.0)])
    cases = cases_from_units(np.vstack([corners, np.full((1, UNITS), 0.5)]))
    for ratio in (0.0, 1.0, 1e4):
        cases["peak"] = ratio * cases["yield_delta"]
        assert_keeps_contract(name, cases)


@pytest.mark.parametrize("name", LAWS)
def test_loading_curve_continuous_on_a_dense_scan(name):
    """No jump anywhere on the loading curve (10⁻⁴–10⁴ δ_y, 40 000 geometric points, six
    pairs) nor on the unloading curves from 60 δ_m: a branch boundary at a fixed δ/δ_y
    falls between two grid points 1.0005 apart, where a jump of 1e-3 of the force shows."""
    cases = cases_from_units(np.linspace(0.05, 0.95, 6)[:, None] * np.ones(UNITS))
    law = batched_law(contact_law_class(name), cases)
    delta = cases["yield_delta"][:, None] * np.geomspace(1e-4, 1e4, 40000)[None, :]
    force, stiffness = _kernel(law, delta, delta)
    assert not np.any(_jumps(law, delta, delta, force, stiffness))
    for ratio in np.geomspace(1e-2, 1e4, 60):
        peak = ratio * cases["yield_delta"]
        final = np.asarray(law.permanent_indentation(peak), float)
        span = final[:, None] + (peak - final)[:, None] * np.linspace(0.0, 1.0, 2001)[None, :]
        history = np.broadcast_to(peak[:, None], span.shape)
        force, stiffness = _kernel(law, span, history)
        assert not np.any(_jumps(law, span, history, force, stiffness)), ratio


# -- half-space ------------------------------------------------------------------------------------
def halfspace_violations(law, mass, velocity, pair) -> list[str]:
    """Contract clauses broken by one half-space impact (solver tolerance 1e-12; slack 1e-8)."""
    result = halfspace_impact(law, mass, velocity)
    broken = []
    if law.elastic:
        energy = 0.5 * mass * velocity**2
        own_peak = float(law.loading_force(law.indentation_for_energy(energy)))
        if abs(result.restitution - 1.0) > 1e-8:
            broken.append(f"elastic law: e = {result.restitution!r} ≠ 1")
        if abs(result.peak_force - own_peak) > 1e-8 * own_peak:
            broken.append(f"elastic law: peak {result.peak_force!r} N ≠ its energy balance {own_peak!r} N")
        return broken
    hertz = float(hertz_peak_force(mass, velocity, 4.0 / 3.0 * math.sqrt(pair.effective_radius) * pair.effective_modulus))
    if not result.restitution <= 1.0 + 1e-8:
        broken.append(f"e = {result.restitution!r} > 1")
    if not result.peak_force <= hertz * (1.0 + 1e-8):
        broken.append(f"peak force {result.peak_force!r} N > elastic Hertz peak {hertz!r} N")
    return broken


def yield_velocity(pair, mass):
    """V_y [m/s]: the speed whose Hertz impact just reaches δ_y (p0 = 1.6 Y)."""
    yield_delta = pair.effective_radius * (math.pi * 1.6 * pair.yield_strength / (2 * pair.effective_modulus)) ** 2
    energy = 0.4 * 4.0 / 3.0 * pair.effective_modulus * math.sqrt(pair.effective_radius) * yield_delta**2.5
    return math.sqrt(2.0 * energy / mass)


@pytest.mark.parametrize("name", LAWS)
@HALFSPACE
@given(units=st.tuples(*[unit] * UNITS), speed=unit, mass=unit)
def test_halfspace_restitution_and_peak(name, units, speed, mass):
    """Half-space impacts at V/V_y log-uniform in 10⁻²–10⁴ and m in 1 g–10 kg: e ≤ 1 and
    the peak force ≤ the elastic Hertz peak (plastic laws); e = 1 and the law's own
    energy-balance peak (elastic laws)."""
    case = cases_from_units(np.array([units]))
    pair = ContactPair(float(case["modulus"][0]), float(case["radius"][0]), float(case["strength"][0]))
    law = contact_law_class(name).from_contact_pair(pair)
    m = float(_log_uniform(mass, 1e-3, 10.0))
    velocity = float(_log_uniform(speed, 1e-2, 1e4)) * yield_velocity(pair, m)
    assert not halfspace_violations(law, m, velocity, pair)


# -- the test of the test ----------------------------------------------------------------------------
ISSUE_PAIR = ContactPair(float(effective_modulus(200e9, 0.3, 70e9, 0.33)), 0.00635, 275e6)
ISSUE_MASS = 7850.0 * 4.0 / 3.0 * math.pi * 0.00635**3


def test_contract_catches_the_printed_stronge_law():
    """The printed refined Stronge law (tests/printed_stronge.py) fails the contract: its
    loading curve rises above Hertz, a cycle just past yield returns more work than it
    absorbed, and on the issue-28 half-space (12.7 mm steel ball on aluminium) at 2 V_y
    it rebounds faster than it came (e = 1.158) with a peak above Hertz's. The package's
    law passes the same checks on the same cases."""
    cases = draw_cases(2028, [])
    broken = violations(PrintedStrongeContact, cases)
    assert np.any(broken["loading above Hertz"])
    assert np.any(broken["returns more work than loading absorbed"])
    assert not any(np.any(mask) for mask in violations(contact_law_class("stronge"), cases).values())
    velocity = 2.0 * yield_velocity(ISSUE_PAIR, ISSUE_MASS)
    printed = PrintedStrongeContact.from_contact_pair(ISSUE_PAIR)
    assert len(halfspace_violations(printed, ISSUE_MASS, velocity, ISSUE_PAIR)) == 2
    assert not halfspace_violations(contact_law_class("stronge").from_contact_pair(ISSUE_PAIR),
                                    ISSUE_MASS, velocity, ISSUE_PAIR)


@numba.njit(cache=False)
def _broken_kernel(alpha, alpha_max, params):
    """Hertz, 1 % stronger beyond α = params[1] (a jump), unloading shifted by a dent that
    shrinks beyond 10 params[1]."""
    if alpha <= 0.0:
        return 0.0, 0.0
    stiffness, mark = params[0], params[1]
    peak = max(alpha, alpha_max)
    final = 0.0 if peak <= mark else (0.1 * (peak - mark) if peak <= 10 * mark else max(0.9 * mark - 0.1 * (peak - 10 * mark), 0.0))
    factor = 1.01 if peak > mark else 1.0
    if alpha < alpha_max:  # Hertz-shaped unloading from (α_max, F_m) to the dent
        peak_force = factor * stiffness * alpha_max**1.5
        gap = alpha - final
        if gap <= 0.0:
            return 0.0, 0.0
        span = alpha_max - final
        return peak_force * (gap / span) ** 1.5, 1.5 * peak_force * math.sqrt(gap) / span**1.5
    return factor * stiffness * alpha**1.5, 1.5 * factor * stiffness * math.sqrt(alpha)


@dataclasses.dataclass(frozen=True)
class _BrokenContact(HertzContact):
    """Not registered: a Hertz law with a force jump at δ_y and a shrinking dent."""

    name: ClassVar[str] = "broken"
    elastic: ClassVar[bool] = False
    mark: ClassVar[float] = 1e-6  # the indentation of the jump [m], set by the test
    kernel = staticmethod(_broken_kernel)

    @property
    def kernel_parameters(self):
        mark = np.asarray(self.effective_radius, float) * 0.0 + _BrokenContact.mark
        return np.stack(np.broadcast_arrays(np.asarray(self.stiffness, float), mark))

    def permanent_indentation(self, max_indentation):
        peak = np.clip(np.asarray(max_indentation, float), 0.0, None)
        mark = _BrokenContact.mark
        return np.where(peak <= mark, 0.0, np.where(peak <= 10 * mark, 0.1 * (peak - mark),
                                                    np.clip(0.9 * mark - 0.1 * (peak - 10 * mark), 0.0, None)))


def test_contract_catches_a_jump_and_a_shrinking_dent():
    """A law whose force jumps by 1 % at one indentation and whose dent shrinks past
    another is caught by the continuity and the monotone-dent clauses (one pair, so the
    marks sit at fixed indentations)."""
    cases = cases_from_units(np.full((1, UNITS), 0.5))
    _BrokenContact.mark = float(cases["yield_delta"][0])
    many = {key: np.repeat(value, 400) for key, value in cases.items()}
    many["peak"] = many["yield_delta"] * np.geomspace(1e-2, 1e3, 400)
    broken = violations(_BrokenContact, many)
    assert np.any(broken["force jumps on the loading curve"])
    assert np.any(broken["permanent indentation decreases as δ_m grows"])
