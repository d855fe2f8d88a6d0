"""Entry point of ``python -m train.select`` (:mod:`train.tools.select`)."""

import sys

from train.tools.select import main

if __name__ == "__main__":
    sys.exit(main())
