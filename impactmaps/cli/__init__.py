"""The ``impactmaps`` command line. Every subcommand accepts ``--json``.

Subcommands: chart (the main job), point, asymptote, classify, lookup, sweep,
simulate, fd, halfspace, restitution, plot, init, check, modes, warm-up, materials, laws. ``impactmaps SUBCOMMAND --help``
documents each. Bad input exits with status 2 and one line naming the option as typed,
its value and the valid range; Ctrl-C exits with status 130 (a sweep saves its points
first). With ``--json`` the output is strict JSON: a quantity that does not exist
(NaN, inf) is ``null`` and a companion ``…_note`` key says why.

The subcommands live in :mod:`.commands_maps` (the normalised maps) and
:mod:`.commands_cases` (physical cases and catalogues); what they share (output, option
checks, errors, exit codes) in :mod:`._common`.
"""

from __future__ import annotations

import os

# One BLAS thread per process, set before NumPy loads its BLAS (a value the user set is
# kept): the work is many small dense problems, and a sweep's worker processes inherit the
# setting — N workers with N BLAS threads each oversubscribe the cores (the default chart
# computed with --zeta-count 100 on 2 cores: 7.6 CPU-s and 6.1 s wall with two BLAS threads
# a process, 6.0 CPU-s and 5.4 s with one).
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

from . import _signals

# Ctrl-C and SIGTERM end the program with status 130 and one line from here on, also during the
# imports below (NumPy, the commands: about half a second), before main() takes them over
if _signals.started_as_program():
    _signals.install_early_handlers()

import argparse
import importlib
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path

from ..jsonio import dumps
from ._common import (
    EXIT_BAD_INPUT,
    EXIT_FAILED,
    EXIT_OK,
    Parser,
    UsageError,
    emit,
    error_text,
    interrupted,
    plain_text,
)
from .commands_cases import (
    cmd_fd,
    cmd_halfspace,
    cmd_laws,
    cmd_materials,
    cmd_restitution,
    cmd_simulate,
)
from .commands_modes import cmd_modes
from ._signals import EXIT_INTERRUPTED
from .commands_tools import CASE_TEMPLATES, cmd_check, cmd_init, cmd_warm_up
from .plot import cmd_plot
from .commands_maps import (
    SCHEDULER_TIMEOUT_S,
    cmd_asymptote,
    cmd_chart,
    cmd_classify,
    cmd_lookup,
    cmd_point,
    cmd_sweep,
)

__all__ = ["main", "build_parser", "SCHEDULER_TIMEOUT_S"]

ZETA_HELP = ("loss factor ζ in (0, 1e6]: how strongly the structure carries the impact energy away in "
             "waves (plate: ζ = sqrt(m K/(ρh D))/16)")
LAMBDA_HELP = "relative stiffness λ = K_static/K_contact > 0: structure stiffness over contact stiffness"


class _Deferred(Sequence):
    """A sequence constant of a module, imported on first use.

    The parser's choices and defaults (laws, shipped theories, the chart's ζ range) live in
    modules that import xarray, numba and the solvers; building the parser from deferred
    constants keeps ``impactmaps --help`` and every command that never reads them from
    importing those modules. ``transform`` derives the sequence from the constant.
    """

    def __init__(self, module: str, name: str, transform=tuple):
        self._source = (module, name, transform)
        self._value = None

    def _resolve(self) -> tuple:
        if self._value is None:
            module, name, transform = self._source
            self._value = tuple(transform(getattr(importlib.import_module(module), name)))
        return self._value

    def __getitem__(self, index):
        return self._resolve()[index]

    def __len__(self) -> int:
        return len(self._resolve())

    def __contains__(self, value) -> bool:
        return value in self._resolve()

    def __iter__(self):
        return iter(self._resolve())

    def __eq__(self, other) -> bool:
        return tuple(self) == (tuple(other) if isinstance(other, Sequence) else other)

    def __repr__(self) -> str:
        return repr(self._resolve())


