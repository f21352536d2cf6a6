"""Slenderness families of the shear-deformable maps: lookups at any slenderness ≥ 10, interpolated in 1/s."""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pytest

from impactmaps.maps.read.slenderness import slenderness_members, slenderness_error_grid
from impactmaps import lookup
from impactmaps.maps.family.builtin_families import MEMBER_SLENDERNESSES
from impactmaps.maps.family.structures import structure_from_name
from impactmaps.maps.compute.linear_points import solve_points
from impactmaps.solvers.modal_settings import ModalSettings

from ..helpers import case_text

FAMILIES = [("beam", "timoshenko", "linear"), ("beam", "timoshenko", "hertz"), ("plate", "mindlin", "linear")]


def test_members_run_from_the_thin_limit_to_the_thickest():
    members = slenderness_members("plate", "mindlin")
    assert [s for _, s in members] == [None, 50.0, 20.0, 10.0]
    assert [x for x, _ in members] == sorted(x for x, _ in members)
    with pytest.raises(ValueError, match="no slenderness members"):
        slenderness_members("plate", "mindlin", "hertz")  # a Mindlin Hertz impact loads the contact patch


@pytest.mark.parametrize("structure, theory, law", FAMILIES)
def test_a_member_slenderness_reads_that_member_exactly(structure, theory, law):
    """At s = 10, 20, 50 the interpolation weight is 0 or 1: the member's value and band."""
    for slenderness in MEMBER_SLENDERNESSES:
        found = lookup(1.0, 1.0, kind=structure, theory=theory, slenderness=slenderness, law=law)
        member = lookup(1.0, 1.0, kind=structure, theory=theory, law=law, slenderness=slenderness)
        assert found.fmax_normalised == member.fmax_normalised
        assert found.fmax_error == pytest.approx(member.fmax_error, rel=1e-12)


@pytest.mark.parametrize("structure, theory, law", FAMILIES)
def test_leave_one_out_error_is_finite_where_the_members_have_values(structure, theory, law):
    _, _, errors = slenderness_error_grid(structure, theory, law)
    s20 = np.isfinite(lookup(1.0, 1.0, kind=structure, theory=theory, law=law).fmax_normalised)
    assert s20 and np.isfinite(errors).sum() >= 1500  # where every member has a value
    assert np.nanmax(errors) < 0.2


@pytest.mark.parametrize("structure, theory", [("beam", "timoshenko"), ("plate", "mindlin")])
def test_lookup_at_other_slendernesses_holds_a_direct_solve_within_its_band(structure, theory):
    """Random (ζ, λ) at slenderness 15, 35 and 75: the interpolated F̄max within its band
    (the larger member band plus the leave-one-out slenderness error) of the value the
    sweep solver gives on the structure of that slenderness."""
    rng = np.random.default_rng(5)
    base = structure_from_name(f"{structure}-{'ss' if structure == 'beam' else 'ssss'}-{theory}-s20")
    checked = 0
    for slenderness in (15.0, 35.0, 75.0):
        for zeta, lam in zip(np.exp(rng.uniform(np.log(0.05), np.log(50.0), 3)),
                             np.exp(rng.uniform(np.log(0.05), np.log(20.0), 3))):
            (direct,) = solve_points(replace(base, slenderness=slenderness), [(zeta, lam)], ModalSettings())
            try:
                found = lookup(zeta, lam, kind=structure, theory=theory, slenderness=slenderness)
            except ValueError as error:
                assert "holds no value" in str(error) or "unresolved" in str(error)
                continue
            assert abs(found.fmax_normalised - direct["fmax_normalised"]) <= found.fmax_error + direct["fmax_error"]
            checked += 1
    assert checked >= 6


def test_thicker_than_the_thickest_member_is_refused():
    with pytest.raises(ValueError, match="slenderness"):
        lookup(1.0, 1.0, kind="beam", theory="timoshenko", slenderness=8.0)


def test_lookup_case_at_slenderness_30_matches_simulate():
    """A steel Timoshenko beam of span/height 30, linear contact: `lookup --case` answers
    from the family (it used to refuse every slenderness but 20), within its band of
    `simulate`."""
    from impactmaps.cases import parse_case, run_case
    from impactmaps import lookup

    text = case_text("""
        type = "beam"
        length = 0.6
        width = 0.02
        height = 0.02
        material = "structural-steel"
        theory = "timoshenko"
        supports = "ss"
    """, radius=0.01, law="linear", after="stiffness = 2e7\n",
                     name="steel ball on a 0.6 m, 20 x 20 mm Timoshenko beam, linear contact")
    case = parse_case(text)
    answer = lookup(case=case)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the model-validity notice (steel yields under so stiff a contact)
        result, _ = run_case(case)
    assert "1/s" in answer["map"]
    assert abs(answer["peak_force_N"] - result.peak_force) <= answer["peak_force_error_N"] + 1e-3 * result.peak_force
