"""Case files (impactmaps.cases): the shipped examples, output round trips, validation.

The examples are run with coarse settings (few modes, short time limit, coarse FD grid):
these tests check the plumbing from TOML to solver to files, not convergence. The
physics checks use the exact half-space solutions (docs/physics_contract.md §3.1 and Hertz theory),
closed-form stiffnesses and the dimensionless definitions of seed 001.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from impactmaps.cases import (
    Case,
    case_dimensionless,
    load_case,
    parse_case,
    read_case_outputs,
    run_case,
    write_case_outputs,
)
from impactmaps.materials import material
from impactmaps.solvers.modal_settings import ConvergenceWarning

from ..helpers import EXAMPLES, case_text, strict_json_loads

MODAL_EXAMPLES = ["steel_plate_hertz.toml", "aluminium_beam_linear.toml",
                  "composite_plate_sun_chen.toml"]

SUMMARY_KEYS = ("peak_force_N", "contact_intervals_s", "first_contact_duration_s", "total_contact_time_s", "max_deflection_m",
                "impacts", "restitution", "energy_transferred_J", "beta", "lambda", "zeta",
                "lambda_basis", "contact_stiffness_N_m")
FD_SUMMARY_KEYS = ("peak_force_N", "contact_intervals_s", "restitution", "energy_loss_J",
                   "permanent_indentation_m", "beam_plastic_work_J", "energy_balance_error")


def _fast(case: Case) -> Case:
    """Coarse modal settings: few modes (the residual flexibility keeps the statics exact)."""
    return replace(case, settings=replace(case.settings, cutoff_ratio=6.0, min_modes=4,
                                          time_step_ratio=0.05))


# -------------------------------------------------------------------------------------
# Examples
# -------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", MODAL_EXAMPLES)
def test_modal_example_loads_runs_and_round_trips(name, tmp_path):
    """Each shipped modal example loads, runs (coarse settings) and writes its outputs.

    Invariants checked: energy balance of the run (exact-step integrator: < 1e-4 of the
    impact energy, far above its round-off and far below any plumbing error such as a
    wrong mass), positive peak force and deflection, and an exact round trip of
    summary.json (strict JSON, no NaN) and history.csv (same rows and columns).
    """
    case = _fast(load_case(EXAMPLES / name))
    assert isinstance(case, Case)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        result, summary = run_case(case)
    for key in SUMMARY_KEYS:
        assert key in summary
    assert summary["peak_force_N"] > 0
    assert summary["max_deflection_m"] > 0
    assert summary["impacts"] == len(summary["contact_intervals_s"]) >= 1
    assert summary["energy_balance_error"] < 1e-4
    paths = write_case_outputs(case, result, tmp_path)
    summary_text = paths["summary"].read_text()
    assert strict_json_loads(summary_text) == summary
    history, read_summary = read_case_outputs(tmp_path)
    assert read_summary == summary
    assert list(history.columns[:5]) == ["time_s", "force_N", "indentation_m",
                                         "impactor_displacement_m", "impactor_velocity_m_s"]
    assert "target_displacement_m" in history.columns
    assert len(history) == len(result.history)
    np.testing.assert_allclose(history["force_N"].to_numpy(), result.history["force_N"].to_numpy(),
                               rtol=1e-12, atol=0.0)
    assert paths["case"].read_text() == (EXAMPLES / name).read_text()
    # the written case file is itself a valid case
    assert load_case(paths["case"]).velocity == case.velocity


def test_fd_example_loads_runs_and_writes(tmp_path):
    """The finite-difference example loads and runs on a coarse grid for 1 ms.

    Checks: the beam built from the file (780 mm span, 60 × 27.8 mm section, simply
    supported, S235 yield stress), the required FD summary keys, the FD energy ledger
    (|error| < 1e-3 of the impact energy: the scheme's O(Δt²) contact-work mismatch is
    ~1e-6, a wrong mass or force sign gives O(1)), and strict JSON output when the
    record ends in contact (restitution undefined → null, never NaN).
    """
    case = load_case(EXAMPLES / "steel_beam_fd_stronge.toml", solver="fd")
    assert isinstance(case, Case) and case.solver_kind == "fd"
    assert case.fd_beam.length == pytest.approx(0.78)
    assert (case.fd_beam.width, case.fd_beam.height) == pytest.approx((0.060, 0.0278))
    assert case.fd_beam.supports == ("ss", "ss")
    assert case.fd_beam.yield_strength == pytest.approx(235e6)
    assert case.sphere.mass == pytest.approx(7850.0 * 4.0 / 3.0 * math.pi * 0.07**3)
    coarse = replace(case, fd_settings=replace(case.fd_settings, n_elements=60, n_half_layers=4),
                     duration=1.0e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        warnings.simplefilter("ignore", UserWarning)
        result, summary = run_case(coarse)
    for key in FD_SUMMARY_KEYS:
        assert key in summary
    assert summary["peak_force_N"] > 0
    assert abs(summary["energy_balance_error"]) < 1e-3
    paths = write_case_outputs(coarse, result, tmp_path)
    assert strict_json_loads(paths["summary"].read_text()) == summary
    history, _ = read_case_outputs(tmp_path)
    assert "target_displacement_m" in history.columns


# -------------------------------------------------------------------------------------
# Physics through the case file
# -------------------------------------------------------------------------------------
HALFSPACE = """
[impactor]
radius = 0.01
material = {{ youngs_modulus = 200e9, poisson_ratio = 0.3, density = 8000.0 }}
velocity = 2.0

