"""A numba kernel compiled for the signatures it is called with, on first call, not at import.

:class:`LazyKernel` keeps what eager signatures give (a fixed set of specialisations,
other argument types refused) without making every import pay for the compile; a
kernel's variants are derived from its other arguments and compiled only when needed.
"""

from __future__ import annotations

import contextlib

__all__ = ["LazyKernel"]


def _locked_cache_saves(dispatcher) -> None:
    """Serialise the on-disk cache saves of ``dispatcher`` across processes (a POSIX file lock
    beside the index), so that two processes saving different specialisations at once do not
    pick one data-file name. A no-op where the cache, ``fcntl`` or numba's internals differ.
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
    """Call a numba dispatcher compiled for fixed signatures only, compiling each on first use
    (a call with other argument types raises ``TypeError``, as with eager signatures).

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        An ``njit`` function given without signature (``cache=True`` recommended).
    signature : numba signature or dict
        The one signature; or ``{variant: signature}``, ``variant`` the dispatcher's last
        argument, chosen by ``choose(args)`` from the caller's arguments.
    choose : callable, optional
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
