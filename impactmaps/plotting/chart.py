"""The main job: the normalised maximum-force chart (seed 001 Figure 2) with its data.

:func:`make_chart` sweeps and draws it for the linear law (ζ, λ) or the Hertz law
(ζ_h, λ_h, F̄max = F_max/F_hs); :func:`make_plastic_chart` draws the elastic-plastic
panels from the shipped (β, λ, ζ) maps, with no sweep.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .._files import written_atomically
from . import plot_fmax_chart, plot_plastic_chart, plot_regime_map, plot_regime_strip, structure_label
from ..solvers.modal_settings import ModalSettings
from ..maps.family.builtin_families import family_layout
from ..maps.compute.dataset import tidy_frame, with_asymptote_peaks
from ..maps.read.lookup import markdown_table
from ..maps.files.shipped import load_shipped_map
from ..maps.family.builtin_families import PLASTIC_LAWS
from ..maps.family.structures import MapStructure
from ..maps.compute.sweep import log_grid, require_map_fits, sweep

__all__ = ["CHART_STRUCTURES", "DEFAULT_CHART_LAMBDAS", "DEFAULT_ZETA_RANGE", "DEFAULT_ZETA_COUNT", "DEFAULT_PLASTIC_BETAS",
           "DEFAULT_PLASTIC_LAMBDA", "DEFAULT_STRUCTURE_ZETA_COUNT", "DEFAULT_STRUCTURE_LAMBDAS", "chart_structures",
           "check_chart_grid", "make_chart", "make_plastic_chart"]

CHART_STRUCTURES = (
    MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,)),
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS"),
)
DEFAULT_CHART_LAMBDAS = (0.05, 0.1, 0.2, 0.425, 1.0, 2.0, 5.0, 20.0)
#: ζ range of the default chart (seed 001 Figure 2).
DEFAULT_ZETA_RANGE = (0.005, 100.0)
#: ζ points per curve of the default chart: enough that the re-impact peaks of F̄max(ζ)
#: are resolved, not jagged (issue 12).
DEFAULT_ZETA_COUNT = 200
#: ζ points per curve of the chart of another structure (``chart --case``/``--target``): with
#: :data:`DEFAULT_STRUCTURE_LAMBDAS`, a chart of a clamped plate or a laminate in under a minute on
#: 2 cores (measured in docs/chart.rst).
DEFAULT_STRUCTURE_ZETA_COUNT = 20
#: λ of the chart of another structure: four of the shipped chart's, so its reference curves are
#: the shipped ones.
DEFAULT_STRUCTURE_LAMBDAS = (0.05, 0.2, 1.0, 5.0)


def chart_structures(structure: MapStructure | None = None) -> tuple:
    """The structures of a chart: the shipped ones (:data:`CHART_STRUCTURES`) for None, else the
    shipped simply supported structure of ``structure``'s kind (the reference its curves are drawn
    beside) and ``structure`` (alone when it is that one)."""
    if structure is None:
        return CHART_STRUCTURES
    reference = next(s for s in CHART_STRUCTURES if s.kind == structure.kind)
    return (reference,) if structure == reference else (reference, structure)


def check_chart_grid(zeta_range, zeta_count, lambdas, law: str = "linear",
                     structures: int = len(CHART_STRUCTURES)) -> None:
    """Refuse (``ValueError`` naming the command-line option) a chart grid that cannot be drawn
    or would not fit in memory, before anything is computed.
    """
    low, high = (float(v) for v in zeta_range)
    if not (0.0 < low < high < np.inf):
        raise ValueError(f"--zeta-range = {low:g} {high:g} is invalid: need 0 < A < B")
    if isinstance(zeta_count, bool) or int(zeta_count) != zeta_count or zeta_count < 2:
        raise ValueError(f"--zeta-count = {zeta_count!r} is invalid: valid range is [2, inf) (a chart needs "
                         "at least two ζ values)")
    if lambdas is not None:
        values = np.asarray(lambdas, dtype=float).ravel()
        if values.size < 2 or len(np.unique(values)) != values.size:
            raise ValueError(f"--lambdas = {' '.join(f'{v:g}' for v in values)} is invalid: give at least two "
                             "distinct values (the regime maps need two λ rows)")
        if np.any(~np.isfinite(values) | (values <= 0)):
            raise ValueError(f"--lambdas = {' '.join(f'{v:g}' for v in values)} is invalid: valid range is (0, inf)")
    n_lambdas = len(DEFAULT_CHART_LAMBDAS) if lambdas is None else np.asarray(lambdas).size
    require_map_fits(structures, {"--zeta-count": int(zeta_count), "--lambdas": n_lambdas}, law,
                     "a smaller --zeta-count or fewer --lambdas")


def make_chart(
    out_dir: Path | str = "impactmaps-output",
    *,
    zeta_range=DEFAULT_ZETA_RANGE,
    zeta_count: int = DEFAULT_ZETA_COUNT,
    lambdas=None,
    structures=CHART_STRUCTURES,
    settings: ModalSettings | None = None,
    progress: bool = True,
    max_workers: int | None = None,
    overwrite: bool = False,
    law: str = "linear",
) -> dict:
    """Compute and draw the F̄max(ζ, λ) chart of ``structures`` (default the SS beam and square
    plate; :func:`chart_structures` for another structure beside its simply supported reference).

    Writes into ``out_dir``: ``fmax_map.nc`` (the resumable sweep result), ``fmax_map.csv``,
    ``fmax_chart.png`` and ``.svg``, ``regime_map_<structure>.png`` and ``lookup_table.md``;
    returns their paths by kind.

    Parameters
    ----------
    out_dir : path-like
    zeta_range : (float, float)
        Smallest and largest loss factor ζ.
    zeta_count : int
        Number of log-spaced ζ values per curve.
    lambdas : sequence of float, optional
        Relative stiffnesses λ (default :data:`DEFAULT_CHART_LAMBDAS`).
    structures : sequence of MapStructure
        The structures swept and drawn (several of a kind: each its line style, named in the legend).
    settings : ModalSettings, optional
    progress : bool
    max_workers : int, optional
        Local worker processes (default: all cores).
    overwrite : bool
        Replace an ``fmax_map.nc`` of another grid or law instead of refusing it.
    law : {"linear", "hertz"}
        The linear chart over (ζ, λ) or the Hertz chart over (ζ_h, λ_h).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    check_chart_grid(zeta_range, zeta_count, lambdas, law if isinstance(law, str) else law.name, len(structures))
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out = {str(out)!r} is a file, not a directory")
    zetas = log_grid(zeta_range[0], zeta_range[1], zeta_count)
    lambdas = np.asarray(DEFAULT_CHART_LAMBDAS if lambdas is None else lambdas, dtype=float)
    paths = {"netcdf": out / "fmax_map.nc"}
    dataset = sweep(structures, zetas, lambdas, settings=settings, path=paths["netcdf"], progress=progress,
                    max_workers=max_workers, overwrite=overwrite, law=law)
    out.mkdir(parents=True, exist_ok=True)

    paths["csv"] = out / "fmax_map.csv"
    with written_atomically(paths["csv"]) as part:
        tidy_frame(dataset).to_csv(part, index=False)

    figure, (ax, strip) = plt.subplots(2, 1, figsize=(9, 9), sharex=True,
                                       gridspec_kw={"height_ratios": [3, 1.3]})
    family = family_layout(law)
    plot_fmax_chart(dataset, ax=ax, asymptotes=family.closed_form_asymptotes)
    plot_regime_strip(dataset, ax=strip)
    if not family.closed_form_asymptotes:
        _stored_asymptotes(ax, strip, dataset, family.labels)
    ax.set_xlabel("")
    figure.tight_layout()
    paths["png"] = out / "fmax_chart.png"
    paths["svg"] = out / "fmax_chart.svg"
    _save_png(figure, paths["png"], dpi=150)
    _save_svg(figure, paths["svg"])
    plt.close(figure)

    for name in dataset["structure"].values:
        figure, ax = plt.subplots(figsize=(7, 5))
        # the smooth map re-classifies with the closed-form criteria; other maps show their points
        plot_regime_map(dataset, str(name), ax=ax, smooth=family.closed_form_asymptotes)
        if not family.closed_form_asymptotes:
            ax.set_xlabel(family.labels["zeta"])
            ax.set_ylabel(family.labels["lambda"])
            ax.set_title(f"Impact regimes, {family.labels['contact']}: {structure_label(dataset, str(name))}")
        figure.tight_layout()
        paths[f"regime_map_{name}"] = out / f"regime_map_{name}.png"
        _save_png(figure, paths[f"regime_map_{name}"], dpi=120)
        plt.close(figure)

    coarse = [z for z in (0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100) if zetas[0] <= z <= zetas[-1]]
    # each column once: the nearest grid ζ of a coarse grid may be that of two coarse values
    coarse_zetas = sorted({float(zetas[np.argmin(np.abs(np.log(zetas / z)))]) for z in coarse})
    tables = [markdown_table(dataset, str(name), zetas=coarse_zetas) for name in dataset["structure"].values]
    shipped = all(structure in CHART_STRUCTURES for structure in structures)
    heading = family.labels["table"].format(
        structures=family.labels["structures"] if shipped else "each structure as its name says")
    paths["markdown"] = out / "lookup_table.md"
    with written_atomically(paths["markdown"]) as part:
        part.write_text(heading + "\n\n".join(tables) + "\n")
    return paths