def _theories(shipped_maps) -> list[str]:
    return sorted({theory for _, theory in shipped_maps})


def _deferred_choices(action: argparse.Action, choices: _Deferred) -> argparse.Action:
    """Give ``action`` choices that are imported when an argument is checked or help is shown
    (set after ``add_argument``, which would otherwise list them at once)."""
    action.choices = choices
    return action


#: Deferred parser constants (see :class:`_Deferred`).
_MAP_LAWS = _Deferred("impactmaps.maps.files.shipped", "ALL_MAP_LAWS")
_THEORIES = _Deferred("impactmaps.maps.files.shipped", "SHIPPED_MAPS", _theories)
_ZETA_RANGE = _Deferred("impactmaps.plotting.chart", "DEFAULT_ZETA_RANGE")


#: Help of ``simulate --vary`` and ``fd --vary``.
VARY_HELP = ("a parameter study: run the case for N values of the numeric case-file KEY from A to B, evenly "
             "spaced (A:B:N:log: evenly in log), or KEY=V1,V2,…, e.g. impactor.velocity=0.1:10:12:log; writes "
             "study.csv and study.json (every scalar of each run), study.png (peak force and restitution against "
             "KEY), study_forces.png and each run in study/run_NNN (reused when the command is run again)")
#: Help of ``halfspace --law-option``.
LAW_OPTION_HELP = ("a numeric option of the law (impactmaps laws lists them), e.g. sphere_compliance=0.5; "
                   "repeat for several")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``impactmaps`` command."""
    from .. import __version__

    parser = Parser(prog="impactmaps", description=plain_text(__doc__.splitlines()[0]))
    parser.add_argument("--version", action="version", version=f"impactmaps {__version__}")
    parser.add_argument("--no-background-warm-up", action="store_true",
                        help="do not start compiling the solver in the background after the command when its "
                        "cache is cold (IMPACTMAPS_NO_BACKGROUND_WARMUP=1 also turns off the compile "
                        "helper of a cold first run)")
    sub = parser.add_subparsers(dest="command", required=True)

    def add(name, help_text, handler):
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--json", action="store_true", help="print one JSON object")
        p.set_defaults(handler=handler)
        return p

    _chart_parser(add)

    p = add("point", "simulate one (ζ, λ) point on a beam or plate", cmd_point)
    _point_arguments(p)
    p.add_argument("--plot", default=None, metavar="FILE", help="write the normalised histories to an image file")

    p = add("asymptote", "asymptote: infinite beam, infinite plate, quasi-static or half-space "
            "(normalised closed forms, or a case with its own contact law)", cmd_asymptote)
    p.add_argument("which", choices=("infinite-beam", "infinite-plate", "quasi-static", "half-space"))
    p.add_argument("--case", type=Path, help="a physical case file: the asymptote with the case's contact law, "
                   "in newtons and seconds")
    p.add_argument("--zeta", type=float, help=ZETA_HELP + " (infinite-beam, infinite-plate)")
    p.add_argument("--lambda", dest="lambda_", metavar="LAMBDA", type=float, help=LAMBDA_HELP + " (quasi-static)")

    p = add("classify", "regime of an impact at (ζ, λ)", cmd_classify)
    p.add_argument("--zeta", type=float, required=True, help=ZETA_HELP)
    p.add_argument("--lambda", dest="lambda_", metavar="LAMBDA", type=float, required=True, help=LAMBDA_HELP)
    _kind_argument(p, required=True)
    p.add_argument("--tolerance", type=float, default=0.1,
                   help="relative distance to an asymptote that counts as on it, in (0, 1] (default 0.1)")
    p.add_argument("--from-map", action="store_true", help="interpolate the shipped map instead of simulating")
    _point_arguments(p, with_target=False)

    p = add("lookup", "F̄max and regime from the shipped maps, or for a case an on-demand map tile (no simulation)",
            cmd_lookup)
    _kind_argument(p, required=False)
    _deferred_choices(p.add_argument(
        "--theory", help="the structural theory of the map (default: the classical one, euler for a beam, kirchhoff "
        "for a plate)"), _THEORIES)
    p.add_argument("--zeta", type=float, help=ZETA_HELP + "; with --law hertz the Hertz loss factor ζ_h")
    p.add_argument("--lambda", dest="lambda_", metavar="LAMBDA", type=float,
                   help=LAMBDA_HELP + "; with --law hertz the Hertz relative stiffness λ_h")
    _deferred_choices(p.add_argument(
        "--law", default=None,
        help="map law: linear (default; ζ, λ), hertz (the Hertz numbers ζ_h, λ_h), "
        "or yc / stronge / epp (with --beta: the elastic-plastic maps over β, ζ, λ)"), _MAP_LAWS)
    p.add_argument("--beta", type=float, default=None, help="impact number β (with --law yc, stronge or epp)")
    p.add_argument("--slenderness", type=float, default=None,
                   help="span/thickness of a Timoshenko beam or Mindlin plate (≥ 10; default 20: the shipped "
                   "map; others interpolated in 1/slenderness between the shipped slenderness members)")
    p.add_argument("--case", type=Path, help="a physical case file: the map that describes it — a shipped map, or "
                   "an on-demand map tile built once and cached — or a refusal, the peak force in newtons with its "
                   "error band")
    p.add_argument("--no-build", action="store_true",
                   help="with --case: refuse a case no shipped map describes instead of building its map tile")
    p.add_argument("--quiet", action="store_true",
                   help="with --case: no lines on stderr announcing a map tile's build and its progress")

    p = add("sweep", "run a sweep described by a TOML file (resumable)", cmd_sweep)
    p.add_argument("config", type=Path)
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on a Dask cluster, e.g. tcp://host:8786 (needs the dask extra)")
    p.add_argument("--overwrite", action="store_true", help="replace a sweep.nc made by another configuration")
    p.add_argument("--quiet", action="store_true")

    for name, text, handler in (
            ("simulate", "simulate a physical case file (TOML) with the modal solver", cmd_simulate),
            ("fd", "simulate a beam case file with the finite-difference elastic-plastic solver", cmd_fd)):
        p = add(name, text, handler)
        p.add_argument("case", type=Path)
        p.add_argument("--out", default="impactmaps-output",
                       help="directory for history.csv, history.png, summary.json (default ./impactmaps-output)")
        p.add_argument("--vary", default=None, metavar="KEY=A:B:N[:log]", help=VARY_HELP)
        p.add_argument("--quiet", action="store_true", help="no progress lines of a --vary study")

    p = add("halfspace", "sphere on a half-space with any contact law", cmd_halfspace)
    p.add_argument("--law", required=True, help="a contact law (impactmaps laws lists them)")
    p.add_argument("--radius", type=float, required=True, help="sphere radius [m]")
    p.add_argument("--velocity", type=float, required=True, help="impact velocity [m/s]")
    p.add_argument("--mass", type=float, default=None, help="impactor mass [kg] (default: the solid sphere's)")
    p.add_argument("--material", default=None, help="impactor catalogue material (impactmaps materials)")
    p.add_argument("--target-material", default=None, help="target catalogue material")
    p.add_argument("--youngs-modulus", type=float, default=None, help="E [Pa] of the body without a --…material")
    p.add_argument("--poisson-ratio", type=float, default=None, help="ν of the body without a --…material")
    p.add_argument("--density", type=float, default=None, help="ρ [kg/m³] of the body without a --…material")
    p.add_argument("--yield-strength", type=float, default=None, help="yield strength [Pa] (plastic laws)")
    p.add_argument("--law-option", action="append", default=[], metavar="NAME=VALUE", help=LAW_OPTION_HELP)

    p = add("restitution", "coefficient of restitution e(β) of the Yigit–Christoforou law", cmd_restitution)
    p.add_argument("--beta", type=float, required=True, help="impact number β = V0/(ω_h α_y) in (0, 1e8] (Christoforou & Yigit 1998, eq 11)")

    _plot_parser(add)
    _tool_parsers(add)
    return parser


def _chart_parser(add) -> None:
    """The ``chart`` subcommand: the shipped chart, or another structure's beside it."""
    p = add("chart", "the normalised max-force chart (Figure 2), its data and lookup table; with --case or "
            "--target another beam or plate beside it", cmd_chart)
    p.add_argument("--out", default="impactmaps-output", help="output directory (default ./impactmaps-output)")
    p.add_argument("--zeta-range", nargs=2, type=float, default=_ZETA_RANGE, metavar=("A", "B"))
    p.add_argument("--zeta-count", type=int, default=None,
                   help="log-spaced ζ values per curve (≥ 2; default 200, with --case or --target 20)")
    p.add_argument("--lambdas", nargs="+", type=float, default=None,
                   help="λ values (default 0.05 … 20, 8 values; with --case or --target 0.05 0.2 1 5)")
    p.add_argument("--case", type=Path, default=None, metavar="CASE.toml",
                   help="also draw the curves of this case's structure (its target: a beam or plate of any "
                   "supports or edges, theory, aspect ratio, impact point, or a laminate), computed by a resumable "
                   "sweep beside the simply supported structure of its kind")
    p.add_argument("--target", default=None, metavar="KIND-SUPPORTS",
                   help="also draw the curves of this structure, e.g. plate-cccc, plate-cfcf, beam-cc (with "
                   "--theory, --aspect, --slenderness, --position, --position-y)")
    p.add_argument("--theory", default=None, help="of --target: euler|rayleigh|timoshenko or kirchhoff|mindlin")
    p.add_argument("--aspect", type=float, default=None, help="of a plate --target: b/a (default 1)")
    p.add_argument("--slenderness", type=float, default=None, help="of --target: span/thickness (default 20)")
    p.add_argument("--position", type=float, default=None, help="of --target: impact point x0/L or x0/a (default 0.5)")
    p.add_argument("--position-y", type=float, default=None, help="of a plate --target: y0/b (default 0.5)")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all cores)")
    p.add_argument("--overwrite", action="store_true", help="replace an fmax_map.nc made with another grid or law")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    _deferred_choices(p.add_argument(
        "--law", default="linear",
        help="map law: linear (axes ζ, λ, F/(m V0 ω)), hertz (axes ζ_h, λ_h, F/F_hs), or the "
        "elastic-plastic yc / stronge / epp (F̄max, restitution and absorbed energy against ζ at several β, "
        "from the shipped maps); default linear"), _MAP_LAWS)
    p.add_argument("--betas", nargs="+", type=float, default=None,
                   help="impact numbers β of an elastic-plastic chart (default 1 10 100 1000)")


