"""Physics questions are asked of the objects that own them (issue 27, Build 2).

Read from the source with :mod:`ast` (docstrings and comments are not code, so they do
not count):

* no ``isinstance(…, <a ContactLaw subclass>)`` outside ``impactmaps/contact/``: a law
  answers for itself (``linear_stiffness``, ``hertzian_stiffness``, ``yield_scales``,
  ``changed_options``, its registry ``name``); ``isinstance(x, ContactLaw)`` (is it a law
  at all?) is fine;
* no comparison (``==``, ``!=``, ``in``, ``not in``) with a string equal to a registered
  theory name, and no theory name picked by a conditional expression (``"euler" if … else
  "kirchhoff"``), outside ``impactmaps/targets/``: the targets' registry answers
  (:mod:`impactmaps.targets.options`: ``default_theory``, ``classical_theory``,
  ``depends_on_slenderness``, ``is_shear_deformable``, ``point_load_diverges``).

* no comparison with, and no conditional choice of, a map law's name (``"linear"``,
  ``"hertz"``, ``"yc"``, ``"stronge"``, ``"epp"``, ``"plastic"``) outside ``contact/`` and the
  map-family modules (:data:`MAP_FAMILY_MODULES`): the family answers
  (:class:`~impactmaps.maps.family.map_family.MapFamily`: ``file_stem``, ``exact_command``,
  ``scaled_by_contact_frequency``, ``closed_form_asymptotes``, ``labels``, ``chart_zeta_max`` …),
  so a new family is one module and one registration.

:data:`ALLOWED` lists the edges where a name is the point (none today) and
:data:`MAP_LAW_ALLOWED` those of the map-law names, each with its reason; an entry names the
module and the function.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import impactmaps
from impactmaps.contact.base import ContactLaw
from impactmaps.targets.options import BEAM_THEORIES, PLATE_THEORIES

PACKAGE_ROOT = Path(impactmaps.__file__).resolve().parent
#: Registered theory names.
THEORIES = frozenset(BEAM_THEORIES + PLATE_THEORIES)
#: (module path relative to the package, enclosing function) where a finding is allowed.
ALLOWED: frozenset[tuple[str, str]] = frozenset()
_COMPARISONS = (ast.Eq, ast.NotEq, ast.In, ast.NotIn)
#: Map-law names (and the word the elastic-plastic ones share).
MAP_LAWS = frozenset({"linear", "hertz", "yc", "stronge", "epp", "plastic"})
#: The modules that define the map families (the names are theirs to compare).
MAP_FAMILY_MODULES = ("maps/family/map_family.py", "maps/family/builtin_families.py", "maps/compute/linear_points.py",
                      "maps/compute/hertz_points.py", "maps/compute/plastic_points.py")
#: (module, function) → why a map-law name is compared there.
MAP_LAW_ALLOWED = {
    ("cases/case.py", "parse_case"): "the finite-difference solver's default contact law, named once",
    ("cases/run.py", "case_summary"): "the vocabulary of the case's numbers (cases/numbers.py), not a map law",
    ("targets/patch.py", "patch_transform"): "'hertz' names a pressure distribution, not a law",
    ("targets/patch.py", "mean_square_transform"): "'hertz' names a pressure distribution, not a law",
}


def _law_classes() -> frozenset[str]:
    """Names of every ContactLaw subclass (the built-in laws loaded), not the base itself."""
    import impactmaps.contact  # noqa: F401 (registers the built-in laws)

    found, stack = set(), list(ContactLaw.__subclasses__())
    while stack:
        cls = stack.pop()
        found.add(cls.__name__)
        stack.extend(cls.__subclasses__())
    return frozenset(found)


def _names(node) -> list[str]:
    """The class names an ``isinstance`` second argument mentions (a name, an attribute, a tuple)."""
    if isinstance(node, ast.Name):
        return [node.id]
    if isinstance(node, ast.Attribute):
        return [node.attr]
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [name for element in node.elts for name in _names(element)]
    return []


def _strings(node) -> list[str]:
    """The string constants of a comparison operand (itself, or the elements of a literal collection)."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [s for element in node.elts for s in _strings(element)]
    return []