def _save_svg(figure, path) -> None:
    """Save ``figure`` as SVG, the same bytes for the same chart: no date, clip-path ids from a
    fixed salt (matplotlib otherwise writes the time and random ids)."""
    import matplotlib

    with matplotlib.rc_context({"svg.hashsalt": "impactmaps"}), written_atomically(path) as part:
        figure.savefig(part, metadata={"Date": None})


def _save_png(figure, path, dpi: int) -> None:
    """Save ``figure`` as PNG at ``dpi``, whole or not at all."""
    with written_atomically(path) as part:
        figure.savefig(part, dpi=dpi)


#: Most ζ points of a drawn stored asymptote (taken from the chart's grid).
STORED_ASYMPTOTE_POINTS = 50


def _stored_asymptotes(ax, strip, dataset, labels: dict) -> None:
    """The asymptotes and labels of a family without closed-form asymptotes: the peaks its
    sweep stored with the result.
    """
    dataset = with_asymptote_peaks(dataset)
    zeta = dataset["zeta"].values
    dense = np.unique(np.linspace(0, zeta.size - 1, STORED_ASYMPTOTE_POINTS).round().astype(int))
    kinds = [str(kind) for kind in dataset["kind"].values]
    for kind in sorted(set(kinds), reverse=True):
        peaks = dataset["infinite_structure_peak"].values[kinds.index(kind)]
        ax.plot(zeta[dense], peaks[dense], color="0.55", lw=3.0, alpha=0.6,
                ls="-" if kind == "plate" else "--", zorder=1,
                label="infinite plate (Zener)" if kind == "plate" else "infinite beam")
    # each λ in the colour of its curve (plot_fmax_chart labels one line per λ)
    colours = {line.get_label(): line.get_color() for line in ax.get_lines()}
    for lam, peak in zip(dataset["lambda_"].values, dataset["quasi_static_peak"].values[0]):
        colour = colours.get(f"λ = {lam:g}", "0.3")
        ax.axhline(float(peak), color=colour, lw=0.9, ls=":", zorder=1)
    ax.plot([], [], color="k", ls=":", lw=0.9, label=labels["quasi_static"])
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax.set_ylabel(labels["fmax"])
    ax.set_title(f"Normalised maximum force, {labels['contact']}: plates solid, beams dashed")
    strip.set_xlabel(labels["zeta"])


