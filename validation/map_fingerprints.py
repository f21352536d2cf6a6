"""Fingerprints of the maps' behaviour: shipped data, lookups, short sweeps and CLI answers.

Records SHA-256 digests of (a) every shipped map file's data (variables and
coordinates, bytes and dtypes; the refinements and shipped sweep results too), (b)
lookups (:func:`impactmaps.lookup`) at a few hundred random points per shipped map — linear
and Hertz maps, the slenderness members and slendernesses between them, the elastic-plastic
maps — and of a few physical cases, each answer's value, band, status
and regime, or its refusal's message, and (c) a short sweep of each map family (a few
points each, serially), and a command-line ``lookup --json``. A refactoring that changes
no behaviour leaves every digest unchanged.

    python validation/map_fingerprints.py --out validation/work/fingerprints-before.json
    python validation/map_fingerprints.py --compare validation/work/fingerprints-before.json
    python validation/map_fingerprints.py --smoke      # the digests of two shipped files, into a temporary directory

``--compare`` recomputes the digests and prints those that differ (exit status 1 if any).
Run it with the worktree's package first on the path (``PYTHONPATH=.``).
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
import warnings
from importlib import resources
from pathlib import Path

import numpy as np
import xarray as xr

from _script_options import parse

ROOT = Path(__file__).resolve().parents[1]
#: Random lookups per shipped map.
POINTS = 300
#: Attributes of a dataset that are part of its behaviour (not its creation time or version).
_ATTRS = ("fingerprint", "description", "contact_law", "point_methods", "complete", "title", "method",
          "solver_revision", "base_fingerprint", "data_digest")


def _digest_dataset(dataset: xr.Dataset, attrs: bool = True) -> str:
    digest = hashlib.sha256()
    for name in sorted([*dataset.coords, *dataset.data_vars]):
        values = np.ascontiguousarray(dataset[name].values)
        digest.update(f"{name}:{values.dtype.str}:{values.shape}:{dataset[name].dims}".encode())
        if values.dtype.kind in "OUS":
            digest.update(json.dumps([str(v) for v in values.ravel()]).encode())
        else:
            digest.update(values.tobytes())
        digest.update(json.dumps({k: str(v) for k, v in sorted(dataset[name].attrs.items())}).encode())
    if attrs:
        digest.update(json.dumps({k: str(dataset.attrs.get(k)) for k in _ATTRS}).encode())
    return digest.hexdigest()


def _digest(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True, default=_plain).encode()).hexdigest()


def _plain(value):
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()] if value.ndim else _plain(value.item())
    if isinstance(value, (np.floating, float)):
        return float(value).hex()
    if isinstance(value, np.integer):
        return int(value)
    return str(value)


def shipped_data(limit: int | None = None) -> dict:
    out = {}
    data = Path(str(resources.files("impactmaps.maps").joinpath("data")))
    from impactmaps.maps.files.data_io import read_dataset

    for path in sorted([*data.rglob("*.nc"), *data.rglob("*.npz")])[:limit]:
        # keyed without the suffix: a file packed (.npz) compares with its NetCDF (.nc) before
        out[f"data/{path.relative_to(data).with_suffix('')}"] = _digest_dataset(read_dataset(path))
    return out


def _answer(call):
    try:
        found = call()
    except ValueError as error:
        return {"refused": str(error)}
    return {key: (float(value).hex() if isinstance(value, float) else str(value))
            for key, value in vars(found).items()}


def _log_uniform(rng, low, high, count):
    return np.exp(rng.uniform(np.log(low), np.log(high), count))


def lookups() -> dict:
    from impactmaps import lookup
    from impactmaps.maps.family.builtin_families import LAYOUTS, MEMBER_SLENDERNESSES
    from impactmaps.maps.files.shipped import SHIPPED_MAPS, load_shipped_map

    PLASTIC_MAPS = LAYOUTS["yc"].shipped

    out = {}
    rng = np.random.default_rng(27)
    maps = [(s, t, law, None) for (s, t) in SHIPPED_MAPS for law in ("linear", "hertz")]
    maps += [(s, t, law, sl) for (s, t) in (("beam", "timoshenko"), ("plate", "mindlin")) for law in ("linear", "hertz")
             for sl in MEMBER_SLENDERNESSES if sl != 20.0 and not (t == "mindlin" and law == "hertz")]
    for structure, theory, law, slenderness in maps:
        try:
            dataset = load_shipped_map(structure, theory, law, slenderness)
        except (FileNotFoundError, ValueError):
            continue
        z = _log_uniform(rng, dataset["zeta"].min(), dataset["zeta"].max() * 1.02, POINTS)
        lam = _log_uniform(rng, dataset["lambda_"].min(), dataset["lambda_"].max(), POINTS)
        answers = [_answer(lambda a=a, b=b: lookup(a, b, kind=structure, theory=theory, law=law,
                                                    slenderness=slenderness)) for a, b in zip(z, lam)]
        answers.append(_answer(lambda: lookup(z[:20], lam[:20] * 0 + float(dataset["lambda_"][3]), kind=structure,
                                              theory=theory, law=law, slenderness=slenderness)))
        grid = (dataset["zeta"].values[::17], dataset["lambda_"].values[::9])
        answers += [_answer(lambda a=a, b=b: lookup(a, b, kind=structure, theory=theory, law=law,
                                                     slenderness=slenderness)) for a in grid[0] for b in grid[1]]
        out[f"lookup/{structure}-{theory}-{law}-s{slenderness}"] = _digest(answers)
    for structure, theory, law in (("beam", "timoshenko", "linear"), ("beam", "timoshenko", "hertz"),
                                   ("plate", "mindlin", "linear")):
        dataset = load_shipped_map(structure, theory, law, 10.0)
        s = rng.uniform(10.0, 80.0, 60)
        z = _log_uniform(rng, dataset["zeta"].min(), dataset["zeta"].max(), 60)
        lam = _log_uniform(rng, dataset["lambda_"].min(), dataset["lambda_"].max(), 60)
        out[f"slenderness/{structure}-{theory}-{law}"] = _digest([_answer(
            lambda a=a, b=b, c=c: lookup(a, b, kind=structure, theory=theory, slenderness=c, law=law))
            for a, b, c in zip(z, lam, s)])
    for (structure, theory) in PLASTIC_MAPS:
        for law in ("yc", "stronge"):
            dataset = load_shipped_map(structure, theory, law)
            b = _log_uniform(rng, dataset["beta"].min(), dataset["beta"].max(), POINTS)
            z = _log_uniform(rng, dataset["zeta"].min(), dataset["zeta"].max() * 1.02, POINTS)
            lam = _log_uniform(rng, dataset["lambda_"].min(), dataset["lambda_"].max(), POINTS)
            answers = [_answer(lambda a=a, c=c, d=d: lookup(a, c, d, kind=structure, theory=theory,
                                                                     law=law)) for a, c, d in zip(b, z, lam)]
            answers.append(_answer(lambda: lookup(b[:30], z[:30] * 0 + float(dataset["zeta"][12]),
                                                          lam[:30] * 0 + float(dataset["lambda_"][12]),
                                                          kind=structure, theory=theory, law=law)))
            out[f"plastic/{structure}-{theory}-{law}"] = _digest(answers)
    return out


def cases() -> dict:
    """lookup(case=...) on a few physical cases (shipped maps, plastic maps, refusals)."""
    from impactmaps import lookup
    from impactmaps.cases import load_case

    out = {}
    for name in ("steel_plate_hertz.toml", "aluminium_beam_linear.toml", "steel_beam_fd_stronge.toml",
                 "composite_plate_sun_chen.toml"):
        case = load_case(ROOT / "examples" / name)
        try:
            answer = lookup(case=case, build=False)
        except ValueError as error:
            answer = {"refused": str(error)}
        out[f"case/{name}"] = _digest(json.loads(json.dumps(answer, default=str).replace(str(ROOT), "ROOT")))
    return out


def short_sweeps() -> dict:
    """A few points of each family, solved serially (values and dataset layout)."""
    from impactmaps.maps.family.structures import MapStructure
    from impactmaps.maps.compute.sweep import sweep

    out = {}
    beam = MapStructure(kind="beam", theory="euler", supports="ss", impact_fraction=(0.5,))
    plate = MapStructure(kind="plate", theory="kirchhoff", supports="SSSS")
    timo = MapStructure(kind="beam", theory="timoshenko", supports="ss", impact_fraction=(0.5,))
    zetas, lambdas = [0.003, 0.3, 30.0], [0.01, 1.0]
    for law in ("linear", "hertz"):
        for structure in (beam, plate, timo):
            dataset = sweep([structure], zetas, lambdas, law=law, progress=False, max_workers=1)
            out[f"sweep/{law}/{structure.name}"] = _digest_dataset(dataset)
    betas = [3.0, 300.0]
    for law in ("yc", "stronge"):
        for structure in (beam, plate):
            dataset = _plastic_sweep(structure, law, betas, [0.01, 1.0], [0.05, 3.0])
            out[f"sweep/{law}/{structure.name}"] = _digest_dataset(dataset)
    return out


def _plastic_sweep(structure, law, betas, zetas, lambdas):
    from impactmaps.maps.compute import sweep as sweep_module

    try:
        return sweep_module.sweep([structure], zetas, lambdas, law=law, axes={"beta": betas}, progress=False,
                                  max_workers=1).drop_vars("regime", errors="ignore")
    except TypeError:  # before the map families: the plastic pipeline of its own
        from impactmaps.maps.compute.plastic_points import plastic_map, solve_plastic_points

        points = [(b, z, l) for b in betas for l in lambdas for z in zetas]
        return plastic_map(structure, law, betas, zetas, lambdas, solve_plastic_points(structure, law, points))


def cli() -> dict:
    out = {}
    commands = [["lookup", "--zeta", "0.3", "--lambda", "0.2", "--json"],
                ["lookup", "--zeta", "0.3", "--lambda", "0.2", "--law", "hertz", "--kind", "beam",
                 "--theory", "euler", "--json"],
                ["lookup", "--zeta", "0.1", "--lambda", "0.5", "--law", "yc", "--beta", "10", "--kind", "beam",
                 "--theory", "euler", "--json"],
                ["lookup", "--case", "examples/steel_plate_hertz.toml", "--json", "--no-build"],
                ["lookup", "--case", "examples/aluminium_beam_linear.toml", "--json", "--no-build"]]
    for command in commands:
        run = subprocess.run([sys.executable, "-m", "impactmaps.cli", *command], cwd=ROOT, capture_output=True,
                             text=True)
        out["cli/" + " ".join(command)] = _digest([run.returncode, run.stdout, run.stderr.splitlines()[-1:]])
    return out


def _options(parser) -> None:
    parser.add_argument("--out", type=Path, help="write the digests here (JSON; default OUT_DIR/fingerprints.json)")
    parser.add_argument("--compare", type=Path, help="compare with digests written earlier")
    parser.add_argument("--skip", nargs="*", default=(), choices=("data", "lookups", "cases", "sweeps", "cli"))


def main(argv=None) -> int:
    args = parse(__doc__.splitlines()[0], argv, default_out=ROOT / "validation" / "work", add_arguments=_options)
    args.out = args.out or args.out_dir / "fingerprints.json"
    warnings.simplefilter("ignore")
    digests = {}
    parts = (("data", shipped_data), ("lookups", lookups), ("cases", cases), ("sweeps", short_sweeps), ("cli", cli))
    if args.smoke:
        parts = (("data", lambda: shipped_data(limit=2)),)
    for name, part in parts:
        if name not in args.skip:
            digests |= part()
            print(f"{name}: {len(digests)} digests")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(digests, indent=1, sort_keys=True))
    if args.compare:
        before = json.loads(args.compare.read_text())
        changed = sorted(k for k in digests if k in before and before[k] != digests[k])
        missing = sorted(k for k in before if k not in digests and k.split("/")[0] not in args.skip)
        print(f"{len(digests)} digests compared: {len(changed)} differ, {len(missing)} missing")
        for key in changed + missing:
            print(("differs: " if key in changed else "missing: ") + key)
        return 1 if changed or missing else 0
    return 0


if __name__ == "__main__":
    if main():
        sys.exit(1)
