"""Store the asymptote peaks in the shipped (ζ, λ) maps, so that a lookup computes no asymptote.

A lookup's regime compares the interpolated F̄max with the infinite-structure peak at ζ and
the quasi-static peak at λ (:func:`impactmaps.maps.family.regimes.classify`). Every map that the
sweep writes now stores them, per structure and grid value of their axis
(:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`); the shipped maps were built before
and get them here. Each map of a family with regimes (linear, Hertz) that lacks them is read,
given ``infinite_structure_peak`` (structure, ζ) and ``quasi_static_peak`` (structure, λ),
and written back through :func:`impactmaps.maps.files.store.save_atomic`; every other variable and
attribute is left as it was (checked: the script refuses to write a map whose other
variables would change). Deterministic: the peaks are the family's asymptotes at the grid
values. The plastic maps have no regimes and are left alone. A map that already stores the
peaks is skipped. A packed map (``.npz``) is read and written as NetCDF beside it (the
reader takes the ``.nc`` first); ``python data_build/pack_map_data.py`` then packs it.

    python data_build/add_asymptote_peaks.py                 # the package's maps, in place
    python data_build/add_asymptote_peaks.py --smoke         # one linear map, copied into a temporary directory
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

from impactmaps.maps.files.data_io import read_dataset
from impactmaps.maps.compute.dataset import ASYMPTOTE_PEAKS, map_law, with_asymptote_peaks
from impactmaps.maps.family.registry import map_family
from impactmaps.maps.files.store import save_atomic

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402

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
    """Add the asymptote peaks to the map at ``path`` (written as ``.nc`` beside a packed one, in
    place otherwise); what was done, in words."""
    dataset = read_dataset(path)
    if not map_family(map_law(dataset)).classifies:
        return "no regimes (left alone)"
    if all(name in dataset for name in ASYMPTOTE_PEAKS):
        return "already stores its asymptote peaks"
    start = time.perf_counter()
    target = path.with_suffix(".nc")
    original = target.read_bytes() if target.is_file() else None
    save_atomic(with_asymptote_peaks(dataset), target)
    if not same_data(dataset, read_dataset(target)):
        if original is None:
            target.unlink()
        else:
            target.write_bytes(original)
        raise RuntimeError(f"{path.name}: writing the peaks would change another variable (left as it was)")
    packed = " (written as NetCDF beside it: run data_build/pack_map_data.py)" if target != path else ""
    return f"asymptote peaks added ({time.perf_counter() - start:.1f} s){packed}"


def _options(parser) -> None:
    parser.add_argument("--only", nargs="*", default=None, help="only these map names (file stems)")


def main(argv=None) -> None:
    args = parse(__doc__.splitlines()[0], argv, default_out=DATA, add_arguments=_options)
    stems = sorted({path.stem for path in DATA.iterdir() if path.suffix in (".nc", ".npz")})
    paths = [DATA / f"{stem}.nc" if (DATA / f"{stem}.nc").is_file() else DATA / f"{stem}.npz" for stem in stems]
    if args.only:
        paths = [path for path in paths if path.stem in args.only]
    if args.smoke:  # the smallest linear map without its peaks, in a temporary directory
        source = min((p for p in paths if p.stem.startswith("plate-ssss-mindlin-s10")), key=lambda p: p.stat().st_size)
        paths = [args.out_dir / f"{source.stem}.nc"]
        save_atomic(read_dataset(source).drop_vars(ASYMPTOTE_PEAKS, errors="ignore"), paths[0])
    elif args.out_dir != DATA:
        paths = [args.out_dir / f"{path.stem}.nc" for path in paths]
        for path, stem in zip(paths, (p.stem for p in paths)):
            save_atomic(read_dataset(DATA / f"{stem}.nc" if (DATA / f"{stem}.nc").is_file() else DATA / f"{stem}.npz"),
                        path)
    for path in paths:
        print(f"{path.name}: {add_peaks(path)}")


if __name__ == "__main__":
    main()
