"""One BLAS thread for the dense linear algebra an answer depends on.

LAPACK's eigen-solvers and factorisations give different bits with a different number of
BLAS threads (a threaded matrix–vector product sums in another order): the drop-weight
example's peak force differed in its 13th digit between a library call on 2 cores (two
OpenBLAS threads) and the command line, the tests and the sweep workers (one each), and a
basis kept on disk carried the bits of whichever computed it first (docs/plates_any_edges.rst). :func:`single_blas_thread` runs a computation with one BLAS thread, so
an answer is the same bits from Python, the command line, a sweep worker and the cache.
The command line already ran this way (``impactmaps/cli/__init__.py``); what one thread costs a
Python session on several cores is measured in docs/plates_any_edges.rst.
"""

from __future__ import annotations

import functools

__all__ = ["single_blas_thread"]


@functools.lru_cache(maxsize=1)
def _controller():
    """The thread-pool controller of the BLAS libraries loaded (NumPy's and SciPy's: SciPy's
    linear algebra is imported first, so its library is among them)."""
    import scipy.linalg  # noqa: F401  (loads SciPy's BLAS before the libraries are listed)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def single_blas_thread(function):
    """Decorator: ``function`` runs with one BLAS thread (the previous limit restored after)."""

    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        with _controller().limit(limits=1, user_api="blas"):
            return function(*args, **kwargs)

    return wrapper
