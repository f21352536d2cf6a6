"""Charts of the (ζ, λ) maps: F̄max against ζ, the regimes, the elastic-plastic panels
(each takes ``ax=None`` and returns the Axes).
"""

from __future__ import annotations

import numpy as np

from ..maps.family.accuracy import STATUSES
from ..maps.family.builtin_families import LAYOUTS, PlasticLayout, family_layout
from ..maps.family.map_family import map_law
from ..maps.family.regimes import REGIMES, classify, infinite_structure_peak, quasi_static_peak
from ..targets.options import depends_on_slenderness
from .axes import axes_or_new

__all__ = ["REGIME_COLOURS", "SENSITIVE_ALPHA", "FMAX_LABELS", "PLASTIC_PANELS", "NORMALISATION_NOTES",
           "structure_label", "plot_fmax_chart",
           "plot_plastic_chart", "plot_regime_strip", "plot_regime_map"]

REGIME_COLOURS = {
    "local": "#cfe8cf",
    "infinite-structure": "#cfe0f3",
    "transition": "#f6e3c7",
    "quasi-static": "#e6d5ef",
}


#: Opacity of the band drawn over sensitive stretches of a curve.
SENSITIVE_ALPHA = 0.3

#: Map law → (ζ axis label, F̄max axis label) of its charts (the families' ``labels``); ``"plastic"``:
#: those every elastic-plastic family shares.
FMAX_LABELS = {name: (layout.labels["zeta"], layout.labels["fmax"]) for name, layout in LAYOUTS.items()} | {
    "plastic": (PlasticLayout.labels["zeta"], PlasticLayout.labels["fmax"])}


