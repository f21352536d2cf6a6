"""Lookups as stored interpolation answer what the lookups that computed asymptotes answered.

Every shipped map is read at N random points (log-uniform over its range, seeded by its
name, so two runs draw the same points), vectorised; a point next to an ``unresolved``
map point is refused, and its refusal is an answer too. Two modes:

* ``--record FILE`` writes the answers (F̄max, band, status, regime, or the refusal) to an
  ``.npz``. Run it with the code to compare against first on the path (a checkout of
  the base commit: ``PYTHONPATH=/path/to/base``); ``--no-regime`` leaves the regime out
  (the base code integrates an asymptote per point for it: hours at 10⁴ Hertz-beam points).
* ``--compare FILE`` reads the maps with this checkout and reports, per map, the answers
  whose F̄max, band or status differ from the recorded ones (bit for bit) and the
  refusals that differ. Regimes: the regime from the stored, interpolated asymptote
  peaks against the regime from the exact peaks at the point
  (:func:`impactmaps.maps.family.regimes.infinite_structure_peak`, ``quasi_static_peak``). The
  exact peaks are integrated only where the regime could differ: the peaks'
  interpolation error is bounded per map by twice its largest value at the midpoints of
  the grid cells (measured, exact there), and a point whose criteria (distance to
  each asymptote against the tolerance, and to one another) are farther from their
  thresholds than that error can move them keeps its regime by construction
  (:func:`at_risk`). Written to ``OUT/lookup_equivalence.csv`` and printed.

    PYTHONPATH=/tmp/base python validation/lookup_equivalence.py --record validation/work/lookups-base.npz --no-regime
    PYTHONPATH=. python validation/lookup_equivalence.py --compare validation/work/lookups-base.npz --out-dir validation
    python validation/lookup_equivalence.py --smoke    # 20 points of one map, recorded and compared in a temporary directory
"""

from __future__ import annotations

import csv
import warnings
import zlib
from pathlib import Path

import numpy as np

from _script_options import parse

ROOT = Path(__file__).resolve().parents[1]
#: Regime criteria of a default lookup (:func:`impactmaps.maps.family.regimes.classify`).
TOLERANCE = LOCAL_TOLERANCE = 0.1


def shipped_keys() -> list[tuple]:
    """(structure, theory, law, slenderness) of every shipped map; law yc/stronge/epp: slenderness None."""
    from impactmaps.maps.files.shipped import SHIPPED_MAPS, map_file_stem, shipped_structure_name
    from impactmaps.maps.read.lookup import PLASTIC_MAPS
    from impactmaps.maps.family.builtin_families import PLASTIC_LAWS

    data = ROOT / "impactmaps" / "maps" / "data"
    keys = []
    for law in ("linear", "hertz"):
        for structure, theory in SHIPPED_MAPS:
            for slenderness in (None, 10.0, 50.0) if theory in ("timoshenko", "mindlin") else (None,):
                name = map_file_stem(shipped_structure_name(structure, theory, slenderness), law)
                if any((data / f"{name}{suffix}").is_file() for suffix in (".nc", ".npz")):
                    keys.append((structure, theory, law, slenderness))
    keys += [(structure, theory, law, None) for law in PLASTIC_LAWS for structure, theory in PLASTIC_MAPS]
    return keys


def _name(key) -> str:
    structure, theory, law, slenderness = key
    return f"{structure}-{theory}-{law}" + (f"-s{slenderness:g}" if slenderness else "")


def _dataset(key):
    from impactmaps.maps.files.shipped import load_shipped_map

    structure, theory, law, slenderness = key
    if law in ("linear", "hertz"):
        return load_shipped_map(structure, theory, law, slenderness)
    return load_shipped_map(structure, theory, law)


def points(key, count: int) -> dict:
    """``count`` random numbers of the map ``key``, log-uniform over its axes (seeded by its name)."""
    dataset = _dataset(key)
    rng = np.random.default_rng(zlib.crc32(_name(key).encode()))
    axes = ("beta", "zeta", "lambda_") if "beta" in dataset.dims else ("zeta", "lambda_")
    return {axis: np.exp(rng.uniform(np.log(float(dataset[axis].min())), np.log(float(dataset[axis].max())), count))
            for axis in axes}


def _read(key, numbers: dict):
    """The answer arrays at ``numbers``: (fmax, band, status, regime) or raises ValueError."""
    from impactmaps import lookup

    structure, theory, law, slenderness = key
    if "beta" in numbers:
        found = lookup(numbers["beta"], numbers["zeta"], numbers["lambda_"], kind=structure,
                               theory=theory, law=law)
        regime = np.full(np.shape(found.fmax_normalised), "")
    else:
        found = lookup(numbers["zeta"], numbers["lambda_"], kind=structure, theory=theory, law=law,
                       slenderness=slenderness)
        regime = found.regime
    return (np.atleast_1d(found.fmax_normalised), np.atleast_1d(found.fmax_error), np.atleast_1d(found.status),
            np.atleast_1d(regime))


