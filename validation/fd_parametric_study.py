"""Parametric study with the finite-difference elastic-plastic beam (seed 000's findings).

Reproduces, qualitatively, the parametric findings stated in the abstract of seed 000
("Transient impact response analysis of an elastic-plastic beam"): the effects of the
impactor mass, impact velocity, beam plasticity and impact location on the peak force,
the contact time, the energy loss and the Newton coefficient of restitution, and the
*jump* of the energy loss / restitution caused by impact-induced waves (sub-impacts).
Only the abstract and nomenclature of seed 000 are available, so there are no printed
numbers to compare with; the figures show trends and mark the wave-return time.

Case (what is and is not known)
-------------------------------
* Beam: simply supported, span 780 mm, section 60 mm × 27.8 mm, as in that group's drop
  tests (task brief). Seed 000's nomenclature lists the width B and the height H but the
  OCR text gives no values; **assumed**: width b = 60 mm, height h = 27.8 mm (the bar
  lies flat and is struck on its 60 mm face).
* Steel: E = 206 GPa, ρ = 7850 kg/m³, ν = 0.3 (typical structural-steel values, e.g.
  EN 1993-1-1 §3.2.6 gives E = 210 GPa; 206 GPa is the other common value, the brief's
  range 206–210 GPa). Yield stress σ_y = 235 MPa is **assumed** (nominal S235 of
  EN 10025-2); seed 000's value is unknown here.
* Sphere: steel, radius 12.5 mm (**assumed**), rigid body; its mass is varied
  independently of its radius (a sphere-tipped drop weight), so that the mass study
  changes the mass alone. Contact: refined Stronge law (docs/physics_contract.md §2, defaults), with
  the beam's yield stress (the hardened sphere is taken not to yield).
* Drop test: gravity on the sphere; the sphere touches the beam at t = 0 with V0.
  Base case: m = 1 kg, V0 = 2 m/s, mid-span (velocity/plasticity study: m = 5 kg, so
  that the beam yields). Record: 20 ms (≈ 2 periods of the first
  beam mode); restitution e = (sphere velocity at its final separation in the record)/V0.

Wave-return time
----------------
A flexural pulse of duration T_c has its energy near ω ≈ π/T_c (the half-sine
convention used here); it travels with the Rayleigh-beam group velocity c_g(k) at the
wavenumber k of that frequency and returns from the nearest support after
``t_r = 2 d / c_g``, d = distance from the impact point to that support. When the first
contact lasts longer than t_r, the reflection arrives while the sphere is still in
contact; once the beam swings back into the sphere, sub-impacts appear, and the energy
loss and e jump. The figures mark t_r (computed from each run's first-contact duration)
and the runs with more than one contact.

Contact laws compared
---------------------
``--study laws`` runs the mass, velocity (elastic-plastic and elastic beam) and location
sweeps with each consistent elastic-plastic contact law of the package: the refined
Stronge law (defaults), Yigit–Christoforou (same E*, R, Y) and ``epp`` (the beam's
ν = 0.3; the steel sphere's share of 1/E*, E*(1 − ν²)/E = 0.5: an elastic sphere as stiff
as the beam), and writes ``fd_parametric_laws.csv`` (one row per run) and
``fd_parametric_laws.png`` (peak force, energy loss and restitution of each sweep, the
three laws side by side).

Output: ``figures/fd_force_histories.png``, ``figures/fd_mass_effect.png``,
``figures/fd_velocity_effect.png``, ``figures/fd_location_effect.png`` (``--study stronge``)
and ``figures/fd_parametric_laws.csv``, ``figures/fd_parametric_laws.png`` (``--study laws``).
Runtime ≈ 30 s on 2 cores for the Stronge study (98 runs of 20 ms at N_l = 200, 2N_h = 20),
three times the runs for the law comparison.

    python validation/fd_parametric_study.py [--out-dir DIR] [--study {all,stronge,laws}]
    python validation/fd_parametric_study.py --smoke    # runs of 4 ms on a coarse grid (seconds)
"""

from __future__ import annotations

import pathlib
import time
import warnings
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

