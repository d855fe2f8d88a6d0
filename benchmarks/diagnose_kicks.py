"""Why does a learned aim-to-shoot actor fail? Failures tallied with the strength of its kick.

    python benchmarks/diagnose_kicks.py ACTOR.pt [--episodes 300] [--seed 5000] [--kick-action strength|full]

Runs the actor on the aim-to-shoot task (ideal conditions, episode ``i`` seeded with
``episode_seed(seed, i)`` as in ``ssl-marl eval-skill``) and prints JSON: success
rate, failure reasons, and for every failed episode that kicked, the kick strength
the actor asked for. ``--kick-action`` overrides the mapping stored in the
checkpoint's spec (e.g. to see how a strength-action actor would do if every
positive kick were a full-strength one).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ssl_marl.io import episode_seed  # noqa: E402
from ssl_marl.skills.features import kick_action_of_spec  # noqa: E402
from ssl_marl.skills.learned import load_policy  # noqa: E402
from ssl_marl.skills.wrappers import AimToShootEnv  # noqa: E402


def diagnose(actor: str, episodes: int = 300, seed: int = 5000, kick_action: str | None = None) -> dict:
    policy, meta = load_policy("aim_to_shoot", actor)
    kick_action = kick_action or kick_action_of_spec(meta["obs_spec"])
    env = AimToShootEnv(kick_action=kick_action)
    reasons: Counter[str] = Counter()
    failed_kicks: list[float] = []
    successes = 0
    for i in range(episodes):
        obs, _ = env.reset(seed=episode_seed(seed, i))
        kick_strength = None
        while True:
            action = policy(obs)
            obs, _, terminated, truncated, info = env.step(action)
            if kick_strength is None and info["kicked"]:
                kick_strength = float(action[2]) if kick_action == "strength" else 1.0
            if terminated or truncated:
                break
        if info["is_success"]:
            successes += 1
            continue
        reasons[info["failure_reason"]] += 1
        if kick_strength is not None:
            failed_kicks.append(round(kick_strength, 3))
    weak = [k for k in failed_kicks if k < 0.5]
    return {"actor": actor, "kick_action": kick_action, "episodes": episodes, "seed": seed,
            "success_rate": successes / episodes, "failure_reasons": dict(reasons),
            "failed_kick_strengths": sorted(failed_kicks), "failed_kicks_below_half_strength": len(weak)}


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="python benchmarks/diagnose_kicks.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("actor", help="aim-to-shoot actor file")
    p.add_argument("--episodes", type=int, default=300, help="episodes to run")
    p.add_argument("--seed", type=int, default=5000, help="episode seed base (5000 = validation)")
    p.add_argument("--kick-action", choices=("strength", "full"), default=None,
                   help="kick mapping to apply (default: the one the checkpoint was trained with)")
    a = p.parse_args(argv)
    print(json.dumps(diagnose(a.actor, a.episodes, a.seed, a.kick_action), indent=1))


if __name__ == "__main__":
    main()
