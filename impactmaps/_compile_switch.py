"""The environment switch that turns off compiling in other processes: the compile helper of
a cold first run and the background warm-up (``IMPACTMAPS_NO_BACKGROUND_WARMUP``).

Beneath every layer, so that the command line reads the same rule as the compile plumbing
without entering it.
"""

from __future__ import annotations

import os

__all__ = ["DISABLE_ENV", "switched_off"]

#: Environment variable that turns the compile helper and the background warm-up off (any
#: value but "" and "0").
DISABLE_ENV = "IMPACTMAPS_NO_BACKGROUND_WARMUP"


def switched_off() -> bool:
    """Whether :data:`DISABLE_ENV` turns off the compiling in other processes (the helper
    and the background warm-up): set to anything but "" and "0"."""
    return os.environ.get(DISABLE_ENV, "") not in ("", "0")