from impactmaps.contact import StrongeContact, YigitChristoforouContact, effective_modulus  # noqa: E402
from impactmaps.contact.plastic.epp import EppContact  # noqa: E402
from impactmaps.fd import FDBeam, simulate_fd  # noqa: E402

from _script_options import parse  # noqa: E402

FIGURES = pathlib.Path(__file__).resolve().parents[1] / "figures"

LENGTH, WIDTH, HEIGHT = 0.78, 0.06, 0.0278  # m; width/height assignment assumed (docstring)
MODULUS, DENSITY, POISSON = 206e9, 7850.0, 0.3  # typical steel
YIELD = 235e6  # Pa, assumed (S235 nominal)
SPHERE_RADIUS = 0.0125  # m, assumed
BASE_MASS, BASE_VELOCITY = 1.0, 2.0  # kg, m/s
PLASTICITY_MASS = 5.0  # kg: heavy enough for the beam to yield in the velocity study
DURATION = 20e-3  # s


@dataclass(frozen=True)
class Size:
    """Resolution and extent of the study: record length [s], grid, runs per sweep."""

    duration: float = DURATION
    n_elements: int = 200
    n_half_layers: int = 10
    masses: int = 28
    velocities: int = 22
    positions: int = 23


FULL = Size()
SMOKE = Size(duration=4e-3, n_elements=40, n_half_layers=4, masses=2, velocities=2, positions=2)


def contact_law():
    e_star = float(effective_modulus(MODULUS, POISSON, MODULUS, POISSON))
    return StrongeContact(e_star, SPHERE_RADIUS, YIELD)


def contact_laws() -> dict:
    """The consistent elastic-plastic laws of the comparison, same E*, R, Y (module docstring)."""
    e_star = float(effective_modulus(MODULUS, POISSON, MODULUS, POISSON))
    sphere_share = e_star * (1.0 - POISSON**2) / MODULUS  # steel on steel: 0.5
    return {"stronge": contact_law(),
            "yc": YigitChristoforouContact.from_properties(e_star, SPHERE_RADIUS, YIELD),
            "epp": EppContact(e_star, SPHERE_RADIUS, YIELD, poisson_ratio=POISSON, sphere_compliance=sphere_share)}


def beam(plastic=True, size=FULL):
    return FDBeam(LENGTH, WIDTH, HEIGHT, MODULUS, DENSITY, YIELD, poisson_ratio=POISSON,
                  n_elements=size.n_elements, n_half_layers=size.n_half_layers, plastic=plastic)


def wave_return_time(target: FDBeam, contact_duration, distance):
    """t_r = 2 d / c_g(k) with ω(k) = π / T_c on the Rayleigh dispersion curve [s]."""
    omega = np.pi / contact_duration
    k_max = np.sqrt(target.mass_per_length / target.rotary_inertia_per_length) * 50
    # Rayleigh beam: ω(k) increases monotonically to the bar limit c0 k... solve ω(k) = ω
    k = brentq(lambda q: float(target.rayleigh_frequency(q)) - omega, 1e-9, k_max)
    return 2.0 * distance / float(target.rayleigh_group_velocity(k))


def run(mass=BASE_MASS, velocity=BASE_VELOCITY, position=LENGTH / 2, plastic=True, law=None,
        stride=20, size=FULL):
    target = beam(plastic, size)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = simulate_fd(target, law or contact_law(), mass, velocity, position,
                             duration=size.duration, gravity=True, history_stride=stride)
    distance = min(result.details.impact_node_position, LENGTH - result.details.impact_node_position)
    return result, dict(
        mass_kg=mass, velocity_m_s=velocity, position_m=result.details.impact_node_position,
        plastic=plastic, peak_force_N=result.peak_force, impacts=result.impacts,
        first_contact_s=result.first_contact_duration, contact_span_s=result.contact_span,
        second_contact_start_s=(result.contact_intervals[1, 0] if result.impacts > 1 else np.nan),
        contact_time_s=result.total_contact_time,
        energy_loss_fraction=result.energy_loss / result.impact_energy,
        restitution=result.restitution,
        plastic_work_fraction=result.details.energy["beam_plastic_work"] / result.impact_energy,
        contact_dissipation_fraction=result.details.energy["contact_dissipation"] / result.impact_energy,
        permanent_deflection_m=result.details.permanent_beam_deflection,
        permanent_indentation_m=result.permanent_indentation,
        wave_return_s=wave_return_time(target, result.first_contact_duration, distance),
        ledger_error=result.energy_balance_error,
        time_limit_reached=result.time_limit_reached,
    )


