"""Entry point of ``python -m train.mappo_bc`` (:mod:`train.mappo.bc`)."""

import sys

from train.mappo.bc import main

if __name__ == "__main__":
    sys.exit(main())
