"""Level 6 tables for the README: FE plate frequencies per case and mesh, and the current toolkit.

``python validation/fe/level6_report.py`` (seconds, no ccx) reads ``results/level6_plates.json``
and prints markdown tables: the FE bending modes (best mesh), the mesh difference, wall
times, and the toolkit's Kirchhoff plate (and, where the toolkit has them, the Mindlin plate
with any edges and the laminated plate) against the FE.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ccx_tools as ct  # noqa: E402

import impactmaps  # noqa: E402

STEEL = impactmaps.material("structural-steel")
PLY = impactmaps.material("as4-3501-6")
ANGLES = {"qi": [0, 45, -45, 90, 0, 45, -45, 90], "cp": [0, 90, 0, 90, 0, 90, 0, 90]}


def _fmt(values, digits=1):
    return " / ".join(f"{v:.{digits}f}" for v in values)


def _pct(values):
    return " / ".join(f"{100 * v:+.2f}" for v in values)


def plate_for(key, case, theory):
    if key.startswith("solid"):
        edges = key.split("-")[1]
        return impactmaps.Plate.isotropic(case["length_x_m"], case["length_y_m"], case["thickness_m"],
                                          STEEL, theory=theory, edges=edges)
    laminate = impactmaps.Laminate.from_layup(PLY, ANGLES[key.split("-")[1]], symmetric=True)
    return impactmaps.Plate.from_laminate(case["length_x_m"], case["length_y_m"], laminate,
                                          theory=theory, edges="CCCC")


def toolkit_hz(key, case, theory, count=8):
    """Sorted first ``count`` frequencies [Hz], or the reason the toolkit cannot give them."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            plate = plate_for(key, case, theory)
            if hasattr(plate, "natural_frequencies_hz"):
                return np.sort(np.asarray(plate.natural_frequencies_hz(count)))[:count]
            w = np.asarray(plate.modes(0.0, min_modes=count).frequencies[:count])
            return np.sort(w) / (2 * np.pi)
    except (ValueError, AttributeError) as exc:
        return str(exc).split(";")[0][:90]


def main():
    record = json.loads((ct.RESULTS / "level6_plates.json").read_text())
    print("| case | FE bending modes 1–8 [Hz] (best mesh) | mesh Δ (second-best − best) [%] | "
          "meshes | ccx wall [s] |\n|---|---|---|---|---|")
    for key, entry in record["cases"].items():
        best = entry[entry["best_mesh"]]
        walls = " / ".join(f"{entry[m]['wall_time_s']:.0f}" for m in ("coarse", "fine", "finest")
                           if m in entry)
        meshes = " / ".join("×".join(map(str, entry[m]["elements"])) for m in ("coarse", "fine", "finest")
                            if m in entry)
        print(f"| {key} | {_fmt(best['fe_bending_hz'])} | {_pct(entry['mesh_difference'])} | "
              f"{meshes} | {walls} |")
    print()
    print("| case | theory | toolkit − FE, sorted modes 1–8 [%] |\n|---|---|---|")
    for key, entry in record["cases"].items():
        best = entry[entry["best_mesh"]]
        fe = np.sort(best["fe_bending_hz"])
        for theory in ("kirchhoff", "mindlin"):
            got = toolkit_hz(key, best, theory)
            text = _pct(got / fe - 1) if isinstance(got, np.ndarray) else f"not available: {got}"
            print(f"| {key} | {theory} | {text} |")


if __name__ == "__main__":
    main()
