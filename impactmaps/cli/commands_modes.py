"""``impactmaps modes CASE.toml``: a target's natural frequencies, to check a model against a
tap test or an FE model."""

from __future__ import annotations

import math

__all__ = ["cmd_modes"]

#: Most modes ``--count`` may ask for.
MAX_COUNT = 2000


def cmd_modes(args) -> dict:
    """The lowest ``--count`` natural frequencies [Hz] of the case's target, with labels."""
    from ..cases import load_case

    count = args.count
    if not 1 <= count <= MAX_COUNT:
        raise ValueError(f"--count = {count} is invalid: valid range is 1 … {MAX_COUNT}")
    case = load_case(args.case)
    target = case.target
    table_of = getattr(target, "mode_table", None)
    if table_of is None:
        raise ValueError(f"the case's target ({case.target_type}) has no vibration modes: valid targets are "
                         "plates and beams")
    table = table_of(count)
    frequencies = [float(f) for f in table["frequencies_hz"]]
    values = {
        "case": case.name,
        "target_type": case.target_type,
        "theory": getattr(target, "theory", None),
        "edges": getattr(target, "edges", None) or getattr(target, "supports", None),
        "method": table["method"],
        "basis": table["basis"],
        "resolved_frequency_hz": table["resolved_frequency_hz"] if math.isfinite(table["resolved_frequency_hz"])
        else None,
        "resolved": table["resolved"],
        "frequencies_hz": frequencies,
        "labels": table["labels"],
    }
    if values["resolved_frequency_hz"] is None:
        values["resolved_frequency_hz_note"] = "exact modes (no basis limit)"
    if not table["resolved"]:
        values["resolved_note"] = (f"only the modes below {table['resolved_frequency_hz']:.6g} Hz are resolved by "
                                   f"the largest basis ({table['basis']}); the others are not converged")
    if not args.json:
        rows = {f"mode {i + 1:>3}  {label:>9}": f"{f:.6g} Hz" for i, (label, f) in
                enumerate(zip(table["labels"], frequencies))}
        values = {k: v for k, v in values.items() if k not in ("frequencies_hz", "labels")}
        values["modes"] = rows
    return values
