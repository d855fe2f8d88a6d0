"""Entry point of ``python -m train.mappo_report`` (:mod:`train.mappo.report`)."""

import sys

from train.mappo.report import main

if __name__ == "__main__":
    sys.exit(main())