def plot_fmax_chart(dataset, *, structures=None, lambdas=None, asymptotes=True, shade_regimes=True, ax=None):
    """Figure 2 of Christoforou & Yigit 1998: F̄max against ζ (log axis) for several λ.

    Plates solid, beams dashed; the quasi-static and infinite-structure peaks as asymptotes
    (linear maps only); ``sensitive`` points as a band between ``fmax_low`` and ``fmax_high``,
    marked ×. Axis labels follow the map's contact law (:data:`FMAX_LABELS`); an
    elastic-plastic map is drawn at one β (see :func:`plot_plastic_chart`).

    Parameters
    ----------
    dataset : xarray.Dataset
        A sweep result (dims ``structure``, ``lambda_``, ``zeta``).
    structures : list of str, optional
        Structure names to draw (default all).
    lambdas : list of float, optional
        λ values to draw (default all), each at the nearest grid λ (the legend's).
    asymptotes : bool
        Draw the quasi-static and infinite-structure asymptotes (linear maps only).
    shade_regimes : bool
        Shade the local band (F̄max ≥ 0.9) and the quasi-static band along ζ.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """

    if "beta" in dataset.dims:
        raise ValueError("dataset is an elastic-plastic map over β: select one β "
                         "(dataset.sel(beta=..., method='nearest')) or draw it with plot_plastic_chart")
    ax = axes_or_new(ax)
    family = family_layout(map_law(dataset))
    asymptotes = asymptotes and family.closed_form_asymptotes
    structures, lambda_values = _selection(dataset, structures, lambdas)
    kinds = {name: str(dataset["kind"].sel(structure=name).item()) for name in structures}
    styles = _structure_styles(kinds)
    zeta = dataset["zeta"].values
    colours, markers = _lambda_styles(len(lambda_values))
    if shade_regimes:
        ax.axhspan(0.9, 1.05, color=REGIME_COLOURS["local"], alpha=0.6, lw=0, zorder=0)
        # above every curve (F̄max ≤ 1 with a linear law), in the middle of the ζ range
        ax.text(np.sqrt(zeta[0] * zeta[-1]), 1.025, r"local band: $\bar{F}_{max} \geq 0.9$", fontsize=8,
                ha="center", va="center", color="#2f6f2f")
        if "regime" in dataset:
            _shade_regime_bands(ax, dataset, structures, lambda_values)
    if asymptotes:
        dense = np.geomspace(zeta[0], zeta[-1], 300)
        if "plate" in kinds.values():
            ax.plot(dense, infinite_structure_peak(dense, "plate"), color="0.55", lw=3.0, alpha=0.6,
                    label="infinite plate", zorder=1)
        if "beam" in kinds.values():
            ax.plot(dense, infinite_structure_peak(dense, "beam"), color="0.55", lw=3.0, alpha=0.6, ls="--",
                    label="infinite beam", zorder=1)
    marks = max(1, zeta.size // 8)
    for colour, marker, lam in zip(colours, markers, lambda_values):
        if asymptotes:
            ax.axhline(float(quasi_static_peak(lam)), color=colour, lw=0.9, ls=":", zorder=1)
        for name in structures:
            kind = kinds[name]
            curve = dataset.sel(structure=name).sel(lambda_=lam, method="nearest")
            values = _draw_sensitive_bands(ax, zeta, curve, colour, kind)
            ax.plot(zeta, values, color=colour, ls=styles[name], lw=1.6, zorder=2,
                    marker=marker, markevery=marks, ms=4, mfc="white" if kind == "beam" else colour)
        ax.plot([], [], color=colour, lw=2.0, marker=marker, ms=4, label=f"λ = {lam:g}")
    several = len(set(kinds.values())) < len(kinds)
    if several:  # several structures of a kind (laminates, edges): each named by its line
        for name in structures:
            label = structure_label(dataset, name)  # its details on a second line: the legend stays narrow
            ax.plot([], [], color="k", ls=styles[name], lw=1.6, label=label.replace(" (", "\n(", 1))
    for kind, style in (("plate", "-"), ("beam", "--")):
        if kind in kinds.values() and not several:
            ax.plot([], [], color="k", ls=style, lw=1.6, label=f"{kind}s")
    if asymptotes:
        ax.plot([], [], color="k", ls=":", lw=0.9, label=r"quasi-static $\sqrt{\lambda/(1+\lambda)}$")
    if _has_sensitive(dataset, structures, lambda_values):
        ax.plot([], [], ls="none", marker="x", ms=6, mew=1.3, color="0.3",
                label="sensitive (×): no converged value;\nband = spread of " + r"$\bar{F}_{max}$"
                + (" (beams hatched)" if "beam" in kinds.values() else ""))
    ax.set_xscale("log")
    ax.set_xlim(zeta[0], zeta[-1])
    top = 0.0 if family.fmax_at_most_one else float(np.nanmax(dataset["fmax_normalised"].values, initial=0.0))
    ax.set_ylim(0.0, max(1.05, 1.05 * top))
    ax.set_xlabel(family.labels["zeta"])
    ax.set_ylabel(family.labels["fmax"])
    ax.set_title("Normalised maximum impact force" + ("" if several else ": plates solid, beams dashed")
                 + ("; quasi-static dotted" if asymptotes else ""))
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    note = NORMALISATION_NOTES.get(map_law(dataset))
    if note:
        ax.text(1.01, 0.0, note, transform=ax.transAxes, fontsize=7.5, va="bottom", ha="left", color="0.25")
    return ax


#: Map law → the definitions a reader of its chart needs and the axis labels do not give.
NORMALISATION_NOTES = {
    "linear": "ω = √(K/m_i): the angular frequency of\nthe impactor on the contact spring K\n"
              "λ = K_st/K: static stiffness of the\nstructure at the impact point over K\n"
              "ζ: loss factor (waves carry energy\naway; docs: chart page)",
}


def _sensitive_mask(curve):
    """True at the points of one curve whose status is ``sensitive`` (no converged value)."""
    if "status" not in curve:
        return np.zeros(curve["zeta"].size, dtype=bool)
    return np.asarray(curve["status"].values) == STATUSES.index("sensitive")


def _has_sensitive(dataset, structures, lambda_values):
    """Whether any drawn curve has a sensitive point (the band then gets a legend entry)."""
    if "status" not in dataset:
        return False
    return any(_sensitive_mask(dataset.sel(structure=name).sel(lambda_=lam, method="nearest")).any()
               for name in structures for lam in lambda_values)


def _draw_sensitive_bands(ax, zeta, curve, colour, kind="plate"):
    """Fill between ``fmax_low`` and ``fmax_high`` over each run of sensitive points of one
    curve (a beam's band hatched); returns the curve's F̄max with NaN where a band stands.
    """
    values = np.array(curve["fmax_normalised"].values, dtype=float)
    sensitive = _sensitive_mask(curve)
    if not sensitive.any():
        return values
    low = np.asarray(curve["fmax_low"].values, dtype=float)
    high = np.asarray(curve["fmax_high"].values, dtype=float)
    beam = kind == "beam"
    for start, stop in _runs(sensitive):
        first, last = max(start - 1, 0), min(stop + 1, zeta.size - 1)
        span = slice(first, last + 1)
        ax.fill_between(zeta[span], low[span], high[span], facecolor=colour, alpha=SENSITIVE_ALPHA, lw=0,
                        zorder=1.5, hatch="////" if beam else None, edgecolor=colour if beam else "none")
        for edge in (low, high):
            ax.plot(zeta[span], edge[span], color=colour, lw=0.6, ls="--" if beam else "-", alpha=0.8,
                    zorder=1.6)
    ax.plot(zeta[sensitive], 0.5 * (low[sensitive] + high[sensitive]), ls="none", marker="x", ms=6, mew=1.3,
            color=colour, zorder=3)
    values[sensitive] = np.nan
    return values


#: Line styles of the plate and the beam structures of one chart, the first of each kind solid
#: (plates) or dashed (beams).
_LINE_STYLES = {"plate": ("-", "-.", (0, (1, 1)), (0, (5, 1, 1, 1, 1, 1))),
                "beam": ("--", (0, (6, 2)), (0, (3, 1, 1, 1)), (0, (2, 3)))}


def _structure_styles(kinds: dict) -> dict:
    """Structure name → line style: solid plates and dashed beams, and where a kind has several
    structures (a sweep of laminates or edges) each its own style, cycling."""
    styles, seen = {}, {"plate": 0, "beam": 0}
    for name, kind in kinds.items():
        options = _LINE_STYLES[kind]
        count = sum(1 for other in kinds.values() if other == kind)
        styles[name] = options[seen[kind] % len(options)] if count > 1 else options[0]
        seen[kind] += 1
    return styles


def _lambda_styles(count):
    """Distinct colours and markers for ``count`` λ curves (neighbouring λ differ in both)."""
    import matplotlib.pyplot as plt

    palette = plt.get_cmap("tab10").colors
    colours = [palette[k % len(palette)] for k in range(count)]
    symbols = ("o", "s", "^", "D", "v", "P", "X", "*")
    return colours, [symbols[k % len(symbols)] for k in range(count)]


def _selection(dataset, structures, lambdas):
    """The structures and the grid λ values to draw (default all): each asked λ replaced
    by the grid's nearest in log λ, once.
    """
    structures = list(dataset["structure"].values) if structures is None else list(structures)
    grid = np.asarray(dataset["lambda_"].values, float)
    if lambdas is None:
        return structures, grid
    asked = np.atleast_1d(np.asarray(lambdas, float))
    if not np.all(np.isfinite(asked) & (asked > 0)):
        raise ValueError(f"lambdas = {list(asked)} is invalid: give positive finite λ values")
    nearest = [float(grid[np.argmin(np.abs(np.log(grid) - np.log(value)))]) for value in asked]
    return structures, np.array(list(dict.fromkeys(nearest)))


def _regime_codes(regimes):
    """Regime labels → their index in ``REGIMES`` (NaN where not computed)."""
    codes = np.full(np.shape(regimes), np.nan)
    for index, name in enumerate(REGIMES):
        codes[regimes == name] = index
    return codes


def _shade_regime_bands(ax, dataset, structures, lambda_values):
    """Vertical bands over the ζ ranges where every drawn point shares one regime."""
    regimes = dataset["regime"].sel(structure=structures).sel(lambda_=lambda_values, method="nearest")
    zeta = dataset["zeta"].values
    columns = [set(np.asarray(regimes.isel(zeta=k).values).ravel()) for k in range(zeta.size)]
    edges = np.sqrt(zeta[1:] * zeta[:-1])
    edges = np.concatenate([[zeta[0]], edges, [zeta[-1]]])
    for name in ("quasi-static",):  # the local regime is the horizontal band F̄max ≥ 0.9 already
        shared = np.array([column == {name} for column in columns])
        if not shared.any():
            continue
        for start, stop in _runs(shared):
            ax.axvspan(edges[start], edges[stop + 1], color=REGIME_COLOURS[name], alpha=0.5, lw=0, zorder=0)
            middle = np.sqrt(edges[start] * edges[stop + 1])
            ax.text(middle, 0.5, f"{name}\n(every λ)", fontsize=8, ha="center", va="bottom", color="0.3")


def _runs(mask):
    """(first, last) index of each run of True in a boolean array."""
    runs, start = [], None
    for index, value in enumerate(mask):
        if value and start is None:
            start = index
        if not value and start is not None:
            runs.append((start, index - 1))
            start = None
    if start is not None:
        runs.append((start, len(mask) - 1))
    return runs


def plot_regime_strip(dataset, *, structures=None, lambdas=None, ax=None):
    """The regime of every point of a chart: one row per (structure, λ), ζ along x, from a
    sweep result ``dataset`` with a ``regime`` variable (``structures``, ``lambdas``:
    default all).
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    ax = axes_or_new(ax)
    structures, lambda_values = _selection(dataset, structures, lambdas)
    rows, labels = [], []
    kinds = [str(dataset["kind"].sel(structure=name).item()) for name in structures]
    short = _short_names(dataset, structures)
    for name, kind in zip(structures, kinds):
        shown = short[name] if kinds.count(kind) > 1 else kind  # several of a kind: each named
        for lam in lambda_values:
            regimes = dataset["regime"].sel(structure=name).sel(lambda_=lam, method="nearest").values
            rows.append(_regime_codes(regimes))
            labels.append(f"{shown} λ={lam:g}")
    cmap = ListedColormap([REGIME_COLOURS[name] for name in REGIMES])
    ax.pcolormesh(dataset["zeta"].values, np.arange(len(rows)), np.array(rows), cmap=cmap, vmin=-0.5,
                  vmax=len(REGIMES) - 0.5, shading="nearest")
    ax.set_xscale("log")
    ax.set_yticks(np.arange(len(rows)))
    ax.set_yticklabels(labels, fontsize=6)
    ax.invert_yaxis()
    ax.set_xlabel("loss factor ζ")
    ax.legend(handles=[Patch(color=REGIME_COLOURS[n], label=n) for n in REGIMES], fontsize=7, ncol=4,
              loc="upper center", bbox_to_anchor=(0.5, -0.22), frameon=False)
    return ax


def _short_names(dataset, structures) -> dict:
    """Structure name → a short row label (``CCCC mindlin laminate``), or the names themselves
    where the short labels of two structures would be the same."""
    short = {}
    for name in structures:
        one = dataset.sel(structure=name)
        try:
            words = [str(one["supports"].item()), str(one["theory"].item())]
        except (KeyError, ValueError):
            return {name: str(name) for name in structures}
        short[name] = " ".join(words + (["laminate"] if "-lam" in str(name) else []))
    return short if len(set(short.values())) == len(short) else {name: str(name) for name in structures}


_SUPPORTS = {"ss": "simply supported", "cc": "clamped–clamped", "cs": "clamped–simply supported",
             "sc": "simply supported–clamped", "cf": "cantilever", "fc": "cantilever", "ff": "free–free",
             "SSSS": "simply supported", "CCCC": "clamped"}
_THEORIES = {"euler": "Euler–Bernoulli", "rayleigh": "Rayleigh", "timoshenko": "Timoshenko",
             "kirchhoff": "Kirchhoff", "mindlin": "Mindlin"}


def structure_label(dataset, structure) -> str:
    """A reader's name for the map structure ``structure`` of ``dataset``, e.g. "simply
    supported Euler–Bernoulli beam"; the name itself when its coordinates are missing.
    """
    one = dataset.sel(structure=structure)
    try:
        kind, supports, theory = (str(one[key].item()) for key in ("kind", "supports", "theory"))
    except (KeyError, ValueError):
        return str(structure)
    words = [_SUPPORTS.get(supports, f"{supports} edges" if kind == "plate" else f"{supports} supports"),
             _THEORIES.get(theory, theory), kind]
    extra = []
    if kind == "plate" and "aspect_ratio" in one.coords:
        ratio = float(one["aspect_ratio"].item())
        extra.append("square" if ratio == 1.0 else f"aspect ratio {ratio:g}")
    if depends_on_slenderness(theory) and "slenderness" in one.coords:
        extra.append(f"{'L' if kind == 'beam' else 'a'}/h = {float(one['slenderness'].item()):g}")
    if "-lam" in str(structure):  # a laminate's stiffness ratios (MapStructure.name: their digest)
        extra.append("laminate " + str(structure).rpartition("-lam")[2])
    return " ".join(words) + (f" ({', '.join(extra)})" if extra else "")


def plot_regime_map(dataset, structure, *, smooth=True, ax=None):
    """Regimes of the structure named ``structure`` on the (ζ, λ) plane (log axes), from a
    sweep result with a ``regime`` variable; ``smooth``: classify on a dense grid
    interpolated as a lookup does (when every point is computed and resolved), else one block per
    point (an ``unresolved`` point, whose F̄max is NaN, blank).
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    ax = axes_or_new(ax)
    cmap = ListedColormap([REGIME_COLOURS[name] for name in REGIMES])
    zeta, lam = dataset["zeta"].values, dataset["lambda_"].values
    one = dataset.sel(structure=structure)
    complete = bool(one["done"].values.all() and np.isfinite(one["fmax_normalised"].values).all()) \
        if "done" in one else False
    if smooth and complete and len(zeta) > 1 and len(lam) > 1:
        dense = [_log_dense(zeta, lam, one[name].values)
                 for name in ("fmax_normalised", "peak_time_normalised", "reflection_time_normalised")]
        grid_lam, grid_zeta = np.meshgrid(dense[0][1], dense[0][0], indexing="ij")
        codes = _regime_codes(classify(dense[0][2], grid_zeta, grid_lam, str(one["kind"].item()),
                                       peak_time=dense[1][2], reflection_time=dense[2][2]))
        ax.pcolormesh(dense[0][0], dense[0][1], codes, cmap=cmap, vmin=-0.5, vmax=len(REGIMES) - 0.5,
                      shading="nearest", rasterized=True)
    else:
        codes = _regime_codes(one["regime"].values)
        ax.pcolormesh(zeta, lam, codes, cmap=cmap, vmin=-0.5, vmax=len(REGIMES) - 0.5, shading="nearest")
    # contours of F̄max interpolated linearly in (log ζ, log λ) on a dense grid: the lines
    # have enough vertices for the labels to sit on them (a coarse grid's inline gaps
    # cut whole segments and left the labels floating)
    dense_zeta, dense_lam, fmax = _log_dense(zeta, lam, dataset["fmax_normalised"].sel(structure=structure).values)
    contours = ax.contour(dense_zeta, dense_lam, fmax, levels=[0.3, 0.5, 0.7, 0.9], colors="k", linewidths=0.7)
    # horizontal labels on a white box over their own line: rotated inline labels printed
    # vertically or upside down along steep contours and seemed to float beside them
    for level, segments in zip(contours.levels, contours.allsegs):
        spot = _label_spot(segments, dense_zeta, dense_lam)
        if spot is not None:
            ax.text(*spot, rf"$\bar{{F}}_{{max}}$={level:.1f}", fontsize=7, ha="center", va="center", zorder=5,
                    bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 0.6})
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("loss factor ζ")
    ax.set_ylabel("relative stiffness λ")
    ax.set_title(f"Impact regimes: {structure_label(dataset, structure)}")
    ax.legend(handles=[Patch(color=REGIME_COLOURS[n], label=n) for n in REGIMES], fontsize=8, loc="lower left")
    return ax


