"""Test configuration: single-threaded BLAS (the machine has 2 cores and the tests
already run work in parallel; threaded BLAS under load is 10–20× slower)."""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")
