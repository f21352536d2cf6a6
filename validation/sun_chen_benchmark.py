"""External benchmark: graphite/epoxy plate struck by a 12.7 mm steel ball (Sun & Chen set-up).

The case is the one attributed to Sun & Chen (J. Composite Materials 19 (1985), "On the impact
of initially stressed composite laminates") and used by Qian & Swanson (Composite Structures 14
(1990) 177-192, "A comparison of solution techniques for impact response of composite plates")
to compare solution methods: a T300/934 [0/90/0/90/0]s plate, simply supported on all four
edges, struck at its centre by a steel ball. It is defined in
``examples/composite_plate_sun_chen.toml`` (the same file the CLI runs).

**Status of the reference data.** No stored copy of either paper, nor of a later paper
quoting the set-up or its results, could be found (sources checked: see
``validation/BENCHMARKS.md``). The set-up in the case file is therefore the one *recalled*
in the task brief (dimensions, layup, velocity, ply thickness 0.269 mm) and the catalogue ply
data (``impactmaps.materials``, entry "t300-934", itself flagged unverified), and
:data:`PUBLISHED` holds no numbers. If the published peak force and contact duration are
found, enter them in :data:`PUBLISHED` (with their source); the script then draws them on the
figure and reports the differences.

What the script computes (impactmaps, modal solver, Hertz contact with the laminate contact
compliance 1/E2 of Tan & Sun 1985):

* Mindlin plate (the reference model), mode cut-off 20, 40 and 80 times the contact frequency,
  and the time step halved at cut-off 40 — to show what the result depends on;
* Kirchhoff plate at cut-off 40 — the shear-rigid model, for comparison.

The Mindlin point-contact result does not converge as the cut-off grows: the point-load
deflection of a shear-deformable plate diverges logarithmically (docs/physics_contract.md §3.3), so the
cut-off acts as a regularisation of the contact patch. The script reports the contact radius
at the peak force, ``a = sqrt(R α_max)``, and the equivalent shortest half-wavelength of the
retained modes (:func:`shortest_half_wavelength`), so that the physically meaningful cut-off
(shortest half-wavelength comparable to the contact diameter 2a) can be judged.

Run ``python validation/sun_chen_benchmark.py [--out-dir DIR]``; writes
``figures/sun_chen_force_history.png`` and ``figures/sun_chen_cutoff.png`` and prints a
Markdown table (used in BENCHMARKS.md). ``--smoke``: cut-offs 20 and 40 only (no 80).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from impactmaps.cases import load_case, run_case  # noqa: E402

from _script_options import parse  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CASE_FILE = ROOT / "examples" / "composite_plate_sun_chen.toml"
FIGURES = ROOT / "figures"

#: Published results to compare with. ``None``: not found in any source we could read
#: (see validation/BENCHMARKS.md). Fill in as (value, "source, figure/table") when found.
PUBLISHED = {
    "peak_force_N": None,
    "contact_duration_s": None,
}

#: Mode cut-offs (multiples of the contact frequency) of the Mindlin study.
CUTOFFS = (20.0, 40.0, 80.0)
#: Cut-off of the reference run.
REFERENCE_CUTOFF = 40.0


def run(case, *, theory=None, cutoff=REFERENCE_CUTOFF, refine_step=False):
    """Run the case with another theory / cut-off / step; return (result, summary)."""
    target = case.target if theory is None else replace(case.target, theory=theory)
    settings = replace(case.settings, cutoff_ratio=cutoff)
    if refine_step:
        settings = replace(settings, time_step_ratio=settings.time_step_ratio / 2,
                           resolve_ratio=settings.resolve_ratio / 2)
    with warnings.catch_warnings():
        # Mindlin at high cut-off: "thickness-shear branches omitted" (documented in plate.py)
        warnings.filterwarnings("ignore", message=".*thickness-shear.*")
        return run_case(replace(case, target=target, settings=settings))


def shortest_half_wavelength(case, modes):
    """Equivalent shortest retained half-wavelength [m] from the number of modes ``modes``.

    A point load at the centre of a SSSS plate excites the (odd, odd) modes only. If the
    retained modes fill the quarter disc m² + n² ≤ m_max² (equivalent isotropic square),
    a quarter of them are odd-odd: ``N ≈ π m_max²/16``, so the shortest half-wavelength is
    ``sqrt(a b / m_max²) = sqrt(π a b / (16 N))``. An estimate (the laminate is
    orthotropic), used only to compare with the contact diameter.
    """
    plate = case.target
    return math.sqrt(math.pi * plate.length_x * plate.length_y / (16.0 * modes))


def contact_radius(case, result):
    """Hertz contact radius at the largest indentation, a = sqrt(R α_max) [m]."""
    return math.sqrt(case.sphere.radius * result.max_indentation)


def runs(case, cutoffs=CUTOFFS):
    """All runs of the study (Mindlin at each of ``cutoffs``, which must hold
    :data:`REFERENCE_CUTOFF`), keyed by label."""
    out = {}
    for cutoff in cutoffs:
        out[f"Mindlin, cut-off {cutoff:g}ω"] = run(case, theory="mindlin", cutoff=cutoff) + (cutoff,)
    out[f"Mindlin, cut-off {REFERENCE_CUTOFF:g}ω, Δt/2"] = run(
        case, theory="mindlin", cutoff=REFERENCE_CUTOFF, refine_step=True) + (REFERENCE_CUTOFF,)
    out[f"Kirchhoff, cut-off {REFERENCE_CUTOFF:g}ω"] = run(
        case, theory="kirchhoff", cutoff=REFERENCE_CUTOFF) + (REFERENCE_CUTOFF,)
    return out


def plot_force_history(case, results, ax=None):
    """Force histories [N] vs time [μs] with the published values when known. Returns the Axes."""
    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 4.5))
    styles = {0: dict(color="0.6", lw=1.0), 1: dict(color="C0", lw=2.0), 2: dict(color="0.3", lw=1.0, ls=":"),
              3: dict(color="C0", lw=1.0, ls="--"), 4: dict(color="C3", lw=1.5, ls="-.")}
    for index, (label, (result, summary, _)) in enumerate(results.items()):
        history = result.history
        ax.plot(history["time_s"] * 1e6, history["force_N"], label=label, **styles.get(index, {}))
    peak = PUBLISHED["peak_force_N"]
    duration = PUBLISHED["contact_duration_s"]
    if peak is not None:
        ax.axhline(peak[0], color="k", ls="--", lw=1.0, label=f"published peak force ({peak[1]})")
    if duration is not None:
        ax.axvline(duration[0] * 1e6, color="k", ls=":", lw=1.0,
                   label=f"published contact duration ({duration[1]})")
    if peak is None and duration is None:
        ax.text(0.98, 0.97, "published peak force and contact duration:\nnot found in the sources "
                "checked\n(validation/BENCHMARKS.md)", transform=ax.transAxes, ha="right", va="top",
                fontsize=8, bbox=dict(boxstyle="round", fc="white", ec="0.7"))
    ax.set_xlabel("time [μs]")
    ax.set_ylabel("contact force [N]")
    ax.set_title(f"{case.name}\nT300/934 [0/90/0/90/0]s, 200×200×2.69 mm SSSS, 12.7 mm steel ball, "
                 f"{case.velocity:g} m/s (set-up unverified)", fontsize=9)
    ax.set_xlim(0, 1e6 * max(r.contact_intervals[-1, 1] for r, _, _ in results.values()) * 1.15)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, loc="center right")
    ax.grid(alpha=0.3)
    return ax


def plot_cutoff_study(case, results, ax=None):
    """Peak force vs mode cut-off (Mindlin) with the Kirchhoff value. Returns the Axes."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 4.0))
    mindlin = [(c, s["peak_force_N"]) for label, (_, s, c) in results.items()
               if label.startswith("Mindlin") and "Δt" not in label]
    cut, peak = np.array(mindlin).T
    ax.semilogx(cut, peak, "o-", color="C0", label="Mindlin (modes ≤ cut-off, + residual flexibility)")
    kirchhoff = next(s["peak_force_N"] for label, (_, s, _) in results.items() if label.startswith("Kirchhoff"))
    ax.axhline(kirchhoff, color="C3", ls="-.", label="Kirchhoff, cut-off 40ω")
    if PUBLISHED["peak_force_N"] is not None:
        ax.axhline(PUBLISHED["peak_force_N"][0], color="k", ls="--", label="published")
    ax.set_xticks(cut)
    ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("mode cut-off Ω_max/ω [-]")
    ax.set_ylabel("peak contact force [N]")
    ax.set_title("Sun & Chen set-up: peak force vs mode cut-off", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return ax


def comparison_table(case, results) -> str:
    """Markdown table of our runs (and the published values if known)."""
    lines = [
        "| model | modes | peak force [N] | first contact [μs] | impacts | contact radius at peak [mm] "
        "| shortest half-wavelength ≈ [mm] |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, (result, summary, _cutoff) in results.items():
        first = 1e6 * (result.contact_intervals[0, 1] - result.contact_intervals[0, 0])
        half = shortest_half_wavelength(case, summary["n_modes"])
        lines.append(f"| {label} | {summary['n_modes']} | {summary['peak_force_N']:.0f} | {first:.1f} | "
                     f"{summary['impacts']} | {1e3 * contact_radius(case, result):.2f} | {1e3 * half:.2f} |")
    return "\n".join(lines)


def published_table(results) -> str:
    """Published vs ours (difference in %), or 'not found'."""
    reference = next(v for k, v in results.items() if k == f"Mindlin, cut-off {REFERENCE_CUTOFF:g}ω")
    result, summary, _ = reference
    ours = {
        "peak_force_N": summary["peak_force_N"],
        "contact_duration_s": float(result.contact_intervals[0, 1] - result.contact_intervals[0, 0]),
    }
    rows = ["| quantity | published | source | impactmaps (Mindlin, 40ω) | difference |", "|---|---|---|---|---|"]
    names = {"peak_force_N": ("peak contact force", 1.0, "N"),
             "contact_duration_s": ("duration of the first contact", 1e6, "μs")}
    for key, (name, scale, unit) in names.items():
        value = PUBLISHED[key]
        if value is None:
            rows.append(f"| {name} [{unit}] | not found | — | {ours[key] * scale:.4g} | — |")
        else:
            diff = 100.0 * (ours[key] - value[0]) / value[0]
            rows.append(f"| {name} [{unit}] | {value[0] * scale:.4g} | {value[1]} | {ours[key] * scale:.4g} "
                        f"| {diff:+.1f} % |")
    return "\n".join(rows)


def main(argv=None):
    args = parse(__doc__.splitlines()[0], argv, default_out=FIGURES)
    case = load_case(CASE_FILE)
    results = runs(case, CUTOFFS[:2] if args.smoke else CUTOFFS)
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    plot_force_history(case, results, ax=ax)
    fig.tight_layout()
    fig.savefig(args.out_dir / "sun_chen_force_history.png", dpi=150)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5.5, 4.0))
    plot_cutoff_study(case, results, ax=ax)
    fig.tight_layout()
    fig.savefig(args.out_dir / "sun_chen_cutoff.png", dpi=150)
    plt.close(fig)
    dims = results[f"Mindlin, cut-off {REFERENCE_CUTOFF:g}ω"][1]
    print(f"impactor mass {case.impactor_mass * 1e3:.3f} g, K_h = {case.law.stiffness:.4g} N/m^1.5, "
          f"plate mass {case.target.mass * 1e3:.1f} g, h = {case.target.thickness * 1e3:.3f} mm")
    print(f"D11 = {case.target.D11:.4g}, D22 = {case.target.D22:.4g}, D12 = {case.target.D12:.4g}, "
          f"D66 = {case.target.D66:.4g} N m; A44 = A55 = {case.target.A44:.4g} N/m")
    print(f"lambda = {dims['lambda']:.4g}, zeta = {dims['zeta']:.4g} ({dims['lambda_basis']})")
    print()
    print(comparison_table(case, results))
    print()
    print(published_table(results))


if __name__ == "__main__":
    main()