def _plot_parser(add) -> None:
    """The ``plot`` subcommand: a user's study or sweep drawn."""
    p = add("plot", "draw a parameter study (simulate --vary) or a sweep or chart result", cmd_plot)
    p.add_argument("path", type=Path, help="a study's --out directory or study.csv; a sweep's output directory, "
                   "a chart's --out directory, or a .nc/.npz map file")
    p.add_argument("--out", default=None, help="image file (.png, .svg, .pdf; default study.png or sweep_chart.png "
                   "beside the input)")
    p.add_argument("--quantity", action="append", default=None, metavar="COLUMN",
                   help="a study column to draw, one panel each (default peak_force_N and restitution); repeat")
    p.add_argument("--lambdas", nargs="+", type=float, default=None,
                   help="a sweep's λ values to draw (each at the grid's nearest λ; default all)")
    p.add_argument("--beta", type=float, default=None, help="an elastic-plastic map's β to draw (the nearest grid β)")


def _tool_parsers(add) -> None:
    """The subcommands around the solvers: init, check, warm-up, materials, laws."""
    p = add("init", "write a commented case file to start from (beam, plate, laminate or fd)", cmd_init)
    p.add_argument("template", choices=sorted(CASE_TEMPLATES), help="what the case describes")
    p.add_argument("file", nargs="?", default=None, metavar="FILE",
                   help="the case file to write (default: the template's name, e.g. plate.toml for init plate)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing FILE")

    p = add("check", "validate a case file without running it: its numbers (ζ, λ, β), the map that reads it, "
            "its regime, scales and estimated cost", cmd_check)
    p.add_argument("case", type=Path, help="the case file (TOML)")

    p = add("warm-up", "compile the solver's kernels once into numba's cache, so that the first simulation "
            "starts at once (run after installing)", cmd_warm_up)
    p.add_argument("--workers", type=int, default=None,
                   help="processes compiling at once (default 2; 1 compiles in this process)")

    add("materials", "the material catalogue with its values (SI) and sources", cmd_materials)
    p = add("modes", "a target's natural frequencies in Hz, lowest first, with labels ((m, n) half-waves "
            "for a simply supported plate), the basis size and the frequency it resolves", cmd_modes)
    p.add_argument("case", help="the case file (TOML)")
    p.add_argument("--count", type=int, default=10, help="how many modes (default 10)")
    add("laws", "the registered contact laws with their options and sources", cmd_laws)