def _findings(path: Path, law_classes: frozenset[str]) -> list[tuple[str, int, str, str]]:
    """(kind, line, enclosing function, text) of every isinstance on a law class and every
    comparison with a theory name in one module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []

    def visit(node, function: str):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            function = node.name
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "isinstance"
                and len(node.args) == 2):
            laws = [name for name in _names(node.args[1]) if name in law_classes]
            if laws:
                found.append(("isinstance", node.lineno, function, ast.unparse(node)))
        for kind, names in (("theory", THEORIES), ("map law", MAP_LAWS)):
            if isinstance(node, ast.Compare) and any(isinstance(op, _COMPARISONS) for op in node.ops):
                if any(s in names for operand in (node.left, *node.comparators) for s in _strings(operand)):
                    found.append((kind, node.lineno, function, ast.unparse(node)))
            if isinstance(node, ast.IfExp) and any(s in names for s in _strings(node.body) + _strings(node.orelse)):
                found.append((kind, node.lineno, function, ast.unparse(node)))  # a default chosen by name
        for child in ast.iter_child_nodes(node):
            visit(child, function)

    visit(tree, "<module>")
    return found


def _violations(kind: str, *owners: str, allowed=ALLOWED) -> list[str]:
    law_classes = _law_classes()
    out = []
    for path in sorted(PACKAGE_ROOT.rglob("*.py")):
        relative = path.relative_to(PACKAGE_ROOT).as_posix()
        if any(relative.startswith(owner + "/") or relative == owner for owner in owners):
            continue
        for found_kind, line, function, text in _findings(path, law_classes):
            if found_kind == kind and (relative, function) not in allowed:
                out.append(f"{relative}:{line} ({function}): {text}")
    return out


def test_no_isinstance_on_contact_law_classes_outside_contact():
    violations = _violations("isinstance", "contact")
    assert not violations, "ask the law (a property of ContactLaw), not its class:\n" + "\n".join(violations)


def test_no_theory_name_compared_outside_targets():
    violations = _violations("theory", "targets")
    assert not violations, ("ask impactmaps.targets.options (default_theory, is_shear_deformable, …), not the "
                            "theory's name:\n" + "\n".join(violations))


def test_no_map_law_name_compared_outside_the_families():
    violations = _violations("map law", "contact", *MAP_FAMILY_MODULES, allowed=MAP_LAW_ALLOWED)
    assert not violations, ("ask the map family (impactmaps.maps.family.map_family.MapFamily: file_stem, exact_command, "
                            "labels, …), not the law's name:\n" + "\n".join(violations))


def test_the_walk_sees_both_kinds(tmp_path):
    """The detector itself: each kind is caught; a docstring and a keyword argument are not."""
    source = tmp_path / "sample.py"
    source.write_text('"""theory == "mindlin" in a docstring."""\n'
                      "def f(law, theory):\n"
                      "    make(theory=\"euler\")\n"
                      "    default = \"euler\" if theory is None else theory\n"
                      "    if isinstance(law, (int, HertzContact)):\n"
                      "        return theory in (\"timoshenko\", \"mindlin\")\n"
                      "    return law == \"hertz\"\n", encoding="utf-8")
    found = _findings(source, frozenset({"HertzContact"}))
    assert [(kind, line, function) for kind, line, function, _ in found] == [
        ("theory", 4, "f"), ("isinstance", 5, "f"), ("theory", 6, "f"), ("map law", 7, "f")]


def test_the_targets_registry_answers_the_theory_questions():
    """What the maps used to decide by name, asked of :mod:`impactmaps.targets.options`."""
    from impactmaps.targets import options

    assert (options.default_theory("beam"), options.default_theory("plate")) == ("euler", "kirchhoff")
    assert [options.classical_theory(t) for t in ("timoshenko", "mindlin", "euler", "rayleigh")] == [
        "euler", "kirchhoff", "euler", "rayleigh"]
    assert [t for t in sorted(THEORIES) if options.depends_on_slenderness(t)] == ["mindlin", "rayleigh", "timoshenko"]
    assert [t for t in sorted(THEORIES) if options.is_shear_deformable(t)] == ["mindlin", "timoshenko"]
    assert [t for t in sorted(THEORIES) if options.point_load_diverges(t)] == ["mindlin"]


def test_the_laws_answer_the_map_questions():
    """The numbers a map places a law's impacts by, asked of the law."""
    from impactmaps.contact import HertzContact, LinearContact, StrongeContact, YigitChristoforouContact
    from impactmaps.contact.plastic.epp import EppContact

    assert HertzContact(2e9).hertzian_stiffness == 2e9
    assert LinearContact(1e6).hertzian_stiffness is None and LinearContact(1e6).yield_scales is None
    yc = YigitChristoforouContact(2e9, 1e-6)
    assert YigitChristoforouContact.from_yield_scales(*yc.yield_scales) == yc
    for cls in (StrongeContact, EppContact):
        law = cls(1e11, 0.01, 3e8)
        assert law.changed_options() == {}
        rebuilt = cls.from_yield_scales(*(float(v) for v in law.yield_scales))
        assert [float(v) for v in rebuilt.yield_scales] == pytest.approx([float(v) for v in law.yield_scales], rel=1e-12)
    assert EppContact(1e11, 0.01, 3e8, poisson_ratio=0.4).changed_options() == {"poisson_ratio": 0.4}