#: β of the curves of the default elastic-plastic chart (nearest grid values are drawn).
DEFAULT_PLASTIC_BETAS = (1.0, 10.0, 100.0, 1000.0)
#: λ = K_st/K_y of the default elastic-plastic chart.
DEFAULT_PLASTIC_LAMBDA = 0.1


def make_plastic_chart(out_dir: Path | str = "impactmaps-output", *, law: str = "yc",
                       lambda_: float = DEFAULT_PLASTIC_LAMBDA, betas=DEFAULT_PLASTIC_BETAS) -> dict:
    """Draw the elastic-plastic chart from the shipped maps: F̄max, e and absorbed energy vs ζ
    for the SS Euler beam and the SSSS square Kirchhoff plate; writes
    ``fmax_chart_{law}.png``, ``.svg`` and ``.csv`` into ``out_dir`` and returns their paths.

    Parameters
    ----------
    out_dir : path-like
    law : {"yc", "stronge"}
        Yigit–Christoforou or the refined Stronge law (default constants).
    lambda_ : float
        K_st/K_y of the curves, inside the maps' λ range [-] (nearest grid λ).
    betas : sequence of float
        Impact numbers inside the maps' β range [-] (nearest grid β).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if law not in PLASTIC_LAWS:
        raise ValueError(f"--law = {law!r} is invalid for the elastic-plastic chart: choose "
                         + " or ".join(PLASTIC_LAWS))
    maps = [load_shipped_map(s.kind, s.theory, law) for s in CHART_STRUCTURES]
    for name, values, axis in (("--lambdas", [lambda_], "lambda_"), ("--betas", list(betas), "beta")):
        low = max(float(m[axis].min()) for m in maps) * (1 - 1e-12)
        high = min(float(m[axis].max()) for m in maps) * (1 + 1e-12)
        if not values or any(not (low <= float(v) <= high) for v in values):
            raise ValueError(f"{name} = {' '.join(f'{float(v):g}' for v in values)} is invalid: valid range is "
                             f"[{low:g}, {high:g}] (the shipped {law} maps)")
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out = {str(out)!r} is a file, not a directory")
    out.mkdir(parents=True, exist_ok=True)
    figure, axes = plt.subplots(3, 1, figsize=(9, 11), sharex=True)
    plot_plastic_chart(maps, lambda_, betas=betas, axes=axes)
    figure.tight_layout()
    paths = {"png": out / f"fmax_chart_{law}.png", "svg": out / f"fmax_chart_{law}.svg",
             "csv": out / f"fmax_chart_{law}.csv"}
    _save_png(figure, paths["png"], dpi=150)
    _save_svg(figure, paths["svg"])
    plt.close(figure)
    frames = []
    for dataset in maps:
        drawn = dataset.sel(beta=list(betas), lambda_=[lambda_], method="nearest")
        frames.append(tidy_frame(drawn).assign(structure=str(dataset["structure"].values[0])))
    import pandas as pd

    with written_atomically(paths["csv"]) as part:
        pd.concat(frames, ignore_index=True).to_csv(part, index=False)
    return paths