def _kind_argument(p, required: bool) -> None:
    """``--kind beam|plate``; ``--structure``, its old name, still accepted (not shown)."""
    from ..targets.options import STRUCTURE_KINDS

    group = p.add_mutually_exclusive_group(required=required)
    group.add_argument("--kind", choices=STRUCTURE_KINDS, help="beam or plate")
    group.add_argument("--structure", dest="kind", choices=STRUCTURE_KINDS, help=argparse.SUPPRESS)


def _point_arguments(p, with_target=True):
    if with_target:
        p.add_argument("--target", required=True, help="beam-ss, beam-cc, beam-cs, beam-cf, beam-ff, plate-ss, …")
        p.add_argument("--theory", default=None, help="euler|rayleigh|timoshenko or kirchhoff|mindlin")
        p.add_argument("--zeta", type=float, required=True, help=ZETA_HELP)
        p.add_argument("--lambda", dest="lambda_", metavar="LAMBDA", type=float, required=True, help=LAMBDA_HELP)
    p.add_argument("--aspect", type=float, default=None, help="plate aspect ratio b/a (default 1)")
    p.add_argument("--slenderness", type=float, default=None, help="span/thickness (default 20)")
    p.add_argument("--position", type=float, default=None, help="impact point x0/L (or x0/a) (default 0.5)")
    p.add_argument("--position-y", type=float, default=None, help="impact point y0/b, plates (default 0.5)")
    p.add_argument("--cutoff-ratio", type=float, default=None, help="mode cut-off / contact frequency (default 40)")
    p.add_argument("--time-step-ratio", type=float, default=None,
                   help="upper bound of ω Δt, ω the highest mode kept (default: the modal solver's)")
    p.add_argument("--no-check", action="store_true", help="skip the convergence re-run")


