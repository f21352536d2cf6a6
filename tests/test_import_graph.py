"""The package's import graph has no circles, its imports point down the documented layers,
and it says which private names cross modules.

The graph is read from the source with :mod:`ast` (nothing is imported): an edge
``a → b`` for every ``import``/``from … import`` of an impactmaps module in ``a``,
whether at module level, under ``if TYPE_CHECKING:`` or inside a function (an import
moved into a function to dodge a circle still ties the two modules together).
``from package import name`` points at the submodule ``package.name`` when there is one,
else at the package. A circle is a strongly connected component of more than one module;
the test prints each one with the edges that close it.

The layer order is read from ``docs/architecture.rst`` (the block after the line
``.. layer order: read by tests/test_import_graph.py``): a module belongs to the longest
documented unit (a package, a subpackage such as ``maps.read`` or a top-level module) that
names it, and an import between two units may only point to a unit of the same or a lower
layer. The scripts outside the package (validation, benchmarks, examples, tests) import
their neighbours by file name; those imports have no circle either.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path


import impactmaps

PACKAGE_ROOT = Path(impactmaps.__file__).resolve().parent
REPOSITORY = Path(__file__).resolve().parents[1]
ARCHITECTURE = REPOSITORY / "docs" / "architecture.rst"
LAYER_MARKER = ".. layer order: read by tests/test_import_graph.py"

def _modules() -> dict[str, tuple[Path, bool]]:
    """Dotted module name → (file, is a package ``__init__``)."""
    found = {}
    for path in PACKAGE_ROOT.rglob("*.py"):
        parts = list(path.relative_to(PACKAGE_ROOT.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        found[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return found


MODULES = _modules()


def _known(name: str) -> str | None:
    """``name``, or the nearest enclosing module the package has."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def _imports(module: str) -> list[tuple[str, str, int, list[str]]]:
    """(target module, the module as written, line, imported names) of every import in ``module``."""
    path, is_package = MODULES[module]
    base = module if is_package else module.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "impactmaps":
                    found.append((_known(alias.name), alias.name, node.lineno, []))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = base
                for _ in range(node.level - 1):
                    anchor = anchor.rpartition(".")[0]
                written = anchor + (f".{node.module}" if node.module else "")
            else:
                written = node.module or ""
            if written.split(".")[0] != "impactmaps":
                continue
            names = [alias.name for alias in node.names]
            for name in names:
                target = f"{written}.{name}"
                found.append((target if target in MODULES else _known(written), written, node.lineno, [name]))
    return found


def import_graph() -> dict[str, dict[str, int]]:
    """module → {imported module: line of the first such import}, self-imports left out."""
    graph = {}
    for module in MODULES:
        edges = graph.setdefault(module, {})
        for target, _, line, _ in _imports(module):
            if target and target != module:
                edges.setdefault(target, line)
    return graph


