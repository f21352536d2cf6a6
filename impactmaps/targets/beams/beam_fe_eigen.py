"""Eigen-solution of the banded beam finite-element model: dense (flexibility form) for
small models, spectrum slicing with Sturm-sequence checks for large ones."""

from __future__ import annotations

import numba
import numpy as np
import scipy.linalg
import scipy.sparse.linalg
from ..._blas import single_blas_thread

__all__ = ["eigenpairs_below", "count_below"]

#: FE models with at most this many unknowns are solved densely, larger ones by
#: spectrum slicing (shift-invert Lanczos with Sturm-sequence checks).
_DENSE_LIMIT = 1500
#: Target number of eigenvalues per spectrum slice.
_SLICE_SIZE = 48


@single_blas_thread
def eigenpairs_below(K, M, upper, width, reference, singular):
    """Eigenpairs (λ [rad²/s²], M-normalised vectors) of ``K x = λ M x`` with λ < ``upper``, ascending.

    ``K``, ``M``: sparse symmetric banded matrices of half-bandwidth ``width``;
    ``reference``: the scale of the lowest eigenvalue [rad²/s²]; ``singular``: K has a
    null space (free–free beam).
    """
    if K.shape[0] <= _DENSE_LIMIT:
        # Flexibility form (K + σM)^{-1} M: the low modes are its largest eigenvalues and
        # keep full relative accuracy (K x = ω² M x directly loses about eps·ω_max²/ω_1²
        # in the fundamental: 1e-5 and worse on fine meshes).
        return _solve_dense(K, M, upper, reference if singular else 0.0)
    return _solve_sliced(K.tocsc(), M.tocsc(), upper, -1e-3 * reference if singular else 0.0, width)


def _solve_dense(K, M, upper, shift):
    """All eigenpairs with λ < ``upper`` in flexibility form (relative accuracy kept)."""
    Kd, Md = K.toarray(), M.toarray()
    factor = scipy.linalg.cholesky(Kd + shift * Md, lower=True)
    half = scipy.linalg.solve_triangular(factor, Md, lower=True)
    flexibility = scipy.linalg.solve_triangular(factor, half.T, lower=True)
    flexibility = 0.5 * (flexibility + flexibility.T)
    lowest = 1.0 / (upper + shift)
    mu, y = scipy.linalg.eigh(flexibility, subset_by_value=(lowest, np.inf), driver="evr")
    mu, y = mu[::-1], y[:, ::-1]
    vectors = scipy.linalg.solve_triangular(factor, y, lower=True, trans="T") / np.sqrt(mu)
    return 1.0 / mu - shift, vectors


def _solve_sliced(K, M, upper, start, width):
    """All eigenpairs with ``start`` < λ < ``upper`` by spectrum slicing (inertia-checked slices)."""
    kband, mband = _lower_band(K, width), _lower_band(M, width)
    n = K.shape[0]

    def below(value):
        return _count_below(kband, mband, value)

    low = start
    below_low = below(low)
    remaining = below(upper) - below_low
    span = (upper - start) * min(1.0, _SLICE_SIZE / max(remaining, 1))
    values, vectors = [], []
    while remaining > 0:
        high = min(upper, low + span)
        count = below(high) - below_low
        while count > 2 * _SLICE_SIZE:
            span *= 0.5
            high = low + span
            count = below(high) - below_low
        while count == 0:
            span *= 2.0
            high = min(upper, low + span)
            count = below(high) - below_low
        extra = 8
        for _attempt in range(5):
            k = min(count + extra, n - 2)
            lam, vec = scipy.sparse.linalg.eigsh(
                K, k=k, M=M, sigma=0.5 * (low + high), which="LM", tol=0.0,
                ncv=min(n - 1, max(2 * k + 1, 40)))
            order = np.argsort(lam)
            above = lam[order] > low
            lam, vec = lam[order][above], vec[:, order][:, above]
            boundary = 0.5 * (lam[count - 1] + lam[count]) if lam.size > count else high
            if lam.size >= count and below(boundary) - below_low == count:
                break
            extra *= 2
        else:
            raise RuntimeError("spectrum slicing of the beam FE model failed: an eigenvalue "
                               "count did not match the Sturm sequence")
        values.append(lam[:count])
        vectors.append(vec[:, :count])
        low, below_low, remaining = boundary, below_low + count, remaining - count
        span *= min(2.0, max(0.5, _SLICE_SIZE / count))
    lam = np.concatenate(values) if values else np.zeros(0)
    vec = np.concatenate(vectors, axis=1) if vectors else np.zeros((n, 0))
    norms = np.sqrt(np.einsum("ij,ij->j", vec, M @ vec))
    return lam, vec / norms


def count_below(K, M, width: int, shift: float) -> int:
    """Number of eigenvalues of ``K x = λ M x`` below ``shift`` [rad²/s²] (Sylvester's inertia), no mode built."""
    return int(_count_below(_lower_band(K, width), _lower_band(M, width), float(shift)))


@numba.njit(cache=True)
def _count_below(stiffness_band, mass_band, shift):  # pragma: no cover - numba
    """Number of negative pivots of the banded LDLᵀ of ``K − shift·M`` (Sylvester's inertia)."""
    width = stiffness_band.shape[0] - 1
    n = stiffness_band.shape[1]
    lower = np.zeros((width + 1, n))
    pivots = np.zeros(n)
    negatives = 0
    tiny = 1e-300
    for j in range(n):
        value = stiffness_band[0, j] - shift * mass_band[0, j]
        for k in range(max(0, j - width), j):
            value -= lower[j - k, k] ** 2 * pivots[k]
        if value == 0.0:
            value = tiny
        pivots[j] = value
        if value < 0.0:
            negatives += 1
        for i in range(j + 1, min(n, j + width + 1)):
            entry = stiffness_band[i - j, j] - shift * mass_band[i - j, j]
            for k in range(max(0, i - width), j):
                entry -= lower[i - k, k] * lower[j - k, k] * pivots[k]
            lower[i - j, j] = entry / value
    return negatives


def _lower_band(matrix, width: int) -> np.ndarray:
    n = matrix.shape[0]
    band = np.zeros((width + 1, n))
    for d in range(width + 1):
        band[d, : n - d] = matrix.diagonal(-d)
    return band

