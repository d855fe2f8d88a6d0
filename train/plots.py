"""Entry point of ``python -m train.plots`` (:mod:`train.tools.plots`)."""

import sys

from train.tools.plots import main

if __name__ == "__main__":
    sys.exit(main())
