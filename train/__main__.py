"""``python -m train`` (and ``ssl-marl train``): the two training command lines.

``python -m train SKILL --seed 0 --out runs/NAME [--algo td3] [--config X.json] [--resume] [--samples N] [--set k=v ...]``
trains a skill with DDPG or TD3 (:mod:`train.offpolicy.cli`; ``python -m train SKILL --help``).

``python -m train mappo --task TASK --seed S --out DIR [--resume] [--decisions N] [--set k=v ...]``
trains the multi-agent MAPPO (:mod:`train.mappo.cli`; ``python -m train mappo --help``).
"""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None, prog: str = "python -m train") -> int:
    """Run the MAPPO command line when the first argument is ``mappo``, else the skill one
    (``prog`` names the command in messages)."""
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "mappo":
        from train.mappo.cli import main as mappo_main

        return mappo_main(argv[1:], prog=f"{prog} mappo")
    from train.offpolicy.cli import main as skill_main

    return skill_main(argv, prog=prog)


if __name__ == "__main__":
    sys.exit(main())
