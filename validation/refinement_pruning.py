"""What dropping a refinement's deeper levels would do to the lookups: statuses, values, bands.

Each shipped refinement (:mod:`impactmaps.maps.family.refinement`) is read at ``--points``
log-uniform random points (seeded as ``validation/packed_maps_check.py``) in full and with
only the points of its first ``L`` levels kept (``L`` = 2, 1: the cells of the deeper
levels unsplit, a consistent tree), through the steps of
:func:`impactmaps.maps.read.reader.read_values`. Per map and ``L``: the points kept, how many
answers change status, the largest change of F̄max, and how many pruned answers no longer
cover the full answer within their band. The packed data ships the refinements whole
(docs/install.rst, "Package data"); this is the measurement behind that.

Writes ``refinement_pruning.csv``.

    python validation/refinement_pruning.py --out-dir validation
    python validation/refinement_pruning.py --smoke
"""

from __future__ import annotations

import csv
import sys
import warnings
from pathlib import Path

import numpy as np

from _script_options import parse
from packed_maps_check import _logs, points

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # this checkout's impactmaps

from impactmaps.maps.files import shipped as lookup_module  # noqa: E402
from impactmaps.maps.read import reader  # noqa: E402
from impactmaps.maps.family.refinement import Refinement  # noqa: E402
from impactmaps.maps.family.map_family import map_family  # noqa: E402


def read(key, refinement, numbers):
    """(F̄max, band, status) at ``numbers`` of the map ``key`` read with ``refinement``."""
    dataset = lookup_module.load_shipped_map(*key)
    values, errors, codes = reader._read_plane(reader.prepare_map(dataset, map_family(key[2]), refinement),
                                               _logs(dataset, ("zeta", "lambda_"), numbers))
    status = np.asarray(reader.corner_status(codes, errors["fmax_error"]))
    return values["fmax_normalised"], errors["fmax_error"], status


def pruned(refinement: Refinement, levels: int) -> Refinement:
    """``refinement`` with the points of its first ``levels`` levels only."""
    u, v = refinement.position(refinement.codes)
    keep = refinement.creation_level(u, v) <= levels
    return Refinement(refinement.shape, refinement.codes[keep], {k: a[keep] for k, a in refinement.values.items()},
                      refinement.max_level)


def _options(parser) -> None:
    parser.add_argument("--points", type=int, default=10_000, help="random points per map (default 10⁴)")


def main(argv=None) -> int:
    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation", add_arguments=_options)
    keys = [(s, t, law, None) for (s, t) in lookup_module.SHIPPED_MAPS for law in ("linear", "hertz")]
    if args.smoke:
        args.points, keys = 200, keys[:1]
    warnings.simplefilter("ignore")
    rows = []
    for key in keys:
        full = lookup_module.load_shipped_refinement(*key)
        numbers = points(key, args.points)
        value, band, status = read(key, full, numbers)
        for levels in (2, 1):
            small = pruned(full, levels)
            new_value, new_band, new_status = read(key, small, numbers)
            ok = np.isfinite(value) & np.isfinite(new_value)
            change = np.abs(new_value - value)[ok]
            rows.append({"map": lookup_module.map_file_stem(lookup_module.shipped_structure_name(*key[:2]), key[2]),
                         "levels_kept": levels, "points_kept": small.codes.size, "points": full.codes.size,
                         "lookups": args.points, "status_changed": int(np.sum(status != new_status)),
                         "max_value_change": f"{np.max(change, initial=0.0):.3g}",
                         "not_covered_by_band": int(np.sum(change > new_band[ok]))})
            print(", ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
    with open(args.out_dir / "refinement_pruning.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return 0


if __name__ == "__main__":
    if main():
        sys.exit(1)
