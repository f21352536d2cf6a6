"""Store the asymptote peaks in the shipped (ζ, λ) maps, so that a lookup computes no asymptote.

A lookup's regime compares the interpolated F̄max with the infinite-structure peak at ζ and
the quasi-static peak at λ (:func:`impactmaps.maps.regimes.classify`). Every map that the
sweep writes now stores them, per structure and grid value of their axis
(:func:`impactmaps.maps.dataset.with_asymptote_peaks`); the shipped maps were built before
and get them here. Each map of a family with regimes (linear, Hertz) that lacks them is read,
given ``infinite_structure_peak`` (structure, ζ) and ``quasi_static_peak`` (structure, λ),
and written back through :func:`impactmaps.maps.store.save_atomic`; every other variable and
attribute is left as it was (checked: the script refuses to write a map whose other
variables would change). Deterministic: the peaks are the family's asymptotes at the grid
values. The plastic maps have no regimes and are left alone. A map that already stores the
peaks is skipped.

    python validation/add_asymptote_peaks.py                 # the package's maps, in place
    python validation/add_asymptote_peaks.py --smoke         # one linear map, copied into a temporary directory
"""

from __future__ import annotations

import shutil
import time
from pathlib import Path

import numpy as np
import xarray as xr

from impactmaps.maps.dataset import ASYMPTOTE_PEAKS, map_law, with_asymptote_peaks
from impactmaps.maps.registry import map_family
from impactmaps.maps.store import save_atomic

from _script_options import parse

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "impactmaps" / "maps" / "data"


def _same_attrs(before: dict, after: dict) -> bool:
    return before.keys() == after.keys() and all(np.array_equal(np.asarray(before[key]), np.asarray(after[key]))
                                                 for key in before)


def same_data(before: xr.Dataset, after: xr.Dataset) -> bool:
    """Whether every variable, coordinate and attribute of ``before`` is in ``after`` unchanged (bit for bit)."""
    if not _same_attrs(before.attrs, after.attrs):
        return False
    for name in [*before.coords, *before.data_vars]:
        old, new = before[name], after[name]
        if old.dims != new.dims or not _same_attrs(old.attrs, new.attrs) or old.dtype != new.dtype:
            return False
        if old.dtype.kind in "OUS":
            if not np.array_equal(old.values.astype(str), new.values.astype(str)):
                return False
        elif old.values.tobytes() != new.values.tobytes():
            return False
    return True


def add_peaks(path: Path) -> str:
    """Add the asymptote peaks to the map at ``path`` (in place); what was done, in words."""
    with xr.open_dataset(path, engine="scipy") as opened:
        dataset = opened.load()
    if not map_family(map_law(dataset)).classifies:
        return "no regimes (left alone)"
    if all(name in dataset for name in ASYMPTOTE_PEAKS):
        return "already stores its asymptote peaks"
    start = time.perf_counter()
    original = path.read_bytes()
    save_atomic(with_asymptote_peaks(dataset), path)
    with xr.open_dataset(path, engine="scipy") as opened:
        written = opened.load()
    if not same_data(dataset, written):
        path.write_bytes(original)
        raise RuntimeError(f"{path.name}: writing the peaks would change another variable (left as it was)")
    return f"asymptote peaks added ({time.perf_counter() - start:.1f} s)"


def _options(parser) -> None:
    parser.add_argument("--only", nargs="*", default=None, help="only these map names (file stems)")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=DATA, add_arguments=_options)
    paths = sorted(DATA.glob("*.nc"))
    if args.only:
        paths = [path for path in paths if path.stem in args.only]
    if args.smoke:  # a copy of the smallest linear map, never the package's
        source = min((p for p in paths if p.stem.startswith("plate-ssss-mindlin-s10")), key=lambda p: p.stat().st_size)
        paths = [Path(shutil.copy(source, args.out_dir / source.name))]
    elif args.out_dir != DATA:
        paths = [Path(shutil.copy(path, args.out_dir / path.name)) for path in paths]
    for path in paths:
        print(f"{path.name}: {add_peaks(path)}")


if __name__ == "__main__":
    main()