def sweep(name, values, make):
    rows = []
    start = time.perf_counter()
    for value in values:
        rows.append(make(value)[1])
    table = pd.DataFrame(rows)
    print(f"{name}: {len(values)} runs in {time.perf_counter() - start:.1f} s; "
          f"max |ledger error| {table['ledger_error'].abs().max():.1e}")
    return table


def _panels(axes, table, x, label, style="o-", name=None, color=None):
    multi = table["impacts"] > 1
    kw = dict(color=color, label=name)
    ax = axes[0, 0]
    ax.plot(table[x], table["peak_force_N"] / 1e3, style, ms=4, **kw)
    ax.set_ylabel("peak force [kN]")
    ax = axes[0, 1]
    ax.plot(table[x], table["first_contact_s"] * 1e3, style, ms=4, **kw)
    ax.plot(table[x], table["wave_return_s"] * 1e3, "--", color=color or "k", lw=1,
            label=None if name else "wave-return time $t_r$")
    ax.plot(table[x], table["second_contact_start_s"] * 1e3, "^", ms=4, mfc="none",
            color=color or "C2", label=None if name else "start of 2nd contact")
    ax.set_yscale("log")
    ax.set_ylabel("first contact duration [ms]")
    ax = axes[1, 0]
    ax.plot(table[x], table["energy_loss_fraction"], style, ms=4, **kw)
    ax.plot(table[x][multi], table["energy_loss_fraction"][multi], "s", mfc="none", ms=8,
            color=color or "C3", label=None)
    ax.set_ylabel("energy loss / impact energy")
    ax = axes[1, 1]
    ax.plot(table[x], table["restitution"], style, ms=4, **kw)
    ax.plot(table[x][multi], table["restitution"][multi], "s", mfc="none", ms=8,
            color=color or "C3", label=None)
    ax.set_ylabel("Newton restitution e")
    for ax in axes[1]:
        ax.set_xlabel(label)
    for ax in axes.ravel():
        ax.grid(alpha=0.3)


def _mark_jumps(axes, table, x):
    """Vertical lines where the first contact outlasts the wave-return time."""
    late = table["first_contact_s"] > table["wave_return_s"]
    if late.any() and not late.all():
        first = table[x][late].iloc[0]
        for ax in axes.ravel():
            ax.axvline(first, color="0.5", lw=0.8, ls=":")
    multi = table["impacts"] > 1
    if multi.any() and not multi.all():
        first = table[x][multi].iloc[0]
        for ax in axes.ravel():
            ax.axvline(first, color="C3", lw=0.8, ls="-.")


#: The law comparison's sweeps: name → (x column, axis label, logarithmic x axis).
LAW_STUDIES = {
    "mass": ("mass_kg", "impactor mass [kg] (V0 = 2 m/s, mid-span)", True),
    "velocity": ("velocity_m_s", f"V0 [m/s] (m = {PLASTICITY_MASS:g} kg, elastic-plastic beam)", False),
    "velocity-elastic-beam": ("velocity_m_s", f"V0 [m/s] (m = {PLASTICITY_MASS:g} kg, elastic beam)", False),
    "location": ("x_over_L", "impact position x0/L (m = 1 kg, V0 = 2 m/s)", False),
}


def _save(fig, path, title, fontsize, dpi=150):
    """Title ``fig``, lay it out, write it to ``path`` and close it."""
    fig.suptitle(title, fontsize=fontsize)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def _print_columns(table, x):
    """Print the sweep's column ``x`` with the peak force, contacts, timings and energy columns."""
    print(table[[x, "peak_force_N", "impacts", "first_contact_s", "wave_return_s",
                 "energy_loss_fraction", "restitution"]].to_string(float_format=lambda v: f"{v:.4g}"))


