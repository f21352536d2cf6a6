"""Hostile case files a new user wrote (issue 40): each is answered, refused with one line, or
announced — never a hang, never a quiet slip."""

from __future__ import annotations

import json
import warnings

import pytest

from impactmaps.cli import main
from impactmaps.cli.commands_tools import CASE_TEMPLATES


def _template(kind: str, **replace) -> str:
    """The body of ``impactmaps init KIND`` with ``key = value`` lines replaced (first match)."""
    text = f'name = "{kind}"\n' + CASE_TEMPLATES[kind][2]
    lines = text.splitlines()
    for key, value in replace.items():
        for i, line in enumerate(lines):
            if line.split("=")[0].strip() == key:
                lines[i] = f"{key} = {value}"
                break
        else:
            raise KeyError(key)
    return "\n".join(lines) + "\n"


def _write(tmp_path, kind: str, **replace):
    path = tmp_path / f"{kind}.toml"
    path.write_text(_template(kind, **replace), encoding="utf-8")
    return path


# -- item 2: a plate a few micrometres thick --------------------------------------------------
def test_check_integrates_nothing_on_a_micrometre_plate(tmp_path, monkeypatch, capsys):
    """``check`` on a plate 4 µm thick hung (> 150 s) inside the infinite-plate asymptote's
    ``solve_ivp`` reached from its cost estimate: check never integrates now (solve_ivp is made
    to fail if called) and its estimate says the asymptote answers."""
    import scipy.integrate

    from impactmaps.law_asymptotes import local

    def no_integration(*_args, **_kw):
        raise AssertionError("check integrated")

    monkeypatch.setattr(local, "solve_ivp", no_integration)
    monkeypatch.setattr(scipy.integrate, "solve_ivp", no_integration)
    path = _write(tmp_path, "plate", thickness="4e-6")
    status = main(["check", str(path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert status == 0, out
    assert out["estimated_method"] == "infinite-structure-asymptote"


@pytest.mark.parametrize("thickness", [3e-6, 6e-6])
def test_the_infinite_plate_asymptote_of_a_micrometre_plate_is_answered_at_once(thickness):
    """The dashpot of a plate a few micrometres thick is far softer than the Hertz contact: the
    equations are stiff (relaxation ~10⁶ times faster than the contact scale), so DOP853 needed
    billions of steps. Radau answers; the peak force is then the dashpot's, F = Z V0 to within
    the indentation rate at the peak (α̇ = 0 there: F = Z v with v ≈ V0), and the impactor has
    not left the plate within the scaled time limit (the contact lasts ~m/Z)."""
    from impactmaps.contact import law_for_sphere
    from impactmaps.contact import Sphere
    from impactmaps.law_asymptotes.local import infinite_plate_impact, plate_impedance
    from impactmaps.materials import material
    from impactmaps.targets.plate import Plate

    steel = material("structural-steel")
    plate = Plate.isotropic(0.25, 0.25, thickness, steel)
    sphere = Sphere(0.00635, steel)
    law = law_for_sphere("hertz", sphere, steel)
    result = infinite_plate_impact(plate, law, sphere.mass, 2.0)
    assert result.peak_force == pytest.approx(plate_impedance(plate) * 2.0, rel=1e-3)
    assert result.time_limit_reached


def test_an_asymptote_over_its_budget_is_refused(monkeypatch):
    """Every integration has a budget: past MAX_EVALUATIONS the asymptote is a ValueError naming
    the reason, not a run without end."""
    from impactmaps.contact import HertzContact
    from impactmaps.law_asymptotes import local

    monkeypatch.setattr(local, "MAX_EVALUATIONS", 50)
    with pytest.raises(ValueError, match="more than 50 evaluations"):
        local.quasi_static_impact(1e6, HertzContact(1e10), 0.01, 1.0)
