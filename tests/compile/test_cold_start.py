"""What the first run compiles, and the thin Python around the kernel (issue 30, items 2 and 4).

* A run without coupled modes (any non-linear law, or the sampled contact phase) compiles
  the integrator's variant without the exact contact phase only: that phase is half the
  integrator's compile time on an empty numba cache (``benchmarks/studies/RESULTS_cold_start.md``).
  Checked in a fresh interpreter, where nothing else has compiled a variant.
* The vectorised grouping of degenerate modes gives the groups of the sequential rule it
  replaced, on random bases that include chains of close neighbours drifting beyond the
  tolerance (exact comparison of indices: the rule is discrete).
* ``ModalBasis.participating`` is computed once per basis.
* ``impactmaps --help`` imports neither numba nor xarray nor matplotlib.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np

from impactmaps.targets import base
from impactmaps.targets.base import DEGENERACY_TOLERANCE, ModalBasis


def _run(script: str) -> str:
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(script)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_a_hertz_run_compiles_the_integrator_without_the_exact_contact_phase():
    out = _run("""
        import numba
        from impactmaps.contact import contact_law
        from impactmaps.maps.family.structures import structure_from_name
        from impactmaps.solvers.integrator.exact_step import integrate_impact
        from impactmaps.solvers.modal import simulate
        basis = structure_from_name("beam-ss-euler").build().modes(1e5, min_modes=4)
        simulate(basis, contact_law("hertz", stiffness=1e9), 0.01, 1.0, record=False)
        signatures = integrate_impact.dispatcher.signatures
        assert len(signatures) == 1 and signatures[0][-1] == numba.types.none, signatures
        print("ok")
    """)
    assert out.strip() == "ok"


def _sequential_starts(frequencies, damping):
    """The sequential rule, mode by mode (reference)."""
    n = frequencies.size
    starts = [0] if n else []
    for j in range(1, n):
        close = (abs(frequencies[j] - frequencies[j - 1]) <= DEGENERACY_TOLERANCE * frequencies[j]
                 and damping[j] == damping[j - 1])
        if not close or abs(frequencies[j] - frequencies[starts[-1]]) > DEGENERACY_TOLERANCE * frequencies[j]:
            starts.append(j)
    return np.asarray(starts, dtype=np.intp)


def test_vectorised_degenerate_grouping_matches_the_sequential_rule():
    rng = np.random.default_rng(30)
    drifting = 0
    for _ in range(3000):
        n = int(rng.integers(0, 25))
        frequencies = np.sort(rng.choice([1.0, 2.0, 5.0], n)) * 1e3
        frequencies = frequencies * (1 + rng.choice([0.0, 0.6, 1.5, 3.0], n) * DEGENERACY_TOLERANCE * rng.random(n))
        if rng.random() < 0.5:
            frequencies = np.sort(frequencies)
        damping = rng.choice([0.0, 0.01], n) if rng.random() < 0.3 else np.zeros(n)
        expected = _sequential_starts(frequencies, damping)
        got = base._degenerate_group_starts(frequencies, damping)
        assert np.array_equal(got, expected), (frequencies, damping)
        if n > 1:
            candidates = np.flatnonzero(np.concatenate(([True], ~(
                (np.abs(np.diff(frequencies)) <= DEGENERACY_TOLERANCE * frequencies[1:])
                & (damping[1:] == damping[:-1])))))
            drifting += candidates.size != expected.size
    assert drifting > 10  # the sequential splitting of drifting chains was exercised


def test_participating_basis_is_computed_once():
    basis = ModalBasis(np.array([1.0, 1.0, 2.0]), np.array([0.5, 0.5, 1.0]), 0.0)
    merged = basis.participating()
    assert merged.size == 2 and basis.participating() is merged


def test_help_imports_no_solver_stack():
    out = _run("""
        import sys
        from impactmaps.cli import main
        try:
            main(["--help"])
        except SystemExit:
            pass
        print(sorted(m for m in ("numba", "xarray", "matplotlib", "scipy") if m in sys.modules))
    """)
    assert out.strip().splitlines()[-1] == "[]"
