"""``python -m masonry_dem``: the command line (see :mod:`masonry_dem.cli`)."""

import sys

from .cli import main

sys.exit(main())