[target]
type = "halfspace"
material = {{ youngs_modulus = 70e9, poisson_ratio = 0.33, density = 2700.0 }}

[contact]
{contact}
"""


def test_halfspace_linear_case_matches_exact_solution():
    """Half-space, linear contact: F(t) = m V ω sin(ωt), contact time π/ω (docs/physics_contract.md §3.1).

    The integrator is exact for a linear spring between events; the tolerance 1e-4
    covers the event location. λ and ζ are undefined for a half-space (None).
    """
    case = parse_case(HALFSPACE.format(contact='law = "linear"\nstiffness = 2.0e7'))
    result, summary = run_case(case)
    mass = 8000.0 * 4.0 / 3.0 * math.pi * 0.01**3
    omega = math.sqrt(2.0e7 / mass)
    assert summary["peak_force_N"] == pytest.approx(mass * 2.0 * omega, rel=1e-4)
    assert summary["first_contact_duration_s"] == pytest.approx(math.pi / omega, rel=1e-4)
    assert summary["restitution"] == pytest.approx(1.0, rel=1e-4)
    assert summary["lambda"] is None and summary["zeta"] is None and summary["beta"] is None
    assert summary["lambda_basis"] == "linear law stiffness K"


def test_halfspace_hertz_case_matches_hertz_theory():
    """Half-space, Hertz contact built from the two materials (seed 001 eqs 7–8).

    Energy gives α_m = (5 m V²/(4 K_h))^{2/5} and F_max = K_h α_m^{3/2} exactly; the
    contact time is t_c = 2 (α_m/V) ∫0^1 dx / sqrt(1 − x^{5/2}) (Johnson 1985, §11.4).
    K_h is recomputed here from E, ν and R independently of the package. Tolerance 2e-4
    (time-step resolution of the peak and of the separation event).
    """
    case = parse_case(HALFSPACE.format(contact='law = "hertz"'))
    result, summary = run_case(case)
    mass = 8000.0 * 4.0 / 3.0 * math.pi * 0.01**3
    e_star = 1.0 / ((1 - 0.3**2) / 200e9 + (1 - 0.33**2) / 70e9)
    k_h = 4.0 / 3.0 * math.sqrt(0.01) * e_star
    alpha_m = (5.0 * mass * 2.0**2 / (4.0 * k_h)) ** 0.4
    integral, _ = quad(lambda x: 1.0 / math.sqrt(1.0 - x**2.5), 0.0, 1.0)
    assert summary["peak_force_N"] == pytest.approx(k_h * alpha_m**1.5, rel=2e-4)
    assert summary["first_contact_duration_s"] == pytest.approx(2.0 * alpha_m / 2.0 * integral, rel=2e-4)


PLATE = case_text("""
    type = "plate"
    length_x = 0.3
    length_y = 0.3
    thickness = 0.003
    material = "aluminium-6061-t6"
    edges = "SSSS"
""", law="{law}", name="test plate", after="""
    [solver]
    cutoff_ratio = 6