def law_comparison(size: Size, out: pathlib.Path) -> pd.DataFrame:
    """The mass, velocity and location sweeps with each law of :func:`contact_laws`; CSV and figure in ``out``."""
    studies = {
        "mass": (np.geomspace(0.05, 5.0, size.masses), lambda law, m: run(mass=m, law=law, size=size)),
        "velocity": (np.linspace(0.5, 7.0, size.velocities),
                     lambda law, v: run(mass=PLASTICITY_MASS, velocity=v, law=law, size=size)),
        "velocity-elastic-beam": (np.linspace(0.5, 7.0, size.velocities),
                                  lambda law, v: run(mass=PLASTICITY_MASS, velocity=v, plastic=False, law=law,
                                                     size=size)),
        "location": (np.linspace(0.06, 0.5, size.positions) * LENGTH, lambda law, x: run(position=x, law=law,
                                                                                           size=size)),
    }
    tables = []
    for name, law in contact_laws().items():
        for study, (values, make) in studies.items():
            table = sweep(f"{study} ({name})", values, lambda value, law=law, make=make: make(law, value))
            tables.append(table.assign(law=name, study=study, x_over_L=table["position_m"] / LENGTH))
    table = pd.concat(tables, ignore_index=True)
    columns = ["law", "study", "mass_kg", "velocity_m_s", "x_over_L", "plastic", "peak_force_N", "impacts",
               "first_contact_s", "wave_return_s", "energy_loss_fraction", "restitution",
               "contact_dissipation_fraction", "plastic_work_fraction", "permanent_indentation_m",
               "permanent_deflection_m"]
    table[columns].to_csv(out / "fd_parametric_laws.csv", index=False, float_format="%.6g")
    fig, axes = plt.subplots(len(LAW_STUDIES), 3, figsize=(12, 13))
    quantities = (("peak_force_N", 1e-3, "peak force [kN]"), ("energy_loss_fraction", 1.0, "energy loss / impact energy"),
                  ("restitution", 1.0, "Newton restitution e"))
    for row, (study, (x, label, log)) in zip(axes, LAW_STUDIES.items()):
        for column, (ax, (quantity, scale, ylabel)) in enumerate(zip(row, quantities)):
            for i, law in enumerate(("stronge", "yc", "epp")):
                part = table[(table["law"] == law) & (table["study"] == study)]
                multi = part["impacts"] > 1
                ax.plot(part[x], part[quantity] * scale, "o-", ms=3, color=f"C{i}", label=law)
                ax.plot(part[x][multi], part[quantity][multi] * scale, "s", mfc="none", ms=7, color=f"C{i}")
            ax.set_xscale("log" if log else "linear")
            ax.set_xlabel(label, fontsize=8)
            ax.set_ylabel(ylabel, fontsize=8)
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    _save(fig, out / "fd_parametric_laws.png",
          "Seed-000 FD beam with three elastic-plastic contact laws (squares: runs with sub-impacts)",
          fontsize=10, dpi=90)
    return table


def _options(parser) -> None:
    parser.add_argument("--study", choices=("all", "stronge", "laws"), default="all",
                        help="the Stronge study's figures, the law comparison, or both (default)")


def main(argv=None):
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES, add_arguments=_options)
    size = SMOKE if args.smoke else FULL
    out = args.out_dir
    start = time.perf_counter()
    if args.study != "stronge":
        law_comparison(size, out)
    if args.study != "laws":
        stronge_study(size, out)
    print(f"total runtime {time.perf_counter() - start:.1f} s")


