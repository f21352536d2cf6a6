"""A plate basis is the same bits with any number of BLAS threads (``impactmaps._blas``).

LAPACK's eigen-solvers give other bits with two OpenBLAS threads than with one; the command
line, the tests and the sweep workers run one, a Python session on a multi-core machine
several. The dense linear algebra behind an answer runs with one thread, so both give the same
bits (the drop-weight example was 4054.856386609983 N from Python and 4054.856386129993 N from
the command line before).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import impactmaps

SCRIPT = r"""
import hashlib, json
import numpy as np
from threadpoolctl import threadpool_limits, threadpool_info
import impactmaps
from impactmaps.targets.plates import plate_any_edges as pae, plate_general as pg

plate = impactmaps.Plate.isotropic(0.15, 0.1, 0.003, impactmaps.material("aluminium-6061-t6"),
                                   theory="mindlin", edges="CCCC")
n = 20
inputs, classes = pae._inputs(plate), pae.class_groups(plate)[0]
top = pae.resolved_frequency(plate, n, n)
load = np.linspace(1.0, 2.0, 3 * n * n)

def digest(solve):
    r = solve(*inputs, n, n, top, classes)
    return hashlib.sha256(r["coefficients"].tobytes() + r["frequencies"].tobytes()).hexdigest()

out = {"threads": max(i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas")}
for threads in (1, 2):
    with threadpool_limits(threads, "blas"):
        out[f"kept_{threads}"] = digest(pg._eigen_solution)
        out[f"bare_{threads}"] = digest(pg._eigen_solution.__wrapped__)
print(json.dumps(out))
"""


def test_a_plate_basis_is_the_same_bits_with_one_or_two_blas_threads(tmp_path):
    """The Ritz eigen-solution of a CCCC Mindlin plate (300 unknowns) computed with two BLAS
    threads allowed equals the one computed with one; where the machine has two threads to give,
    the same solve without :func:`impactmaps._blas.single_blas_thread` differs (so the check can
    fail)."""
    package_root = str(Path(impactmaps.__file__).resolve().parents[1])  # the package this test imported
    env = dict(os.environ, OPENBLAS_NUM_THREADS="2", OMP_NUM_THREADS="2", MKL_NUM_THREADS="2",
               PYTHONPATH=package_root)
    done = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["kept_1"] == out["kept_2"] == out["bare_1"]
    if out["threads"] >= 2 and (os.cpu_count() or 1) >= 2:
        assert out["bare_2"] != out["bare_1"]
