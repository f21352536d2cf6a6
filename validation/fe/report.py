"""Tables (markdown, printed) and figures (figures/fe_*.png) from the committed results.

Run: ``python validation/fe/report.py > /tmp/tables.md`` from the repository root; the
tables of ``validation/fe/README.md`` were pasted from its output.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402

FIGURES = ct.HERE.parents[1] / "figures"


def level1_tables():
    data = json.loads((ct.RESULTS / "level1_modes.json").read_text())["cases"]
    rows = ["| case | FE bending modes 1–5 [Hz] (best mesh) | mesh Δ, modes 1–5 [%] | "
            "Timoshenko/Mindlin − FE [%] | Euler/Kirchhoff − FE [%] | best mesh: elements "
            "(depth), element, ccx wall [s] |",
            "|---|---|---|---|---|---|"]
    order = sorted(data, key=lambda k: (k.split("-")[0], ["face", "clampxz", "clamped",
                                                          "edge"].index(k.split("-")[1]),
                                        int(k.split("-")[2])))
    for key in order:
        case = data[key]
        best = case.get("best_mesh", "fine")
        fe = np.array(case[best]["fe_bending_hz"])
        thick = np.array(case.get("toolkit_timoshenko_hz", case.get("toolkit_mindlin_hz")))
        thin = np.array(case.get("toolkit_euler_hz", case.get("toolkit_kirchhoff_hz")))
        fmt = lambda v: " / ".join(f"{x:+.2f}" for x in v)
        mesh = case[best]
        rows.append(f"| {key} | " + " / ".join(f"{x:.1f}" for x in fe) + " | "
                    + fmt(100 * np.array(case["mesh_difference"])) + " | "
                    + fmt(100 * (thick / fe - 1)) + " | " + fmt(100 * (thin / fe - 1)) + " | "
                    + f"{'×'.join(map(str, mesh['elements']))} ({mesh['elements'][-1]}), "
                    f"{mesh['element_type']}, {mesh['wall_time_s']:.0f} |")
    return "\n".join(rows)


def level3_tables(name="level3_dynamics.json"):
    data = json.loads((ct.RESULTS / name).read_text())
    out = ["| mass [kg] | ζ | λ | quantity | FE spring (ref) | FE mesh coarse | FE half step | "
           "FE half modes | modal (Timoshenko) | diff | FD (Rayleigh) | diff |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in data["cases"]:
        fe = case["fe"]
        for q, label, scale, fmt in (("peak_force_N", "peak force [N]", 1, ".1f"),
                                     ("first_contact_s", "first contact [µs]", 1e6, ".2f"),
                                     ("impacts", "impacts", 1, "d"),
                                     ("restitution", "restitution", 1, ".3f")):
            ref = fe["reference"][q]

            def cell(v):
                return format(v * scale if scale != 1 else v, fmt)

            def diff(v):
                if q in ("impacts",):
                    return f"{v - ref:+d}"
                if q == "restitution":
                    return f"{v - ref:+.3f}"
                return f"{100 * (v / ref - 1):+.2f} %"
            variants = [cell(fe[k][q]) + (f" ({diff(fe[k][q])})" if k in fe else "")
                        if k in fe else "–" for k in ("a070_coarse", "half_step", "half_modes")]
            out.append(f"| {case['mass_kg']:.4g} | {case['zeta']:.3g} | {case['lambda_']:.3g} | "
                       f"{label} | {cell(ref)} | " + " | ".join(variants) + " | "
                       f"{cell(case['modal'][q])} | {diff(case['modal'][q])} | "
                       f"{cell(case['fd'][q])} | {diff(case['fd'][q])} |")
    patch = ["| mass [kg] | a_c [mm] | peak force [N] | first contact [µs] | restitution |",
             "|---|---|---|---|---|"]
    for case in data["cases"]:
        for tag in ("a035_coarse", "a070_coarse", "a140_coarse"):
            if tag in case["fe"]:
                r = case["fe"][tag]
                patch.append(f"| {case['mass_kg']:.4g} | {1e3 * r['patch_radius_m']:.2f} | "
                             f"{r['peak_force_N']:.1f} | {1e6 * r['first_contact_s']:.2f} | "
                             f"{r['restitution']:.3f} |")
    return "\n".join(out) + "\n\nPatch radius (coarse meshes):\n\n" + "\n".join(patch)


def _pct(a, b):
    return f"{100 * (a / b - 1):+.2f} %"


def linear_table(name="level3_dynamics.json"):
    data = json.loads((ct.RESULTS / name).read_text())
    rows = ["| mass [kg] | k [N/m] | FE first peak [N] (mesh Δ, step Δ) | modal | diff | FD | diff | "
            "FE first contact [µs] | modal | diff | impacts FE / modal / FD |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in data["cases"]:
        lin = case.get("linear")
        if lin is None:
            continue
        fe = lin["fe"]
        ref = fe["reference"]
        rows.append(
            f"| {case['mass_kg']:.4g} | {lin['stiffness_N_m']:.3g} | {ref['first_peak_N']:.1f} "
            f"({_pct(fe['a070_coarse']['first_peak_N'], ref['first_peak_N'])}, "
            f"{_pct(fe['half_step']['first_peak_N'], ref['first_peak_N'])}) | "
            f"{lin['modal']['first_peak_N']:.1f} | "
            f"{_pct(lin['modal']['first_peak_N'], ref['first_peak_N'])} | "
            f"{lin['fd']['first_peak_N']:.1f} | {_pct(lin['fd']['first_peak_N'], ref['first_peak_N'])} | "
            f"{1e6 * ref['first_contact_s']:.2f} | {1e6 * lin['modal']['first_contact_s']:.2f} | "
            f"{_pct(lin['modal']['first_contact_s'], ref['first_contact_s'])} | "
            f"{ref['impacts']} / {lin['modal']['impacts']} / {lin['fd']['impacts']} |")
    return "\n".join(rows)


def plate_table():
    data = json.loads((ct.RESULTS / "level3_plate.json").read_text())
    rows = ["| mass [kg] | ζ | λ | FE peak [N] (mesh Δ, step Δ, half modes Δ) | Mindlin modal | diff | "
            "FE contact [µs] | modal | diff | restitution FE / modal |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for case in data["cases"]:
        fe = case["fe"]
        ref = fe["reference"]
        m = case["modal"]
        rows.append(
            f"| {case['mass_kg']:.4g} | {case['zeta']:.3g} | {case['lambda_']:.3g} | "
            f"{ref['peak_force_N']:.1f} ({_pct(fe['plate_a070_coarse']['peak_force_N'], ref['peak_force_N'])}, "
            f"{_pct(fe['half_step']['peak_force_N'], ref['peak_force_N'])}, "
            f"{_pct(fe['half_modes']['peak_force_N'], ref['peak_force_N'])}) | "
            f"{m['peak_force_N']:.1f} | {_pct(m['peak_force_N'], ref['peak_force_N'])} | "
            f"{1e6 * ref['first_contact_s']:.2f} | {1e6 * m['first_contact_s']:.2f} | "
            f"{_pct(m['first_contact_s'], ref['first_contact_s'])} | "
            f"{ref['restitution']:.3f} / {m['restitution']:.3f} |")
    return "\n".join(rows)


def figures():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = [(ct.RESULTS / "level3_history.csv", "solid sphere (32.9 g): one impact"),
              (ct.RESULTS / "level3_history_mass30.csv",
               "30 × the sphere mass (0.99 kg): three impacts")]
    panels = [(p, t) for p, t in panels if p.exists()]
    if panels:
        fig, axes = plt.subplots(len(panels), 1, figsize=(6.4, 3.2 * len(panels)))
        for ax, (path, title) in zip(np.atleast_1d(axes), panels):
            d = np.loadtxt(path, delimiter=",", skiprows=1)
            ax.plot(1e6 * d[:, 0], d[:, 1], "k-", lw=2,
                    label="3D FE modes + Hertz spring (CalculiX)")
            ax.plot(1e6 * d[:, 0], d[:, 2], "C1--", label="modal, Timoshenko + Hertz")
            ax.plot(1e6 * d[:, 0], d[:, 3], "C0:", label="FD, Rayleigh + Hertz")
            ax.set_xlabel("time [µs]")
            ax.set_ylabel("contact force [N]")
            ax.set_title("R 10 mm steel sphere, 1 m/s, SS steel beam 500×20×20 mm — " + title,
                         fontsize=8)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(FIGURES / "fe_level3_force_history.png", dpi=130)
    data = json.loads((ct.RESULTS / "level1_modes.json").read_text())["cases"]
    fig, ax = plt.subplots(figsize=(6, 3.6))
    for support, marker in (("face", "o"), ("edge", "s"), ("clamped", "^"), ("clampxz", "v")):
        keys = [k for k in data if k.startswith(f"beam-{support}-")]
        if not keys:
            continue
        ratios = [int(k.split("-")[2]) for k in keys]
        modes = ((0, "C0"),) if support == "edge" else ((0, "C0"), (2, "C1"), (4, "C2"))
        for j, color in modes:
            diffs = []
            for k in keys:
                fe = data[k][data[k].get("best_mesh", "fine")]["fe_bending_hz"][j]
                diffs.append(100 * (data[k]["toolkit_timoshenko_hz"][j] / fe - 1))
            ax.plot(ratios, diffs, marker=marker, color=color, ls="-",
                    label=f"{support}, mode {j + 1}")
    ax.axhspan(-1, 1, color="0.9")
    ax.set_xscale("log")
    ax.set_xlabel("span / height")
    ax.set_ylabel("Timoshenko − 3D FE [%]")
    ax.legend(fontsize=6, ncol=3)
    fig.tight_layout()
    fig.savefig(FIGURES / "fe_modes_beam.png", dpi=130)


# -- level 4 (full contact dynamics; quasi-static plastic indentation) ----------------
import level4_contact as l4  # noqa: E402
import level4_plastic_indent  # noqa: E402

L4_QUANTITIES = (("peak force [N]", "peak_force_N", 1.0, "rel"),
              ("first contact [µs]", "first_contact_s", 1e6, "rel"),
              ("restitution", "restitution", 1.0, "abs"),
              ("permanent indentation [µm]", "permanent_indentation_m", 1e6, "abs"))
L4_TOOLKIT_COLUMNS = {"elastic": ("modal_hertz", "fd_hertz"),
                   "plastic": ("modal_stronge", "fd_stronge", "modal_yigit-christoforou")}


def _l4_diff(a, b, kind):
    return f"{100 * (a / b - 1):+.2f} %" if kind == "rel" else f"{a - b:+.3f}"


def level4_table(data):
    """Markdown table: case, quantity, FE with its mesh/step differences, toolkit columns."""
    rows = [("| case | quantity | FE (reference) | FE mesh Δ | FE step Δ | modal | diff | "
             "FD | diff | modal YC | diff |"), "|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in l4.CASES:
        ref, mesh_pair, step_pair = l4.fe_reference(data.get("runs", {}), case)
        if ref is None:
            continue
        tk = [data["toolkit"][case][k] for k in L4_TOOLKIT_COLUMNS[case]]
        for label, key, scale, kind in L4_QUANTITIES:
            cells = [f"{ref[key] * scale:.4g}"]
            for pair in (mesh_pair, step_pair):
                cells.append("—" if pair is None else _l4_diff(pair[1][key] * scale,
                                                            pair[0][key] * scale, kind))
            for run in tk:
                cells += [f"{run[key] * scale:.4g}", _l4_diff(run[key] * scale, ref[key] * scale,
                                                           kind)]
            cells += ["", ""] * (3 - len(tk))
            rows.append(f"| {case} | {label} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def level4_toolkit_table(data, case):
    """Markdown table of the toolkit's runs of ``case`` (no FE needed)."""
    runs = data["toolkit"][case]
    rows = ["| toolkit run | " + " | ".join(label for label, *_ in L4_QUANTITIES)
            + " | wall time [ms] |", "|---" * (len(L4_QUANTITIES) + 2) + "|"]
    for name, run in runs.items():
        cells = [f"{run[key] * scale:.4g}" for _, key, scale, _ in L4_QUANTITIES]
        rows.append(f"| {name.replace('_', ' ')} | " + " | ".join(cells)
                    + f" | {run['wall_time_s'] * 1e3:.2g} |")
    return "\n".join(rows)


