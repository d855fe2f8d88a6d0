"""Entry point of ``python -m train.mappo_export`` (:mod:`train.mappo.export`)."""

import sys

from train.mappo.export import main

if __name__ == "__main__":
    sys.exit(main())
