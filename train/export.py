"""Entry point of ``python -m train.export`` (:mod:`train.offpolicy.export`)."""

import sys

from train.offpolicy.export import main

if __name__ == "__main__":
    sys.exit(main())
