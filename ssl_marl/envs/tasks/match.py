"""The full-field match: SSL referee, kickoffs, team rewards (the env's default task).

Start
    Kickoff formation with the ball on the centre mark (``randomize_reset``: robots and
    ball at random); reset options override (see :mod:`ssl_marl.envs.tasks.scene`).
Rules, after every control tick (``referee``, see :mod:`ssl_marl.envs.referee`)
    Goal: the scoring team's score + 1, event ``goal``; the step's remaining ticks are
    skipped. Ball out of play: event ``ball_out``; the ball is placed 0.2 m inside the
    field and robots within 0.5 m of it are moved out. No progress (the ball within
    0.25 m of one spot for ``no_progress_s``, default 10 s, the SSL referee's force
    start): event ``no_progress`` and the same restart at the ball's position.
Reward
    Shared by a team: sum over named terms x ``reward_scales``. ``goal``: +1 when the
    team scores, -1 when it concedes. ``ball_progress``: ball displacement towards the
    opponent goal / (L/2). ``possession``: +dt while a robot of the team holds the ball.
End
    Truncation when simulated time reaches ``max_time_s``; termination after a goal if
    ``after_goal == "terminate"``, otherwise the kickoff formation is placed and play
    goes on.
"""

from __future__ import annotations

import numpy as np

from ..config import MatchRules
from ..referee import NoProgressWatch, clear_robots_from, judge, kickoff_poses, placement_point
from .base import Task
from .engine import Engine
from .scene import Scene, scene_from_options

_WORLD = np.zeros(1, np.intp)  # the single env is world 0 of a one-world NoProgressWatch


class MatchTask(Task):
    """The full-field match (see the module docstring); ``rules`` default to the env's
    ``config.match`` (:class:`~ssl_marl.envs.config.MatchRules`)."""

    name = "match"

    def __init__(self, rules: MatchRules | None = None) -> None:
        super().__init__()
        self.rules = rules
        self.goal_for: str | None = None  #: team that scored in the current step
        self._prev_ball_x = 0.0
        self._watch: NoProgressWatch | None = None

    def bind(self, env: Engine) -> None:
        super().bind(env)
        if self.rules is None:
            self.rules = env.config.match

    def reset_scene(self, env: Engine, options: dict) -> Scene:
        return scene_from_options(env, options, "random" if self.rules.randomize_reset else "kickoff")

    def start(self, env: Engine) -> None:
        self.goal_for = None
        self._prev_ball_x = float(env.world_state().ball_pos[0])
        self._watch = NoProgressWatch(1, self.rules.no_progress_s)
        self._restart_watch(env)

    def _restart_watch(self, env: Engine) -> None:
        w = env.world_state()
        self._watch.restart(_WORLD, w.ball_pos[None, :], np.array([w.t]))

    def begin_step(self, env: Engine) -> None:
        self.goal_for = None

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        if not self.rules.referee:
            return False
        truth, f = env.world_state(), env.field
        call = judge(truth, f, env.config.ball.radius)
        if call.goal_for is not None:
            env.award_goal(call.goal_for, events)
            self.goal_for = call.goal_for
            return True
        if call.ball_out:
            events.append({"type": "ball_out", "t": truth.t, "placement": call.placement.tolist()})
            self._restart_play(env, call.placement)
        elif self._watch.update(_WORLD, truth.ball_pos[None, :], np.array([truth.t]))[0]:
            place = placement_point(truth.ball_pos, f)
            events.append({"type": "no_progress", "t": truth.t, "placement": place.tolist()})
            self._restart_play(env, place)
        return False

    def _restart_play(self, env: Engine, place: np.ndarray) -> None:
        """Ball at ``place`` (m, at rest), robots within 0.5 m of it moved out."""
        pose = env.robot_poses()
        new_pos = clear_robots_from(place, pose[:, 0:2], env.field)
        moved = np.flatnonzero(np.any(new_pos != pose[:, 0:2], axis=1))
        if moved.size:
            pose[moved, 0:2] = new_pos[moved]
            env.place_robots(pose, only=moved)
        env.place_ball(place)
        self._prev_ball_x = float(env.world_state().ball_pos[0])
        self._restart_watch(env)

    def rewards(self, env: Engine) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
        scales = self.rules.reward_scales
        truth = env.world_state()
        bx = float(truth.ball_pos[0])
        progress = (bx - self._prev_ball_x) / env.field.half_length
        self._prev_ball_x = bx
        possess = {"blue": bool(truth.blue.ball_on_dribbler.any()), "yellow": bool(truth.yellow.ball_on_dribbler.any())}
        terms = {}
        for team, sgn in (("blue", 1.0), ("yellow", -1.0)):
            goal = 0.0 if self.goal_for is None else (1.0 if self.goal_for == team else -1.0)
            terms[team] = {"goal": scales["goal"] * goal,
                           "ball_progress": scales["ball_progress"] * sgn * progress,
                           "possession": scales["possession"] * (env.config.dt if possess[team] else 0.0)}
        team_reward = {team: float(sum(t.values())) for team, t in terms.items()}
        return {a: team_reward[env.team_of(a)] for a in env.agents}, terms

    def end(self, env: Engine) -> tuple[bool, bool]:
        terminated = self.goal_for is not None and self.rules.after_goal == "terminate"
        truncated = (env.world_state().t >= self.rules.max_time_s - 1e-9) and not terminated
        return terminated, truncated

    def after_step(self, env: Engine, terminated: bool, truncated: bool) -> None:
        if self.goal_for is not None and not terminated:  # kickoff
            env.place_robots(kickoff_poses(env.field, env.config.n_blue, env.config.n_yellow))
            env.place_ball(np.zeros(2))
            self._prev_ball_x = 0.0
            self._restart_watch(env)