""")


def test_dimensionless_numbers_of_a_plate_case():
    """λ, ζ, β of a case against independent closed forms.

    * K_st of an isotropic square SS plate at its centre is D/(0.011601 a²)
      (docs/physics_contract.md §3.3; the constant is given to 5 digits, hence rel 1e-4);
    * K_y = 1.5 K_h sqrt(α_y), α_y = 0.68 π² S_y² R/E*² with S_y the *smaller* yield
      strength of the pair (S235 sphere 235 MPa < 6061-T6 276 MPa; seed 001 eqs 9, 10);
    * ζ = (1/16) sqrt(m K/(ρh D)) (seed 001 eq 34), β = V/(ω_h α_y),
      ω_h² = K_h α_y^{1/2}/m (eqs 11, 12).
    """
    case = parse_case(PLATE.format(law="yigit-christoforou"))
    numbers = case_dimensionless(case)
    steel, aluminium = material("structural-steel"), material("aluminium-6061-t6")
    h, a, radius = 0.003, 0.3, 0.005
    D = aluminium.youngs_modulus * h**3 / (12 * (1 - aluminium.poisson_ratio**2))
    k_static = D / (0.011601 * a**2)
    e_star = 1.0 / ((1 - steel.poisson_ratio**2) / steel.youngs_modulus
                    + (1 - aluminium.poisson_ratio**2) / aluminium.youngs_modulus)
    k_h = 4.0 / 3.0 * math.sqrt(radius) * e_star
    alpha_y = 0.68 * math.pi**2 * 235e6**2 * radius / e_star**2
    k_y = 1.5 * k_h * math.sqrt(alpha_y)
    mass = steel.density * 4.0 / 3.0 * math.pi * radius**3
    assert numbers["contact_stiffness_N_m"] == pytest.approx(k_y, rel=1e-12)
    assert numbers["static_stiffness_N_m"] == pytest.approx(k_static, rel=1e-4)
    assert numbers["lambda"] == pytest.approx(k_static / k_y, rel=1e-4)
    rho_h = aluminium.density * h
    assert numbers["zeta"] == pytest.approx(math.sqrt(mass * k_y / (rho_h * D)) / 16.0, rel=1e-12)
    omega_h = math.sqrt(k_h * math.sqrt(alpha_y) / mass)
    assert numbers["beta"] == pytest.approx(1.0 / (omega_h * alpha_y), rel=1e-12)
    assert "K_y" in numbers["lambda_basis"]


def test_lambda_falls_back_to_the_solver_reference_stiffness():
    """Without any yield strength, λ and ζ use the solver's reference stiffness (documented)."""
    text = PLATE.format(law="hertz").replace(
        'material = "structural-steel"',
        'material = { youngs_modulus = 210e9, poisson_ratio = 0.3, density = 7850.0 }', 1
    ).replace('material = "aluminium-6061-t6"',
              'material = { youngs_modulus = 68.9e9, poisson_ratio = 0.33, density = 2700.0 }')
    case = parse_case(text)
    numbers = case_dimensionless(case)
    assert numbers["contact_stiffness_N_m"] == numbers["reference_contact_stiffness_N_m"]
    assert numbers["beta"] is None
    assert "reference" in numbers["lambda_basis"]


def test_solver_duration_is_the_time_limit():
    """solver.duration [s] becomes the solver's time limit: a run shorter than the contact
    stops at the first step past it (hit_time_limit, ConvergenceWarning)."""
    text = HALFSPACE.format(contact='law = "linear"\nstiffness = 2.0e7') + "\n[solver]\nduration = 1e-5\n"
    case = parse_case(text)
    with pytest.warns(ConvergenceWarning):
        result, summary = run_case(case)
    assert summary["time_limit_reached"] is True
    assert 1e-5 <= summary["end_time_s"] < 1e-5 + summary["time_step_s"] * (1 + 1e-9)


def test_layup_and_plies_describe_the_same_laminate():
    """A layup table and the equivalent explicit ply list give identical plates."""
    base = case_text("""
        type = "plate"
        length_x = 0.2
        length_y = 0.2
        {laminate}
    """, radius=0.00635, velocity=3.0)
    layup = 'layup = { ply = "t300-934", angles_deg = [0, 90], symmetric = true, ply_thickness = 0.0002 }'
    plies = ("plies = [" + ", ".join(
        f'{{ material = "t300-934", angle_deg = {a}, thickness = 0.0002 }}' for a in (0, 90, 90, 0)
    ) + "]")
    first = parse_case(base.format(laminate=layup))
    second = parse_case(base.format(laminate=plies))
    assert first.target == second.target
    assert first.target.thickness == pytest.approx(0.0008)
    assert first.law == second.law