def main(argv=None) -> int:
    """Entry point of the ``impactmaps`` command; returns the exit status.

    0 on success (also when the reader of the output goes away early, as ``| head``
    does: the rest of the output is dropped quietly), 2 on bad input (one line on
    stderr; with ``--json`` also ``{"error": …}`` on stdout), 1 when a computation fails
    on input the checks let through (one line: a range check is missing — please report
    it), 130 when interrupted (Ctrl-C or SIGTERM, at any moment: :mod:`._signals`).
    """
    _signals.note_output(False)
    try:
        with _signals.signals_as_interrupts():
            status = _main(argv)
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_OK
    except KeyboardInterrupt:  # outside a command's own handling: reading the options, after the output
        status = _signals.say_interrupted(sys.argv[1:] if argv is None else [str(a) for a in argv])
    if status == EXIT_INTERRUPTED and argv is None:  # the program itself, not a call from Python
        _signals.exit_now(status)
    return status


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush of a closed pipe
    raises nothing."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # no file descriptor (captured output)
        pass


class _NotRaised(Exception):
    """Stands for an exception class whose module was never imported (so never raised)."""


def _sweep_interrupted() -> type[Exception]:
    """The sweep store's interruption, if the store was imported (else nothing can raise it):
    the store imports xarray, which commands that never sweep do not need."""
    store = sys.modules.get("impactmaps.maps.files.store")
    return _NotRaised if store is None else store.SweepInterrupted


