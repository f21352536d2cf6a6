"""What goes into and comes out of the compiled modal integrator, by name (numba named tuples).

The integrator takes the contact law (kernel pointer, parameters, linear stiffness) and
:class:`KernelModes`, :class:`KernelImpact`, :class:`KernelRun`, :class:`KernelCoupled`,
and returns the history, the contact intervals and :class:`KernelScalars`; the ``*_TYPE``
constants are their numba types.
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

__all__ = ["kernel_array", "KernelModes", "KernelImpact", "KernelRun", "KernelCoupled", "KernelScalars", "MODES_TYPE",
           "IMPACT_TYPE", "RUN_TYPE", "COUPLED_TYPE", "SCALARS_TYPE"]

_F8 = numba.types.float64
_I8 = numba.types.int64
_BOOL = numba.types.boolean
_VECTOR = numba.types.Array(_F8, 1, "C")
_MATRIX = numba.types.Array(_F8, 2, "C")


def kernel_array(values: np.ndarray) -> np.ndarray:
    """``values`` as C-contiguous, writeable float64 (the same array when it already is, else a
    copy), as the kernel's signature takes them.
    """
    if type(values) is np.ndarray and values.dtype == np.float64:  # noqa: E721 (a subclass takes np.require)
        flags = values.flags
        if flags.c_contiguous and flags.writeable:
            return values  # what np.require returns here, without its keyword handling (~1 µs a call)
    return np.require(values, dtype=np.float64, requirements=("C", "W"))


class KernelModes(NamedTuple):
    """The retained modes at the impact point (C-contiguous float64 arrays): ``frequencies``
    ω_j [rad/s] ascending, ``participation`` φ_j(x0) [1/sqrt(kg)], ``damping_ratios`` ζ_j [-],
    ``residual`` compliance of the dropped modes [m/N].
    """

    frequencies: np.ndarray
    participation: np.ndarray
    damping_ratios: np.ndarray
    residual: float


class KernelImpact(NamedTuple):
    """The impactor: ``mass`` [kg] and approach ``velocity`` [m/s]."""

    mass: float
    velocity: float


class KernelRun(NamedTuple):
    """The step and limits of one run: ``time_step`` h [s], ``max_time`` [s], ``record``,
    ``max_events`` (interval-table capacity), ``max_rows`` (history cap) and ``stop`` (int64
    flag: the run ends at its next step once it is non-zero).
    """

    time_step: float
    max_time: float
    record: bool
    max_events: int
    max_rows: int
    stop: np.ndarray


class KernelCoupled(NamedTuple):
    """The coupled modes of a linear contact (empty arrays for the sampled phase):
    ``frequencies`` Ω_k [rad/s], ``force_row`` c_k, ``from_coupled``, ``to_coupled``,
    ``row_spacing`` of recorded rows [s] and ``step_scale`` [-].
    """

    frequencies: np.ndarray
    force_row: np.ndarray
    from_coupled: np.ndarray
    to_coupled: np.ndarray
    row_spacing: float
    step_scale: float


class KernelScalars(NamedTuple):
    """The scalars of one run (SI units); ``time_limit_reached`` is also set by the stop flag,
    ``events_overflow``, ``row_cap_reached`` and ``stalled``.
    """

    peak_force: float
    peak_time: float
    max_indentation: float
    final_velocity: float
    structure_energy: float
    damping_work: float
    end_time: float
    time_limit_reached: bool
    steps: int
    events_overflow: bool
    row_cap_reached: bool
    stalled: bool


MODES_TYPE = numba.types.NamedTuple((_VECTOR, _VECTOR, _VECTOR, _F8), KernelModes)
IMPACT_TYPE = numba.types.NamedUniTuple(_F8, 2, KernelImpact)  # what numba.typeof gives a homogeneous tuple
RUN_TYPE = numba.types.NamedTuple((_F8, _F8, _BOOL, _I8, _I8, numba.types.Array(_I8, 1, "C")), KernelRun)
COUPLED_TYPE = numba.types.NamedTuple((_VECTOR, _VECTOR, _MATRIX, _MATRIX, _F8, _F8), KernelCoupled)
SCALARS_TYPE = numba.types.NamedTuple((_F8,) * 7 + (_BOOL, _I8, _BOOL, _BOOL, _BOOL), KernelScalars)


class Work(NamedTuple):
    """What the integrator's stages share through a run (internal): step, limits, step
    coefficients, scratch arrays, free-flight propagators and the contact-interval table.
    """

    h: float
    max_time: float
    max_steps: int
    record: bool
    compliance_h: float
    damped: bool
    coef: np.ndarray
    sub: np.ndarray
    q_try: np.ndarray
    v_try: np.ndarray
    free_coef: np.ndarray
    free_ready: np.ndarray
    scratch: np.ndarray
    intervals: np.ndarray
