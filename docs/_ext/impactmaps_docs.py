"""Sphinx directives of the impactmaps documentation.

``.. options-table:: DOTTED.PATH [MORE.PATHS]`` renders the keyword options of a
constructor or dataclass (the keys of a case or sweep table) with their defaults and
the descriptions of their numpydoc docstrings (units included), so the format pages
list every key the code accepts and cannot drift from it.

``.. case-example:: ../examples/NAME.toml`` runs a case file at build time and shows
the file, its force-history figure and its summary: the gallery.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import re
import warnings
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective


def _resolve(dotted: str):
    parts = dotted.split(".")
    for split in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        for name in parts[split:]:
            obj = getattr(obj, name)
        return obj
    raise ValueError(f"cannot import {dotted}")


def _parameters(obj) -> dict:
    """name → (type, description) from a numpydoc docstring (Parameters, else Attributes)."""
    from numpydoc.docscrape import ClassDoc, FunctionDoc

    doc = ClassDoc(obj) if isinstance(obj, type) else FunctionDoc(obj)
    out = {}
    for section in ("Parameters", "Attributes"):
        for parameter in doc[section]:
            text = " ".join(parameter.desc).strip()
            for name in parameter.name.split(","):
                name = name.strip()
                if name and text and not text.startswith("See ") and name not in out:
                    out[name] = (parameter.type, text)
    return out


def _defaults(obj) -> dict:
    """Keyword options with defaults: dataclass fields or signature parameters."""
    if dataclasses.is_dataclass(obj) and isinstance(obj, type):
        out = {}
        for f in dataclasses.fields(obj):
            if not f.init or f.name.startswith("_"):
                continue
            if f.default is not dataclasses.MISSING:
                out[f.name] = f.default
            elif f.default_factory is not dataclasses.MISSING:
                out[f.name] = f.default_factory()
        return out
    out = {}
    for name, parameter in inspect.signature(obj).parameters.items():
        if parameter.kind is inspect.Parameter.VAR_KEYWORD:
            owner = getattr(obj, "__self__", None)
            if owner is not None:
                out.update(_defaults(owner))
        elif parameter.default is not inspect.Parameter.empty:
            out[name] = parameter.default
    return out


def option_rows(paths, keys=None) -> list[tuple[str, str, str]]:
    """(key, default, description) of every keyword option of the first object, described
    by any of the objects' docstrings."""
    objects = [_resolve(p) for p in paths]
    described = {}
    for obj in objects + [getattr(o, "__self__", None) for o in objects]:
        if obj is not None:
            for name, value in _parameters(obj).items():
                described.setdefault(name, value)
    rows = []
    defaults = _defaults(objects[0])
    if keys is not None:
        defaults = {k: defaults[k] for k in keys}
    for name, default in defaults.items():
        kind, text = described.get(name, ("", ""))
        shown = "(computed)" if default is None else repr(default)
        rows.append((name, shown, text or kind))
    return rows


class OptionsTable(SphinxDirective):
    required_arguments = 1
    optional_arguments = 5
    option_spec = {"prefix": directives.unchanged, "keys": directives.unchanged}

    def run(self):
        prefix = self.options.get("prefix", "")
        lines = [".. list-table::", "   :header-rows: 1", "   :widths: 22 18 60", "",
                 "   * - key", "     - default", "     - meaning (unit)"]
        keys = self.options.get("keys")
        for name, default, text in option_rows(self.arguments, keys.split() if keys else None):
            lines += [f"   * - ``{prefix}{name}``", f"     - ``{default}``", f"     - {text}"]
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source=""), self.content_offset, container)
        return container.children


class CaseExample(SphinxDirective):
    required_arguments = 1

    def run(self):
        import matplotlib

        matplotlib.use("Agg")
        from impactmaps.cases import load_case, run_case
        from impactmaps.plotting import save_impact_history

        source = (Path(self.env.srcdir) / self.arguments[0]).resolve()
        self.env.note_dependency(str(source))
        case = load_case(source)
        with warnings.catch_warnings():  # shown below, from the summary, as the command prints them
            warnings.simplefilter("ignore")
            result, summary = run_case(case)
        images = Path(self.env.srcdir) / "_generated"
        images.mkdir(exist_ok=True)
        image = images / f"{source.stem}.png"
        save_impact_history(result, image)
        lines = [".. code-block:: toml", ""]
        lines += [f"   {line}" for line in source.read_text(encoding="utf-8").splitlines()]
        lines += ["", f".. image:: /_generated/{image.name}", f"   :alt: force history of {source.stem}", "",
                 ".. list-table:: summary (from ``impactmaps simulate``)", "   :header-rows: 0", ""]
        for key in ("peak_force_N", "first_contact_duration_s", "total_contact_time_s", "impacts",
                    "max_indentation_m", "restitution", "energy_transferred_J", "zeta", "lambda"):
            value = summary.get(key)
            text = f"{value:.5g}" if isinstance(value, float) else str(value)
            lines += [f"   * - ``{key}``", f"     - {text}"]
        command = "fd" if case.solver_kind == "fd" else "simulate"
        if summary["model_warnings"]:  # what the command prints (impactmaps.validity): the page shows it too
            lines += ["", f".. warning:: ``impactmaps {command}`` warns of this case (``model_warnings``, "
                      ":mod:`impactmaps.validity`):", ""]
            lines += [f"   * {message}" for message in summary["model_warnings"]]
        else:
            lines += ["", f"``impactmaps {command}`` prints no validity warning for this case (:mod:`impactmaps.validity`)."]
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source=str(source)), self.content_offset, container)
        return container.children


_ABSOLUTE_VALUE = re.compile(r"(?<![\w`|\\])\|([^|`\n]+?)\|(?![\w|`])")


def escape_absolute_values(app, what, name, obj, options, lines):
    """Docstrings write |x| for absolute values; reST would read a substitution."""
    lines[:] = [_ABSOLUTE_VALUE.sub(r"\\|\1\\|", line) for line in lines]


def setup(app):
    app.connect("autodoc-process-docstring", escape_absolute_values)
    app.add_directive("options-table", OptionsTable)
    app.add_directive("case-example", CaseExample)
    return {"version": "1", "parallel_read_safe": True}