def _background_warm_up(args) -> None:
    """Start compiling the solver in the background if its cache is cold
    (:mod:`impactmaps._compile.background_warm_up`; about a millisecond here), unless turned off
    by ``--no-background-warm-up`` or :data:`~impactmaps._compile_switch.DISABLE_ENV`
    (asked here: a command with the warm-up off never enters the compile plumbing)."""
    from .._compile_switch import switched_off

    if args.no_background_warm_up or args.command == "warm-up" or switched_off():
        return
    from .._compile import background_warm_up

    background_warm_up.start_background()


def _main(argv) -> int:
    argv = sys.argv[1:] if argv is None else [str(a) for a in argv]
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except UsageError as error:
        if "--json" in argv:
            print(dumps({"error": str(error)}))
        print(error, file=sys.stderr)
        return EXIT_BAD_INPUT
    status = _run(args)
    if status != EXIT_INTERRUPTED:
        _background_warm_up(args)  # after the command's output: it never competes with the command
    return status


def _show_warning(message, shown: set) -> None:
    """Print a warning on stderr as one line, once per text."""
    text = str(message)
    if text not in shown:
        shown.add(text)
        print(f"warning: {plain_text(text)}", file=sys.stderr, flush=True)


def _interrupted(args, text: str) -> int:
    """Say ``text`` (one line on stderr, and ``{"error": …}`` with ``--json``); the exit status of Ctrl-C."""
    if getattr(args, "json", False):
        print(dumps({"error": text}), flush=True)
    print(f"impactmaps {args.command}: {text}", file=sys.stderr)
    return EXIT_INTERRUPTED


def _run(args) -> int:
    """Run the parsed command: print its output, or one line for an error; its exit status."""
    caught, shown = [], set()

    def collect(message, category, *_location, **_kw):  # an announcement (a long run) is shown before the run
        (_show_warning(message, shown) if getattr(category, "announce_at_once", False) else caught.append(message))

    status = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            warnings.showwarning = collect
            values = args.handler(args)
    except _sweep_interrupted() as stop:
        return _interrupted(args, f"interrupted: {stop.saved} of {stop.total} points saved; run the same "
                                  "command to resume")
    except KeyboardInterrupt:
        return _interrupted(args, "interrupted")
    except SystemError as error:  # Ctrl-C while compiled (numba) code returns reaches Python as this
        if not interrupted(error):
            raise
        return _interrupted(args, "interrupted")
    except BrokenPipeError:
        raise
    except (ValueError, TypeError, OSError, MemoryError) as error:
        message, status = error_text(error), EXIT_BAD_INPUT
    except NotImplementedError as error:  # a combination the toolkit refuses (e.g. a Mindlin plate's edges)
        message, status = f"not implemented: {error_text(error)}", EXIT_BAD_INPUT
    except (RuntimeError, ArithmeticError) as error:
        message, status = (f"the computation failed ({type(error).__name__}: {error_text(error)}); the input "
                           "passed the range checks, so one is missing: please report it"), EXIT_FAILED
    finally:
        for warning in caught:
            _show_warning(warning, shown)
    if status is not None:
        message = plain_text(message)
        if args.json:
            print(dumps({"error": message}))
        print(f"impactmaps {args.command}: error: {message}", file=sys.stderr)
        return status
    emit(values, args.json)
    _signals.note_output()
    return EXIT_OK