def import_cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), sorted."""
    index, low, stack, on_stack, components = {}, {}, [], set(), []

    def visit(start):
        # iterative Tarjan: (node, iterator over its successors)
        work = [(start, iter(sorted(graph.get(start, {}))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            advanced = False
            for successor in successors:
                if successor not in index:
                    index[successor] = low[successor] = len(index)
                    stack.append(successor)
                    on_stack.add(successor)
                    work.append((successor, iter(sorted(graph.get(successor, {})))))
                    advanced = True
                    break
                if successor in on_stack:
                    low[node] = min(low[node], index[successor])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(sorted(component))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    return sorted(components)


def _describe(cycle: list[str], graph) -> str:
    members = set(cycle)
    edges = [f"    {a} → {b} (line {line})" for a in cycle for b, line in sorted(graph[a].items())
             if b in members]
    return "  " + " ⇄ ".join(cycle) + "\n" + "\n".join(edges)


def test_the_graph_sees_every_kind_of_import():
    """The walker itself: relative, absolute, function-level and package-vs-submodule imports."""
    graph = import_graph()
    assert "impactmaps.solvers.modal" in graph["impactmaps.closed_forms.halfspace"] or \
        "impactmaps.contact.contact_scale" in graph["impactmaps.closed_forms.halfspace"]
    assert "impactmaps._checks" in graph["impactmaps.contact.pair"]  # from .._checks import …
    assert "impactmaps.contact.pair" in graph["impactmaps.contact.sphere"]
    # a toy graph with a circle a → b → c → a and a tail d → a
    toy = {"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}, "d": {"a": 1}}
    assert import_cycles(toy) == [["a", "b", "c"]]
    assert import_cycles({"a": {"b": 1}, "b": {}}) == []


def test_no_import_cycles():
    """No circle of imports anywhere in the package."""
    graph = import_graph()
    cycles = import_cycles(graph)
    report = "\n".join(_describe(c, graph) for c in cycles)
    assert not cycles, f"{len(cycles)} import circle(s):\n{report}"


def private_imports() -> list[str]:
    """``importer:line: from module import _name`` for every private name taken from another module.

    Dunder names and imports of a private *module* (``from . import _checks``,
    ``from ._checks import x``) are not counted: only a leading-underscore name
    defined in another module.
    """
    found = []
    for module in sorted(MODULES):
        for target, written, line, names in _imports(module):
            for name in names:
                if name.startswith("_") and not name.startswith("__") and f"{written}.{name}" not in MODULES \
                        and written != module:
                    found.append(f"{module}:{line}: from {written} import {name}")
    return found


#: The most imports of other modules' private names allowed; lower it as they go.
MAX_PRIVATE_IMPORTS = 19


def test_private_names_crossing_modules_are_counted():
    """Reports (and caps) the imports of another module's private names.

    A private name used across modules is part of an undeclared interface; the list
    is printed (``pytest -rP tests/test_import_graph.py``) so it can be worked down, and the cap keeps it from growing.
    """
    found = private_imports()
    print(f"\n{len(found)} imports of other modules' private names:\n  " + "\n  ".join(found))
    assert len(found) <= MAX_PRIVATE_IMPORTS, "\n".join(found)


def documented_layers(text: str | None = None) -> list[tuple[str, list[str]]]:
    """``(layer name, [units])`` bottom up, from the layer block of ``docs/architecture.rst``:
    one layer a line, ``number  name  unit, unit, …`` (columns two or more spaces apart);
    a unit is a dotted path below ``impactmaps`` (``__init__``: the package's own module)."""
    lines = (ARCHITECTURE.read_text(encoding="utf-8") if text is None else text).splitlines()
    start = lines.index(LAYER_MARKER)
    layers, seen_block = [], False
    for line in lines[start + 1:]:
        if line.strip() == "::" or not line.strip():
            seen_block = seen_block or line.strip() == "::"
            if layers and not line.strip():
                break
            continue
        if not line.startswith(" "):
            break
        number, name, units = re.split(r"\s{2,}", line.strip(), maxsplit=2)
        assert int(number) == len(layers) + 1, line
        layers.append((name, [unit.strip() for unit in units.split(",")]))
    assert seen_block and layers, f"no layer block after {LAYER_MARKER!r} in {ARCHITECTURE}"
    return layers


def unit_of(module: str, units) -> str | None:
    """The longest documented unit holding ``module`` (None if none does)."""
    if module == "impactmaps":
        return "__init__" if "__init__" in units else None
    parts = module.split(".")[1:]
    for size in range(len(parts), 0, -1):
        if ".".join(parts[:size]) in units:
            return ".".join(parts[:size])
    return None


def _layer_index() -> dict[str, int]:
    return {unit: number for number, (_, units) in enumerate(documented_layers()) for unit in units}


def unit_graph(graph, layer) -> dict[str, dict[str, str]]:
    """unit → {imported unit: one module-level edge that makes the arrow}."""
    units = {}
    for module, edges in graph.items():
        source = unit_of(module, layer)
        for target, line in edges.items():
            destination = unit_of(target, layer)
            if source != destination:
                units.setdefault(source, {}).setdefault(destination, f"{module} → {target} (line {line})")
    return units


def test_the_layer_block_is_read():
    """The parser of the documented order, and the unit a module falls in."""
    text = f"x\n\n{LAYER_MARKER}\n\n::\n\n    1  support  __init__, _checks\n    2  maps: read  maps.read, maps\n\nafter"
    layers = documented_layers(text)
    assert layers == [("support", ["__init__", "_checks"]), ("maps: read", ["maps.read", "maps"])]
    assert unit_of("impactmaps.maps.read.lookup", {"maps", "maps.read"}) == "maps.read"
    assert unit_of("impactmaps.maps", {"maps", "maps.read"}) == "maps"
    assert unit_of("impactmaps", {"__init__"}) == "__init__"
    assert len(documented_layers()) >= 8


def test_every_module_has_a_documented_layer():
    """Each module of the package falls in a unit of the documented order, and each unit exists."""
    layer = _layer_index()
    homeless = [module for module in MODULES if unit_of(module, layer) is None]
    assert not homeless, f"modules in no layer of docs/architecture.rst: {homeless}"
    absent = [unit for unit in layer if unit != "__init__" and f"impactmaps.{unit}" not in MODULES]
    assert not absent, f"documented units the package does not have: {absent}"


def test_imports_point_down_the_layers():
    """0 arrows running back up: a unit imports only units of its own layer or lower ones
    (function-level and ``TYPE_CHECKING`` imports included)."""
    layer = _layer_index()
    upward = [f"{source} (layer {layer[source] + 1}) → {target} (layer {layer[target] + 1}): {edge}"
              for source, targets in unit_graph(import_graph(), layer).items()
              for target, edge in sorted(targets.items()) if layer[target] > layer[source]]
    assert not upward, f"{len(upward)} import(s) against the documented order:\n  " + "\n  ".join(upward)


def test_no_package_cycles():
    """0 cycles between units (the same layer included)."""
    layer = _layer_index()
    units = unit_graph(import_graph(), layer)
    cycles = import_cycles({source: dict.fromkeys(targets, 0) for source, targets in units.items()})
    report = "\n".join(" ⇄ ".join(cycle) + ":\n    " + "\n    ".join(
        units[a][b] for a in cycle for b in units.get(a, {}) if b in cycle) for cycle in cycles)
    assert not cycles, report


def test_the_map_readers_import_nothing_of_the_build_side():
    """The read wing of maps (one reader, the lookups) imports no module of the build wing."""
    graph = import_graph()
    crossing = [f"{module} → {target}" for module, edges in graph.items() if module.startswith("impactmaps.maps.read")
                for target in edges if target.startswith("impactmaps.maps.compute")]
    assert not crossing, crossing


def script_graph() -> dict[str, dict[str, int]]:
    """``folder/stem`` → {``folder/stem`` it imports: line} for the scripts outside the package,
    which import a neighbour by its file name (``from level5_beam_plastic import …``)."""
    graph = {}
    for folder in ("validation", "validation/fe", "benchmarks", "examples", "tests"):
        directory = REPOSITORY / folder
        stems = {path.stem for path in directory.glob("*.py")}
        for path in sorted(directory.glob("*.py")):
            edges = graph.setdefault(f"{folder}/{path.stem}", {})
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                names = ([alias.name for alias in node.names] if isinstance(node, ast.Import) else
                         [node.module] if isinstance(node, ast.ImportFrom) and not node.level and node.module else [])
                for name in names:
                    if name in stems and name != path.stem:
                        edges.setdefault(f"{folder}/{name}", node.lineno)
    return graph


def test_no_circles_between_scripts():
    """0 file circles outside the package either (validation/fe/level5_* included)."""
    graph = script_graph()
    assert "validation/fe/level5_beam_plastic" in graph["validation/fe/level5_wide_fd"]  # the walker sees them
    cycles = import_cycles(graph)
    assert not cycles, "\n".join(_describe(cycle, graph) for cycle in cycles)
