"""The contact-law interface, the registry of laws, and contact geometry helpers.

A contact law is a force–indentation relation ``F(α; α_max)`` whose only history is
``α_max``, the largest indentation reached (loading curve at ``α ≥ α_max``, the elastic
unloading curve below, no tension). Each law is one scalar numba kernel
``kernel(alpha, alpha_max, params) -> (force, stiffness)`` shared by every solver.
"""

from __future__ import annotations

import functools
from abc import ABC, abstractmethod
from dataclasses import dataclass, field, fields
from typing import ClassVar

import numba
import numpy as np

from .._checks import (
    require_choice,
    require_nonnegative,
)
from .._compile.lazy_kernel import LazyKernel

__all__ = [
    "ContactLaw",
    "register_contact_law",
    "contact_law",
    "contact_law_class",
    "available_contact_laws",
    "evaluate_kernel",
    "kernel_pointer",
    "KERNEL_TYPE",
]


_F8 = numba.types.float64
_VECTOR = numba.types.Array(_F8, 1, "C")
_MATRIX = numba.types.Array(_F8, 2, "C")
#: Numba type of every contact-law kernel ``(alpha, alpha_max, params) -> (force, stiffness)``.
#: Compiled solvers take the kernel as this first-class *function type* (a function
#: pointer), not as a dispatcher: one compiled solver then serves every law and numba's
#: on-disk cache works (dispatcher-typed arguments break the cache across processes).
KERNEL_TYPE = numba.types.FunctionType(numba.types.UniTuple(_F8, 2)(_F8, _F8, _VECTOR))


class _KernelPointer:
    """A compiled kernel as a ready function pointer (looked up once; keeps the dispatcher alive)."""

    __slots__ = ("dispatcher", "_address")
    _numba_type_ = KERNEL_TYPE

    def __init__(self, dispatcher):
        from numba.experimental.function_type import _get_wrapper_address

        self.dispatcher = dispatcher
        self._address = _get_wrapper_address(dispatcher, KERNEL_TYPE.signature)

    def __wrapper_address__(self) -> int:
        return self._address


@functools.lru_cache(maxsize=64)
def _pointer_of(dispatcher) -> _KernelPointer:
    # A bounded memo of a pure function: the wrapper address of a compiled dispatcher
    # never changes while the process lives. Kernels are module-level dispatchers, one
    # per registered law, so 64 entries never evict in practice; the memo exists because
    # the look-up (≈ 20 µs) costs more than a whole single-mode impact run.
    return _KernelPointer(dispatcher)


def kernel_pointer(kernel) -> _KernelPointer:
    """The function pointer (memoised) of a contact-law ``kernel`` for compiled solvers
    (α, α_max [m] → force [N], stiffness [N/m])."""
    if isinstance(kernel, _KernelPointer):
        return kernel
    return _pointer_of(kernel)


@numba.njit(cache=True)
def _evaluate_many_kernel(kernel, alpha, alpha_max, params):
    n = alpha.shape[0]
    force = np.empty(n)
    stiffness = np.empty(n)
    for i in range(n):
        f, s = kernel(alpha[i], alpha_max[i], np.ascontiguousarray(params[i]))
        force[i] = f
        stiffness[i] = s
    return force, stiffness


# Compiled (or loaded from numba's cache) on its first call, not at import: ``impactmaps
# laws`` and a map lookup import the contact laws but evaluate none (the eager signature
# cost ~0.6 s of every such command).
_evaluate_many = LazyKernel(_evaluate_many_kernel,
                            numba.types.UniTuple(_VECTOR, 2)(KERNEL_TYPE, _VECTOR, _VECTOR, _MATRIX))


