"""The package's size limits, so they stay (issue 27): no module over 500 lines, no
function over 120 lines (numba kernels included) or over 12 parameters.

Measured by walking the syntax tree of every module of the imported package: a function's
lines run from its ``def`` to its last line (docstring included, decorators not); its
parameters count positional, keyword-only, ``*args`` and ``**kwargs`` alike. The issue
allows more than 12 parameters to a numba kernel that takes named tuples; none needs it
(the modal kernel takes 8, its stages at most 12), so the limit holds for every function.
"""

from __future__ import annotations

import ast
from pathlib import Path

import impactmaps

PACKAGE = Path(impactmaps.__file__).resolve().parent
MAX_MODULE_LINES = 500
MAX_FUNCTION_LINES = 120
MAX_PARAMETERS = 12


def _modules():
    return sorted(PACKAGE.rglob("*.py"))


def _functions(path: Path):
    """(qualified name, lines, parameters) of every function and method in ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []

    def visit(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                arguments = child.args
                count = (len(arguments.posonlyargs) + len(arguments.args) + len(arguments.kwonlyargs)
                         + (arguments.vararg is not None) + (arguments.kwarg is not None))
                name = f"{prefix}{child.name}"
                found.append((name, child.end_lineno - child.lineno + 1, count))
                visit(child, f"{name}.")
            elif isinstance(child, ast.ClassDef):
                visit(child, f"{prefix}{child.name}.")
            else:
                visit(child, prefix)

    visit(tree, "")
    return found


def _where(path: Path, name: str) -> str:
    return f"{path.relative_to(PACKAGE.parent)}::{name}"


def test_the_walk_sees_the_package_and_its_largest_functions():
    """The walk reads the whole package, nested functions and methods included (a guard
    against a test that passes because it measured nothing)."""
    modules = _modules()
    assert len(modules) > 100
    names = {name for path in modules for name, _lines, _count in _functions(path)}
    assert {"simulate_fd", "_integrate_impact", "_impact_loop", "contact_phase", "LazyKernel.__call__"} <= names
    lines = {name: length for path in modules for name, length, _count in _functions(path)}
    assert lines["_impact_loop"] > 60  # a real body is measured, not a stub (the modal kernel's loop)


def test_no_module_is_longer_than_500_lines():
    long = {str(path.relative_to(PACKAGE.parent)): n for path in _modules()
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_MODULE_LINES}
    assert not long, long


def test_no_function_is_longer_than_120_lines():
    long = {_where(path, name): lines for path in _modules() for name, lines, _count in _functions(path)
            if lines > MAX_FUNCTION_LINES}
    assert not long, long


def test_no_function_takes_more_than_12_parameters():
    wide = {_where(path, name): count for path in _modules() for name, _lines, count in _functions(path)
            if count > MAX_PARAMETERS}
    assert not wide, wide


#: The most modules a folder of the package holds (``__init__.py`` not counted): a folder is one job.
MAX_FOLDER_MODULES = 10


def test_no_folder_holds_more_than_10_modules():
    folders = {}
    for path in _modules():
        if path.name != "__init__.py":
            folders.setdefault(path.parent, []).append(path.name)
    largest = max(folders.items(), key=lambda item: len(item[1]))
    print(f"\nlargest folder: {largest[0].relative_to(PACKAGE.parent)} ({len(largest[1])} modules)")
    crowded = {str(folder.relative_to(PACKAGE.parent)): len(names) for folder, names in folders.items()
               if len(names) > MAX_FOLDER_MODULES}
    assert not crowded, crowded