def answers(key, numbers: dict) -> dict:
    """Every point's answer; the refused ones (split until each refusal is one point's) with their message."""
    count = len(numbers["zeta"])
    out = {"fmax": np.full(count, np.nan), "band": np.full(count, np.nan), "status": np.full(count, "", dtype=object),
           "regime": np.full(count, "", dtype=object), "refusal": np.full(count, "", dtype=object)}

    def visit(index: np.ndarray) -> None:
        try:
            fmax, band, status, regime = _read(key, {axis: values[index] for axis, values in numbers.items()})
        except ValueError as error:
            if index.size == 1:
                out["refusal"][index] = str(error)
                return
            visit(index[: index.size // 2])
            visit(index[index.size // 2:])
            return
        out["fmax"][index], out["band"][index], out["status"][index], out["regime"][index] = fmax, band, status, regime

    alone = _near_missing(_dataset(key), numbers)  # likely refused: read one by one (their messages)
    for index in np.flatnonzero(alone):
        visit(np.array([index]))
    for chunk in np.array_split(np.flatnonzero(~alone), max(1, int(np.count_nonzero(~alone)) // 2000)):
        if chunk.size:
            visit(chunk)
    return out


def _near_missing(dataset, numbers: dict) -> np.ndarray:
    """Points with a grid corner that holds no value (the refused ones, and a few more)."""
    fmax = dataset["fmax_normalised"].isel(structure=0).values
    missing = ~np.isfinite(fmax)
    corners = np.zeros(len(numbers["zeta"]), bool)
    axes = [axis for axis in ("beta", "lambda_", "zeta") if axis in numbers]
    brackets = []
    for axis in axes:
        grid = np.log(dataset[axis].values)
        upper = np.clip(np.searchsorted(grid, np.log(numbers[axis])), 0, grid.size - 1)
        brackets.append((np.clip(upper - 1, 0, grid.size - 1), upper))
    for choice in np.ndindex(*(2,) * len(axes)):
        corners |= missing[tuple(bracket[c] for bracket, c in zip(brackets, choice))]
    return corners


def record(path: Path, count: int, keys, regime: bool) -> None:
    """Record the answers of the code on the path at ``count`` points per map into ``path``."""
    if not regime:  # the base code integrates the asymptotes inside lookup: skip the regime there
        import impactmaps.maps.read.lookup as reading
        reading.classify = lambda fmax, *args, **kwargs: np.full(np.shape(fmax), "", dtype=object)
    stored = {}
    for key in keys:
        numbers = points(key, count)
        found = answers(key, numbers)
        name = _name(key)
        stored |= {f"{name}/{axis}": values for axis, values in numbers.items()}
        stored |= {f"{name}/{field}": np.asarray(values, dtype=float if field in ("fmax", "band") else str)
                   for field, values in found.items()}
        print(f"recorded {name}: {count} points, {np.count_nonzero(found['refusal'] != '')} refused")
    np.savez_compressed(path, **stored)


def peak_errors(key) -> tuple[float, float]:
    """Largest |stored-and-interpolated − exact| asymptote peak at the grid cells' midpoints (infinite, quasi-static)."""
    from impactmaps.maps.read.interpolator import interpolate_line
    from impactmaps.maps.family.regimes import infinite_structure_peak, quasi_static_peak

    dataset = _dataset(key)
    structure, _, law, _ = key
    errors = []
    for name, axis, exact in (("infinite_structure_peak", "zeta", lambda x: infinite_structure_peak(x, structure, law)),
                              ("quasi_static_peak", "lambda_", lambda x: quasi_static_peak(x, law))):
        grid = np.log(dataset[axis].values)
        middles = 0.5 * (grid[1:] + grid[:-1])
        stored = interpolate_line(dataset[name].isel(structure=0).values, np.arange(grid.size - 1) + 0.5)
        errors.append(float(np.max(np.abs(stored - np.asarray(exact(np.exp(middles)), float)))))
    return errors[0], errors[1]


def _distance(fmax, peak):
    return np.abs(fmax - peak) / peak


def at_risk(fmax, infinite, quasi, error_infinite: float, error_quasi: float, tolerance: float = TOLERANCE):
    """Points whose regime can change when each peak moves by up to its error: a criterion
    (distance to an asymptote against ``tolerance``, or the two distances against each
    other) closer to its threshold than the peaks' errors can move the distance."""
    moves = []
    for peak, error in ((infinite, error_infinite), (quasi, error_quasi)):
        here = _distance(fmax, peak)
        low, high = np.maximum(peak - error, 1e-300), peak + error
        move = np.maximum(np.abs(_distance(fmax, low) - here), np.abs(_distance(fmax, high) - here))
        move = np.where((fmax >= low) & (fmax <= high), np.maximum(move, here), move)  # the kink at peak = fmax
        moves.append((here, move))
    (d_inf, m_inf), (d_q, m_q) = moves
    return ((np.abs(d_inf - tolerance) <= m_inf) | (np.abs(d_q - tolerance) <= m_q)
            | (np.abs(d_inf - d_q) <= m_inf + m_q))


def compare(path: Path, out_dir: Path, keys) -> list[dict]:
    """Compare this checkout's answers with the recorded ones (module docstring); the rows written."""
    from impactmaps.maps.read.lookup import shipped_reader
    from impactmaps.maps.read.reader import read_values
    from impactmaps.maps.family.regimes import classify, infinite_structure_peak, quasi_static_peak
    from impactmaps.maps.family.map_family import map_family

    recorded = np.load(path, allow_pickle=False)
    rows = []
    for key in keys:
        name = _name(key)
        numbers = {axis: recorded[f"{name}/{axis}"] for axis in ("beta", "zeta", "lambda_") if f"{name}/{axis}" in recorded}
        old = {field: recorded[f"{name}/{field}"] for field in ("fmax", "band", "status", "regime", "refusal")}
        new = answers(key, numbers)
        answered = old["refusal"] == ""
        row = {"map": name, "points": answered.size, "refused": int(np.count_nonzero(~answered)),
               "refusals_differ": int(np.count_nonzero(old["refusal"] != new["refusal"].astype(str))),
               "fmax_differ": int(np.count_nonzero(old["fmax"][answered] != new["fmax"][answered])),
               "band_differ": int(np.count_nonzero(old["band"][answered] != new["band"][answered])),
               "status_differ": int(np.count_nonzero(old["status"][answered] != new["status"][answered].astype(str)))}
        structure, theory, law, slenderness = key
        if law in ("linear", "hertz") and answered.any():
            prepared, _ = shipped_reader(structure, theory, law, slenderness)
            zeta, lam = numbers["zeta"][answered], numbers["lambda_"][answered]
            values = read_values(None, map_family(law), (zeta, lam), ("loss_factor", "relative_stiffness"),
                                 where=name, prepared=prepared).values
            fmax, infinite, quasi = values["fmax_normalised"], values["infinite_structure_peak"], values["quasi_static_peak"]
            errors = [2.0 * e for e in peak_errors(key)]
            risky = at_risk(fmax, infinite, quasi, *errors)
            exact_infinite, exact_quasi = infinite.copy(), quasi.copy()
            if risky.any():
                exact_infinite[risky] = infinite_structure_peak(zeta[risky], structure, law)
                exact_quasi[risky] = quasi_static_peak(lam[risky], law)
            times = {"peak_time": np.exp(values["log_peak_time"]), "reflection_time": np.exp(values["log_reflection_time"])}
            exact = classify(fmax, zeta, lam, structure, peaks=(exact_infinite, exact_quasi), **times)
            stored = new["regime"][answered].astype(str)
            row |= {"peak_error_infinite": errors[0] / 2, "peak_error_quasi_static": errors[1] / 2,
                    "regime_at_risk": int(risky.sum()), "regime_differ": int(np.count_nonzero(exact != stored))}
            if (old["regime"][answered] != "").any():
                row["regime_differ_recorded"] = int(np.count_nonzero(old["regime"][answered] != stored))
        rows.append(row)
        print(row)
    fields = list(dict.fromkeys(field for row in rows for field in row))
    with open(out_dir / "lookup_equivalence.csv", "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    return rows


def _options(parser) -> None:
    parser.add_argument("--record", type=Path, help="record this code's answers into FILE (.npz)")
    parser.add_argument("--compare", type=Path, help="compare this checkout's answers with FILE")
    parser.add_argument("--points", type=int, default=10_000, help="random points per map (default 10 000)")
    parser.add_argument("--no-regime", action="store_true", help="record without the regime (no asymptote run)")
    parser.add_argument("--only", nargs="*", default=None, help="only these maps (names as printed)")


def main(argv=None) -> None:
    warnings.simplefilter("ignore")  # the Mindlin maps' point-load warning, once per lookup
    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation", add_arguments=_options)
    keys = [key for key in shipped_keys() if not args.only or _name(key) in args.only]
    if args.smoke:
        keys = [key for key in keys if _name(key) == "plate-mindlin-linear-s10"]
        args.points, args.record = 20, args.out_dir / "lookups.npz"
        record(args.record, args.points, keys, regime=True)
        args.compare = args.record
    elif args.record:
        record(args.record, args.points, keys, regime=not args.no_regime)
    if args.compare:
        compare(args.compare, args.out_dir, keys)


if __name__ == "__main__":
    main()
