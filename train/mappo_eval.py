"""Entry point of ``python -m train.mappo_eval`` (:mod:`train.mappo.eval`)."""

import sys

from train.mappo.eval import main

if __name__ == "__main__":
    sys.exit(main())
