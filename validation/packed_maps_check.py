"""The packed shipped maps answer as the NetCDF ones did: value, band and status at random points.

For every shipped map — the (ζ, λ) maps of both laws with their refinements, the
slenderness members and the elastic-plastic (β, ζ, λ) maps — the lookup's reading
(what :func:`impactmaps.maps.read.reader.read_values` computes for :func:`impactmaps.lookup`, taken from its steps so that a point
next to an unresolved one is marked "refused" instead of refusing the whole batch) is taken at ``--points``
log-uniform random points (seeded) from the packed data of this checkout and from the data
before packing (``--old-data``: the ``impactmaps/maps/data`` folder of a checkout of the
commit before, e.g. ``git worktree add /tmp/base b4b262f``). Per map it reports how many
values are bit-identical, the largest change of the value, the band's change (new/old − 1:
the refinement points' own error is stored rounded up to 8 significant bits,
``data_build/pack_map_data.py``) and how many statuses changed. The regime is not read
here: it is classified from the value and the stored times, which are unchanged bit for bit.

Writes ``packed_maps_check.csv`` (the summary) and ``packed_maps_reference.csv`` (the old
answers at the first ``--reference`` points of each map, floats in hex), which
``tests/maps/test_packed_data.py`` checks the packed maps against.

    python validation/packed_maps_check.py --old-data /tmp/base/impactmaps/maps/data --out-dir validation
    python validation/packed_maps_check.py --smoke     # packed against packed, 40 points a map
"""

from __future__ import annotations

import csv
import sys
import warnings
from pathlib import Path

import numpy as np

from _script_options import parse

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps

from impactmaps.maps.files import shipped  # noqa: E402
from impactmaps.maps.read import lookup as lookup_module  # noqa: E402
from impactmaps.maps.files.data_io import read_dataset  # noqa: E402
from impactmaps.maps.read import reader  # noqa: E402
from impactmaps.maps.family.map_family import map_family  # noqa: E402
from impactmaps.maps.family.builtin_families import MEMBER_SLENDERNESSES  # noqa: E402

PACKED = ROOT / "impactmaps" / "maps" / "data"
SEED = 30


def maps() -> list[tuple]:
    """(structure, theory, law, slenderness) of every shipped map a lookup reads."""
    out = [(s, t, law, None) for (s, t) in shipped.SHIPPED_MAPS for law in ("linear", "hertz")]
    out += [(s, t, law, sl) for (s, t) in (("beam", "timoshenko"), ("plate", "mindlin")) for law in ("linear", "hertz")
            for sl in MEMBER_SLENDERNESSES if sl != 20.0 and not (t == "mindlin" and law == "hertz")]
    out += [(s, t, law, None) for (s, t) in lookup_module.PLASTIC_MAPS for law in ("yc", "stronge", "epp")]
    return out


def use_data(folder: Path) -> None:
    """Make the lookups read the shipped data from ``folder`` (either format), caches cleared."""
    def read_shipped(*parts):
        for suffix in (".nc", ".npz"):
            path = folder.joinpath(*parts[:-1], parts[-1] + suffix)
            if path.exists():
                return read_dataset(path)
        return None

    shipped.read_shipped = read_shipped
    for cached in (shipped.load_shipped_map, shipped.load_shipped_refinement):
        cached.cache_clear()


def points(key, count: int) -> tuple:
    """The random numbers of a map (seeded by its key): (ζ, λ) or (β, ζ, λ), log-uniform inside it."""
    structure, theory, law, slenderness = key
    plastic = law in ("yc", "stronge", "epp")
    dataset = (shipped.load_shipped_map(structure, theory, law) if plastic
               else shipped.load_shipped_map(structure, theory, law, slenderness))
    rng = np.random.default_rng([SEED, *map(ord, "-".join(map(str, key)))])
    axes = (["beta"] if plastic else []) + ["zeta", "lambda_"]
    return tuple(np.exp(rng.uniform(np.log(dataset[a].values.min()), np.log(dataset[a].values.max()), count))
                 for a in axes)


