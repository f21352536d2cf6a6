"""The documentation site builds without warnings, and documents every key of the
case-file and sweep formats (the keys the code accepts, read from the code)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import fields

import pytest

from .helpers import ROOT


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    # the installed package, as the other tests (docs/conf.py; not run from the checkout, which
    # `python -m` would put first on sys.path): its compiled kernels are shipped with it
    run = subprocess.run([sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-q", "-b", "html",
                          "-d", str(out / "doctrees"), str(ROOT / "docs"), str(out / "html")],
                         cwd=out, capture_output=True, text=True, timeout=600,
                         env={**os.environ, "IMPACTMAPS_DOCS_INSTALLED": "1"})
    assert run.returncode == 0, run.stderr
    return out / "html"


def _text(site, page):
    return re.sub(r"<[^>]+>", " ", (site / page).read_text(encoding="utf-8"))


def test_site_builds_without_warnings(site):
    for page in ("index.html", "cases.html", "sweeps.html", "cli.html", "api/solvers.html",
                 "gallery/steel_plate_hertz.html"):
        assert (site / page).exists(), page
    assert list((site / "_images").glob("steel_beam_fd_stronge*.png")), "the gallery runs the examples"


def test_every_case_key_is_documented(site):
    from impactmaps.cases import case as case_module
    from impactmaps.materials import _tables as _materials
    from impactmaps.fd import FDSettings
    from impactmaps.contact.plastic.stronge import StrongeContact  # noqa: F401 (its options are listed)

    text = _text(site, "cases.html")
    keys = set(case_module._TOP_KEYS) | set(case_module._IMPACTOR_KEYS) | set(case_module._SOLVER_EXTRA)
    keys |= set(case_module.target_keys("beam")) | set(case_module.target_keys("plate"))
    keys |= set(_materials._ISOTROPIC_KEYS) | set(_materials._PLY_KEYS) | set(_materials._LAYUP_KEYS)
    keys |= {f.name for f in fields(FDSettings)} - {"duration"}
    keys |= {"target_radius", "stiffness", "yield_pressure_factor", "plastic_pressure_factor",
             "plastic_indentation_ratio"}
    keys |= {f.name for f in fields(case_module.OutputSettings)}
    missing = sorted(key for key in keys if key not in text)
    assert not missing, f"case keys not documented: {missing}"


def test_every_sweep_key_is_documented(site):
    from impactmaps.maps.compute import config
    from impactmaps.maps.family.structures import MapStructure
    from impactmaps.solvers.modal_settings import ModalSettings

    text = _text(site, "sweeps.html")
    keys = set(config._TOP_KEYS) | set(config._LAMINATE_KEYS) | {"zeta", "lambda", "min", "max", "count"}
    keys |= {f.name for f in fields(MapStructure)} | {f.name for f in fields(ModalSettings)}
    missing = sorted(key for key in keys if key not in text)
    assert not missing, f"sweep keys not documented: {missing}"


def test_citation_file_names_the_software_and_its_papers():
    """CITATION.cff (Citation File Format 1.2.0) parses, has the keys the format requires,
    the package's version and licence, and cites the two papers the physics rests on."""
    import tomllib

    yaml = pytest.importorskip("yaml")
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert citation["cff-version"] == "1.2.0"
    assert citation["message"] and citation["title"] and citation["authors"]
    assert citation["version"] == project["version"] and citation["license"] == project["license"]["text"]
    titles = [reference["title"] for reference in citation["references"]]
    assert "Effect of flexibility on low velocity impact response" in titles
    assert all(reference.get("authors") for reference in citation["references"])


def test_docs_cite_papers_not_seed_files():
    """No page of the manual or the README points at a seeds folder or names a paper by its
    seed number (the repository does not have them): they cite the papers."""
    pages = [*(ROOT / "docs").rglob("*.rst"), *(ROOT / "docs").rglob("*.md"), ROOT / "README.md"]
    for page in pages:
        text = page.read_text(encoding="utf-8")
        assert "seeds/" not in text, page
        assert not re.search(r"seed[ -]00[01]", text), page
