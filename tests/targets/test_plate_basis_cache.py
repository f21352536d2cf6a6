"""Plate bases kept on disk and shared by the runs on a plate (issue 39 items 2 and 7).

The disk cache (:mod:`impactmaps.targets.plates.basis_cache`) gives the bits a cold
computation gives; a truncated, corrupted or foreign file is ignored and rebuilt. A plate
pinned to one basis (:mod:`impactmaps.targets.plates.shared_basis`) gives each cut-off the
same bits whatever was computed before, and its answers converge towards those of the
largest basis. The Hertz tangent stiffness read without the compiled kernel has its bits.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from impactmaps.contact.base import ContactLaw
from impactmaps.contact.hertz import HertzContact
from impactmaps.materials import material
from impactmaps.targets.plates import basis_cache, plate_any_edges, plate_general
from impactmaps.targets.plates.plate import Plate
from impactmaps.targets.plates.shared_basis import PinnedBasisPlate, shared_basis

ALUMINIUM = material("aluminium-6061-t6")


def _plate(**kwargs):
    return Plate.isotropic(0.15, 0.1, 0.006, ALUMINIUM, theory="mindlin", edges=kwargs.pop("edges", "CCCS"),
                           **kwargs)


def _solve(plate, n=12):
    """The general eigen-solution, past the in-process cache (the disk only)."""
    top = plate_any_edges.resolved_frequency(plate, n, n)
    return plate_general.solve_general_plate.__wrapped__(*plate_any_edges._inputs(plate), n, n, top, None)


def _inputs_of(plate, n=12):
    top = plate_any_edges.resolved_frequency(plate, n, n)
    names = ("length_x", "length_y", "theory", "edges", "D", "shear", "mass_per_area", "rotary_inertia")
    return dict(zip(names, plate_any_edges._inputs(plate))) | {"n_x": n, "n_y": n, "resolved_frequency": top,
                                                                "classes": None}


def test_disk_cache_gives_the_cold_bits(tmp_path, monkeypatch):
    """A basis read back from disk is the computed one bit for bit; a second plate (another
    thickness) gets its own file."""
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    plate = _plate()
    cold = _solve(plate)
    path = basis_cache.basis_path("general-modes", _inputs_of(plate))
    assert path.is_file() and path.parent == tmp_path / basis_cache.SUBDIRECTORY
    stored = _solve(plate)
    assert np.array_equal(stored.frequencies, cold.frequencies)
    assert np.array_equal(stored.coefficients, cold.coefficients)
    assert not stored.coefficients.flags.writeable
    other = _plate(impact_point=None, shear_correction=0.8)
    assert basis_cache.basis_path("general-modes", _inputs_of(other)) != path


@pytest.mark.parametrize("damage", ["truncate", "garbage", "foreign"])
def test_damaged_or_foreign_file_is_rebuilt(tmp_path, monkeypatch, damage):
    """A partial or corrupted file, or one holding another plate's arrays under this name,
    is ignored: the answer is the cold one and the file is rewritten whole."""
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    plate = _plate()
    cold = _solve(plate)
    path = basis_cache.basis_path("general-modes", _inputs_of(plate))
    if damage == "truncate":
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    elif damage == "garbage":
        data = bytearray(path.read_bytes())
        data[-200:-100] = b"\x00" * 100
        path.write_bytes(bytes(data))
    else:
        other = _solve(_plate(edges="CCCC"))
        np.savez(path, __key__=np.array("another plate"), __digest__=np.array("0"),
                 frequencies=other.frequencies, coefficients=other.coefficients)
    again = _solve(plate)
    assert np.array_equal(again.frequencies, cold.frequencies)
    assert np.array_equal(again.coefficients, cold.coefficients)
    with np.load(path) as stored:  # rewritten whole
        assert np.array_equal(stored["coefficients"], cold.coefficients)


def test_unwritable_cache_changes_nothing(tmp_path, monkeypatch):
    """A cache directory that cannot be created (a file in its way) costs time, not answers."""
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(blocker))
    plate = _plate()
    first, second = _solve(plate), _solve(plate)
    assert np.array_equal(first.coefficients, second.coefficients)


def test_pinned_basis_is_pure_and_truncates_one_basis(tmp_path, monkeypatch):
    """A pinned plate answers a cut-off from its one basis (the same size for every cut-off
    below it) with the same bits whichever cut-off was asked first; its modes below a
    cut-off lie at or below those of the basis grown for that cut-off (Ritz: lower is
    better)."""
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    plate = _plate()
    top = plate_any_edges.resolved_frequency(plate, 14, 14)
    pinned = shared_basis(plate, top)
    assert isinstance(pinned, PinnedBasisPlate) and pinned.basis_functions == 14
    assert shared_basis(pinned, 10 * top) is pinned
    low, high = 0.1 * top, 0.9 * top
    assert plate_any_edges.basis_size(plate, low)[0] < 14  # grown alone, a smaller basis

    def answers(order):
        plate_general.solve_general_plate.cache_clear()
        from impactmaps.targets.plates.plate import _plate_modes

        _plate_modes.cache_clear()
        out = {cut: pinned.modes(cut, contact_radius=0.001) for cut in order}
        return out, plate_any_edges.grown_solution(pinned, low, 1).n

    first, n_low = answers((low, high))
    second, _ = answers((high, low))
    assert n_low == 14
    for cut in (low, high):
        assert np.array_equal(first[cut].frequencies, second[cut].frequencies)
        assert np.array_equal(first[cut].participation, second[cut].participation)
        assert first[cut].residual_compliance == second[cut].residual_compliance
    grown = plate.modes(low, contact_radius=0.001)
    assert grown.size == first[low].size
    assert np.all(first[low].frequencies <= grown.frequencies * (1 + 1e-12))
    assert first[low].frequencies == pytest.approx(grown.frequencies, rel=1e-3)


def test_shared_basis_leaves_other_targets_alone():
    """Navier and Kirchhoff Ritz plates have no cut-off-dependent basis: not pinned."""
    navier = Plate.isotropic(0.2, 0.2, 0.004, ALUMINIUM, theory="mindlin")
    ritz_plate = Plate.isotropic(0.2, 0.2, 0.004, ALUMINIUM, edges="CCCC")
    assert shared_basis(navier, 1e5) is navier and shared_basis(ritz_plate, 1e5) is ritz_plate


def test_general_mode_count_counts_in_the_largest_basis():
    """mode_count of a general-basis plate: the modes of its largest basis below the
    frequency, non-decreasing in it and never beyond what that basis resolves."""
    base = Plate.isotropic(0.3, 0.2, 0.003, ALUMINIUM, edges="CCCC")
    plate = Plate.isotropic(0.3, 0.2, 0.003, ALUMINIUM, edges="CCCC", D16=0.1 * base.D11)
    assert plate_any_edges.uses_general_basis(plate)
    classes = plate_any_edges.class_groups(plate)[0]
    largest = plate_any_edges.solution(plate, plate_any_edges.max_functions("kirchhoff", classes), classes)
    probes = largest.frequencies[[0, 3, 10]] * (1 + 1e-9)
    counts = [plate.mode_count(f) for f in probes]
    assert counts == [1, 4, 11]
    assert plate.mode_count(1e12) == int(np.sum(largest.frequencies <= largest.resolved_frequency))


def test_hertz_tangent_stiffness_has_the_kernel_bits():
    """HertzContact.tangent_stiffness in NumPy equals the compiled kernel's bit for bit
    (scalars, arrays, batches, α ≤ 0)."""
    rng = np.random.default_rng(7)
    for stiffness in 10 ** rng.uniform(6, 12, 5):
        law = HertzContact(float(stiffness))
        alpha = np.concatenate([[0.0, -1e-6, 1e-300], 10 ** rng.uniform(-9, -2, 40)])
        assert np.array_equal(law.tangent_stiffness(alpha, alpha), ContactLaw.tangent_stiffness(law, alpha, alpha))
        assert np.array_equal(law.tangent_stiffness(alpha[5]), ContactLaw.tangent_stiffness(law, alpha[5]))
    batch = HertzContact(np.array([1e9, 3e10]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.array_equal(batch.tangent_stiffness(2e-5), ContactLaw.tangent_stiffness(batch, 2e-5))


def test_simulate_from_cold_and_disk_cache_same_bits(tmp_path, monkeypatch):
    """A whole run on a clamped Mindlin plate: the same bits with the basis computed, then
    read from disk by a process that has none in memory (the in-process caches cleared)."""
    from impactmaps.solvers.modal import simulate
    from impactmaps.targets.plates.plate import _plate_modes

    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    plate = Plate.isotropic(0.15, 0.1, 0.01, ALUMINIUM, theory="mindlin", edges="CCCC")
    law = HertzContact.from_sphere(0.01, material("structural-steel"), ALUMINIUM)

    def run():
        plate_general.solve_general_plate.cache_clear()
        _plate_modes.cache_clear()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return simulate(plate, law, 2.0, 1.0, record=False)

    cold = run()
    assert list((tmp_path / basis_cache.SUBDIRECTORY).glob("general-modes-*.npz"))
    again = run()
    assert again.peak_force == cold.peak_force and again.peak_time == cold.peak_time


def test_patch_weights_and_loads_have_the_bits_of_the_direct_evaluation():
    """The patch quadrature's w functions kept for a run (plate_any_edges._disc_basis) give the
    bits of evaluating them directly: the modal weights (mode shapes at the nodes) and the static
    load of a clamped plate and of its simply supported twin (the same w functions on Mindlin)."""
    plate = _plate(edges="CCCC")
    result = plate_any_edges.solution(plate, 12)
    point, radius = plate.impact_point, 7.5e-4
    offsets, weights = plate_general.disc_quadrature(radius)
    nodes = np.asarray(point)[None, :] + offsets
    direct = weights @ result.mode_shapes(nodes, 5)
    assert np.array_equal(plate_any_edges.patch_weights(result, point, radius, 5), direct)
    twin = plate_general.GeneralPlateSolution(result.length_x, result.length_y, "mindlin", "SSSS", 12, 12,
                                              np.zeros(0), np.zeros((0, 0)), 0.0, None)
    for solution in (result, twin):
        assert np.array_equal(plate_any_edges._patch_load(solution, point, radius),
                              weights @ solution.deflection_basis(nodes))


def test_the_static_factor_uses_the_eigenproblems_stiffness_bits():
    """The stiffness matrix kept for a basis (plate_general._last_stiffness) is stiffness_matrix's,
    read-only: the eigenproblem and the static factor of one basis assemble it once."""
    plate = _plate(edges="CCCC")
    inputs = plate_any_edges._inputs(plate)
    kept = plate_general._last_stiffness(*inputs[:6], 10, 10, None)
    assert not kept.flags.writeable
    assert np.array_equal(kept, plate_general.stiffness_matrix(*inputs[:4], np.array(inputs[4]), np.array(inputs[5]),
                                                               10, 10))


def test_the_classical_compliance_of_a_coupled_plate_is_kept_on_disk(tmp_path, monkeypatch):
    """A coupled plate's classical compliance (a cached lookup asks for it) is stored with the
    plate bases and read back with the computed bits."""
    monkeypatch.setenv("IMPACTMAPS_CACHE_DIR", str(tmp_path))
    plate = Plate(length_x=0.12, length_y=0.08, thickness=0.002, D11=40.0, D22=25.0, D12=10.0, D66=12.0, D16=3.0,
                  D26=2.0, A44=2e7, A55=3e7, mass_per_area=3.2, rotary_inertia_per_area=1e-6, edges="CCCC")
    computed = plate_any_edges._classical_compliance(plate, plate_any_edges.max_functions("kirchhoff", (
        (0, 0), (1, 1))), ((0, 0), (1, 1)))
    assert plate_any_edges.classical_compliance.__wrapped__(plate) == computed
    assert list((tmp_path / basis_cache.SUBDIRECTORY).glob("classical-compliance-*.npz"))
    assert plate_any_edges.classical_compliance.__wrapped__(plate) == computed
