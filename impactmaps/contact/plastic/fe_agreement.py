"""How far each elastic-plastic law is from the finite-element continuum reference
(docs/epp_calibration.rst), read from ``data/fe_agreement.csv``
(written by ``validation/plastic_laws_table.py``).
"""

from __future__ import annotations

import csv
from importlib import resources

__all__ = ["FE_AGREEMENT_RANGE", "fe_agreement"]

#: Where the measured errors hold: the reference runs' range.
FE_AGREEMENT_RANGE = ("half-space impact, rigid sphere on an elastic-perfectly plastic flat of Poisson ratio 0.3, "
                      "V/V_y 2-2700 (max indentation up to 0.05 R), quasi-static contact")


def fe_agreement(name: str) -> dict | None:
    """``{quantity: (lowest, highest) relative error}`` of law ``name`` against the FE
    reference (quantities ``peak_force``, ``restitution``, ``permanent_indentation``), or
    ``None`` for a law that was not measured (the elastic ones)."""
    source = resources.files("impactmaps.contact") / "data" / "fe_agreement.csv"
    with source.open(encoding="utf-8") as stream:
        rows = [row for row in csv.DictReader(stream) if row["law"] == name]
    if not rows:
        return None
    return {row["quantity"]: (float(row["lowest"]), float(row["highest"])) for row in rows}
