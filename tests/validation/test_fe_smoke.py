"""End-to-end smoke test of the CalculiX cross-check scripts (marker ``fe``).

Skipped, with the reason, when ``ccx`` (Debian/Ubuntu ``calculix-ccx``) or the
``gmsh`` Python module (``pip install -e ".[fe]"``) is missing.  It meshes the
coarsest level-1 case (half-width steel beam, span/height 10, end faces held in z,
two 20-node hexahedra through the depth), runs ``ccx`` on it (a few seconds) and
checks the parsed bending frequencies against the toolkit's Timoshenko beam.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

FE_DIR = Path(__file__).resolve().parents[2] / "validation" / "fe"
sys.path.insert(0, str(FE_DIR))

import ccx_tools  # noqa: E402

_AVAILABLE, _REASON = ccx_tools.have_fe_tools()

pytestmark = [pytest.mark.fe, pytest.mark.skipif(not _AVAILABLE, reason=_REASON)]


def test_coarse_beam_modes_end_to_end(tmp_path):
    """Mesh → deck → ccx → .dat parsing → comparison, on the coarse L/h = 10 beam.

    The committed fine-mesh result is within 0.1 % of the Timoshenko beam for the first
    three modes (validation/fe/README.md); this coarse run (2 elements through the
    depth, 0.03 % from the fine mesh) must stay within 0.5 % for those and classify
    the first five bending modes with 1..5 half-waves.
    """
    import level1_modes

    deck, meta, mesh = level1_modes.beam_deck(10, "face", nz=2)
    dat, _ = ccx_tools.run_ccx(deck, "smoke", tmp_path)
    text = dat.read_text()
    omegas = ccx_tools.parse_eigenvalues(text)
    info = level1_modes.classify(ccx_tools.parse_node_prints(text, "AXIS"), mesh, 0)
    bending = [(w, n) for w, (is_bending, n) in zip(omegas, info) if is_bending][:5]
    assert [n for _, n in bending] == [1, 2, 3, 4, 5]
    fe = np.array([w for w, _ in bending]) / (2 * np.pi)
    toolkit = np.array(level1_modes.toolkit_beam(10, "ss", "timoshenko"))
    np.testing.assert_allclose(fe[:3], toolkit[:3], rtol=5e-3)
