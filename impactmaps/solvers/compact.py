"""Former name of :mod:`impactmaps.solvers.halfspace` (a thin alias, nothing else).

Kept only while impactmaps/cli.py, impactmaps/__init__.py,
validation/figure1_restitution.py and tests/test_cli.py still import it; delete it once
they import :mod:`impactmaps.solvers.halfspace`.
"""

from .halfspace import *  # noqa: F401,F403
from .halfspace import __all__  # noqa: F401
