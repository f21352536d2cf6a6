"""The main job: the normalised maximum-force chart (seed 001 Figure 2) with its data."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..solvers.modal import ModalSettings
from .lookup import markdown_table
from .structures import MapStructure
from .sweep import log_grid, sweep

__all__ = ["CHART_STRUCTURES", "DEFAULT_CHART_LAMBDAS", "make_chart", "tidy_frame"]

CHART_STRUCTURES = (
    MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,)),
    MapStructure(kind="plate", theory="kirchhoff", supports="SSSS"),
)
DEFAULT_CHART_LAMBDAS = (0.05, 0.1, 0.2, 0.425, 1.0, 2.0, 5.0, 20.0)


def tidy_frame(dataset):
    """A sweep dataset as a tidy pandas DataFrame (one row per computed point)."""
    frame = dataset.drop_vars(["kind", "theory", "supports", "aspect_ratio", "slenderness"]).to_dataframe().reset_index()
    frame = frame[frame["done"] == 1].drop(columns="done")
    return frame.rename(columns={"lambda_": "lambda"})


def make_chart(
    out_dir: Path | str = "impactmaps-output",
    *,
    zeta_range=(0.005, 100.0),
    zeta_count: int = 60,
    lambdas=None,
    structures=CHART_STRUCTURES,
    settings: ModalSettings | None = None,
    progress: bool = True,
    max_workers: int | None = None,
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
        Number of log-spaced ζ values.
    lambdas : sequence of float, optional
        Relative stiffnesses λ (default :data:`DEFAULT_CHART_LAMBDAS`).
    structures : sequence of MapStructure
    settings : ModalSettings, optional
    progress : bool
        Show a progress bar.
    max_workers : int, optional
        Local worker processes (default: all cores).

    Returns
    -------
    dict
        Paths of the files written, keyed by kind.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plotting import plot_fmax_chart, plot_regime_map, plot_regime_strip

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    zetas = log_grid(zeta_range[0], zeta_range[1], zeta_count)
    lambdas = np.asarray(DEFAULT_CHART_LAMBDAS if lambdas is None else lambdas, dtype=float)
    paths = {"netcdf": out / "fmax_map.nc"}
    dataset = sweep(structures, zetas, lambdas, settings=settings, path=paths["netcdf"], progress=progress,
                    max_workers=max_workers)

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
