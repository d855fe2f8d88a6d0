"""Entry point of ``python -m train.report`` (:mod:`train.tools.report`)."""

import sys

from train.tools.report import main

if __name__ == "__main__":
    sys.exit(main())
