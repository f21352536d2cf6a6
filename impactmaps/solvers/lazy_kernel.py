"""A numba kernel compiled for its one signature on its first call, not at import.

An eager signature (``numba.njit(signature)``) compiles when the module is imported: every
command that merely imports a solver then pays for it (the exact-step integrator takes
~11 s to compile on an empty cache), also the ones that never integrate (the chart drawn
from a shipped result, ``lookup``, ``--help``). :class:`LazyKernel` keeps what the eager
signature gives — exactly one specialisation, arguments of another type refused — and
compiles (or loads from numba's on-disk cache) when the kernel is first called.
"""

from __future__ import annotations

__all__ = ["LazyKernel"]


class LazyKernel:
    """Call a numba dispatcher compiled for ``signature`` only, compiling on first use.

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        An ``njit`` function given without signature (``cache=True`` recommended).
    signature : numba signature
        The one signature it is compiled for; after compiling, the dispatcher compiles no
        other (a call with other argument types raises ``TypeError``, as with an eager
        signature).
    """

    def __init__(self, dispatcher, signature):
        self.dispatcher = dispatcher
        self.signature = signature
        self.__doc__ = dispatcher.py_func.__doc__
        self.__wrapped__ = dispatcher.py_func
        # whether compile() has run: asking the dispatcher for its signatures on every call
        # hashed their types, ~25 µs a call (a tenth of a cheap map point's run)
        self._compiled = False

    def compile(self) -> None:
        """Compile (or load from numba's cache) the one specialisation; idempotent."""
        if not self._compiled:
            if not self.dispatcher.signatures:
                self.dispatcher.compile(self.signature)
                self.dispatcher.disable_compile()
            self._compiled = True

    def __call__(self, *args):
        if not self._compiled:
            self.compile()
        return self.dispatcher(*args)
