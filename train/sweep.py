"""Entry point of ``python -m train.sweep`` (:mod:`train.tools.sweep`)."""

import sys

from train.tools.sweep import main

if __name__ == "__main__":
    sys.exit(main())