def evaluate_kernel(kernel, parameters, indentation, max_indentation):
    """Evaluate a scalar contact kernel element-wise with NumPy broadcasting.

    ``parameters`` (n_params, ...) broadcast against ``indentation`` α and
    ``max_indentation`` α_max [m]; returns force [N] and tangent stiffness [N/m].
    """
    params = np.asarray(parameters, dtype=float)
    alpha = np.asarray(indentation, dtype=float)
    alpha_max = np.asarray(max_indentation, dtype=float)
    batch = params.shape[1:]
    shape = np.broadcast_shapes(alpha.shape, alpha_max.shape, batch)
    n_params = params.shape[0]
    # align the batch dimensions with the trailing dimensions of ``shape`` (NumPy rule)
    params = params.reshape((n_params,) + (1,) * (len(shape) - len(batch)) + batch)
    # writeable C-contiguous copies (the compiled evaluator's signature requires them)
    flat_params = np.array(np.broadcast_to(params, (n_params,) + shape).reshape(n_params, -1).T, order="C")
    flat_alpha = np.array(np.broadcast_to(alpha, shape).ravel(), order="C")
    flat_alpha_max = np.array(np.broadcast_to(alpha_max, shape).ravel(), order="C")
    force, stiffness = _evaluate_many(kernel_pointer(kernel), flat_alpha, flat_alpha_max, flat_params)
    return force.reshape(shape), stiffness.reshape(shape)


@dataclass(frozen=True)
class LawOption:
    """One keyword option of a law's contact-pair constructor: ``name``, SI ``unit`` ("" if
    dimensionless), ``default`` and a one-line ``meaning``."""

    name: str
    unit: str
    default: object
    meaning: str


_OPTION = "contact law option"  # dataclass-field metadata key of law_option


def law_option(default, unit: str, meaning: str):
    """Declare a law field (its ``default``, SI ``unit``, one-line ``meaning``) that is also a
    keyword option of ``from_contact_pair``."""
    return field(default=default, metadata={_OPTION: (unit, meaning)})


