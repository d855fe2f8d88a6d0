"""Entry point of ``python -m train.compare`` (:mod:`train.tools.compare`)."""

import sys

from train.tools.compare import main

if __name__ == "__main__":
    sys.exit(main())
