"""The stated error of map points and lookups covers the measured error (issue 40 item 10).

Reads the committed output of ``validation/band_audit.py`` (random converged points per
family against references four refinement levels above the base) and checks, with the
floors the code states now (:func:`impactmaps.maps.family.accuracy.stated_error`), that
``fmax_error`` covers the error at ≥ 99 % of the points of every family, and the lookup
bands at ≥ 99 % of the lookups.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from impactmaps.maps.family.accuracy import ERROR_FLOOR, REIMPACT_ERROR_FLOOR, STATUSES, stated_error

from ..helpers import ROOT

AUDIT = ROOT / "validation" / "band_audit.csv"
FAMILIES = ("beam-ss-euler", "beam-ss-timoshenko-s20", "plate-ssss-kirchhoff", "plate-ssss-mindlin-s20")


@pytest.fixture(scope="module")
def audit():
    frame = pd.read_csv(AUDIT)
    return frame[frame["reference"].notna()]


@pytest.mark.parametrize("family", FAMILIES)
def test_fmax_error_covers_the_error_at_99_percent_of_converged_points(audit, family):
    part = audit[audit.family == family]
    assert len(part) >= 50, f"{family}: only {len(part)} audited points"
    codes = part["status"].map(STATUSES.index).to_numpy()
    stated = stated_error(part["change"].to_numpy(), codes, part["impacts"].to_numpy())
    error = np.abs(part["fmax"] - part["reference"]).to_numpy()
    assert np.mean(error <= stated) >= 0.99, (family, int(np.sum(error > stated)), len(part))


def test_lookup_bands_cover_the_error_at_99_percent(audit):
    looked = audit[audit["lookup_status"].isin(["converged", "refined", "interpolated"])]
    assert len(looked) >= 200
    inside = np.abs(looked["lookup"] - looked["reference"]) <= looked["lookup_band"]
    assert inside.mean() >= 0.99, int((~inside).sum())


def test_stated_error_is_idempotent_and_floors_only_settled_points():
    converged, sensitive = STATUSES.index("converged"), STATUSES.index("sensitive")
    once = stated_error(np.array([0.0, 5e-4, 3e-3, 1e-5]), np.array([converged, converged, converged, sensitive]),
                        np.array([1, 2, 1, 1]))
    assert once.tolist() == [ERROR_FLOOR, REIMPACT_ERROR_FLOOR, 3e-3, 1e-5]
    assert stated_error(once, np.array([converged] * 3 + [sensitive]), np.array([1, 2, 1, 1])).tolist() == once.tolist()
    assert stated_error(1e-6, converged) == ERROR_FLOOR


def test_a_shipped_map_is_read_with_the_floor():
    """The shipped maps store the bare change (built before the floors): the reader floors it."""
    from impactmaps import lookup

    found = lookup(10.0, 0.01, kind="beam", theory="euler")
    assert found.status in ("converged", "refined", "interpolated")
    assert found.fmax_error >= ERROR_FLOOR
