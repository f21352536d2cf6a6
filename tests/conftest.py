"""Test configuration: single-threaded BLAS (the machine has 2 cores and the tests
already run work in parallel; threaded BLAS under load is 10–20× slower), and the
on-demand map tiles cached in a temporary directory of the session, never in the user's
``~/.cache`` (a test that needs its own cache passes ``cache_dir`` or sets the variable);
no background warm-up of numba's cache."""

import os
import tempfile

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

# no background warm-up from the commands the tests run (tests/compile/test_startup.py checks the
# mechanism with a stand-in target and its own state directory)
os.environ["IMPACTMAPS_NO_BACKGROUND_WARMUP"] = "1"

_TILE_CACHE = tempfile.TemporaryDirectory(prefix="impactmaps-test-tiles-")
os.environ["IMPACTMAPS_CACHE_DIR"] = _TILE_CACHE.name


def pytest_report_header(config):
    """Which impactmaps the run tests: the installed package (its path), not the checkout."""
    import impactmaps

    return f"impactmaps {impactmaps.__version__} from {os.path.dirname(impactmaps.__file__)}"
