"""``python -m impactmaps.cli``: the ``impactmaps`` command."""

import sys

from . import main

sys.exit(main())
