"""``impactmaps plot PATH``: draw a user's own results.

* a parameter study (the ``--out`` directory of ``simulate CASE --vary KEY=…``, or its
  ``study.csv``): the chosen scalars (default peak force and restitution) against the
  varied key, on a log axis when the study was log-spaced;
* a sweep result (the ``output`` directory of ``impactmaps sweep`` or of ``chart``, or a
  ``.nc``/``.npz`` map file): its F̄max chart, every λ or the chosen ones (drawn at the
  grid's nearest λ, labelled with it); an elastic-plastic map at the β given.
"""

from __future__ import annotations

import json
from pathlib import Path

from .._files import written_atomically

__all__ = ["cmd_plot", "draw_study", "draw_sweep", "find_plot_source"]

#: Map files a sweep or chart directory holds, in the order they are looked for.
SWEEP_FILES = ("sweep.nc", "fmax_map.nc")


def find_plot_source(path: Path) -> tuple[str, Path]:
    """(``"study"`` or ``"sweep"``, the file to read) for ``path`` (a directory or a file)."""
    path = Path(path)
    if not path.exists():
        raise ValueError(f"{str(path)!r} does not exist: give a study's --out directory, a sweep's output "
                         "directory, or a study.csv / .nc / .npz file")
    if path.is_dir():
        if (path / "study.csv").is_file():
            return "study", path / "study.csv"
        for name in SWEEP_FILES:
            if (path / name).is_file():
                return "sweep", path / name
        raise ValueError(f"{str(path)!r} holds no study.csv (simulate --vary) and no {' or '.join(SWEEP_FILES)} "
                         "(sweep, chart): nothing to plot")
    if path.suffix == ".csv":
        return "study", path
    if path.suffix in (".nc", ".npz"):
        return "sweep", path
    raise ValueError(f"{str(path)!r} is not a study table (.csv) or a map file (.nc, .npz)")


def _spacing(table_path: Path) -> str | None:
    """The study's spacing from its ``study.json`` beside the table (``None`` if unknown)."""
    side = table_path.with_name("study.json")
    if not side.is_file():
        return None
    try:
        return json.loads(side.read_text(encoding="utf-8")).get("spacing")
    except (json.JSONDecodeError, AttributeError):
        return None


def draw_study(source: Path, path: Path, quantities=None) -> Path:
    """Draw the study in ``source`` (its directory or ``study.csv``) into the image ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    from ..plotting import plot_study

    source = Path(source)
    table_path = source / "study.csv" if source.is_dir() else source
    table = pd.read_csv(table_path)
    if table.empty or len(table.columns) < 2:
        raise ValueError(f"{table_path}: not a study table (no rows)")
    key = str(table.columns[0])
    spacing = _spacing(table_path)
    chosen = tuple(quantities) if quantities else ("peak_force_N", "restitution")
    axes = plot_study(table, key, chosen, log_x=(spacing == "log") if spacing in ("log", "even") else None)
    figure = axes[0].figure
    figure.tight_layout()
    try:
        with written_atomically(path) as part:
            figure.savefig(part, dpi=120)
    finally:
        plt.close(figure)
    return Path(path)


def draw_sweep(source: Path, path: Path, lambdas=None, beta=None) -> Path:
    """Draw the F̄max chart of the map file ``source`` into the image ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..maps.files.data_io import read_dataset
    from ..plotting import plot_fmax_chart

    try:
        dataset = read_dataset(source)
    except Exception as error:  # noqa: BLE001 - any reader failure is a file that is not a map
        raise ValueError(f"{source}: not a readable map file ({(str(error).splitlines() or [''])[0].removeprefix('Error: ')})") from None
    if "fmax_normalised" not in dataset or "zeta" not in dataset.dims:
        raise ValueError(f"{source}: no F̄max over ζ in this file (not a sweep or chart result)")
    if "beta" in dataset.dims:
        grid = [float(b) for b in dataset["beta"].values]
        if beta is None:
            raise ValueError(f"{source} is an elastic-plastic map over β: give --beta B (its β: "
                             f"{', '.join(f'{b:g}' for b in grid)})")
        dataset = dataset.sel(beta=float(beta), method="nearest")
    elif beta is not None:
        raise ValueError(f"--beta = {beta!r}: {source} has no β axis (an elastic map)")
    if "done" in dataset and not bool(dataset["done"].values.all()):
        dataset = dataset.where(dataset["done"] > 0)  # unfinished points: not drawn
    figure, ax = plt.subplots(figsize=(10, 6))
    try:
        plot_fmax_chart(dataset, lambdas=lambdas, ax=ax)
        figure.tight_layout()
        with written_atomically(path) as part:
            figure.savefig(part, dpi=120)
    finally:
        plt.close(figure)
    return Path(path)


def cmd_plot(args) -> dict:
    from ._common import check

    kind, source = find_plot_source(args.path)
    base = args.path if Path(args.path).is_dir() else Path(args.path).parent
    out = Path(args.out) if args.out else base / ("study.png" if kind == "study" else "sweep_chart.png")
    if out.suffix.lower() not in (".png", ".svg", ".pdf"):
        raise ValueError(f"--out = {str(out)!r}: give an image file name ending in .png, .svg or .pdf")
    if not out.parent.is_dir():
        raise ValueError(f"--out = {str(out)!r}: its directory {str(out.parent)!r} does not exist")
    if kind == "study":
        if args.lambdas or args.beta is not None:
            raise ValueError("--lambdas and --beta choose what a sweep's chart draws, not a study's")
        draw_study(source, out, args.quantity)
        return {"kind": "study", "source": str(source), "figure": str(out),
                "quantities": list(args.quantity or ("peak_force_N", "restitution"))}
    if args.quantity:
        raise ValueError("--quantity chooses a study's panels; a sweep's chart draws F̄max")
    for value in args.lambdas or ():
        check("--lambdas", value, 0.0, float("inf"), "a relative stiffness λ")
    draw_sweep(source, out, args.lambdas or None, args.beta)
    return {"kind": "sweep", "source": str(source), "figure": str(out)}
