"""What every ``impactmaps`` subcommand shares: output, option checks, errors, exit codes.

Imports of the physics stay inside the functions, so ``impactmaps --help`` stays fast.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from .._checks import range_end_text, read_text_input
from ..jsonio import dumps

#: Exit status of a successful run.
EXIT_OK = 0
#: Exit status of a computation that failed on input the checks let through (a missing check).
EXIT_FAILED = 1
#: Exit status of bad input (a command line argparse refuses, or a ``ValueError``).
EXIT_BAD_INPUT = 2
# (130 after Ctrl-C or SIGTERM: EXIT_INTERRUPTED, with the signal handlers in ._signals)


# -- output --------------------------------------------------------------------------------
def emit(values: dict, as_json: bool, indent: str = "") -> None:
    """Print ``values`` as one JSON object, or as aligned ``key  value`` lines."""
    if as_json:
        print(dumps(values))
        return
    width = max((len(str(k)) for k in values), default=0)
    for key, value in values.items():
        if isinstance(value, dict):
            print(f"{indent}{key}")
            emit(value, False, indent + "  ")
            continue
        text = f"{value:.6g}" if isinstance(value, float) else ("-" if value is None else plain_text(str(value)))
        print(f"{indent}{key:<{width}}  {text}")


#: How the sources the docstrings cite by their project names read for a user.
_CITATIONS = (
    (r"seed 001 (eqs?\.? )", r"Christoforou & Yigit 1998, \1"),
    (r"seed 001", "Christoforou & Yigit 1998"),
    (r"seed 000", "the paper 'Transient impact response analysis of an elastic-plastic beam'"),
    (r"PHYSICS\.md", "docs/physics_contract.md"),
)


def plain_text(text: str) -> str:
    """``text`` (a docstring line) as plain text for a user: no reStructuredText markup
    (````code````, ``:func:`…```), sources named as a reader finds them (not by the
    project's seed numbers)."""
    import re

    text = re.sub(r":[a-z]+:`~?([^`]+)`", r"\1", text)
    text = text.replace("``", "").replace("**", "")
    for pattern, replacement in _CITATIONS:
        text = re.sub(pattern, replacement, text)
    return text


# -- option checks -------------------------------------------------------------------------
def check(option: str, value, low: float = 0.0, high: float = math.inf, what: str = "",
          low_inclusive: bool = False, high_inclusive: bool = False, note: str = "") -> None:
    """Refuse ``value`` of the command-line ``option`` outside its range (NaN too); ``None`` passes."""
    if value is None:
        return
    above = value >= low if low_inclusive else value > low
    below = value <= high if high_inclusive else value < high
    if not (above and below):
        interval = (f"{'[' if low_inclusive else '('}{range_end_text(low)}, {range_end_text(high)}"
                    f"{']' if high_inclusive else ')'}")
        raise ValueError(f"{option} = {value:g} is invalid: {what + ' ' if what else 'it '}must be in {interval}"
                         f"{'; ' + note if note else ''}")


def refuse(args, options: dict, reason: str) -> None:
    """Refuse the options (``{"--flag": attribute}``) that were given but would be ignored."""
    given = [flag for flag, attribute in options.items() if getattr(args, attribute, None) not in (None, False)]
    if given:
        raise ValueError(f"{', '.join(given)} cannot be used {reason}")


def check_shape_options(args) -> None:
    """Refuse ``--aspect``, ``--slenderness``, ``--position`` or ``--position-y`` of a structure
    given on the command line (``point``, ``chart --target``) outside its range, as typed."""
    from ..targets.beams.beam import MIN_SLENDERNESS
    from ..targets.options import MIN_SUPPORT_DISTANCE, PLATE_ASPECT_RANGE

    check("--aspect", getattr(args, "aspect", None), *PLATE_ASPECT_RANGE, what="the plate aspect ratio b/a",
          low_inclusive=True, high_inclusive=True)
    check("--slenderness", getattr(args, "slenderness", None), MIN_SLENDERNESS, what="span/thickness",
          low_inclusive=True)
    for option, name, what in (("--position", "position", "the impact point x0/L"),
                               ("--position-y", "position_y", "the impact point y0/b")):
        check(option, getattr(args, name, None), MIN_SUPPORT_DISTANCE, 1.0 - MIN_SUPPORT_DISTANCE, what,
              low_inclusive=True, high_inclusive=True, note="1e-6 of the span from a support")


def target_kind_and_supports(args, target: str) -> tuple[str, str]:
    """(kind, supports) of ``--target KIND-SUPPORTS`` (``plate-ss`` is SSSS); a beam target refuses
    ``--aspect`` and ``--position-y``; ``ValueError`` naming ``--target`` as typed."""
    from ..targets.options import STRUCTURE_KINDS

    kind, _, supports = target.partition("-")
    if kind not in STRUCTURE_KINDS or not supports:
        raise ValueError(f"--target = {target!r} is not known: use beam-SUPPORTS (e.g. beam-ss, beam-cc, beam-cf) "
                         "or plate-EDGES (e.g. plate-ss, plate-ssss, plate-cccc, plate-cfcf)")
    if kind == "beam":
        refuse(args, {"--aspect": "aspect", "--position-y": "position_y"}, "with a beam --target")
    if kind == "plate" and supports.lower() == "ss":
        supports = "SSSS"
    return kind, supports


def out_dir(option: str, value) -> Path:
    """The output directory of ``option``, checked writable before anything is computed.

    Refused (``ValueError`` naming ``option``) if it names an existing file, if a parent
    is a file, or if the directory — or, when it does not exist yet, its nearest existing
    parent — does not accept a new file (probed by writing and removing one; nothing is
    created).
    """
    if not str(value).strip():
        raise ValueError(f"{option} = {str(value)!r} is invalid: give a directory (e.g. impactmaps-output)")
    out = Path(value)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{option} = {str(out)!r} is a file, not a directory")
    _probe_writable(option, out)
    return out


def text_file(what: str, value) -> Path:
    """The input file ``value`` (``what``: e.g. ``"sweep file"``), refused — naming it — if it
    does not exist, is a directory, cannot be read or is not UTF-8 text."""
    return read_text_input(what, value)[0]


def plot_file(option: str, value) -> Path:
    """The image file of ``option`` (``--plot``), checked before anything is computed:
    not a directory, an image format matplotlib writes, its directory writable."""
    path = Path(value)
    if path.is_dir():
        raise ValueError(f"{option} = {str(path)!r} is a directory: give an image file name (e.g. history.png)")
    from matplotlib.backend_bases import FigureCanvasBase

    formats = sorted(FigureCanvasBase.get_supported_filetypes())
    suffix = path.suffix.lower().lstrip(".")
    if suffix not in formats:
        raise ValueError(f"{option} = {str(path)!r} is invalid: the file name must end in an image format "
                         f"({', '.join('.' + f for f in formats)})")
    _probe_writable(option, path.parent if str(path.parent) else Path("."))
    return path


def _probe_writable(option: str, directory: Path) -> None:
    """Refuse ``directory`` (or its nearest existing parent) if no file can be created in it."""
    import tempfile

    existing = directory
    while not existing.exists():
        if existing.is_symlink():  # a link to nothing: neither written through nor created
            raise ValueError(f"{option} = {str(directory)!r} cannot be created: {str(existing)!r} is a link to "
                             "a missing target")
        if existing.parent == existing:
            break
        existing = existing.parent
    if existing.exists() and not existing.is_dir():
        raise ValueError(f"{option} = {str(directory)!r} cannot be created: {str(existing)!r} is a file")
    try:
        with tempfile.NamedTemporaryFile(dir=existing, prefix=".impactmaps-probe-"):
            pass
    except OSError as error:
        raise ValueError(f"{option} = {str(directory)!r} is not writable: {error.strerror or error} "
                         f"({existing})") from None


def material_from_args(args, prefix: str, role: str):
    """Catalogue name or explicit E, ν, ρ (+ yield) for the impactor or the target."""
    from ..materials import IsotropicMaterial, material

    name = getattr(args, f"{prefix}material")
    if name is not None:
        chosen = material(name)
        if args.yield_strength is not None and isinstance(chosen, IsotropicMaterial):
            chosen = IsotropicMaterial(chosen.youngs_modulus, chosen.poisson_ratio, chosen.density,
                                       args.yield_strength, chosen.name)
        return chosen
    missing = [flag for flag, value in (("--youngs-modulus", args.youngs_modulus),
                                        ("--poisson-ratio", args.poisson_ratio),
                                        ("--density", args.density)) if value is None]
    if missing:
        raise ValueError(
            f"the {role} material is not given: use --{prefix.replace('_', '-')}material NAME "
            f"or {', '.join(missing)} (explicit values apply to both bodies)"
        )
    return IsotropicMaterial(args.youngs_modulus, args.poisson_ratio, args.density, args.yield_strength)


def refuse_ignored_fd(case, source) -> None:
    """Refuse a case the modal solver would run with an ``[fd]`` section it ignores."""
    if case.solver_kind == "modal" and case.fd_settings is not None:
        raise ValueError(f"{source}: the [fd] section is read by the finite-difference solver only, and this "
                         "case runs the modal solver: run impactmaps fd, set [solver] kind = \"fd\", or remove [fd]")


# -- running -------------------------------------------------------------------------------
def save_figure(result, path: Path, normalised: bool) -> str:
    """Write the force/displacement histories of ``result`` to the image file ``path``
    (checked beforehand with :func:`plot_file`)."""
    from ..plotting import save_impact_history

    save_impact_history(result, path, normalised=normalised)
    return str(path)


# -- errors --------------------------------------------------------------------------------
class UsageError(Exception):
    """A command line argparse cannot parse (reported by ``main`` as one line, exit 2)."""


class Parser(argparse.ArgumentParser):
    """An argument parser that raises :class:`UsageError` instead of exiting."""

    def error(self, message):
        raise UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


def error_text(error: BaseException) -> str:
    """One line saying what went wrong, for stderr and the ``{"error": …}`` JSON."""
    if isinstance(error, MemoryError):
        return "out of memory: the run needs more memory than this machine has (reduce its size or duration)"
    if isinstance(error, OSError) and error.strerror:
        where = f": {error.filename}" if error.filename else ""
        return f"{error.strerror}{where}"
    return str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__


def interrupted(error: BaseException) -> bool:
    """True if a KeyboardInterrupt is among the causes of ``error``."""
    seen = set()
    while error is not None and id(error) not in seen:
        if isinstance(error, KeyboardInterrupt):
            return True
        seen.add(id(error))
        error = error.__cause__ or error.__context__
    return False


def case_model_warnings(case, map_force) -> dict:
    """The case's validity warnings (:func:`impactmaps.validity.case_warnings`, the set ``simulate``
    prints) at the map's peak force [N], or at the half-space bound where no map gives one (``None``);
    each also issued as a warning (``check``, ``lookup --case``)."""
    import warnings

    from .._checks import ModelValidityWarning
    from ..validity import case_warnings

    messages = case_warnings(case, peak_force=map_force)
    for message in messages:
        warnings.warn(message, ModelValidityWarning, stacklevel=3)
    basis = ("the map's peak force" if map_force is not None else
             "the half-space peak force, an upper bound of an elastic contact's force on the structure (the checks "
             "that grow with the force may be pessimistic; the run decides)")
    return {"model_warnings": messages, "model_warnings_note": f"the checks of impactmaps.validity at {basis}"}


#: A lookup band wider than this fraction of its value is announced ("simulate it").
WIDE_BAND_FRACTION = 0.1


def announce_wide_band(values: dict, value_key: str, error_key: str, advice: str) -> dict:
    """``values`` with ``band_warning`` when the band ``values[error_key]`` is wider than
    :data:`WIDE_BAND_FRACTION` of ``values[value_key]`` (also issued as a warning); unchanged
    when either is missing."""
    import math
    import warnings

    value, error = values.get(value_key), values.get(error_key)
    if value is None or error is None or not (math.isfinite(value) and math.isfinite(error)):
        return values
    if abs(error) <= WIDE_BAND_FRACTION * abs(value):
        return values
    share = f"{abs(error) / abs(value):.0%}" if value else "more than all"
    message = (f"the map's band {value_key} {value:.4g} ± {error:.3g} is wide ({share} of the value, above "
               f"{WIDE_BAND_FRACTION:.0%}): the map does not pin this number down; simulate it ({advice})")
    warnings.warn(message, UserWarning, stacklevel=3)
    return values | {"band_warning": message}
