"""The lowest eigenpairs of a large symmetric positive definite matrix: shift-invert block Krylov.

A large Ritz basis of a plate (thousands of unknowns) is solved for its lowest hundred modes or
so. The dense solution spends its time reducing the whole matrix to tridiagonal form, while the
modes wanted are the largest eigenvalues of the inverse, which a Krylov space of a few times
their number holds to the working accuracy. :func:`lowest_by_krylov` takes the inverse as a
function (a plate applies it with the Cholesky factor its static compliance uses anyway,
:func:`impactmaps.targets.plates.plate_general.general_static_compliance`). Measured on the
drop-weight example's largest basis in docs/plates_any_edges.rst ("The eigen-solution of a
large basis"). Deterministic: the start block is drawn from a fixed seed, so the same matrix
gives the same bits.
"""

from __future__ import annotations

import numpy as np

__all__ = ["KRYLOV_MIN_UNKNOWNS", "KRYLOV_BLOCK", "KRYLOV_TOLERANCE", "KRYLOV_FLOOR", "lowest_by_krylov"]

#: Bases of at least this many unknowns are solved by block Krylov (smaller ones densely: there
#: the dense solution takes a fraction of a second).
KRYLOV_MIN_UNKNOWNS = 1200
#: Vectors per Krylov block.
KRYLOV_BLOCK = 24
#: Largest relative residual ``‖A⁻¹y − μy‖/μ`` of a kept pair (μ = 1/λ): eigenvalues to
#: ~1e-20 relative (they are quadratic in it), mode shapes to ~1e-10/gap.
KRYLOV_TOLERANCE = 1e-10
#: Share of the extrapolated blocks to the tolerance added before the next convergence check.
_EXTRAPOLATION_SHARE = 0.6
#: A residual that no longer falls is accepted up to this (:func:`_stagnated`).
KRYLOV_FLOOR = 1e-8
#: Seed of the random start block (fixed: the same matrix gives the same bits).
_SEED = 20261203


def lowest_by_krylov(apply_inverse, size: int, upper: float, max_fraction: float = 0.5):
    """Eigenpairs of a symmetric positive definite A with eigenvalue ≤ ``upper`` (at least the
    lowest one), from the block Krylov space of A⁻¹ (full reorthogonalisation, Rayleigh–Ritz).

    Parameters
    ----------
    apply_inverse : callable
        ``X (size, k) → A⁻¹ X``.
    size : int
        Order of A.
    upper : float
        Largest eigenvalue wanted [same units as A].
    max_fraction : float
        The space stops at this fraction of ``size``; None is returned beyond it.

    Returns
    -------
    (eigenvalues ascending, orthonormal eigenvectors (size, k)) or None
        None when the pairs did not converge to :data:`KRYLOV_TOLERANCE` within the space
        (the caller solves densely).
    """
    import scipy.linalg

    block = KRYLOV_BLOCK
    max_dim = max(int(max_fraction * size) // block * block, 2 * block)
    basis = np.empty((size, max_dim), order="F")  # column blocks contiguous
    images = np.empty((size, max_dim), order="F")
    projected = np.empty((max_dim, max_dim))  # basisᵀ A⁻¹ basis, grown a block at a time
    latest = _orthonormal(np.random.default_rng(_SEED).standard_normal((size, block)))
    dim, count, next_check, residuals = 0, 1, 2 * block, []
    while dim + block <= max_dim:
        new = slice(dim, dim + block)
        basis[:, new] = latest
        images[:, new] = apply_inverse(latest)
        dim += block
        column = basis[:, :dim].T @ images[:, new]
        projected[:dim, new] = column
        projected[new, :dim] = column.T
        if dim >= next_check:
            symmetric = 0.5 * (projected[:dim, :dim] + projected[:dim, :dim].T)
            if not residuals:  # still counting: the Ritz values below upper only grow in number (they interlace)
                count = max(count, int(np.count_nonzero(scipy.linalg.eigvalsh(symmetric) >= 1.0 / upper)))
            if 2 * count + block > max_dim:
                return None  # more wanted than the space may hold
            if dim < 2 * count + block:
                next_check = max(2 * count + block, int(1.5 * dim))  # few counts while the count grows
            else:
                found, worst, count = _converged_pairs(basis[:, :dim], images[:, :dim], symmetric, upper)
                if found is not None and (worst <= KRYLOV_TOLERANCE or _stagnated(residuals, worst)):
                    return found
                residuals.append((dim, worst))
                next_check = dim + block * _steps_to_tolerance(residuals, block)
        grown = images[:, new].copy(order="F")
        for _ in range(2):  # classical Gram–Schmidt, twice
            grown -= basis[:, :dim] @ (basis[:, :dim].T @ grown)
        latest = _orthonormal(grown)
    return None


def _orthonormal(columns):
    import scipy.linalg

    return scipy.linalg.qr(columns, mode="economic", check_finite=False)[0]


def _steps_to_tolerance(residuals, block: int) -> int:
    """Blocks to add before the next check, from ``residuals`` [(space size, worst relative
    residual)] of the checks so far: the worst residual's decay per block between the last two
    checks (one block when only one was made), extrapolated to :data:`KRYLOV_TOLERANCE`, times
    :data:`_EXTRAPOLATION_SHARE` (the decay quickens as the space grows, so the extrapolation
    overestimates; a check costs an eigen-solution of the projected matrix, a block its solves)."""
    if len(residuals) < 2 or not residuals[-1][1] < residuals[-2][1]:
        return 1
    (dim_before, before), (dim_now, now) = residuals[-2:]
    decay = np.log(before / now) / ((dim_now - dim_before) / block)  # per block
    needed = np.log(now / KRYLOV_TOLERANCE) / decay
    return max(int(np.ceil(_EXTRAPOLATION_SHARE * needed)), 1)


def _converged_pairs(basis, images, projected, upper):
    """(pairs, worst residual, count): the Ritz pairs of A⁻¹ with λ ≤ ``upper`` (``projected`` =
    basisᵀ A⁻¹ basis; the lowest one when none is), as (λ ascending, vectors) when the space
    holds at least twice their number plus a block, else None; their worst relative residual
    ``‖A⁻¹y − μy‖/μ`` (inf when not checked); and their number, which only grows with the space
    (the Ritz values interlace)."""
    import scipy.linalg

    mu, coefficients = scipy.linalg.eigh(projected, subset_by_value=(1.0 / upper, np.inf), driver="evr")
    if mu.size == 0:
        order = projected.shape[0]
        mu, coefficients = scipy.linalg.eigh(projected, subset_by_index=(order - 1, order - 1), driver="evr")
    count = mu.size
    if basis.shape[1] < 2 * count + KRYLOV_BLOCK or mu[0] <= 0.0:
        return None, np.inf, count
    mu, coefficients = mu[::-1], coefficients[:, ::-1]
    vectors = basis @ coefficients
    worst = float(np.max(np.linalg.norm(images @ coefficients - vectors * mu, axis=0) / mu))
    return (1.0 / mu, vectors), worst, count


def _stagnated(residuals, worst: float) -> bool:
    """True when the worst residual is at the floor of applying A⁻¹ in floating point: at most
    :data:`KRYLOV_FLOOR` and less than halved since the previous check (a plate whose lowest
    mode lies far below the resolved frequency, a cantilever's: docs/plates_any_edges.rst)."""
    return bool(residuals) and worst <= KRYLOV_FLOOR and worst > 0.5 * residuals[-1][1]
