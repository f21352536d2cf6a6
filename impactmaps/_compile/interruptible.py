"""Compiled loops that Ctrl-C and SIGTERM stop at once.

A compiled (numba) loop does not see a signal: Python handles signals between bytecodes,
so a loop of minutes ignores Ctrl-C for minutes. :func:`run_interruptibly` runs such a
loop (compiled with ``nogil=True`` and reading a one-element stop flag at every step) in a
worker thread while the calling thread waits in short slices; on ``KeyboardInterrupt`` it
sets the flag, waits for the loop to return (one step) and re-raises.
"""

from __future__ import annotations

import signal
import threading

__all__ = ["run_interruptibly", "interrupts_ignored"]

#: The signals that stop a command (the command line turns SIGTERM into Ctrl-C).
_STOPPING_SIGNALS = (signal.SIGINT, signal.SIGTERM)

#: How long the waiting thread sleeps between looks at its signals [s].
WAIT_SLICE_S = 0.1


def interrupts_ignored() -> bool:
    """Whether no Python handler would see Ctrl-C or SIGTERM (a sweep's workers ignore SIGINT and
    leave SIGTERM at its default): then nothing can interrupt a loop. A command started in the
    background of a script inherits an ignored SIGINT but still handles SIGTERM."""
    return not any(callable(signal.getsignal(number)) for number in _STOPPING_SIGNALS)


def run_interruptibly(call, stop, name: str = "impactmaps-compiled-loop"):
    """``call()`` in a worker thread, stopped through ``stop`` on Ctrl-C.

    Parameters
    ----------
    call : callable
        A call of a compiled loop that releases the GIL and returns once ``stop[0] != 0``.
    stop : ndarray
        The loop's one-element integer stop flag (0: run on).
    name : str, optional
        The worker thread's name.

    Returns
    -------
    object
        What ``call`` returns; the arithmetic is the loop's own (bit for bit a direct call).

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C (or a signal handler that raises it) while the loop runs, once the loop
        has returned. Outside the main thread, or where Ctrl-C is ignored, ``call`` runs
        directly: no signal can arrive there.
    """
    if interrupts_ignored() or threading.current_thread() is not threading.main_thread():
        return call()
    outcome = {}
    done = threading.Event()  # not Thread.join: a join interrupted by Ctrl-C can return early later

    def work():
        try:
            outcome["result"] = call()
        except BaseException as error:  # noqa: BLE001 (handed to the caller's thread)
            outcome["error"] = error
        finally:
            done.set()

    threading.Thread(target=work, name=name, daemon=True).start()
    try:
        while not done.wait(WAIT_SLICE_S):
            pass
    except KeyboardInterrupt:
        stop[0] = 1
        done.wait()
        raise
    if "error" in outcome:
        raise outcome["error"]
    return outcome["result"]