# -------------------------------------------------------------------------------------
# Validation: bad keys and values name the key path
# -------------------------------------------------------------------------------------
GOOD = case_text("""
    type = "plate"
    length_x = 0.3
    length_y = 0.2
    thickness = 0.003
    material = "aluminium-6061-t6"
    impact_point = [0.15, 0.1]
""")


def test_the_reference_text_is_valid():
    """The unmodified text used by the error tests loads (so each error is caused by its edit)."""
    case = parse_case(GOOD)
    assert case.target.impact_point == (0.15, 0.1)


@pytest.mark.parametrize(
    "old, new, expected",
    [
        ("[impactor]", "[impacter]", ["impacter", "impactor"]),
        ("length_x = 0.3", "lenght_x = 0.3", ["target.lenght_x", "length_x"]),
        ("radius = 0.005", "radius = -0.005", ["impactor.radius", "-0.005", "(0, 10]"]),
        ("velocity = 1.0", 'velocity = "fast"', ["impactor.velocity", "fast", "not a number"]),
        ("velocity = 1.0\n", "", ["impactor.velocity", "required"]),
        ('law = "hertz"', 'law = "hurtz"', ["contact.law", "hurtz", "'hertz'"]),
        ('law = "hertz"', 'law = "hertz"\nyield_strength = 1e8', ["contact.yield_strength", "stiffness"]),
        ('type = "plate"', 'type = "shell"', ["target.type", "shell", "'beam'"]),
        ('material = "aluminium-6061-t6"', 'material = "unobtainium"',
         ["target.material", "unobtainium", "structural-steel"]),
        ('material = "aluminium-6061-t6"', 'material = "t300-934"', ["target.material", "ply", "layup"]),
        ('material = "structural-steel"',
         "material = { youngs_modulus = 2e11, poisson_ratio = 0.6, density = 7800.0 }",
         ["impactor.material.poisson_ratio", "0.6"]),
        ('material = "structural-steel"',
         "material = { youngs_modulus = 2e11, poisson_ratio = 0.3, densty = 7800.0 }",
         ["impactor.material.densty", "density"]),
        ("impact_point = [0.15, 0.1]", "impact_point = [0.15, 0.25]",
         ["target.impact_point[1]", "0.25", "[2e-07, 0.1999998]"]),
        ("impact_point = [0.15, 0.1]", "impact_point = [0.15]", ["target.impact_point", "2 entries"]),
        ("velocity = 1.0", "velocity = 1.0\nmass = 0.01\ndensity = 7000.0",
         ["impactor.mass", "impactor.density"]),
        ("thickness = 0.003", "thickness = 0", ["target.thickness", "(0, 10000]"]),
        ('law = "hertz"', 'law = "hertz"\n[solver]\ncutoff_ratio = -1', ["solver.cutoff_ratio", "(0, 10000]"]),
        ('law = "hertz"', 'law = "hertz"\n[solver]\nmin_modes = 2.5', ["solver.min_modes", "integer"]),
        ('law = "hertz"', 'law = "hertz"\n[output]\nhistory_stride = 0', ["output.history_stride", "0"]),
        ('law = "hertz"', 'law = "hertz"\n[fd]\nn_elements = 2', ["fd.n_elements", "[4, inf)"]),
        ('law = "hertz"', 'law = "hertz"\n[solver]\ncheck_convergence = "yes"',
         ["solver.check_convergence", "boolean"]),
    ],
)
def test_bad_keys_and_values_name_the_key(old, new, expected):
    """Every invalid edit raises ValueError whose message names the key path and the value
    or the valid range/choices (so typos and out-of-range values cannot pass)."""
    assert old in GOOD
    text = GOOD.replace(old, new, 1)
    with pytest.raises(ValueError) as info:
        parse_case(text)
    message = str(info.value)
    for fragment in expected:
        assert fragment in message, f"{fragment!r} not in {message!r}"


