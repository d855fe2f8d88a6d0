"""A PettingZoo Parallel API loop with a random policy: 3v3 on the Division B field.

    python examples/pettingzoo_random.py [--seconds 10] [--seed 0]

Every agent (``blue_0`` .. ``yellow_2``) samples from its action space
(body-frame vx, vy, omega, dribbler, kick, all in [-1, 1]) each 1/60 s step; the
episode ends after ``--seconds`` simulated seconds. Prints the score, the number
of kicks and the ball's final position (field frame, m).
"""

from __future__ import annotations

import argparse

import numpy as np

from ssl_marl.envs import parallel_env


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seconds", type=float, default=10.0, help="simulated seconds (default 10)")
    p.add_argument("--seed", type=int, default=0, help="env and policy seed (default 0)")
    args = p.parse_args(argv)

    env = parallel_env(n_blue=3, n_yellow=3, field="div_b", max_time_s=args.seconds, realism="none")
    obs, infos = env.reset(seed=args.seed)
    for i, agent in enumerate(env.possible_agents):
        env.action_space(agent).seed(args.seed + i)
    steps, kicks, total_reward = 0, 0, {a: 0.0 for a in env.possible_agents}
    while env.agents:  # empty once the episode is over
        actions = {a: env.action_space(a).sample() for a in env.agents}
        obs, rewards, terminations, truncations, infos = env.step(actions)
        steps += 1
        for a, r in rewards.items():
            total_reward[a] += r
        kicks += sum(e["type"] == "kick" for e in next(iter(infos.values()), {}).get("events", []))
    ws = env.world_state()  # ground truth, field frame
    assert all(env.observation_space(a).contains(o) for a, o in obs.items())
    print(f"{steps} steps ({ws.t:.1f} s), score blue {env.score['blue']} - {env.score['yellow']} yellow, "
          f"{kicks} kicks, ball at ({ws.ball_pos[0]:+.2f}, {ws.ball_pos[1]:+.2f}) m, "
          f"obs shape {next(iter(obs.values())).shape}")
    env.close()
    return {"steps": steps, "score": dict(env.score), "kicks": kicks, "ball": np.asarray(ws.ball_pos).tolist()}


if __name__ == "__main__":
    main()
