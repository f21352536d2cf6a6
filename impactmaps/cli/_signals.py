"""How Ctrl-C and SIGTERM end the ``impactmaps`` program: status 130, one line, no traceback,
from the moment the program starts running the command line.

Three stages:

* :func:`install_early_handlers`, called at the top of :mod:`impactmaps.cli` when that import
  starts the program (:func:`started_as_program`: the ``impactmaps`` console script or
  ``python -m impactmaps.cli``), before the imports of NumPy and the commands (about half a
  second on a loaded machine): a signal then ends the process at once with status 130 and the
  line ``impactmaps: interrupted``. A library import of :mod:`impactmaps.cli` leaves the
  handlers alone.
* :func:`signals_as_interrupts`, around a command (``impactmaps.cli.main``): Ctrl-C is
  Python's ``KeyboardInterrupt`` and SIGTERM raises it too, so a sweep saves its points and
  a compiled loop stops (:mod:`impactmaps._compile.interruptible`) before the command says
  ``interrupted``.
* :func:`exit_now`: the interrupted program ends without the interpreter's slow teardown.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading

__all__ = ["EXIT_INTERRUPTED", "started_as_program", "install_early_handlers", "signals_as_interrupts", "exit_now",
           "note_output", "say_interrupted"]

#: Exit status after Ctrl-C or SIGTERM (128 + SIGINT, as a shell reports Ctrl-C).
EXIT_INTERRUPTED = 130
#: The module ``python -m`` runs as the program.
_PROGRAM_MODULES = ("impactmaps.cli", "impactmaps.cli.__main__")
#: File names of the console script (pip's launcher on Windows runs ``impactmaps-script.py``).
_SCRIPT_NAMES = ("impactmaps", "impactmaps.exe", "impactmaps-script.py")
#: Interpreter options that take a value (skipped when looking for ``-m``).
_VALUED_OPTIONS = ("-X", "-W", "--check-hash-based-pycs")
#: Whether the command has written its output (then an early handler adds no JSON error after it).
_state = {"output": False}


def started_as_program() -> bool:
    """Whether the running process is the ``impactmaps`` program: ``python -m impactmaps.cli`` (read
    from :data:`sys.orig_argv`), or the console script as the main module (not a process of
    :mod:`multiprocessing` re-importing it, whose main module is ``__mp_main__``)."""
    arguments = iter(getattr(sys, "orig_argv", [])[1:])
    for argument in arguments:
        if argument in _VALUED_OPTIONS:
            next(arguments, None)
        elif argument.startswith("-m"):
            return (argument[2:] or next(arguments, "")) in _PROGRAM_MODULES
        elif not argument.startswith("-") or argument.startswith("-c") or argument == "-":
            break
    main = sys.modules.get("__main__")
    script = os.path.basename(str(getattr(main, "__file__", "") or ""))
    return getattr(main, "__name__", "") == "__main__" and script in _SCRIPT_NAMES


def _end_quietly(signum, frame) -> None:
    """The early handler: flush what was printed, say ``interrupted`` (with ``--json``, as JSON on
    stdout unless the command printed its output already) and end with status 130."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    with contextlib.suppress(OSError):
        if "--json" in sys.argv[1:] and not _state["output"]:
            os.write(1, b'{"error": "interrupted"}\n')
        os.write(2, b"impactmaps: interrupted\n")
    os._exit(EXIT_INTERRUPTED)


def install_early_handlers() -> None:
    """End the process at once with status 130 on Ctrl-C or SIGTERM (:func:`_end_quietly`), for
    the program's start; a signal the process ignores stays ignored (``nohup``, a background job)."""
    if threading.current_thread() is not threading.main_thread():
        return
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _end_quietly)
    if signal.getsignal(signal.SIGTERM) is signal.SIG_DFL:
        signal.signal(signal.SIGTERM, _end_quietly)


def say_interrupted(argv: list) -> int:
    """Say ``impactmaps: interrupted`` (stderr; with ``--json`` in ``argv`` also ``{"error":
    "interrupted"}`` on stdout, unless the output was printed); :data:`EXIT_INTERRUPTED`."""
    if "--json" in argv and not _state["output"]:
        print('{"error": "interrupted"}', flush=True)
    print("impactmaps: interrupted", file=sys.stderr, flush=True)
    return EXIT_INTERRUPTED


def note_output(printed: bool = True) -> None:
    """Record whether the command has printed its output (if so, no JSON error follows it)."""
    _state["output"] = printed


def _raise_interrupt(*_) -> None:
    raise KeyboardInterrupt


@contextlib.contextmanager
def signals_as_interrupts():
    """Within: Ctrl-C raises ``KeyboardInterrupt`` (Python's own handler, in place of an early
    one) and SIGTERM (``kill``) raises it too, so that a command ends as on Ctrl-C: a sweep saves
    what is done and stops its workers, its lock removed. The handlers before are restored after
    (outside the main thread nothing is changed)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    early = signal.getsignal(signal.SIGINT) is _end_quietly
    previous = signal.signal(signal.SIGTERM, _raise_interrupt)
    if early:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        if early:
            signal.signal(signal.SIGINT, _end_quietly)


def exit_now(status: int) -> None:
    """End the interrupted program at once: run the exit handlers and flush the output, but skip
    the interpreter's teardown of numba, pandas and xarray (about a second on a busy machine),
    so that a signal ends every command within a second."""
    import atexit

    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(status)
