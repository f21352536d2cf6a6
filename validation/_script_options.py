"""Command-line options shared by the validation scripts: ``--smoke`` and ``--out-dir``.

Every script in ``validation/`` and ``data_build/`` (which imports this module from here)
runs in two sizes:

* full (the default): the study quoted in docs/validation.rst and ``BENCHMARKS.md``, writing its
  figures into ``figures/`` (``data_build/build_default_maps.py``: the shipped maps;
  ``lookup_error.py``: ``validation/lookup_error.csv``);
* ``--smoke``: the same code path on a tiny setting (seconds; the numbers it prints are
  not meaningful), used by ``tests/validation/test_validation_scripts.py``. It writes into
  ``--out-dir`` or, when that is not given, into a new temporary directory — never into
  the repository.

Each script's ``main(argv=None)`` takes the command-line arguments as a list.
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

SMOKE_HELP = "tiny run (seconds) to check the script works; numbers not meaningful; writes to a temporary directory"


def one_blas_thread() -> None:
    """One BLAS thread a process (OpenBLAS, OpenMP, MKL) unless the environment sets them: call it before NumPy loads."""
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(name, "1")


def parse(description: str, argv=None, *, default_out: Path, add_arguments=None) -> argparse.Namespace:
    """Parse ``--smoke``, ``--out-dir`` and the script's own options.

    Parameters
    ----------
    description : str
        Help text (the script's docstring's first line).
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).
    default_out : Path
        Output directory of the full run.
    add_arguments : callable, optional
        ``add_arguments(parser)`` adds the script's own options.

    Returns
    -------
    argparse.Namespace
        With ``smoke`` (bool) and ``out_dir`` (an existing directory).
    """
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    parser.add_argument("--out-dir", type=Path, default=None,
                        help=f"output directory (default: {default_out}; with --smoke a new temporary directory)")
    if add_arguments is not None:
        add_arguments(parser)
    args = parser.parse_args(argv)
    if args.out_dir is None:
        args.out_dir = Path(tempfile.mkdtemp(prefix="impactmaps-smoke-")) if args.smoke else Path(default_out)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    return args
