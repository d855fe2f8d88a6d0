"""A scripted 6v6 match driven from Python, with a custom play for blue.

    python examples/custom_play_match.py [--seconds 20] [--seed 0] [--render match.gif]

Blue runs "all-out attack", a play written here: the goalie stays, one attacker
goes for the ball (the go-to-ball-and-shoot tactic, learned skills), and the other
four robots take ``Support`` roles spread across the opponent half, ready for a
pass or a rebound. Yellow runs the standard plays (kickoff / offense / defense)
with the hand-coded baseline skills. The loop is the plain PettingZoo one: each
tick both team controllers read what their team sees (``env.vision_state(team)``,
own goal at -x) and return ``{agent: action}``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from ssl_marl.envs import parallel_env
from ssl_marl.plays.play import Play, PlayContext, attacker_role, goalie_role, support_role
from ssl_marl.plays.team import TeamSpec, build_team


def all_out_attack_plays(*, ball, decider) -> tuple[Play, ...]:
    """The custom team's plays (a ``PlaysFactory``: ``ball`` and ``decider`` unused)."""
    return (all_out_attack(),)


def all_out_attack() -> Play:
    """Goalie, attacker, then up to four supports (higher priority = filled first)."""
    roles = (goalie_role(100), attacker_role(90)) + tuple(support_role(k, 80 - 10 * k) for k in range(4))

    def always(ctx: PlayContext) -> bool:  # applicable in every situation
        return True

    return Play("all_out_attack", always, roles, timeout_s=1e9)


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seconds", type=float, default=20.0, help="simulated seconds (default 20)")
    p.add_argument("--seed", type=int, default=0, help="env seed (default 0)")
    p.add_argument("--render", type=Path, default=None, help="also write a GIF of the match")
    args = p.parse_args(argv)

    env = parallel_env(n_blue=6, n_yellow=6, field="div_b", max_time_s=args.seconds, after_goal="kickoff",
                       render_mode="rgb_array" if args.render else None, render_width_px=480)
    blue = build_team(TeamSpec(plays=all_out_attack_plays, skills="learned"), "blue", 6, env.field,
                      robot=env.config.robot, ball=env.config.ball)
    yellow = build_team(TeamSpec(skills="baseline"), "yellow", 6, env.field, robot=env.config.robot,
                        ball=env.config.ball)
    env.reset(seed=args.seed, options={"formation": "kickoff"})
    frames, roles_seen, steps = [], set(), 0
    while env.agents:
        actions = {**blue.act(env), **yellow.act(env)}
        env.step(actions)
        roles_seen.update(blue.roles.values())
        steps += 1
        if args.render and steps % 6 == 0:  # 10 frames per simulated second
            frames.append(env.render())
    env.close()
    if args.render:
        from ssl_marl.envs.animation import write_animation

        write_animation(frames, args.render, fps=10)
    ball = np.asarray(env.world_state().ball_pos)
    print(f"{steps / 60:.0f} s: blue (all-out attack, learned) {env.score['blue']} - {env.score['yellow']} "
          f"yellow (standard plays, baseline); blue roles used: {sorted(roles_seen)}; "
          f"yellow plays used: {sorted(k for k, v in yellow.selector.summary().items() if v['selections'])}"
          + (f"; GIF -> {args.render}" if args.render else ""))
    return {"score": dict(env.score), "blue_roles": sorted(roles_seen), "ball": ball.tolist(), "steps": steps}


if __name__ == "__main__":
    main()