@pytest.mark.parametrize(
    "laminate, expected",
    [
        ('layup = { ply = "t300-934", angle_deg = [0, 90] }', ["target.layup.angle_deg", "angles_deg"]),
        ('layup = { ply = "t300-934", angles_deg = [0, "ninety"] }', ["target.layup.angles_deg[1]"]),
        ('layup = { ply = "structural-steel", angles_deg = [0] }', ["target.layup.ply", "isotropic"]),
        ('plies = [{ material = "t300-934", thickness = -1.0 }]', ["target.plies[0].thickness", "(0, 10000]"]),
        ('plies = []', ["target.plies", "non-empty"]),
        ('layup = { ply = "t300-934", angles_deg = [0] }\nthickness = 0.001', ["target.thickness", "plies"]),
        ('layup = { ply = "t300-934", angles_deg = [0] }\nmaterial = "structural-steel"',
         ["exactly one of", "target.material"]),
    ],
)
def test_bad_laminate_descriptions_name_the_key(laminate, expected):
    """Laminate tables are validated like the rest (key path in the message)."""
    text = case_text("""
        type = "plate"
        length_x = 0.2
        length_y = 0.2
        {laminate}
    """).format(laminate=laminate)
    with pytest.raises(ValueError) as info:
        parse_case(text)
    for fragment in expected:
        assert fragment in str(info.value), f"{fragment!r} not in {str(info.value)!r}"


def test_load_case_errors_name_the_file(tmp_path):
    """load_case prefixes the file name; a missing file and invalid TOML are ValueErrors."""
    path = tmp_path / "broken.toml"
    path.write_text(GOOD.replace("radius = 0.005", "radius = 0.0"))
    with pytest.raises(ValueError, match=r"broken\.toml: impactor\.radius = 0\.0"):
        load_case(path)
    path.write_text("[impactor\nradius = 1")
    with pytest.raises(ValueError, match="not valid TOML"):
        load_case(path)
    with pytest.raises(ValueError, match="does not exist"):
        load_case(tmp_path / "missing.toml")


FD_GOOD = case_text("""
    type = "beam"
    length = 0.5
    width = 0.02
    height = 0.01
    material = "structural-steel"
""", radius=0.01, after="""
    [solver]
    duration = 0.001
    [fd]
    n_elements = 40
""")


@pytest.mark.parametrize(
    "old, new, expected",
    [
        ('type = "beam"', 'type = "plate"', ["target.type", "'beam'"]),
        ("duration = 0.001", "time_step_ratio = 0.01", ["solver.duration", "required"]),
        ('material = "structural-steel"\n[contact]',
         'material = { youngs_modulus = 2e11, poisson_ratio = 0.3, density = 7800.0 }\n[contact]',
         ["target.material.yield_strength", "required"]),
        ("n_elements = 40", "n_elements = 40\nplastik = true", ["fd.plastik", "plastic"]),
        ("n_elements = 40", "n_elements = 40\ndamping_per_length = -1.0",
         ["fd.damping_per_length", "[0, inf)"]),
        ("height = 0.01", "height = 0.01\nsupports = \"pinned\"", ["target.supports", "'ss'"]),
    ],
)
def test_bad_fd_cases_name_the_key(old, new, expected):
    """FD-specific requirements (beam target, duration, yield strength, [fd] keys)."""
    assert parse_case(FD_GOOD, solver="fd").fd_beam.n_elements == 40
    assert old in FD_GOOD
    with pytest.raises(ValueError) as info:
        parse_case(FD_GOOD.replace(old, new, 1), solver="fd")
    for fragment in expected:
        assert fragment in str(info.value), f"{fragment!r} not in {str(info.value)!r}"


def test_fd_support_codes_map_to_beam_ends():
    """Modal support codes map to the (left, right) ends of the FD beam."""
    case = parse_case(FD_GOOD.replace("height = 0.01", 'height = 0.01\nsupports = "cf"'), solver="fd")
    assert case.fd_beam.supports == ("cc", "free")


# -------------------------------------------------------------------------------------
# The benchmark laminate: infinite-plate check (and a correction to docs/physics_contract.md eq 31)
# -------------------------------------------------------------------------------------
def _infinite_plate_peak(mass, velocity, hertz, admittance):
    """Peak Hertz force [N] on an infinite Kirchhoff plate, ẇ = Y F (solve_ivp, tight tolerances)."""
    from scipy.integrate import solve_ivp

    def rhs(_t, y):
        alpha = y[0] - y[2]
        force = hertz * alpha**1.5 if alpha > 0 else 0.0
        return [y[1], -force / mass, admittance * force]

    times = np.linspace(0.0, 60e-6, 6001)
    solution = solve_ivp(rhs, (0.0, times[-1]), [0.0, velocity, 0.0], t_eval=times, rtol=1e-10,
                         atol=1e-15, max_step=2e-8)
    alpha = solution.y[0] - solution.y[2]
    return float(np.max(hertz * np.clip(alpha, 0.0, None) ** 1.5))


