"""Pack the shipped map data (``impactmaps/maps/data``) into compressed ``.npz`` archives.

Every map, refinement and shipped sweep result is read — a NetCDF ``.nc`` as the build
scripts write it, or a ``.npz`` packed before — and written packed
(:mod:`impactmaps.maps.files.data_io`), replacing the ``.nc``. Re-run it after merging a branch
that rebuilt maps or added variables to them: it is deterministic (the same datasets give
the same bytes) and idempotent (a packed file packs to itself).

What is stored in fewer bits (each packed file's header says so; docs/install.rst):

* the (ζ, λ) and (β, ζ, λ) maps: ``contact_time_normalised``, ``first_contact_normalised``
  and ``energy_transferred_fraction`` as float32 (no lookup reads them; they are compared
  with simulations at 1e-5 and 5e-3, and F̄max is converged to 1e-3). F̄max, its band and
  status, the times the regimes read and everything else keep their bits;
  ``log_peak_time``, ``log_reflection_time``, ``fmax_low`` and ``fmax_high`` are recomputed
  on reading where that gives their exact bits (:data:`impactmaps.maps.files.data_io.DERIVED`);
* the refinements: ``surplus`` is not stored — it is recomputed from the points' values
  (:meth:`impactmaps.maps.family.refinement.Refinement.recomputed_surplus`), checked here bit for bit
  (a refinement where it is not exact keeps it) — and each point's own ``fmax_error`` is kept
  to 8 significant bits, rounded up (bfloat16: the band only widens, by < 0.8 % of that
  error), except at the points where that could carry a lookup's band over the tolerance and
  change its status (:func:`status_safe`: those keep their float32);
* the shipped sweep results: nothing (a sweep served from one must equal a direct run bit for bit).

Every file is read back and checked: exact variables bit for bit, the others within their
rounding. ``--smoke`` packs one map, its refinement and one result into ``--out-dir``.

    python data_build/pack_map_data.py                 # in place: impactmaps/maps/data
    python data_build/pack_map_data.py --smoke
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))  # _script_options
from _script_options import parse  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps

from impactmaps.maps.files.data_io import PACKED_SUFFIX, read_dataset  # noqa: E402
from impactmaps.maps.family.accuracy import BAND_TOLERANCE  # noqa: E402
from impactmaps.maps.read.interpolator import interpolation_error  # noqa: E402
from impactmaps.maps.family.refinement import Refinement, all_leaves, leaf_estimate  # noqa: E402
from impactmaps.maps.files.store import save_atomic  # noqa: E402

DATA = ROOT / "impactmaps" / "maps" / "data"
#: Map variables stored as float32 (read back as float64).
SINGLE = ("contact_time_normalised", "first_contact_normalised", "energy_transferred_fraction")
#: Refinement variables stored as bfloat16 rounded up.
BFLOAT16_UP = ("fmax_error",)


def sources(data: Path) -> list[tuple[str, Path]]:
    """(kind, file) of every dataset under ``data``: a stem's ``.nc`` wins over its ``.npz``
    (a rebuilt map is written as ``.nc`` beside the packed one)."""
    found = {}
    for kind, folder in (("map", data), ("refinement", data / "refinements"), ("result", data / "results")):
        for path in sorted([*folder.glob("*.npz"), *folder.glob("*.nc")], key=lambda p: p.suffix != ".nc"):
            found.setdefault((kind, path.parent, path.stem), path)
    return [(kind, path) for (kind, _, _), path in sorted(found.items(), key=lambda item: str(item[1]))]


def without_surplus(stored, base_fmax):
    """The refinement ``stored`` without its surplus if :meth:`Refinement.recomputed_surplus`
    gives the same bits; else as it is."""
    if "surplus" not in stored:
        return stored, "recomputed"
    refinement = Refinement.from_dataset(stored)
    again = refinement.recomputed_surplus(base_fmax)
    if np.array_equal(again.view(np.uint32), np.asarray(stored["surplus"].values, np.float32).view(np.uint32)):
        return stored.drop_vars("surplus"), "recomputed"
    return stored, "stored (recomputation not exact)"


def status_safe(stored, base) -> np.ndarray:
    """Where a refinement point's own error must stay exact so that no lookup's status changes.

    A lookup is ``interpolated`` where its band — the largest own error of the corners it reads
    plus its leaf's estimate (none on a lattice point) — exceeds :data:`BAND_TOLERANCE`. For
    every leaf, every corner that is a refinement point and every set of corners a lookup can
    read (the four, the two of each edge with the corner, the corner alone), the point is kept
    exact if its error rounded up would carry that band over the tolerance and the exact one
    does not. The corner need not be the largest of its set: a superset of the points that matter.
    """
    refinement = Refinement.from_dataset(stored, base["fmax_normalised"])
    leaves = all_leaves(refinement)
    estimate = interpolation_error(base["fmax_normalised"])
    corners = leaves.corners()
    edges = ((0, 1), (2, 3), (0, 2), (1, 3))
    rounded = read_back_bfloat16(refinement.values["fmax_error"])
    keep = np.zeros(refinement.codes.size, bool)
    sets = [(0, 1, 2, 3), *edges]
    estimates = {used: leaf_estimate(refinement, leaves, estimate, [np.full(leaves.u.shape, j in used) for j in range(4)])
                 for used in sets}
    for k, (cu, cv) in enumerate(corners):
        point = (cu % refinement.scale != 0) | (cv % refinement.scale != 0)
        where, found = refinement.index(refinement.code(cu[point], cv[point]))
        assert found.all()
        exact = refinement.values["fmax_error"][where].astype(float)
        up = rounded[where].astype(float)
        bands = [(exact, up)]  # the corner alone: its own error
        for used in sets:
            if k in used:
                bands.append((exact + estimates[used][point], up + estimates[used][point]))
        crosses = np.any([(low <= BAND_TOLERANCE) & (high > BAND_TOLERANCE) for low, high in bands], axis=0)
        keep[where[crosses]] = True
    return keep


def read_back_bfloat16(values) -> np.ndarray:
    """``values`` as a bfloat16-up variable reads back (float32)."""
    from impactmaps.maps.files.data_io import _bfloat16_up

    return (_bfloat16_up(values).astype(np.uint32) << 16).view(np.float32)


def check(original, packed_path: Path, single, bfloat16_up, base_fmax=None) -> None:
    """Read ``packed_path`` back and compare with ``original``; ``AssertionError`` naming what differs."""
    again = read_dataset(packed_path)
    if "surplus" in original and "surplus" not in again:
        refinement = Refinement.from_dataset(again, base_fmax)
        again = again.assign(surplus=("point", refinement.values["surplus"]))
    assert sorted(again.variables) == sorted(original.variables), (packed_path, sorted(original.variables))
    assert {k: str(v) for k, v in again.attrs.items()} == {k: str(v) for k, v in original.attrs.items()}, packed_path
    for name in original.variables:
        old, new = np.asarray(original[name].values), np.asarray(again[name].values)
        assert old.dtype == new.dtype and old.shape == new.shape and again[name].dims == original[name].dims, name
        assert {k: str(v) for k, v in again[name].attrs.items()} == {k: str(v) for k, v in original[name].attrs.items()}
        if old.dtype.kind in "OUS":
            assert old.tolist() == new.tolist(), name
        elif name in single:
            assert np.array_equal(new, old.astype(np.float32).astype(old.dtype), equal_nan=True), name
        elif name in bfloat16_up:  # (those kept exact are exact: the status check below is the test)
            finite = np.isfinite(old)
            assert np.array_equal(finite, np.isfinite(new)), name
            assert np.all(new[finite] >= old[finite]) and np.all(new[finite] <= old[finite] * (1 + 2.0**-7)), name
        else:
            assert old.tobytes() == new.tobytes(), (packed_path, name)


def pack_one(kind: str, path: Path, data: Path, out: Path, in_place: bool) -> dict:
    """Pack one file of ``data`` into the same place under ``out``; its sizes and what was done."""
    original = read_dataset(path)
    target = out / path.relative_to(data).with_suffix(PACKED_SUFFIX)
    single, bfloat16_up, base_fmax, surplus, keep = (), (), None, "", None
    if kind == "map":
        single = tuple(name for name in SINGLE if name in original)
    elif kind == "refinement":
        base = read_dataset(next(p for p in (data / f"{path.stem}{s}" for s in (".nc", PACKED_SUFFIX)) if p.exists()))
        base_fmax = base["fmax_normalised"].isel(structure=0).values
        bfloat16_up = BFLOAT16_UP
        stored, surplus = without_surplus(original, base_fmax)
        keep = {"fmax_error": status_safe(original, {"fmax_normalised": base_fmax})}
        surplus += f"; own error exact at {int(keep['fmax_error'].sum())} points (statuses)"
    stored = stored if kind == "refinement" else original
    save_atomic(stored, target, single=single, bfloat16_up=bfloat16_up, keep_exact=keep)
    check(original, target, single, bfloat16_up, base_fmax)
    before = path.stat().st_size
    if in_place and path.suffix == ".nc":
        path.unlink()
        stale = path.with_suffix(PACKED_SUFFIX)
        assert stale == target or not stale.exists()
    return {"file": str(target.relative_to(out)), "kind": kind, "before": before, "after": target.stat().st_size,
            "surplus": surplus}


def _options(parser) -> None:
    parser.add_argument("--data", type=Path, default=DATA, help=f"the data to pack (default {DATA})")


def main(argv=None) -> int:
    args = parse(__doc__.splitlines()[0], argv, default_out=DATA, add_arguments=_options)
    data, out = args.data.resolve(), args.out_dir.resolve()
    in_place = data == out
    todo = sources(data)
    if args.smoke:  # one map, its refinement and one result
        refinement = next(path for kind, path in todo if kind == "refinement")
        todo = [t for t in todo if (t[0] != "result" and t[1].stem == refinement.stem)][:2] + \
               [next(t for t in todo if t[0] == "result")]
    rows = []
    for kind, path in todo:
        rows.append(pack_one(kind, path, data, out, in_place))
        row = rows[-1]
        print(f"{row['file']}: {row['before'] / 1e6:.2f} MB → {row['after'] / 1e6:.2f} MB"
              + (f" (surplus {row['surplus']})" if row["surplus"] else ""), flush=True)
    for kind in ("map", "refinement", "result"):
        chosen = [row for row in rows if row["kind"] == kind]
        print(f"{kind}s: {len(chosen)} files, {sum(r['before'] for r in chosen) / 1e6:.1f} MB → "
              f"{sum(r['after'] for r in chosen) / 1e6:.1f} MB")
    print(f"total: {sum(r['before'] for r in rows) / 1e6:.1f} MB → {sum(r['after'] for r in rows) / 1e6:.1f} MB")
    return 0


if __name__ == "__main__":
    if main():
        sys.exit(1)