def stronge_study(size: Size, out: pathlib.Path) -> None:
    """The force histories and the mass, velocity/plasticity and location figures with the Stronge law."""
    law = contact_law()

    # -- force histories -------------------------------------------------------------------
    fig, (early, late) = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True,
                                      gridspec_kw=dict(width_ratios=[1, 1.4]))
    for i, mass in enumerate((0.3, 0.75, 3.0)):
        result, row = run(mass=mass, law=law, stride=5, size=size)
        h = result.history
        label = (f"m = {mass} kg ({row['impacts']} contact{'s' if row['impacts'] > 1 else ''}, "
                 f"e = {row['restitution']:.2f})")
        for ax in (early, late):
            ax.plot(h["time_s"] * 1e3, h["force_N"] / 1e3, color=f"C{i}", lw=1.2,
                    label=label if ax is early else None)
        early.axvline(row["wave_return_s"] * 1e3, color=f"C{i}", ls="--", lw=0.8)
    early.set_xlim(0, 1.5)
    late.set_xlim(0, size.duration * 1e3)
    early.set_ylabel("contact force [kN]")
    for ax in (early, late):
        ax.set_xlabel("time [ms]")
        ax.grid(alpha=0.3)
    early.set_title("first 1.5 ms; dashed: wave-return time $t_r$", fontsize=9)
    late.set_title("whole record: sub-impacts when the beam swings back", fontsize=9)
    early.legend(fontsize=8)
    _save(fig, out / "fd_force_histories.png",
          "SS steel beam 780 mm, V0 = 2 m/s at mid-span, refined Stronge contact", fontsize=10)

    # -- impactor mass ---------------------------------------------------------------------
    masses = np.geomspace(0.05, 5.0, size.masses)
    table = sweep("mass", masses, lambda m: run(mass=m, law=law, size=size))
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    _panels(axes, table, "mass_kg", "impactor mass [kg]")
    _mark_jumps(axes, table, "mass_kg")
    for ax in axes.ravel():
        ax.set_xscale("log")
    axes[0, 1].legend(fontsize=8)
    _save(fig, out / "fd_mass_effect.png",
          "Effect of impactor mass (V0 = 2 m/s, mid-span). Squares: sub-impacts; "
          "dash-dot: first run with sub-impacts; dotted: first contact > $t_r$", fontsize=9)
    _print_columns(table, "mass_kg")

    # -- velocity and beam plasticity --------------------------------------------------------
    velocities = np.linspace(0.5, 7.0, size.velocities)
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    tables = {}
    for plastic, color in ((True, "C0"), (False, "C1")):
        tables[plastic] = sweep(f"velocity (plastic={plastic})", velocities,
                                lambda v, p=plastic: run(mass=PLASTICITY_MASS, velocity=v, plastic=p,
                                                         law=law, size=size))
        _panels(axes, tables[plastic], "velocity_m_s", "impact velocity V0 [m/s]",
                name="elastic-plastic beam" if plastic else "elastic beam", color=color)
    ax = axes[0, 0].twinx()
    ax.plot(velocities, tables[True]["plastic_work_fraction"], "k:", lw=1)
    ax.set_ylabel("beam plastic work / impact energy (dotted)")
    axes[0, 0].legend(fontsize=8)
    _save(fig, out / "fd_velocity_effect.png",
          f"Effect of impact velocity and beam plasticity (m = {PLASTICITY_MASS:g} kg, mid-span, Stronge "
          "contact in both); squares: sub-impacts; dashed: $t_r$", fontsize=9)
    print(pd.DataFrame({
        "V0": velocities,
        "F_plastic": tables[True]["peak_force_N"], "F_elastic": tables[False]["peak_force_N"],
        "e_plastic": tables[True]["restitution"], "e_elastic": tables[False]["restitution"],
        "Wp/E": tables[True]["plastic_work_fraction"],
        "impacts_pl": tables[True]["impacts"], "impacts_el": tables[False]["impacts"],
    }).to_string(float_format=lambda v: f"{v:.4g}"))

    # -- impact location ---------------------------------------------------------------------
    positions = np.linspace(0.06, 0.5, size.positions) * LENGTH
    table = sweep("location", positions, lambda x: run(position=x, law=law, size=size))
    table["x_over_L"] = table["position_m"] / LENGTH
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    _panels(axes, table, "x_over_L", "impact position x0 / L")
    axes[0, 1].legend(fontsize=8)
    _save(fig, out / "fd_location_effect.png",
          "Effect of impact location (m = 1 kg, V0 = 2 m/s); $t_r$ = 2 d / $c_g$ with "
          "d the distance to the nearest support; squares: sub-impacts", fontsize=9)
    _print_columns(table, "x_over_L")


if __name__ == "__main__":
    main()
