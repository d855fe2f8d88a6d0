"""``ssl-marl demo``: one scripted episode on the full field, written to a GIF."""

from __future__ import annotations

import argparse

from ..envs.animation import VIDEO_SUFFIXES
from .options import FIELDS, positive_float, positive_int, robots


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``demo`` subparser."""
    d = subparsers.add_parser("demo", help="one scripted episode on the full field, written to a GIF",
                              description="Play one episode with scripted robots (baseline go-to-ball, then "
                                          "aim-to-shoot) on the full field and write it to a GIF.")
    d.add_argument("--robots", type=robots, default=6, help="robots per team, 1-11 (default 6)")
    d.add_argument("--field", choices=FIELDS, default="div_b", help="field geometry (default div_b)")
    d.add_argument("--seconds", type=positive_float("--seconds"), default=20.0, help="simulated seconds (default 20)")
    d.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    d.add_argument("--fps", type=positive_int("--fps"), default=20, help="GIF frames per second (default 20)")
    d.add_argument("--out", default="demo.gif",
                   help="output GIF/MP4 path; missing folders are created (default demo.gif)")
    d.add_argument("--quiet", action="store_true", help="no progress bar")
    d.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """A real episode on the full field with scripted robots, written to a GIF."""
    from tqdm import tqdm

    from ..envs import parallel_env
    from ..envs.animation import VideoSink
    from ..io import prepare_output_file
    from ..skills import SkillStatus, make_skill

    prepare_output_file(args.out, VIDEO_SUFFIXES, "--out")
    env = parallel_env(n_blue=args.robots, n_yellow=args.robots, field=args.field, max_time_s=args.seconds,
                       render_mode="rgb_array", render_trails=True,
                       render_team_labels={"blue": "scripted, baseline skills", "yellow": "scripted, baseline skills"})
    env.reset(seed=args.seed)
    skills = {a: (make_skill("go_to_ball", "baseline", env.field), make_skill("aim_to_shoot", "baseline", env.field))
              for a in env.possible_agents}
    aiming = {a: False for a in env.possible_agents}
    every = max(1, round(60 / args.fps))
    steps = int(round(args.seconds * 60))
    kicks = 0
    sink = VideoSink(args.out, args.fps)  # frames go to disk as they come (constant memory)
    for k in tqdm(range(steps), desc="demo", unit="step", disable=args.quiet):
        acts = {}
        for team in ("blue", "yellow"):
            ws = env.vision_state(team)
            for i in range(ws.team(team).n):
                agent = f"{team}_{i}"
                go, aim = skills[agent]
                if not aiming[agent] and bool(ws.team(team).ball_on_dribbler[i]):
                    aiming[agent] = True
                    aim.reset()
                acts[agent] = (aim if aiming[agent] else go).act(ws, i)
                if aiming[agent] and aim.status != SkillStatus.RUNNING:
                    aiming[agent] = False
        _, _, _, _, infos = env.step(acts)
        kicks += sum(ev["type"] == "kick" for ev in next(iter(infos.values()), {}).get("events", []))
        if k % every == 0:
            sink.add(env.render())
        if not env.agents:
            break
    sink.close()  # publish atomically; after an exception the sink deletes its partial file
    print(f"demo: {args.robots}v{args.robots} {args.field}, {env.world_state().t:.1f} s simulated, "
          f"score blue {env.score['blue']} - {env.score['yellow']} yellow, {kicks} kicks, GIF -> {args.out}")
    return 0