class ContactLaw(ABC):
    """A stateful force–indentation law ``F(α; α_max)``.

    Subclasses are frozen dataclasses of the law's parameters (SI, may be arrays: one
    object, a batch of cases) with class attributes ``name``, ``elastic``,
    ``needs_yield_strength``, ``revision`` (bumped when answers change) and
    ``stiffness_unit``, and provide ``kernel``, :attr:`kernel_parameters`,
    :meth:`permanent_indentation` and :meth:`from_contact_pair`.
    """

    name: ClassVar[str]
    elastic: ClassVar[bool]
    needs_yield_strength: ClassVar[bool]
    kernel: ClassVar  # staticmethod(numba dispatcher)
    revision: ClassVar[int] = 1
    stiffness_unit: ClassVar[str | None] = None

    @property
    @abstractmethod
    def kernel_parameters(self) -> np.ndarray:
        """Float parameter vector for :attr:`kernel`, shape ``(n_params, *batch)``."""

    @abstractmethod
    def permanent_indentation(self, max_indentation):
        """Permanent indentation α_f [m] left after unloading from ``max_indentation`` [m]."""

    # -- construction from a contact pair -------------------------------------------
    @classmethod
    def options(cls) -> dict[str, LawOption]:
        """Keyword options of :meth:`from_contact_pair` by name: the fields declared with :func:`law_option`."""
        return {
            f.name: LawOption(f.name, f.metadata[_OPTION][0], f.default, f.metadata[_OPTION][1])
            for f in fields(cls) if _OPTION in f.metadata
        }

    @classmethod
    def check_options(cls, options, also_valid=()) -> None:
        """``ValueError`` if ``options`` holds a key that is neither an option nor in ``also_valid``."""
        valid = set(cls.options()) | set(also_valid)
        unknown = set(options) - valid
        if unknown:
            raise ValueError(f"options {sorted(unknown)} are not known for law {cls.name!r}: "
                             f"valid options are {sorted(valid)}")

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "ContactLaw":
        """Build the law for a :class:`~impactmaps.contact.pair.ContactPair` (E* [Pa], R [m], yield strength [Pa]).

        Raises
        ------
        ValueError
            An unknown option, or (laws with ``needs_yield_strength``) no yield strength.
        """
        raise ValueError(
            f"contact law {cls.name!r} has no from_contact_pair builder: construct it directly"
        )

    # -- evaluation -------------------------------------------------------------
    @property
    def python_kernel(self):
        """:attr:`kernel` run as Python, for scalar calls from Python code (an asymptote's rates,
        a bisection): the same operations, the same bits (IEEE arithmetic and libm in both), and
        the kernel itself not compiled or loaded (the first compiled call in a process costs
        ~0.2 s; compiled helpers a kernel calls, as the plastic laws' loading curves, still are)."""
        return getattr(self.kernel, "py_func", self.kernel)

    def force(self, indentation, max_indentation=0.0):
        """Contact force [N] at indentation α [m] with history α_max [m] (default: virgin)."""
        return evaluate_kernel(self.kernel, self.kernel_parameters, indentation, max_indentation)[0]

    def tangent_stiffness(self, indentation, max_indentation=0.0):
        """Tangent contact stiffness dF/dα [N/m] at α [m] with history α_max [m]."""
        return evaluate_kernel(self.kernel, self.kernel_parameters, indentation, max_indentation)[1]

    def loading_force(self, indentation):
        """Force [N] on the virgin loading curve at indentation α ≥ 0 [m]."""
        alpha = np.asarray(indentation, dtype=float)
        return self.force(alpha, alpha)

    # -- energies ---------------------------------------------------------------
    def loading_energy(self, max_indentation, points: int = 2001):
        """Work [J] done loading the contact from 0 to α_max [m] (Simpson on ``points`` graded points)."""
        alpha_max = np.asarray(max_indentation, dtype=float)
        s = _graded_grid(points)
        alpha = alpha_max[..., None] * s
        # quadrature points on a trailing axis: give the parameter batch a matching one
        force = evaluate_kernel(self.kernel, self._parameters_with_point_axis(), alpha, alpha)[0]
        return _simpson(force, alpha)

    def recovered_energy(self, max_indentation, points: int = 2001):
        """Work [J] returned by the contact unloading from α_max to α_f [m] (quadrature)."""
        alpha_max = np.asarray(max_indentation, dtype=float)
        alpha_f = np.asarray(self.permanent_indentation(alpha_max), dtype=float)
        s = _graded_grid(points)
        alpha = alpha_f[..., None] + (alpha_max - alpha_f)[..., None] * s
        force = evaluate_kernel(
            self.kernel, self._parameters_with_point_axis(), alpha, alpha_max[..., None]
        )[0]
        return _simpson(force, alpha)

    def _parameters_with_point_axis(self) -> np.ndarray:
        params = np.asarray(self.kernel_parameters, dtype=float)
        return params if params.ndim == 1 else params[..., None]

    def dissipated_energy(self, max_indentation):
        """Energy [J] dissipated by a full load–unload cycle to α_max [m] (≥ 0)."""
        if self.elastic:
            return np.zeros_like(np.asarray(max_indentation, dtype=float))
        return self.loading_energy(max_indentation) - self.recovered_energy(max_indentation)

    # -- derived numbers ---------------------------------------------------------------
    @property
    def linear_stiffness(self):
        """Stiffness K [N/m] of a linear law ``F = K α``; ``None`` for a nonlinear law."""
        return None

    @property
    def contact_radius_scale(self):
        """Effective radius R [m] of the sphere–target pair when the law knows it (patch radius
        ``sqrt(R α)``), else ``None``."""
        return getattr(self, "effective_radius", None)

    def impact_number(self, impactor_mass, velocity):
        """Impact number β [-] of an impact by mass m_i [kg] at V0 [m/s]; ``None`` for elastic laws."""
        return None

    def indentation_for_energy(self, energy):
        """Indentation α_m [m] at which the loading work equals ``energy`` [J] (≥ 0; 0 → 0).

        Raises
        ------
        ValueError
            ``energy`` negative or not finite, or not absorbed within 1000 m of indentation.
        """
        return _invert_loading_energy(self, energy)

    # -- what places the law's impacts on a normalised map ------------------------------
    @property
    def hertzian_stiffness(self):
        """K_h [N/m^1.5] of an elastic Hertz law ``F = K_h α^{3/2}``; ``None`` for any other law."""
        return None

    @property
    def yield_scales(self):
        """``(K_h [N/m^1.5], α_y [m])`` of the Yigit–Christoforou law placing this law's impacts; ``None`` without a
        yield scale."""
        return None

    def changed_options(self) -> dict:
        """Name → value of the :meth:`options` that differ from their defaults (an array: any value)."""
        return {name: getattr(self, name) for name, option in self.options().items()
                if not np.all(np.asarray(getattr(self, name), float) == float(option.default))}