def test_benchmark_laminate_first_peak_is_the_infinite_orthotropic_plate():
    """Sun & Chen set-up, Kirchhoff: the first force peak (≈22 μs, before any reflection
    matters — it is the same for 200 and 400 mm plates) equals that of an *infinite*
    specially orthotropic plate, whose point admittance is real and frequency-independent,
    Y = 1/(8 sqrt(ρh D_eff)), with

        1/sqrt(D_eff) = (1/2π) ∫0^{2π} dθ / sqrt(D11 c⁴ + 2(D12 + 2D66) c²s² + D22 s⁴)
                      ⇔ D_eff = sqrt(D11 D22) (π / (2 K(m)))²,  m = (1 − A)/2,
        A = (D12 + 2D66)/sqrt(D11 D22)

    (pole residue of the 2-D Fourier integral; K the complete elliptic integral). Modal
    (finite plate, 227+ modes, residual flexibility) and infinite-plate peaks agree to 1e-4.
    The effective stiffness printed as seed 001 eq (31) / docs/physics_contract.md §3.3,
    D* = ½(D12 + 2D66 + sqrt(D11 D22)), is exact only for A = 1 (isotropic); for this
    laminate (A = 0.215) it is 23 % low and predicts a peak force 9.5 % low — the test
    asserts that too, as the proof that eq (31) is not the infinite-plate stiffness.
    """
    from scipy.special import ellipk

    case = load_case(EXAMPLES / "composite_plate_sun_chen.toml")
    plate = replace(case.target, theory="kirchhoff")
    result, summary = run_case(replace(case, target=plate,
                                       settings=replace(case.settings, cutoff_ratio=20.0)))
    d11, d22, h = plate.D11, plate.D22, plate.D12 + 2.0 * plate.D66
    g = lambda t: d11 * np.cos(t) ** 4 + 2 * h * np.cos(t) ** 2 * np.sin(t) ** 2 + d22 * np.sin(t) ** 4  # noqa: E731
    integral, _ = quad(lambda t: 1.0 / math.sqrt(g(t)), 0.0, 2.0 * math.pi, limit=200)
    d_eff = (2.0 * math.pi / integral) ** 2
    anisotropy = h / math.sqrt(d11 * d22)
    assert d_eff == pytest.approx(math.sqrt(d11 * d22) * (math.pi / (2.0 * ellipk((1.0 - anisotropy) / 2.0))) ** 2,
                                  rel=1e-10)
    peak = _infinite_plate_peak(case.impactor_mass, case.velocity, case.law.stiffness,
                                1.0 / (8.0 * math.sqrt(plate.mass_per_area * d_eff)))
    assert summary["peak_force_N"] == pytest.approx(peak, rel=1e-4)
    d_star_eq31 = 0.5 * (h + math.sqrt(d11 * d22))
    assert plate.effective_bending_stiffness == pytest.approx(d_star_eq31, rel=1e-12)
    peak_eq31 = _infinite_plate_peak(case.impactor_mass, case.velocity, case.law.stiffness,
                                     1.0 / (8.0 * math.sqrt(plate.mass_per_area * d_star_eq31)))
    assert (summary["peak_force_N"] - peak_eq31) / summary["peak_force_N"] > 0.05