def answers(key, numbers) -> dict:
    """Every variable's value and band and the status at ``numbers``: what
    :func:`~impactmaps.maps.read.reader.read_values` computes, with "refused" (and NaN) where it
    refuses a point next to an unresolved one (it raises for the whole call)."""
    structure, theory, law, slenderness = key
    if law in ("yc", "stronge", "epp"):
        dataset = shipped.load_shipped_map(structure, theory, law)
        logs = _logs(dataset, ("beta", "zeta", "lambda_"), numbers)
        values, errors, codes = reader._read_cube(reader.prepare_map(dataset, map_family(law)), map_family(law), logs)
    else:
        dataset = shipped.load_shipped_map(structure, theory, law, slenderness)
        refinement = shipped.load_shipped_refinement(structure, theory, law, slenderness)
        logs = _logs(dataset, ("zeta", "lambda_"), numbers)
        values, errors, codes = reader._read_plane(reader.prepare_map(dataset, map_family(law), refinement), logs)
        values = {"fmax_normalised": values["fmax_normalised"]}
    status = np.atleast_1d(reader.corner_status(codes, errors["fmax_error"])).ravel().astype(object)
    refused = (status == "unresolved") | ~np.isfinite(values["fmax_normalised"])
    status[refused] = "refused"
    out = {name: np.where(refused, np.nan, np.asarray(value, float).ravel()) for name, value in (values | errors).items()}
    return out | {"status": status.astype(str)}


def _logs(dataset, axes, numbers) -> dict:
    """The numbers' logarithms by axis, as read_values takes them (clipped into the map)."""
    return {axis: np.log(np.clip(values, float(dataset[axis].min()), float(dataset[axis].max()))).ravel()
            for axis, values in zip(axes, numbers)}


def compare(key, old: dict, new: dict) -> dict:
    """The summary row of one map."""
    values = [k for k in old if k != "status" and not k.endswith("_error")]
    bands = [k for k in old if k.endswith("_error")]
    same = np.all([old[k].view(np.uint64) == new[k].view(np.uint64) for k in values], axis=0)
    change = max(float(np.nanmax(np.abs(new[k] - old[k]), initial=0.0)) for k in values)
    ratio = np.concatenate([(new[k] / old[k])[old[k] > 0] for k in bands])
    return {"map": shipped.map_file_stem(
                shipped.shipped_structure_name(key[0], key[1], key[3]) if key[2] not in ("yc", "stronge", "epp")
                else lookup_module.PLASTIC_MAPS[(key[0], key[1])], key[2]),
            "points": old["status"].size, "refused": int(np.sum(old["status"] == "refused")),
            "values_bit_identical": int(same.sum()), "max_value_change": f"{change:.3g}",
            "bands_bit_identical": int(np.all([old[k].view(np.uint64) == new[k].view(np.uint64) for k in bands],
                                              axis=0).sum()),
            "band_ratio_min": f"{np.min(ratio, initial=1.0):.6f}", "band_ratio_max": f"{np.max(ratio, initial=1.0):.6f}",
            "status_changed": int(np.sum(old["status"] != new["status"])),
            "status_changes": " ".join(sorted({f"{a}->{b}" for a, b in zip(old["status"], new["status"]) if a != b}))}


def _options(parser) -> None:
    parser.add_argument("--old-data", type=Path, help="impactmaps/maps/data of a checkout before packing")
    parser.add_argument("--points", type=int, default=10_000, help="random points per map (default 10⁴)")
    parser.add_argument("--reference", type=int, default=60, help="points per map kept in the reference CSV")


def main(argv=None) -> int:
    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation", add_arguments=_options)
    if args.smoke:
        args.points, args.reference = 40, 5
    old_data = args.old_data or PACKED
    warnings.simplefilter("ignore")
    rows, reference = [], []
    for key in maps():
        use_data(PACKED)
        numbers = points(key, args.points)
        new = answers(key, numbers)
        use_data(old_data)
        old = answers(key, numbers)
        rows.append(compare(key, old, new))
        print(", ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
        for i in range(min(args.reference, numbers[0].size)):
            reference.append({"map": rows[-1]["map"], "key": "/".join(map(str, key)),
                              "numbers": " ".join(float(n[i]).hex() for n in numbers), "status": old["status"][i]}
                             | {k: float(v[i]).hex() for k, v in old.items() if k != "status"})
    _write(args.out_dir / "packed_maps_check.csv", rows)
    _write(args.out_dir / "packed_maps_reference.csv", reference)
    total = sum(r["points"] for r in rows)
    print(f"{len(rows)} maps, {total} points: values bit-identical at {sum(r['values_bit_identical'] for r in rows)}, "
          f"statuses changed at {sum(r['status_changed'] for r in rows)}; old data {old_data}")
    return 0


def _write(path: Path, rows: list[dict]) -> None:
    names = list(dict.fromkeys(k for row in rows for k in row))
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=names, restval="")
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    if main():
        sys.exit(1)