def test_load_shipped_map_names_a_plastic_map_by_its_family():
    """One namer of shipped files: a plastic law's map of a structure its family does not ship
    is refused naming the structures it does (not a missing file that never existed)."""
    from impactmaps.maps.files.shipped import load_shipped_map

    with pytest.raises(ValueError, match=r"\(kind, theory\) = \('plate', 'mindlin'\) is not known"):
        load_shipped_map("plate", "mindlin", "yc")


def test_one_word_for_beam_or_plate_and_the_old_spellings_still_work(capsys):
    """``kind`` is beam or plate everywhere (docs/architecture.rst, "Words"); ``LookupResult.structure``,
    ``Target.structure`` and ``--structure`` are its old spellings: the same answer, with a
    FutureWarning in Python. The old keyword ``structure=`` is gone (a ``TypeError``)."""
    import json

    import impactmaps as im
    from impactmaps.cli import main
    from impactmaps.maps.family.regimes import classify

    new = im.lookup(1.198, 0.425, kind="plate", theory="kirchhoff")
    assert new.kind == "plate"
    with pytest.warns(FutureWarning, match="LookupResult.structure is now LookupResult.kind"):
        assert new.structure == "plate"
    with pytest.raises(TypeError, match="structure"):
        im.lookup(1.198, 0.425, structure="plate", theory="kirchhoff")
    with pytest.raises(TypeError, match="structure"):
        classify(0.5, 1.0, 1.0, structure="beam")
    plate = im.Plate.isotropic(0.3, 0.3, 0.004, im.IsotropicMaterial(210e9, 0.3, 7800.0))
    with pytest.warns(FutureWarning, match="Plate.structure is now .kind"):
        assert plate.structure == plate.kind == "plate"
    answers = []
    for option in ("--kind", "--structure"):
        assert main(["lookup", option, "plate", "--theory", "kirchhoff", "--zeta", "1", "--lambda", "1", "--json"]) == 0
        answers.append(json.loads(capsys.readouterr().out))
    assert answers[0] == answers[1]
    from impactmaps.cli import build_parser  # the old option is accepted, not shown

    help_text = build_parser()._subparsers._group_actions[0].choices["lookup"].format_help()
    assert "--kind" in help_text and "--structure" not in help_text


def test_family_alone_means_a_map_family():
    """"Family" alone is a map family (docs/architecture.rst, "Words"); the maps of a shear-deformable
    theory at span/thickness 10, 20, 50 are its slenderness members, in the code and in the manual."""
    import re

    stale = re.compile(r"\bfamily members?\b|\bslenderness[- ]famil|\bFAMILY_(SLENDERNESSES|STRUCTURES)\b",
                       re.IGNORECASE)
    docs = PACKAGE_ROOT.parent / "docs"
    files = [*PACKAGE_ROOT.rglob("*.py"), *docs.glob("*.rst"), *docs.glob("*.md")]
    found = [f"{path.name}:{number}: {line.strip()}" for path in files
             for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if stale.search(line)]
    assert not found, "say 'slenderness member(s)' (MEMBER_SLENDERNESSES, MEMBER_STRUCTURES):\n" + "\n".join(found)
