"""A numba kernel compiled for the signatures it is called with, on first call, not at import.

An eager signature (``numba.njit(signature)``) compiles when the module is imported: every
command that merely imports a solver then pays for it (the exact-step integrator takes
seconds to compile on an empty cache), also the ones that never integrate (the chart drawn
from a shipped result, ``lookup``, ``--help``). :class:`LazyKernel` keeps what eager
signatures give — a fixed set of specialisations, arguments of another type refused —
and compiles (or loads from numba's on-disk cache) a specialisation when a call first
needs it. A kernel with several variants (:data:`impactmaps.solvers.integrator.exact_step.integrate_impact`)
takes a trailing variant argument that the caller does not pass: ``choose(args)`` derives
it from the other arguments, and only the variants that calls need are compiled.
"""

from __future__ import annotations

import contextlib

__all__ = ["LazyKernel"]


def _locked_cache_saves(dispatcher) -> None:
    """Serialise the on-disk cache saves of ``dispatcher`` across processes (a POSIX file lock).

    numba's ``IndexDataCacheFile.save`` names a new entry's data file from the index it has
    just read: two processes saving *different* specialisations of one function at once (the
    integrator's variants, compiled by ``impactmaps warm-up``'s two processes or by a sweep's
    workers on an empty cache) could both pick one name, leaving the index naming one
    specialisation and the file holding the other (a later load then registers the wrong
    signature). Holding a lock beside the index for the whole save lets the second process read
    the first one's index. Nothing changes where the cache, ``fcntl`` or numba's internals are
    not as expected (then saves are as numba does them).
    """
    try:
        import fcntl

        cache = dispatcher._cache
        lock_path = cache._cache_file._index_path + ".lock"
        save = cache.save_overload
    except (ImportError, AttributeError):  # no cache (cache=False), Windows, or numba changed
        return
    if getattr(save, "_impactmaps_locked", False):
        return

    def locked_save(sig, data):
        with contextlib.ExitStack() as stack:
            try:
                handle = stack.enter_context(open(lock_path, "a"))
                fcntl.flock(handle, fcntl.LOCK_EX)
            except OSError:  # a read-only cache directory: numba's own save fails quietly too
                pass
            save(sig, data)

    locked_save._impactmaps_locked = True
    cache.save_overload = locked_save


class LazyKernel:
    """Call a numba dispatcher compiled for fixed signatures only, compiling each on first use.

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        An ``njit`` function given without signature (``cache=True`` recommended).
    signature : numba signature or dict
        The one signature it is compiled for; or ``{variant: signature}`` with ``choose``,
        where ``variant`` is the value of the dispatcher's last argument.
    choose : callable, optional
        ``choose(args) -> variant`` for the arguments a caller passes (all but the last);
        the call is then ``dispatcher(*args, variant)``.

    Notes
    -----
    Outside :meth:`compile` the dispatcher compiles nothing: a call with other argument
    types raises ``TypeError``, as with eager signatures.
    """

    def __init__(self, dispatcher, signature, choose=None):
        self.dispatcher = dispatcher
        self.signatures = signature if isinstance(signature, dict) else {None: signature}
        self.signature = signature
        self._choose = choose
        self.__doc__ = dispatcher.py_func.__doc__
        self.__wrapped__ = dispatcher.py_func
        # the variants compiled: asking the dispatcher for its signatures on every call
        # hashed their types, ~25 µs a call (a tenth of a cheap map point's run)
        self._compiled = set()
        _locked_cache_saves(dispatcher)

    def compile(self, *args) -> None:
        """Compile (or load from numba's cache) the variant ``args`` need, every variant
        without ``args``; idempotent."""
        if args and self._choose is not None:
            variants = [self._choose(args)]
        else:
            variants = list(self.signatures)
        for variant in variants:
            self.compile_variant(variant)

    def variant_of(self, args):
        """The variant a call with ``args`` (all but the last argument) needs (``None`` for
        a kernel without variants)."""
        return None if self._choose is None else self._choose(args)

    def compile_variant(self, variant) -> None:
        """Compile (or load from numba's cache) one variant, named by its last argument
        (``None`` for a kernel without variants); idempotent."""
        if variant not in self.signatures:
            raise ValueError(f"variant = {variant!r} is not one of {sorted(map(repr, self.signatures))}")
        if variant not in self._compiled:
            self.dispatcher.disable_compile(False)
            try:
                self.dispatcher.compile(self.signatures[variant])
            finally:  # numba refuses to disable a dispatcher without any signature (an
                # interrupted first compile: Ctrl-C then raised an AssertionError, not the interrupt)
                if self.dispatcher.signatures:
                    self.dispatcher.disable_compile()
            self._compiled.add(variant)

    def __call__(self, *args):
        if self._choose is None:
            if not self._compiled:
                self.compile()
            return self.dispatcher(*args)
        variant = self._choose(args)
        if variant not in self._compiled:
            self.compile(*args)
        return self.dispatcher(*args, variant)
