"""The main job: the normalised maximum-force chart (seed 001 Figure 2) with its data."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..solvers.modal import ModalSettings
from .lookup import markdown_table
from .structures import MapStructure
from .sweep import log_grid, sweep

__all__ = ["CHART_STRUCTURES", "DEFAULT_CHART_LAMBDAS", "DEFAULT_ZETA_COUNT", "check_chart_grid", "make_chart", "tidy_frame"]

CHART_STRUCTURES = (
    MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,)),
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS"),
)
DEFAULT_CHART_LAMBDAS = (0.05, 0.1, 0.2, 0.425, 1.0, 2.0, 5.0, 20.0)
#: ζ points per curve of the default chart: enough that the re-impact peaks of F̄max(ζ)
#: are resolved, not jagged (issue 12).
DEFAULT_ZETA_COUNT = 200


def tidy_frame(dataset):
    """A sweep dataset as a tidy pandas DataFrame (one row per computed point).

    The ``method`` column holds the model's name (``modal+residual``,
    ``modal+residual-capped``, ``infinite-structure-asymptote``), not its code.
    """
    from .sweep import METHODS

    frame = dataset.drop_vars(["kind", "theory", "supports", "aspect_ratio", "slenderness"]).to_dataframe().reset_index()
    frame = frame[frame["done"] == 1].drop(columns="done")
    if "method" in frame:
        frame["method"] = [METHODS[int(code)] for code in frame["method"]]
    return frame.rename(columns={"lambda_": "lambda"})


def check_chart_grid(zeta_range, zeta_count, lambdas) -> None:
    """Refuse a chart grid that cannot be drawn, before anything is computed.

    The names in the messages are the command-line options (``--zeta-count``, …).
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


def make_chart(
    out_dir: Path | str = "impactmaps-output",
    *,
    zeta_range=(0.005, 100.0),
    zeta_count: int = DEFAULT_ZETA_COUNT,
    lambdas=None,
    structures=CHART_STRUCTURES,
    settings: ModalSettings | None = None,
    progress: bool = True,
    max_workers: int | None = None,
    overwrite: bool = False,
) -> dict:
    """Compute and draw the F̄max(ζ, λ) chart for SS beams and square plates.

    Writes into ``out_dir``: ``fmax_map.nc`` (the resumable sweep result, NetCDF),
    ``fmax_map.csv`` (tidy), ``fmax_chart.png`` and ``.svg`` (Figure 2),
    ``regime_map_<structure>.png`` and ``lookup_table.md``.

    Parameters
    ----------
    out_dir : path-like
    zeta_range : (float, float)
        Smallest and largest loss factor ζ.
    zeta_count : int
        Number of log-spaced ζ values per curve (default :data:`DEFAULT_ZETA_COUNT`, 200).
    lambdas : sequence of float, optional
        Relative stiffnesses λ (default :data:`DEFAULT_CHART_LAMBDAS`).
    structures : sequence of MapStructure
    settings : ModalSettings, optional
    progress : bool
        Show a progress bar.
    max_workers : int, optional
        Local worker processes (default: all cores).
    overwrite : bool
        Replace an ``fmax_map.nc`` made with another grid instead of refusing it.

    Returns
    -------
    dict
        Paths of the files written, keyed by kind.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plotting import plot_fmax_chart, plot_regime_map, plot_regime_strip

    check_chart_grid(zeta_range, zeta_count, lambdas)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out = {str(out)!r} is a file, not a directory")
    zetas = log_grid(zeta_range[0], zeta_range[1], zeta_count)
    lambdas = np.asarray(DEFAULT_CHART_LAMBDAS if lambdas is None else lambdas, dtype=float)
    paths = {"netcdf": out / "fmax_map.nc"}
    dataset = sweep(structures, zetas, lambdas, settings=settings, path=paths["netcdf"], progress=progress,
                    max_workers=max_workers, overwrite=overwrite)
    out.mkdir(parents=True, exist_ok=True)

    paths["csv"] = out / "fmax_map.csv"
    tidy_frame(dataset).to_csv(paths["csv"], index=False)

    figure, (ax, strip) = plt.subplots(2, 1, figsize=(9, 9), sharex=True,
                                       gridspec_kw={"height_ratios": [3, 1.3]})
    plot_fmax_chart(dataset, ax=ax)
    ax.set_xlabel("")
    plot_regime_strip(dataset, ax=strip)
    figure.tight_layout()
    paths["png"] = out / "fmax_chart.png"
    paths["svg"] = out / "fmax_chart.svg"
    figure.savefig(paths["png"], dpi=150)
    figure.savefig(paths["svg"])
    plt.close(figure)

    for name in dataset["structure"].values:
        figure, ax = plt.subplots(figsize=(7, 5))
        plot_regime_map(dataset, str(name), ax=ax)
        figure.tight_layout()
        paths[f"regime_map_{name}"] = out / f"regime_map_{name}.png"
        figure.savefig(paths[f"regime_map_{name}"], dpi=120)
        plt.close(figure)

    coarse_zetas = [z for z in (0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100) if zetas[0] <= z <= zetas[-1]]
    tables = [markdown_table(dataset, str(name), zetas=coarse_zetas) for name in dataset["structure"].values]
    paths["markdown"] = out / "lookup_table.md"
    paths["markdown"].write_text(
        "# Normalised maximum force F̄max = Fmax/(m_i V0 ω)\n\n"
        "Linear contact, impact at the centre, simply supported; nearest computed grid point.\n"
        "Peak force in newtons: F̄max · m_i · V0 · sqrt(K/m_i).\n\n" + "\n\n".join(tables) + "\n"
    )
    return paths