def _label_spot(segments, zeta, lam):
    """Where a contour level's label goes: the middle of its longest line, away from the
    axes' edges; ``None`` when the level has no line.
    """
    inner = (np.log(zeta[0]) + 0.08 * np.log(zeta[-1] / zeta[0]), np.log(zeta[-1]) - 0.08 * np.log(zeta[-1] / zeta[0]),
             np.log(lam[0]) + 0.05 * np.log(lam[-1] / lam[0]), np.log(lam[-1]) - 0.05 * np.log(lam[-1] / lam[0]))
    best, best_length = None, 0.0
    for segment in segments:
        if len(segment) < 2:
            continue
        points = np.log(np.asarray(segment, float))
        keep = ((points[:, 0] > inner[0]) & (points[:, 0] < inner[1]) & (points[:, 1] > inner[2])
                & (points[:, 1] < inner[3]))
        points = points[keep]
        if len(points) < 2:
            continue
        steps = np.hypot(*np.diff(points, axis=0).T)
        length = float(steps.sum())
        if length > best_length:
            along = np.concatenate([[0.0], np.cumsum(steps)])
            best, best_length = np.exp(points[int(np.searchsorted(along, 0.5 * length))]), length
    return None if best is None else (float(best[0]), float(best[1]))


def _log_dense(zeta, lam, values, points=200):
    """``values`` on (λ, ζ) interpolated linearly in (log λ, log ζ) onto a dense grid."""
    from scipy.interpolate import RegularGridInterpolator

    if len(zeta) < 2 or len(lam) < 2:
        return zeta, lam, values
    dense_zeta, dense_lam = np.geomspace(zeta[0], zeta[-1], points), np.geomspace(lam[0], lam[-1], points)
    interpolate = RegularGridInterpolator((np.log(lam), np.log(zeta)), values)
    grid_lam, grid_zeta = np.meshgrid(np.log(dense_lam), np.log(dense_zeta), indexing="ij")
    return dense_zeta, dense_lam, interpolate(np.stack([grid_lam, grid_zeta], axis=-1))


