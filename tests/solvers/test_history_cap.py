"""The history of a modal run is bounded inside the kernel (issue 29): a recorded run writes
at most ``run.max_rows`` rows (:data:`~impactmaps.solvers.run_budget.HISTORY_ROW_CAP` from
:func:`~impactmaps.solvers.modal.simulate`), stops there and says so; below the cap
nothing changes."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from impactmaps.contact.base import kernel_pointer
from impactmaps.contact.linear import LinearContact
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.solvers.integrator.exact_step import integrate_impact
from impactmaps.solvers.integrator.kernel_types import KernelCoupled, KernelImpact, KernelModes, KernelRun

_NO_COUPLED = KernelCoupled(np.zeros(0), np.zeros(0), np.zeros((0, 0)), np.zeros((0, 0)), 1e-6, 1.0)


def _kernel_run(max_rows: int, record: bool = True):
    """A sampled linear-contact run on an SS Euler beam (a few thousand steps), recorded."""
    law = LinearContact(1e7)
    basis = structure_from_name("beam-ss-euler").build().modes(2e5, min_modes=4).participating()
    modes = KernelModes(np.ascontiguousarray(basis.frequencies), np.ascontiguousarray(basis.participation),
                        np.ascontiguousarray(basis.damping_ratios), float(basis.residual_compliance))
    run = KernelRun(2e-6, 1.0, record, 1000, max_rows, np.zeros(1, dtype=np.int64))
    return integrate_impact(kernel_pointer(law.kernel), np.array(law.kernel_parameters, dtype=float), 1e7, modes,
                            KernelImpact(0.05, 1.0), run, _NO_COUPLED)


def test_a_run_at_its_row_cap_stops_there_and_says_so():
    """With a cap below the rows the run needs: exactly ``max_rows`` rows, the first rows
    of the uncapped run bit for bit, and the run flagged (row cap, time limit)."""
    full_history, _intervals, full = _kernel_run(10**7)
    assert not full.row_cap_reached and not full.time_limit_reached
    rows = full_history.shape[0]
    assert rows > 100  # the cap below binds
    history, _intervals, capped = _kernel_run(50)
    assert history.shape == (50, 8)
    assert np.array_equal(history, full_history[:50])
    assert capped.row_cap_reached and capped.time_limit_reached
    assert capped.end_time < full.end_time and capped.steps < full.steps
    # exactly at the run's own length: the last row written, the cap reached (said, not hidden)
    history, _intervals, exact = _kernel_run(rows)
    assert np.array_equal(history, full_history) and exact.row_cap_reached
    # without a record the cap plays no part: the scalars of the uncapped run
    _history, _intervals, unrecorded = _kernel_run(1, record=False)
    assert unrecorded == full


@pytest.mark.slow
def test_a_billion_kilogram_impactor_stays_under_the_row_cap():
    """A 1e9 kg Hertz impactor on a 4 mm SS Kirchhoff steel plate (1.37 M steps to its end;
    before: as many history rows, ~0.4 GB, no word) in a fresh interpreter: at most
    HISTORY_ROW_CAP rows, the run stopped there with a warning naming the knobs, the result
    not converged, and the process's peak memory (ru_maxrss, as the CLI fuzz test measures
    it) grows by less than the budget's estimate of a capped history plus 200 MB."""
    script = textwrap.dedent("""
        import json, resource, warnings
        from impactmaps.contact.sphere import Sphere, law_for_sphere
        from impactmaps.materials import CATALOGUE
        from impactmaps.solvers.modal import simulate
        from impactmaps.solvers.run_budget import HISTORY_ROW_BYTES, HISTORY_ROW_CAP
        from impactmaps.targets.plates.plate import Plate

        steel = CATALOGUE["structural-steel"]
        plate = Plate.isotropic(0.25, 0.25, 0.004, steel, theory="kirchhoff")
        law = law_for_sphere("hertz", Sphere(0.005, steel), steel)
        simulate(plate, law, 0.004, 2.0, record=False)  # compiled and imported before measuring
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = simulate(plate, law, 1e9, 1.0)
        after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
        print(json.dumps({"rows": len(result.history), "cap": HISTORY_ROW_CAP, "bytes": HISTORY_ROW_BYTES,
                          "growth": after - before, "time_limit_reached": result.time_limit_reached,
                          "converged": result.converged, "note": result.convergence_note,
                          "warnings": [str(w.message) for w in caught]}))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    import json

    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["rows"] <= out["cap"]
    assert out["growth"] < out["cap"] * out["bytes"] + 200 * 2**20, out["growth"]
    assert out["rows"] == out["cap"]  # the run needs more: stopped, flagged and said
    assert out["time_limit_reached"] and out["converged"] is False and "row cap reached" in out["note"]
    assert any("row cap reached" in w and "record=False" in w for w in out["warnings"])