def level4_figure(data, path, indentation=None):
    """Force histories (FE runs, modal and FD toolkit runs) of both cases and, if given,
    the quasi-static indentation curves of ``level4_plastic_indent.json``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    for ax, case in zip(axes, l4.CASES):
        for name, run in sorted(data.get("runs", {}).items()):
            if run["case"] == case and run["mesh"] != "smoke":
                h = np.loadtxt(ct.RESULTS / run["csv"], delimiter=",", skiprows=1)
                ax.plot(h[:, 0] * 1e6, h[:, 1], lw=1.2, label=f"FE {run['mesh']}, "
                        f"Δt {run['time_step_s'] * 1e6:.2g} µs")
        for key, (result, _) in l4.toolkit_runs_cached(case).items():
            hist = result.history
            ax.plot(hist["time_s"] * 1e6, hist["force_N"], "--", lw=1.0,
                    label=key.replace("_", " "))
        has_fe = any(r["case"] == case for r in data.get("runs", {}).values())
        ax.set(title=f"{case} target, 1 m/s" + ("" if has_fe else " (toolkit only, no FE run)"),
               xlabel="time [µs]", ylabel="contact force [N]", xlim=(0, 110))
        ax.legend(fontsize=7)
    ax = axes[2]
    for mesh, run in sorted((indentation or {}).items()):
        h = np.loadtxt(ct.RESULTS / run["csv"], delimiter=",", skiprows=1)
        ax.plot(np.r_[0, h[:, 0]] * 1e6, np.r_[0, h[:, 1]], "o-", ms=3, lw=1.2,
                label=f"FE quasi-static, {mesh} mesh")
    if indentation:
        law = l4.impactmaps.law_for_sphere("stronge", l4.sphere(), l4.STEEL)
        a_max = next(iter(indentation.values()))["max_indentation_m"]
        alpha = np.linspace(0, a_max, 200)
        ax.plot(alpha * 1e6, law.loading_force(alpha), "k--", lw=1, label="refined Stronge")
        ax.plot(alpha * 1e6, law.force(alpha, a_max), "k--", lw=1)
    ax.set(title="elastic sphere on elastic–plastic block (S_y 235 MPa)",
           xlabel="approach of the sphere [µm]", ylabel="force [N]")
    ax.legend(fontsize=7)
    fig.suptitle("Level 4: steel sphere R 10 mm on the SS steel beam 500×20×20 mm — "
                 "3D contact (CalculiX) vs toolkit", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def level4(figure_path=None):
    """Print the level-4 tables; re-derive the FE quantities from the committed CSVs with
    the current rules (``level4_contact.quantities_from_csv``) and store them; draw
    ``figures/fe_level4_force_history.png``."""
    path = ct.RESULTS / "level4_contact.json"
    data = json.loads(path.read_text())
    for run in data.get("runs", {}).values():
        run.update(l4.quantities_from_csv(ct.RESULTS / run["csv"]))
    path.write_text(json.dumps(data, indent=1))
    print(level4_table(data))
    print()
    print(level4_toolkit_table(data, "plastic"))
    indent = ct.RESULTS / "level4_plastic_indent.json"
    indentation = json.loads(indent.read_text()) if indent.exists() else None
    if indentation:
        print()
        print(level4_plastic_indent.table(indentation))
    level4_figure(data, figure_path or FIGURES / "fe_level4_force_history.png", indentation)


if __name__ == "__main__":
    print("## Level 1\n")
    print(level1_tables())
    if (ct.RESULTS / "level3_dynamics.json").exists():
        print("\n## Level 3\n")
        print(level3_tables())
        print("\n## Level 3, linear law\n")
        print(linear_table())
    if (ct.RESULTS / "level3_dynamics_short.json").exists():
        print("\n## Level 3, short beam\n")
        print(level3_tables("level3_dynamics_short.json").split("\n\nPatch radius")[0])
        print("\n## Level 3, short beam, linear law\n")
        print(linear_table("level3_dynamics_short.json"))
    if (ct.RESULTS / "level3_plate.json").exists():
        print("\n## Level 3, plate\n")
        print(plate_table())
    if (ct.RESULTS / "level4_contact.json").exists():
        print("\n## Level 4\n")
        level4()
    figures()
