"""The structure of ``impactmaps chart --case CASE.toml`` or ``--target KIND-SUPPORTS``: the
map structure whose F̄max(ζ, λ) curves the chart draws beside the shipped simply supported
one of its kind.
"""

from __future__ import annotations

from ._common import check_shape_options, refuse, target_kind_and_supports

__all__ = ["STRUCTURE_OPTIONS", "chart_structure"]

#: The options that shape a ``--target`` structure (attribute names of the parsed arguments).
STRUCTURE_OPTIONS = {"--theory": "theory", "--aspect": "aspect", "--slenderness": "slenderness",
                     "--position": "position", "--position-y": "position_y"}


def chart_structure(args):
    """The :class:`~impactmaps.maps.family.structures.MapStructure` of the chart's ``--case`` or
    ``--target`` (with ``--theory``, ``--aspect``, ``--slenderness``, ``--position``,
    ``--position-y``), or None (the shipped chart); ``ValueError`` naming the option as typed.
    """
    case, target = getattr(args, "case", None), getattr(args, "target", None)
    if case is not None and target is not None:
        raise ValueError(f"--case and --target = {target} are exclusive: give the structure once")
    if target is None:
        refuse(args, STRUCTURE_OPTIONS, "without --target (a case file gives its own structure)" if case
               else "without --target or --case (the shipped chart is of the simply supported structures)")
    if case is not None:
        return _case_structure(case)
    if target is not None:
        return _target_structure(args, target)
    return None


def _case_structure(path):
    """The structure of the case file at ``path`` (its target; the chart's law is ``--law``)."""
    from ..cases import load_case
    from ..cases.on_demand import case_structure

    case = load_case(path)
    if case.target_type not in ("beam", "plate"):
        raise ValueError(f"--case {path}: target type {case.target_type!r} has no (ζ, λ) chart: give a beam or "
                         "a plate")
    try:
        structure, _patch = case_structure(case, "linear")
    except ValueError as error:
        raise ValueError(f"--case {path}: no map structure describes its target: {error}") from None
    return structure


def _target_structure(args, target: str):
    """The structure ``--target KIND-SUPPORTS`` (``plate-cccc``, ``beam-cf``; ``plate-ss`` is SSSS)."""
    from ..maps.family.structures import MapStructure
    from ..targets.options import default_theory

    kind, supports = target_kind_and_supports(args, target)
    check_shape_options(args)
    theory = getattr(args, "theory", None) or default_theory(kind)
    values = {"aspect_ratio": getattr(args, "aspect", None), "slenderness": getattr(args, "slenderness", None)}
    x, y = (getattr(args, name, None) for name in ("position", "position_y"))
    fractions = (0.5 if x is None else x,) if kind == "beam" else (0.5 if x is None else x, 0.5 if y is None else y)
    try:
        structure = MapStructure(kind=kind, theory=theory, supports=supports, impact_fraction=fractions,
                                 **{key: value for key, value in values.items() if value is not None})
        structure.build()
    except (TypeError, ValueError) as error:
        raise ValueError(f"--target {target} --theory {theory}: {error}") from None
    return structure