def test_beam_cases_isotropic_and_laminated():
    """Beam targets from a case file.

    Isotropic (the aluminium example): K_st at mid-span of the SS Timoshenko beam is
    1/K = L³/(48EI) + L/(4kGA) (docs/physics_contract.md §3.2, narrow beam EI = E b h³/12), so
    λ·K = K_st to round-off. Laminated: a layup builds Beam.from_laminate with
    b·D11 of the laminate (seed 001 (16)–(17)); its static stiffness uses the same
    closed form with EI → b D11 and kGA → k b A55.
    """
    case = load_case(EXAMPLES / "aluminium_beam_linear.toml")
    numbers = case_dimensionless(case)
    al = material("aluminium-6061-t6")
    length, width, height = 0.5, 0.025, 0.010
    inertia = width * height**3 / 12
    shear = 5.0 / 6.0 * al.youngs_modulus / (2 * (1 + al.poisson_ratio)) * width * height
    k_static = 1.0 / (length**3 / (48 * al.youngs_modulus * inertia) + length / (4 * shear))
    assert numbers["static_stiffness_N_m"] == pytest.approx(k_static, rel=1e-9)
    assert numbers["lambda"] * numbers["contact_stiffness_N_m"] == pytest.approx(k_static, rel=1e-9)
    text = case_text("""
        type = "beam"
        length = 0.3
        width = 0.02
        supports = "ss"
        layup = { ply = "t300-934", angles_deg = [0, 90, 0], symmetric = true }
    """)
    laminated = parse_case(text)
    laminate = laminated.target_material
    bd11, kba55 = 0.02 * laminate.D11, 5.0 / 6.0 * 0.02 * laminate.A55
    expected = 1.0 / (0.3**3 / (48 * bd11) + 0.3 / (4 * kba55))
    assert laminated.target.static_stiffness() == pytest.approx(expected, rel=1e-9)
    with pytest.raises(ValueError, match=r"target\.height"):
        parse_case(text.replace('width = 0.02', 'width = 0.02\nheight = 0.0015'))


def test_fd_case_defaults_to_refined_stronge():
    """Issue: the FD beam's contact is the refined Stronge law by default. The shipped
    FD example without its [contact] table builds the same law as with law = "stronge"."""
    text = (EXAMPLES / "steel_beam_fd_stronge.toml").read_text()
    assert '[contact]\nlaw = "stronge"\n' in text
    default = parse_case(text.replace('[contact]\nlaw = "stronge"\n', ""), solver="fd")
    explicit = parse_case(text, solver="fd")
    assert default.law_name == "stronge"
    np.testing.assert_array_equal(default.law.kernel_parameters, explicit.law.kernel_parameters)


def test_cantilever_tip_impact_is_a_valid_case():
    """Bug fixed by deriving the schema from the constructors: the case reader refused
    x0 = L, which :class:`Beam` accepts for a cantilever (a tip impact); the beam now
    checks its own impact point, and a supported end stays refused with the key path."""
    text = case_text("""
        type = "beam"
        length = 0.3
        width = 0.02
        height = 0.01
        material = "structural-steel"
        supports = "cf"
        impact_position = 0.3
    """)
    case = parse_case(text)
    assert case.target.impact_position == pytest.approx(0.3)
    with pytest.raises(ValueError, match=r"target\.impact_position = 0\.3"):
        parse_case(text.replace('supports = "cf"', 'supports = "ss"'))


def test_solver_keys_are_the_settings_fields():
    """[solver] accepts exactly the ModalSettings fields (plus kind, duration, time_step):
    a field added to the settings is a case key without another list to update."""
    from dataclasses import fields

    from impactmaps.solvers.modal_settings import ModalSettings

    for f in fields(ModalSettings):
        value = str(f.default).lower() if isinstance(f.default, bool) else repr(f.default)
        case = parse_case(GOOD.replace('law = "hertz"', f'law = "hertz"\n[solver]\n{f.name} = {value}', 1))
        assert getattr(case.settings, f.name) == f.default
    with pytest.raises(ValueError, match=r"solver\.kind = 'explicit'.*'modal', 'fd'"):
        parse_case(GOOD.replace('law = "hertz"', 'law = "hertz"\n[solver]\nkind = "explicit"', 1))


def test_summary_says_whether_the_run_converged(tmp_path):
    """summary.json flags the convergence check (issue 'What a user meets'): True when the
    re-run with twice the cut-off and half the step moved F̄max by ≤ the tolerance, None
    when no check was asked for (never a silent claim)."""
    checked = parse_case(GOOD.replace('law = "hertz"', 'law = "hertz"\n[solver]\ncheck_convergence = true', 1))
    result, summary = run_case(checked)
    assert summary["converged"] is True and result.converged is True
    paths = write_case_outputs(checked, result, tmp_path)
    assert strict_json_loads(paths["summary"].read_text())["converged"] is True
    _, unchecked = run_case(parse_case(GOOD))
    assert unchecked["converged"] is None
