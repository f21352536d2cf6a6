"""Compiled loops that Ctrl-C and SIGTERM stop at once.

A numba loop does not see a signal; :func:`run_interruptibly` runs it (``nogil=True``,
reading a one-element stop flag) in a worker thread, sets the flag on
``KeyboardInterrupt``, waits one step and re-raises.
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
    """Whether no Python handler would see Ctrl-C or SIGTERM (then nothing can interrupt a loop)."""
    return not any(callable(signal.getsignal(number)) for number in _STOPPING_SIGNALS)


def run_interruptibly(call, stop, name: str = "impactmaps-compiled-loop"):
    """``call()`` (a compiled loop that releases the GIL and returns once ``stop[0] != 0``) in a
    worker thread named ``name``, stopped through its one-element flag ``stop`` on Ctrl-C;
    returns what ``call`` returns, bit for bit a direct call.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C while the loop runs, once it has returned (outside the main thread, or
        where Ctrl-C is ignored, ``call`` runs directly).
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
