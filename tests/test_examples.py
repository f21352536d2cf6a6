"""Every example script runs and reproduces its one stored number (as scikit-fem's test_examples).

Each ``examples/*.py`` is run as a user would run it (``runpy.run_path`` with
``__name__ == "__main__"``) from an empty temporary working directory, and one number it
computes is compared with the value stored in :data:`EXPECTED`. A new example needs an
entry there; the test fails until it has one.

The stored values were produced by running each example on this branch (Python 3.11,
numpy/scipy/numba of the test environment). The two Mindlin plate examples moved when the
contact patch became the default on Mindlin plates (issue 14): README example
868.4626 → 852.8427 N (−1.80 %; the point load's value at the 40 ω cut-off, which fell
≈ 1 % per doubling of the cut-off, against the converged patch value),
``steel_plate_hertz`` 751.2676 → 731.2949 N (−2.66 %; point load at its 15 ω cut-off).
With the patch's own cut-off (``patch_cutoff_ratio`` = 20 ω, a third of the modes) they
moved again by +3.2e-5 and −5.5e-5: 852.8699 and 731.2544 N. With the near field made
consistent with 3D elasticity and the Hertz law (``impactmaps.targets.plates.near_field``; the
Mindlin shear flexibility under the patch that the 3D solid does not have, ≈ ln(h/a)/(2π kGh),
removed; verified against 3D FE on a/h = 20 SSSS and CCCC plates within 0.3 %) they rose by
+8.3 % and +6.5 %: 924.0358 and 778.5633 N (thin plates, a/h = 75 and 62.5, where that
spurious shear term is largest against the plate's own local compliance).
Tolerance: relative 1e-6 for all of them. Measured, a relative perturbation of 1e-12 of
an input (velocity or thickness) moves each stored number by at most 2e-12 relative (the
runs are deterministic; platform round-off is of that order), so 1e-6 leaves a margin
of about 10⁵; and it is a thousand times below the discretisation error of the solvers
(≈1e-3: time step, mode cut-off, FD grid), so any change of behaviour, even a small one,
is caught.
"""

from __future__ import annotations

import re
import runpy
import warnings

import pytest

from .helpers import EXAMPLES, ROOT


#: example file → (name of the stored quantity in the script's namespace, value, what it is)
EXPECTED = {
    "readme_example.py": ("result.peak_force", 924.0358044368705,
                          "peak Hertz force [N], 12.7 mm steel ball at 3 m/s on a 4 mm aluminium Mindlin plate"),
    "steel_plate_hertz.py": ("peak_force", 778.5632669889063,
                             "peak Hertz force [N] of examples/steel_plate_hertz.toml"),
    # 0.7197302235773436 until 2026-11-24: simulate's mode floor counted the plate's modes
    # before dropping the ones at rest at the centre and merging degenerate ones, and
    # integrated 3 where the map's points integrate 4 (the map stores its refined run,
    # 0.719766; its base run at 4 modes is this value to 1e-15)
    "dimensionless_point.py": ("fmax_normalised", 0.7197070715998473,
                               "F̄max at (ζ, λ) = (1, 1), SS square Kirchhoff plate (reference table 0.720 ± 0.002)"),
    # 0.8084382192460435 until the refined Stronge law was made energy-consistent (issue 28):
    # softer from δ_y to δ_p, it absorbs less (energy loss 0.488 → 0.338 J of 1.410 J, 6 → 5
    # contacts, same 13.85 kN peak)
    "fd_elastic_plastic_beam.py": ("restitution", 0.8721170916161359,
                                   "Newton restitution of examples/steel_beam_fd_stronge.toml (FD, Stronge)"),
}
RELATIVE_TOLERANCE = 1e-6

#: the README's snippet first, then the others in name order
SCRIPTS = ["readme_example.py"] + sorted(p.name for p in EXAMPLES.glob("*.py") if p.name != "readme_example.py")


def _value(namespace: dict, dotted: str):
    head, *attributes = dotted.split(".")
    value = namespace[head]
    for attribute in attributes:
        value = getattr(value, attribute)
    return value


def _repository_files() -> dict:
    """Every file of the repository outside .git and caches, with its modification time."""
    files = {}
    for path in ROOT.rglob("*"):
        parts = set(path.relative_to(ROOT).parts)
        if path.is_file() and not parts & {".git", "__pycache__", ".pytest_cache", ".hypothesis"}:
            files[path] = path.stat().st_mtime_ns
    return files


def test_every_example_has_a_stored_number():
    assert (EXAMPLES / "readme_example.py").is_file()
    missing = sorted(set(SCRIPTS) - set(EXPECTED))
    assert not missing, f"examples without a stored number in EXPECTED: {missing}"
    assert not set(EXPECTED) - set(SCRIPTS), "EXPECTED names an example that does not exist"


@pytest.mark.parametrize("script", SCRIPTS)
def test_example_reproduces_its_stored_number(script, tmp_path, monkeypatch, capsys):
    """The script runs without error, does not write into the repository, opens with a
    docstring (the physics it solves) and reproduces its stored number."""
    path = EXAMPLES / script
    assert script in EXPECTED, f"add a stored number for examples/{script} to EXPECTED"
    name, stored, _meaning = EXPECTED[script]
    before = _repository_files()
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        # the Mindlin examples run under the contact patch (default): no thickness-shear notice
        warnings.filterwarnings("error", message=".*thickness-shear.*")
        warnings.filterwarnings("error", message=".*half the plate thickness.*")
        namespace = runpy.run_path(str(path), run_name="__main__")
    assert capsys.readouterr().out.strip(), f"{script} prints nothing"
    assert namespace.get("__doc__"), f"{script} has no module docstring"
    assert _repository_files() == before, f"{script} wrote into the repository"
    assert float(_value(namespace, name)) == pytest.approx(stored, rel=RELATIVE_TOLERANCE)


def test_readme_python_section_is_the_readme_example():
    """The code block of README.md's "## Python" section is, line for line, the body of
    examples/readme_example.py (so the README's example is run and checked)."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    snippet = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    script = (EXAMPLES / "readme_example.py").read_text(encoding="utf-8")
    assert snippet.strip() in script
