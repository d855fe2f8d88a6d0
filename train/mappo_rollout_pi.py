"""Entry point of ``python -m train.mappo_rollout_pi`` (:mod:`train.mappo.rollout_pi`)."""

import sys

from train.mappo.rollout_pi import main

if __name__ == "__main__":
    sys.exit(main())