#: First trial indentation of the generic energy inversion [m] (grown or shrunk ×4).
_TRIAL_INDENTATION = 1e-6
#: Largest indentation the generic inversion looks at [m] (beyond: the law's units are wrong).
_LARGEST_INDENTATION = 1e3


def check_energy(energy) -> np.ndarray:
    """``energy`` [J] as a float array, or ``ValueError`` if negative or not finite."""
    require_nonnegative("energy", energy, "J")
    return np.asarray(energy, dtype=float)


def _invert_loading_energy(law: ContactLaw, energy) -> np.ndarray:
    """α_m [m] with ``law.loading_energy(α_m) = energy`` (see ContactLaw.indentation_for_energy)."""
    target = check_energy(energy)
    batch = np.shape(law.kernel_parameters)[1:]
    target = np.broadcast_to(target, np.broadcast_shapes(target.shape, batch))
    active = target > 0.0
    # bracket: grow α ×4 until the work reaches the target, shrink it while α/4 still does
    alpha = np.where(active, _TRIAL_INDENTATION, 0.0)
    while np.any(short := active & (law.loading_energy(alpha) < target)):
        alpha = np.where(short, 4.0 * alpha, alpha)
        if np.any(alpha > _LARGEST_INDENTATION):
            raise ValueError(
                f"energy = {energy!r} J is not absorbed within {_LARGEST_INDENTATION:g} m of "
                "indentation by this law (check the units of the law's parameters)"
            )
    while np.any(long := active & (alpha > 1e-150) & (law.loading_energy(alpha / 4.0) >= target)):
        alpha = np.where(long, alpha / 4.0, alpha)
    # Newton from above; stops when no step moves α by more than a few ulps
    for _ in range(100):
        excess = np.where(active, law.loading_energy(alpha) - target, 0.0)
        force = np.where(active, law.loading_force(alpha), 1.0)
        step = np.where(excess > 0.0, excess / force, 0.0)
        alpha = alpha - step
        if np.all(step <= 4.0 * np.finfo(float).eps * alpha):
            break
    return alpha


def _graded_grid(points: int) -> np.ndarray:
    """Points on [0, 1] clustered at both ends (where the laws have their kinks)."""
    if points % 2 == 0:
        points += 1
    theta = np.linspace(0.0, np.pi, points)
    return 0.5 * (1.0 - np.cos(theta))


def _simpson(values, abscissae):
    from scipy.integrate import simpson

    return simpson(values, x=abscissae, axis=-1)


# -- registry -----------------------------------------------------------------------
_REGISTRY: dict[str, type[ContactLaw]] = {}


def register_contact_law(cls: type[ContactLaw]) -> type[ContactLaw]:
    """Class decorator: add a contact law to the registry under ``cls.name``."""
    if cls.name in _REGISTRY and _REGISTRY[cls.name] is not cls:
        raise ValueError(f"contact law name {cls.name!r} is already registered")
    _REGISTRY[cls.name] = cls
    return cls


def available_contact_laws() -> tuple[str, ...]:
    """Names of all registered contact laws, sorted."""
    return tuple(sorted(_REGISTRY))


def contact_law_class(name: str) -> type[ContactLaw]:
    """The contact-law class registered as ``name`` (``ValueError`` if unknown)."""
    require_choice("contact law", name, available_contact_laws())
    return _REGISTRY[name]


def contact_law(name: str, **parameters) -> ContactLaw:
    """Build the registered contact law ``name`` from keyword parameters (SI units)."""
    return contact_law_class(name)(**parameters)