#: What :func:`plot_plastic_chart` draws per panel: variable, y label.
PLASTIC_PANELS = (
    ("fmax_normalised", PlasticLayout.labels["fmax"]),
    ("restitution", "coefficient of restitution e (rebound / approach speed)"),
    ("absorbed_energy_fraction", "energy absorbed by the contact / ½ m V0²"),
)


def plot_plastic_chart(maps, lambda_, *, betas=None, axes=None):
    """F̄max, restitution and absorbed energy against ζ at a few β for one λ (elastic-plastic maps).

    One curve per (β, structure): plates solid, beams dashed, one colour per β; sensitive
    points as the band ``fmax_low``–``fmax_high``.

    Parameters
    ----------
    maps : sequence of xarray.Dataset
        Elastic-plastic maps of one law (dims ``structure``, ``beta``, ``lambda_``, ``zeta``).
    lambda_ : float
        Relative stiffness K_st/K_y of the curves [-] (nearest grid λ).
    betas : sequence of float, optional
        Impact numbers (default: every second β of the first map; nearest grid β).
    axes : sequence of three matplotlib Axes, optional
        F̄max, restitution and absorbed-energy panels (default: a new figure).

    Returns
    -------
    list of matplotlib.axes.Axes
    """
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(3, 1, figsize=(8, 11), sharex=True)
    first = maps[0]
    betas = first["beta"].values[::2] if betas is None else np.asarray(betas, float)
    colours, markers = _lambda_styles(len(betas))
    for dataset in maps:
        name = str(dataset["structure"].values[0])
        kind = str(dataset["kind"].values[0])
        zeta = dataset["zeta"].values
        for colour, marker, beta in zip(colours, markers, betas):
            curve = dataset.isel(structure=0).sel(beta=beta, lambda_=lambda_, method="nearest")
            for ax, (variable, _label) in zip(axes, PLASTIC_PANELS):
                values = (_draw_sensitive_bands(ax, zeta, curve, colour, kind) if variable == "fmax_normalised"
                          else curve[variable].values)
                ax.plot(zeta, values, color=colour, ls="-" if kind == "plate" else "--", lw=1.5, marker=marker,
                        markevery=max(1, zeta.size // 8), ms=4, mfc="white" if kind == "beam" else colour,
                        label=f"β = {float(curve['beta']):.3g}, {name}")
    law = str(first.attrs.get("contact_law", ""))
    grid = ", ".join(f"{d['kind'].values[0]!s} {float(d['lambda_'].sel(lambda_=lambda_, method='nearest')):.3g}"
                     for d in maps)
    for ax, (_variable, label) in zip(axes, PLASTIC_PANELS):
        ax.set_xscale("log")
        ax.set_ylabel(label, fontsize=9)
        ax.grid(True, which="both", alpha=0.25)
    axes[0].set_title(f"Elastic-plastic contact ({law}), λ = K_st/K_y ≈ {float(lambda_):g} (nearest grid λ: {grid})\n"
                      "plates solid, beams dashed", fontsize=10)
    axes[0].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    axes[-1].set_xlabel(PlasticLayout.labels["zeta"])
    return list(axes)
