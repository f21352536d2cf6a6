"""Sphinx configuration of the impactmaps documentation.

Build: ``python -m sphinx -W -b html docs docs/_build/html`` (needs the ``docs`` extra).
"""

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
# the checkout's package, unless IMPACTMAPS_DOCS_INSTALLED=1 asks for the installed one: the test
# suite's build (tests/test_docs.py) documents and runs the package it tests, the installed one,
# whose wheel ships numba's compiled kernels (a fresh checkout has none: its gallery would compile
# them, ~30 s of CPU)
if os.environ.get("IMPACTMAPS_DOCS_INSTALLED") != "1":
    sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE / "_ext"))

import impactmaps  # noqa: E402

project = "impactmaps"
author = "impactmaps developers"
copyright = "impactmaps developers, MIT licence"
release = version = impactmaps.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "impactmaps_docs",
]
exclude_patterns = ["_build", "_generated", "physics_contract.md", "case-files.md"]
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
autodoc_default_options = {"members": True, "undoc-members": False}
html_theme = "alabaster"
html_title = f"impactmaps {release}"
suppress_warnings = ["autodoc.import_object"]
nitpicky = False
