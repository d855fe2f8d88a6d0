"""``python -m ssl_marl.cli``: the ``ssl-marl`` command line."""

import sys

from . import main

sys.exit(main())
