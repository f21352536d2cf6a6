"""What a :class:`~impactmaps.targets.plates.plate.Plate` takes from the general Ritz basis of
:mod:`impactmaps.targets.plates.plate_general`: when it is used, its size (grown to the cut-off,
capped), its symmetry classes, the modes of an impact with the contact patch and the
residual compliance, the static compliances, and the mode table of ``impactmaps modes``
(docs/plates_any_edges.rst).
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from . import basis_cache, near_field, ritz
from ..._checks import require_in_range
from .plate_general import (
    MAX_FUNCTIONS,
    MIN_FUNCTIONS,
    RESOLUTION_FACTOR,
    RESOLUTION_MARGIN,
    GeneralPlateSolution,
    deflection_functions,
    disc_quadrature,
    field_exponents,
    general_static_compliance,
    selection,
    solve_general_plate,
)

__all__ = ["uses_general_basis", "class_groups", "max_functions", "resolved_frequency", "basis_size", "functions", "solution",
           "grown_solution", "resolved_count", "mode_count_bound", "all_modes", "patch_weights", "patch_static_compliance", "classical_compliance",
           "general_plate_modes", "symmetry_lines", "check_couplings", "laminate_couplings", "mode_table", "MAX_UNKNOWNS", "STATIC_EXTRA_FUNCTIONS"]


def uses_general_basis(plate) -> bool:
    """True when the plate needs this module: Mindlin with edges other than SSSS, or any
    plate with bending–twisting (D16, D26) or A45 coupling (Navier is exact only for
    specially orthotropic SSSS; Kirchhoff specially orthotropic plates on other edges use
    :mod:`impactmaps.targets.plates.ritz`)."""
    coupled = plate.D16 != 0.0 or plate.D26 != 0.0 or plate.A45 != 0.0
    return coupled or (plate.theory == "mindlin" and plate.edges != "SSSS")


def _inputs(plate, edges=None, coupled=True):
    """Hashable arguments of :func:`solve_general_plate` describing ``plate``."""
    d16, d26 = (plate.D16, plate.D26) if coupled else (0.0, 0.0)
    a45 = plate.A45 if coupled else 0.0
    D = ((plate.D11, plate.D12, d16), (plate.D12, plate.D22, d26), (d16, d26, plate.D66))
    k = plate.shear_correction
    shear = ((k * plate.A55, k * a45), (k * a45, k * plate.A44))
    return (plate.length_x, plate.length_y, plate.theory, edges or plate.edges, D, shear,
            plate.mass_per_area, plate.rotary_inertia_per_area)


#: Functions per direction added to the modal basis for the static patch compliance.
STATIC_EXTRA_FUNCTIONS = 8
#: Largest eigenproblem per field set, in unknowns (Mindlin 3 × 34²; dense, seconds).
MAX_UNKNOWNS = 3 * MAX_FUNCTIONS**2


def symmetry_lines(plate) -> tuple[bool, bool]:
    """(about x = a/2, about y = b/2): whether the plate is symmetric about each centre line
    (the same edge on the two sides it separates) and struck on it."""
    on_x, on_y = _on_centre_lines(plate)
    return on_x and plate.edges[0] == plate.edges[2], on_y and plate.edges[1] == plate.edges[3]


def _on_centre_lines(plate) -> tuple[bool, bool]:
    """(on x = a/2, on y = b/2): whether the impact point lies on each centre line."""
    x0, y0 = plate.impact_point
    return (abs(x0 - 0.5 * plate.length_x) <= 1e-12 * plate.length_x,
            abs(y0 - 0.5 * plate.length_y) <= 1e-12 * plate.length_y)


def _twin_classes(plate):
    """The symmetry classes a load at the impact point excites on the plate's simply supported
    twin without couplings (:func:`class_groups` of that twin, first group): its static
    compliance needs no other (a centred load is orthogonal to them)."""
    return _groups(*_on_centre_lines(plate), coupled=False)[0]


def is_symmetric(plate) -> bool:
    """True when the plate is symmetric about both centre lines (same edge on opposite
    sides) and struck at the centre: its modes split into symmetry classes."""
    return all(symmetry_lines(plate))


def class_groups(plate) -> list:
    """The symmetry classes that do not couple, as groups (all modes = their union); the
    first holds the modes the impact excites. Both centre lines: four classes; D16, D26 and
    A45 couple (p, q) with (1 − p, 1 − q) (the plate keeps its symmetry under a half turn
    only). One centre line (e.g. CFFF or SCSF struck on it), without those couplings: the two
    parities about it, every function across it."""
    coupled = plate.D16 != 0.0 or plate.D26 != 0.0 or plate.A45 != 0.0
    return _groups(*symmetry_lines(plate), coupled)


def _groups(about_x: bool, about_y: bool, coupled: bool) -> list:
    """:func:`class_groups` of a plate symmetric about the centre lines it is said to be, with or
    without the couplings of a half turn."""
    if about_x and about_y:
        if coupled:
            return [((0, 0), (1, 1)), ((0, 1), (1, 0))]
        return [((0, 0),), ((0, 1),), ((1, 0),), ((1, 1),)]
    if coupled or not (about_x or about_y):
        return [None]
    if about_y:  # even and odd in y, any function in x
        return [((0, 0), (1, 0)), ((0, 1), (1, 1))]
    return [((0, 0), (0, 1)), ((1, 0), (1, 1))]


def max_functions(theory: str, classes=None) -> int:
    """Largest basis per direction: Mindlin — the eigenproblem of the kept classes holds at
    most :data:`MAX_UNKNOWNS` unknowns; Kirchhoff — :data:`impactmaps.targets.plates.ritz.MAX_FUNCTIONS`."""
    if theory == "kirchhoff":  # as the Kirchhoff Ritz plates (and the static basis of λ)
        return ritz.MAX_FUNCTIONS
    fields, cap = 3, MAX_UNKNOWNS
    fraction = 1.0 if classes is None else len(classes) / 4.0
    return 2 * int(math.sqrt(cap / (fields * fraction)) / 2)


@functools.lru_cache(maxsize=256)
def resolved_frequency(plate, n_x: int, n_y: int) -> float:
    """Highest frequency [rad/s] an ``n_x × n_y`` basis resolves: the simply supported
    frequency (same theory, couplings left out) of the mode with
    ``(n − RESOLUTION_MARGIN)/RESOLUTION_FACTOR`` half-waves in the poorer direction
    (cached: every run's basis size probes it)."""
    return min(_direction_frequencies(plate, n_x, n_y))


def _direction_frequencies(plate, n_x: int, n_y: int) -> tuple:
    """(along x, along y) [rad/s]: what ``n_x`` functions resolve along x, ``n_y`` along y."""
    if plate.theory == "kirchhoff":
        return ritz._direction_frequencies(n_x, n_y, plate.length_x, plate.length_y, plate.D11, plate.D22,
                                           plate.D12, plate.D66, plate.mass_per_area)
    from .plate_navier import mindlin_flexural

    m_x = max((n_x - RESOLUTION_MARGIN) / RESOLUTION_FACTOR, 1.0)
    m_y = max((n_y - RESOLUTION_MARGIN) / RESOLUTION_FACTOR, 1.0)
    omega, _ = mindlin_flexural(plate, np.array([m_x, 1.0]), np.array([1.0, m_y]))
    return float(omega[0]), float(omega[1])


@functools.lru_cache(maxsize=256)
def functions(plate, n: int) -> tuple[int, int]:
    """(n_x, n_y): the basis of size ``n``: ``n`` functions per field along the direction it
    resolves worse, along the other the fewest (``n − 2k``, at least the smallest basis) that
    resolve at least as high. Its resolved frequency is that of the ``n × n`` basis; a
    rectangular plate needs fewer functions across its short side (docs/plates_any_edges.rst,
    "The eigen-solution of a large basis")."""
    n = int(n)
    along_x, along_y = _direction_frequencies(plate, n, n)
    poorer = min(along_x, along_y)
    smallest = MIN_FUNCTIONS if plate.theory == "mindlin" else ritz.MIN_FUNCTIONS
    other = n
    while other - 2 >= smallest:
        candidate = (n, other - 2) if along_x <= along_y else (other - 2, n)
        if min(_direction_frequencies(plate, *candidate)) < poorer:
            break
        other -= 2
    return (n, other) if along_x <= along_y else (other, n)


def basis_size(plate, max_frequency: float, classes=None) -> tuple[int, bool]:
    """(n, enough): the size (:func:`functions`) of the smallest basis resolving ``max_frequency``
    [rad/s], clipped to :func:`max_functions`; ``enough`` is False when even the largest does not."""
    cap = max_functions(plate.theory, classes)
    n = MIN_FUNCTIONS if plate.theory == "mindlin" else ritz.MIN_FUNCTIONS
    while n < cap and resolved_frequency(plate, n, n) < max_frequency:
        n += 2
    n = min(n, cap)
    return n, resolved_frequency(plate, n, n) >= max_frequency


def solution(plate, n: int, classes=None) -> GeneralPlateSolution:
    """The cached general solution of ``plate`` of size ``n`` (:func:`functions`; the kept classes)."""
    n_x, n_y = functions(plate, n)
    return solve_general_plate(*_inputs(plate), n_x, n_y, resolved_frequency(plate, n_x, n_y), classes)


def grown_solution(plate, max_frequency: float, min_modes: int, classes="impact") -> GeneralPlateSolution:
    """Smallest basis resolving ``max_frequency`` [rad/s] and at least ``min_modes`` modes
    (or the largest basis), in the classes a centre impact excites by default; never
    smaller than a pinned plate's ``basis_functions`` (:mod:`.shared_basis`)."""
    if classes == "impact":
        classes = class_groups(plate)[0]
    n, _ = basis_size(plate, max_frequency, classes)
    cap = max_functions(plate.theory, classes)
    n = max(n, min(getattr(plate, "basis_functions", 0), cap))  # a pinned basis (shared_basis.PinnedBasisPlate)
    while True:
        result = solution(plate, n, classes)
        if result.frequencies.size >= min_modes or n >= cap:
            return result
        n = min(n + 4, cap)


def resolved_count(plate, max_frequency: float) -> int:
    """Number of modes with ω ≤ ``max_frequency`` [rad/s] in the largest basis of the classes
    a centre impact excites (at most the modes it resolves): one eigen-solution, kept on
    disk, for every count (:func:`impactmaps.solvers.mode_budget.frequency_cap` probes many)."""
    classes = class_groups(plate)[0]
    result = solution(plate, max_functions(plate.theory, classes), classes)
    top = min(float(max_frequency), result.resolved_frequency)
    return int(np.searchsorted(result.frequencies, top, side="right"))


def mode_count_bound(plate) -> float:
    """An upper bound [-] of every :meth:`Plate.mode_count <impactmaps.targets.plates.plate.Plate.mode_count>`,
    known without an eigen-solution: ``inf`` for SSSS (Navier: no bound); for a Ritz plate the
    unknowns of its largest basis, which no count exceeds — the general basis: of the classes
    :func:`resolved_count` counts in (Mindlin at most :data:`MAX_UNKNOWNS`); the Kirchhoff Ritz
    basis: ``ritz.MAX_FUNCTIONS²``."""
    if plate.uses_navier:
        return math.inf
    if not uses_general_basis(plate):
        return float(ritz.MAX_FUNCTIONS**2)
    classes = class_groups(plate)[0]
    n_x, n_y = functions(plate, max_functions(plate.theory, classes))
    return float(sum(kept.size for kept in selection(plate.theory, n_x, n_y, classes)))


def all_modes(plate, count: int) -> tuple:
    """(ω [rad/s] of the lowest ``count`` resolved modes of every class, sorted; the
    solutions used): one basis size for all classes, grown until ``count`` modes are
    resolved or the largest basis is reached (then fewer may be returned)."""
    groups = class_groups(plate)
    cap = min(max_functions(plate.theory, classes) for classes in groups)
    n = MIN_FUNCTIONS if plate.theory == "mindlin" else ritz.MIN_FUNCTIONS
    while True:
        results = [solution(plate, n, classes) for classes in groups]
        omega = np.sort(np.concatenate([r.frequencies[r.frequencies <= r.resolved_frequency] for r in results]))
        if omega.size >= count or n >= cap:
            return omega[:count], results
        n = min(n + 4, cap)


def patch_weights(result: GeneralPlateSolution, point, contact_radius: float, count: int) -> np.ndarray:
    """Participation [kg^-1/2] of the first ``count`` modes under a Hertz pressure disc of
    ``contact_radius`` [m] centred at ``point`` (the pressure-weighted mean of each mode
    shape; the point value when the radius is 0)."""
    if contact_radius <= 0.0:
        return result.mode_shapes(np.array([point]), count)[0]
    _, weights = disc_quadrature(float(contact_radius))
    basis = _disc_basis(result, point, float(contact_radius))
    return weights @ (basis @ result.coefficients[:basis.shape[1], :int(count)])


def _patch_load(result: GeneralPlateSolution, point, contact_radius: float) -> np.ndarray:
    if contact_radius <= 0.0:
        return result.deflection_basis(np.array([point]))[0]
    _, weights = disc_quadrature(float(contact_radius))
    return weights @ _disc_basis(result, point, float(contact_radius))


def _disc_basis(result: GeneralPlateSolution, point, contact_radius: float) -> np.ndarray:
    """The w basis functions of ``result`` at the quadrature nodes of the patch (:func:`disc_quadrature`)
    centred at ``point`` [m] (its :meth:`~.plate_general.GeneralPlateSolution.deflection_basis`,
    the same bits): kept for the last few patches, as a run's modal weights and both static loads
    of its patch (:func:`patch_static_compliance`) evaluate the same functions."""
    w_exponents = field_exponents(result.theory, result.edges)[0]
    return _disc_basis_of(result.length_x, result.length_y, result.theory, w_exponents, result.n_x, result.n_y,
                          result.classes, tuple(float(x) for x in point), contact_radius)


@functools.lru_cache(maxsize=4)
def _disc_basis_of(length_x, length_y, theory, w_exponents, n_x, n_y, classes, point, contact_radius):
    offsets, _ = disc_quadrature(contact_radius)
    basis = deflection_functions(length_x, length_y, theory, w_exponents, n_x, n_y, classes,
                                 np.asarray(point)[None, :] + offsets)
    basis.setflags(write=False)
    return basis


@functools.lru_cache(maxsize=32)
def patch_static_compliance(plate, n: int, contact_radius: float, classes=None) -> float:
    """Static compliance [m/N] of ``plate`` under the Hertz patch (Mindlin: shear included),
    ``C_basis(edges) + [C_Navier(SSSS) − C_basis(SSSS)]`` with the couplings left out of the
    bracket: the part the polynomial basis misses is local to the load and does not depend
    on the edges (as :meth:`Plate.static_compliance`). Solved in a basis
    :data:`STATIC_EXTRA_FUNCTIONS` larger than the modal one ``n`` (it contains it, so the
    residual is never negative); the factors are cached per plate. Measured (clamped
    quasi-isotropic laminate of the worked example, patch radius 0.5 and 2 mm): n = 12
    is within 3e-4 of n = 48, n = 24 within 3e-5."""
    n_static = -(-(int(n) + STATIC_EXTRA_FUNCTIONS) // 8) * 8  # a multiple of 8: few factors per plate
    n_x, n_y = functions(plate, min(n_static, max(int(n), max_functions(plate.theory, classes))))
    from ..patch import hertz_transform, mean_square_transform
    from .plate_static import navier_patch_residual

    def load_for(edges, kept):
        stand_in = GeneralPlateSolution(plate.length_x, plate.length_y, plate.theory, edges, n_x, n_y,
                                        np.zeros(0), np.zeros((0, 0)), 0.0, kept)
        return _patch_load(stand_in, plate.impact_point, contact_radius)

    full = general_static_compliance(*_inputs(plate)[:6], n_x, n_y, load_for(plate.edges, classes), classes)
    ssss, twin = _inputs(plate, "SSSS", coupled=False), _twin_classes(plate)
    basis_ssss = general_static_compliance(*ssss[:6], n_x, n_y, load_for("SSSS", twin), twin)
    stiffnesses = (plate.D11, plate.D22, plate.D12, plate.D66)
    if plate.theory == "mindlin":
        stiffnesses += (plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)
    exact = navier_patch_residual(plate.length_x, plate.length_y, stiffnesses, plate.impact_point,
                                  contact_radius, hertz_transform, mean_square=mean_square_transform)
    return full + max(exact - basis_ssss, 0.0)


@functools.lru_cache(maxsize=32)
def classical_compliance(plate) -> float:
    """Classical (Kirchhoff) point compliance [m/N] of a plate with D16/D26, any edges:
    ``C_Ritz(edges, full D) + [C_Navier(SSSS) − C_Ritz(SSSS)]`` (D16, D26 left out of the
    bracket), in the largest Kirchhoff basis of the impact classes (it contains every modal
    basis, so the residual compliance is never negative). Kept on disk with the plate bases
    (:mod:`.basis_cache`, the same bits): a cached lookup of the plate asks for it (its patch
    number) and need not factor the two stiffness matrices again."""
    classes = class_groups(plate)[0]
    n = max_functions("kirchhoff", classes)
    inputs = {"length_x": plate.length_x, "length_y": plate.length_y, "edges": plate.edges, "D": _inputs(plate)[4],
              "impact_point": tuple(plate.impact_point), "n": n, "classes": classes}
    stored = basis_cache.cached_arrays("classical-compliance", inputs,
                                       lambda: {"compliance": np.array(_classical_compliance(plate, n, classes))})
    return float(stored["compliance"])


def _classical_compliance(plate, n: int, classes) -> float:
    """:func:`classical_compliance` computed in the ``n × n`` Kirchhoff basis of ``classes``."""
    from .plate_static import navier_static_compliance

    a, b = plate.length_x, plate.length_y
    unit = ((1.0, 0.0), (0.0, 1.0))

    def load_for(edges, kept):
        stand_in = GeneralPlateSolution(a, b, "kirchhoff", edges, n, n, np.zeros(0), np.zeros((0, 0)),
                                        0.0, kept)
        return stand_in.deflection_basis(np.array([plate.impact_point]))[0]

    full = general_static_compliance(a, b, "kirchhoff", plate.edges, _inputs(plate)[4], unit, n, n,
                                     load_for(plate.edges, classes), classes)
    orth = (plate.D11, plate.D22, plate.D12, plate.D66)
    navier = navier_static_compliance(a, b, *orth, plate.impact_point)
    twin = _twin_classes(plate)
    basis_ssss = general_static_compliance(a, b, "kirchhoff", "SSSS", _inputs(plate, "SSSS", coupled=False)[4],
                                           unit, n, n, load_for("SSSS", twin), twin)
    return full + (navier - basis_ssss)


def general_plate_modes(plate, max_frequency: float, min_modes: int, contact_radius: float = 0.0):
    """(:class:`~impactmaps.targets.base.ModalBasis`, mode-shape function, solution) of a plate
    in the general basis: the modes with ω ≤ ``max_frequency`` [rad/s] the basis resolves
    (at least ``min_modes``); residual compliance as documented in :meth:`Plate.modes`.
    """
    from ..base import ModalBasis

    result = grown_solution(plate, max_frequency, min_modes)
    limit = min(max_frequency, result.resolved_frequency)
    count = int(np.sum(result.frequencies <= limit))
    count = max(count, min(min_modes, result.frequencies.size))
    omega = np.asarray(result.frequencies[:count])
    participation = patch_weights(result, plate.impact_point, contact_radius, count)
    damping = np.full(omega.shape, float(plate.damping_ratio))
    if contact_radius > 0.0:
        static = patch_static_compliance(plate, result.n, float(contact_radius), result.classes)
        residual = max(static - float(np.sum(participation**2 / omega**2)), 0.0)
        if plate.theory == "mindlin" and near_field.isotropic_constants(plate) is not None:
            # the 3D-consistent near field (near_field): each retained mode weighted by ρ(k) at
            # its flexural wavenumber, the residual by the SSSS pairs beyond the last one
            participation = participation * np.sqrt(near_field.near_field_factor(
                plate, near_field.flexural_wavenumber(plate, omega)))
            residual = max(residual + near_field.residual_change(
                plate, float(contact_radius), float(near_field.flexural_wavenumber(plate, omega[-1]))), 0.0)
        basis = ModalBasis(omega, participation, residual, damping)
    elif plate.theory == "kirchhoff":
        basis = ModalBasis.from_modes(omega, participation, plate.static_compliance(), damping)
    else:
        # point load on a Mindlin plate: the static deflection is infinite; the residual is the
        # classical compliance not carried by the retained modes (≥ 0), as for Navier
        residual = max(plate.static_compliance() - float(np.sum(participation**2 / omega**2)), 0.0)
        basis = ModalBasis(omega, participation, residual, damping)

    if max_frequency > result.resolved_frequency:
        warnings.warn(
            f"max_frequency = {max_frequency:.6g} rad/s exceeds what the largest Ritz basis "
            f"({result.n_x}×{result.n_y} functions per field) resolves, "
            f"{result.resolved_frequency:.6g} rad/s: modes above that are represented by "
            "the residual compliance only", stacklevel=5)
    if plate.theory == "mindlin" and contact_radius == 0.0:
        from .plate_navier import warn_beyond_thickness_shear

        warn_beyond_thickness_shear(plate, max_frequency, stacklevel=6)

    def shape_function(points):
        return result.mode_shapes(points, count)

    return basis, shape_function, result


def check_couplings(plate) -> None:
    """Raise ``ValueError`` unless D16, D26, A45 are finite, the 3×3 bending stiffness is
    positive definite and ``|A45| < sqrt(A44 A55)``."""
    for name in ("D16", "D26", "A45"):
        value = getattr(plate, name)
        if not (isinstance(value, (int, float, np.floating, np.integer)) and math.isfinite(value)):
            raise ValueError(f"{name} = {value!r} is invalid: must be a finite number")
    if np.linalg.eigvalsh(plate.bending_stiffness_matrix)[0] <= 0.0:
        raise ValueError(
            f"D16 = {plate.D16!r}, D26 = {plate.D26!r} are invalid: the bending stiffness "
            "[[D11, D12, D16], [D12, D22, D26], [D16, D26, D66]] must be positive definite")
    if plate.A45**2 >= plate.A44 * plate.A55:
        raise ValueError(f"A45 = {plate.A45!r} is invalid: valid range is |A45| < sqrt(A44 A55) "
                         f"= {math.sqrt(plate.A44 * plate.A55):.6g} [N/m]")


def laminate_couplings(laminate) -> tuple:
    """(D16 [N·m], D26 [N·m], A45 [N/m]) of a laminate for :meth:`Plate.from_laminate`: each
    0.0 where its coupling ratio is round-off (≤ ``SPECIALLY_ORTHOTROPIC_RTOL``).

    Raises
    ------
    ValueError
        For an unsymmetric laminate (B ≠ 0): the plate has no membrane displacements.
    """
    from ...materials._common import SPECIALLY_ORTHOTROPIC_RTOL

    ratios = laminate.coupling_ratios() if hasattr(laminate, "coupling_ratios") else {}
    if ratios.get("B", 0.0) > SPECIALLY_ORTHOTROPIC_RTOL:
        raise ValueError(
            f"laminate is not supported: it is unsymmetric (extension–bending coupling "
            f"max|B_ij|/sqrt(max|A_ij| max|D_ij|) = {ratios['B']:.3g}); the plate model has no "
            "membrane displacements to carry the coupling; valid: a symmetric layup "
            "(e.g. symmetric = true)")

    def coupling(name, value):
        return float(value) if ratios.get(name, 0.0) > SPECIALLY_ORTHOTROPIC_RTOL else 0.0

    D = getattr(laminate, "D", None)
    if D is None:
        return 0.0, 0.0, 0.0
    return coupling("D16", D[0, 2]), coupling("D26", D[1, 2]), coupling("A45", getattr(laminate, "A45", 0.0))


def mode_table(plate, count: int) -> dict:
    """:meth:`impactmaps.targets.plates.plate.Plate.mode_table` of ``plate``."""
    from .plate_navier import lowest_modes

    require_in_range("count", count, 1, 100000)
    if int(count) != count:
        raise ValueError(f"count = {count!r} is invalid: must be an integer >= 1")
    count = int(count)
    two_pi = 2.0 * math.pi
    if plate.uses_navier:
        m, n, omega = lowest_modes(plate, count)
        return {"frequencies_hz": omega / two_pi, "labels": [f"({i}, {j})" for i, j in zip(m, n)],
                "method": f"Navier ({plate.theory})", "basis": "exact (m, n) half-waves",
                "resolved_frequency_hz": math.inf, "resolved": True}
    if uses_general_basis(plate):
        frequencies, results = all_modes(plate, count)
        n_x, n_y = results[0].n_x, results[0].n_y  # one size for every class
        top = min(r.resolved_frequency for r in results)
        method = f"Ritz, general basis ({plate.theory}, w{', ψx, ψy' if plate.theory == 'mindlin' else ''})"
    else:
        args = (plate.length_x, plate.length_y, plate.D11, plate.D22, plate.D12, plate.D66, plate.mass_per_area)
        n_x = n_y = ritz.MIN_FUNCTIONS
        while True:
            ritz_solution = ritz.solve_ritz_plate(*args, plate.edges, n_x, n_y)
            top = ritz_solution.resolved_frequency
            if np.sum(ritz_solution.frequencies <= top) >= count or n_x >= ritz.MAX_FUNCTIONS:
                break
            n_x = n_y = min(n_x + 4, ritz.MAX_FUNCTIONS)
        frequencies = ritz_solution.frequencies
        method = "Ritz (kirchhoff)"
    omega = np.asarray(frequencies[:count], dtype=float)
    return {"frequencies_hz": omega / two_pi, "labels": [str(i + 1) for i in range(omega.size)],
            "method": method, "basis": f"{n_x}×{n_y} functions per field",
            "resolved_frequency_hz": top / two_pi,
            "resolved": bool(omega.size == count and omega[-1] <= top)}
