"""Attack 3v2: three attackers (blue) against a goalie and a defender (yellow) on half a Division B field.

The engine task behind :class:`ssl_marl.decisions.attack.Attack3v2Env`: the
scene and the judge. Who does what (the attackers' options, the defence's tactics)
is the decision env's business; this task only reads the world.

Robots (field frame, blue attacks +x): ``blue_1..3`` are the attackers; ``blue_0`` is
the attacking team's goalie, parked in its own goal (x = -L/2 + 0.3 m) far from the
play (it keeps the passing play's team layout, where robot 0 is the goalie, and never
takes part); ``yellow_0`` is the goalie, ``yellow_1`` the defender. The task also binds to
a larger defence (``n_yellow`` 3-6, :data:`MAX_DEFENCE`; the match's defence of a 6v6 team:
:class:`~ssl_marl.decisions.attack_drill.AttackDrillDefendedEnv`): ``yellow_2`` a second
defender, ``yellow_3`` a robot pressing the ball, ``yellow_4`` / ``yellow_5`` marks on the two
attackers without the ball.

Start (:class:`AttackSpawn`, drawn from ``env.np_random``; distances along x are measured
from the +x goal line, so the attack is the same on any field: on Division B, L/2 = 4.5 m,
W/2 = 3 m, the x ranges below are those of the field frame; on Division A, L/2 = 6 m, they
lie 1.5 m farther up the field):

* the carrier: one of the three attackers (uniform), 2.0-4.0 m from the goal line (x in
  [0.5, 2.5] m on Division B), |y| <= 2.0 m,
  heading towards the goal centre +- 0.5 rad; the ball rests 0.12-0.30 m in front of
  its centre (at most 0.2 m from the face: "near an attacker", it has to take it);
* the two other attackers: 1.3-4.0 m from the goal line (x in [0.5, 3.2] m on Division B),
  |y| <= 2.6 m, at least 1.0 m from the
  carrier and each other, random heading;
* the goalie: on its goal line, x = L/2 - 0.25 m, |y| <= 0.3 m, facing the field;
* the defender: on the ball-goal segment at 40-70 % of the way from the ball, moved
  sideways by up to +-0.5 m, kept outside its defense area (x <= L/2 - 1.15 m) and at
  least 0.8 m from the ball, facing the ball;
* ``blue_0`` at (-L/2 + 0.3, 0), facing +x;
* with a larger defence (drawn after the above, so the first six robots are placed alike):
  the second defender 0.22-0.35 m beside the first, on the other side of the ball-goal line
  (its spacing on the lane in matches is 0.22 m); the presser 1.5-2.5 m from the ball, within
  +-1.0 rad of the ball-goal direction; each mark 0.35-0.8 m from its attacker towards the goal
  centre, moved sideways by up to +-0.3 m; every defender kept outside its defense area (as the
  first), stepped sideways (0.3 m at a time, up to 0.9 m) off a robot nearer than 0.25 m, and facing the ball.

Reset options ``{"robots": {...}, "ball": {...}}`` (as :mod:`.scene`) replace the draw
for constructed scenes; robots not named then take the kickoff formation.

End (checked after every control tick, in this order):

* ``"goal"``: the ball fully crossed the +x goal line between the posts (terminated;
  reward +1 to every blue robot: a team reward);
* ``"foul"`` (only with ``AttackRules.fouls``): an attacker commits one of SSL's fouls as the
  match's referee calls them (:class:`~ssl_marl.envs.game_control.TouchWatch`: the ball
  dribbled more than 1 m, ``excessive_dribbling``, or touched inside the goalie's defense area,
  ``attacker_in_defense_area``); the free kick would go to the defence, so the attack is over
  (terminated; event ``foul``). The defence's fouls are not called: a defender that gains the
  ball has ended the episode already;
* ``"lost_goalie"`` / ``"lost_defender"``: the ball is on that defender's dribbler (with
  ``AttackRules.contested_plays_on``: and on no attacker's), or (goalie) rests (< ``rest_speed``)
  inside the yellow defense area (terminated);
* ``"out"``: the ball fully left the field, or left the attacking half (x < 0)
  (terminated);
* ``"timeout"``: ``max_time_s`` (15 s) of play (truncated).

Reward 0 otherwise. ``goal`` (0/1) and ``outcome`` are the episode's score.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..game_control import TouchWatch, kicked_rows
from .base import Task
from .engine import Engine
from .scene import Scene, scene_from_options


OUTCOMES = ("goal", "lost_goalie", "lost_defender", "foul", "out", "timeout")
N_ATTACKERS = 3
#: the largest defence the task places (goalie, two defenders, a presser, two marks)
MAX_DEFENCE = 6
#: m: a placed defender moves off any robot whose centre is nearer than this
CLEAR_M = 0.25
ATTACKER_ROBOTS = ("blue_1", "blue_2", "blue_3")


@dataclass(frozen=True)
class AttackSpawn:
    """Spawn ranges (m, rad; module docstring). ``*_goal_dist``: (near, far) distance along x
    from the +x goal line (x = L/2 - distance); ``*_abs_y``: |y| in the field frame."""

    carrier_goal_dist: tuple[float, float] = (2.0, 4.0)
    carrier_abs_y: float = 2.0
    carrier_heading_noise: float = 0.5
    ball_ahead_m: tuple[float, float] = (0.12, 0.30)
    mate_goal_dist: tuple[float, float] = (1.3, 4.0)
    mate_abs_y: float = 2.6
    mate_spacing_m: float = 1.0
    goalie_inset_m: float = 0.25
    goalie_abs_y: float = 0.3
    defender_frac: tuple[float, float] = (0.4, 0.7)
    defender_side_m: float = 0.5
    defender_min_ball_m: float = 0.8
    defender_area_gap_m: float = 0.15
    parked_inset_m: float = 0.3
    second_defender_gap_m: tuple[float, float] = (0.22, 0.35)
    presser_ball_m: tuple[float, float] = (1.5, 2.5)
    presser_angle: float = 1.0
    mark_goal_side_m: tuple[float, float] = (0.35, 0.8)
    mark_side_m: float = 0.3


@dataclass(frozen=True)
class AttackRules:
    """Attributes:
        max_time_s: truncation after this much play (s).
        rest_speed: a ball slower than this (m/s) inside the yellow defense area is the goalie's.
        fouls: call the attackers' SSL fouls (outcome ``"foul"``, module docstring).
        contested_plays_on: a ball on a defender's dribbler ends the attack only while no
            attacker's dribbler holds it too (a contested ball plays on, as in matches); False:
            any defender's contact ends it (Attack 3v2).
    """

    max_time_s: float = 15.0
    rest_speed: float = 0.2
    fouls: bool = False
    contested_plays_on: bool = False


def _facing(q: np.ndarray, ball: np.ndarray) -> tuple[float, float, float]:
    """The pose (x, y, heading) of a robot at ``q`` facing ``ball`` (m, rad, field frame)."""
    return (q[0], q[1], math.atan2(ball[1] - q[1], ball[0] - q[0]))


class AttackTask(Task):
    """Attack 3v2's scene and judge (module docstring). Needs ``n_blue=4`` and ``n_yellow`` 2 (Attack 3v2)
    to :data:`MAX_DEFENCE`."""

    name = "attack_3v2"

    def __init__(self, rules: AttackRules | None = None, spawn: AttackSpawn | None = None) -> None:
        super().__init__()
        self.rules = rules or AttackRules()
        self.spawn = spawn or AttackSpawn()
        self.outcome: str | None = None
        self.goal = 0
        self.carrier_robot: str | None = None
        self.touch: TouchWatch | None = None
        self._event_mark = 0

    def bind(self, env: Engine) -> None:
        cfg = env.config
        if cfg.n_blue != N_ATTACKERS + 1 or not 2 <= cfg.n_yellow <= MAX_DEFENCE:
            raise ValueError(f"AttackTask needs n_blue=4 (a parked goalie and 3 attackers) and n_yellow 2-{MAX_DEFENCE} "
                             f"(a goalie and 1-{MAX_DEFENCE - 1} defenders), got n_blue={cfg.n_blue}, "
                             f"n_yellow={cfg.n_yellow}")
        super().bind(env)
        if self.rules.fouls:
            self.touch = TouchWatch(cfg.n_blue, cfg.n_yellow, cfg.robot.radius, cfg.ball.radius)

    # ------------------------------------------------------------------ start
    def reset_scene(self, env: Engine, options: dict) -> Scene:
        if options and ("robots" in options or "ball" in options):
            self.carrier_robot = None
            return scene_from_options(env, options, default_formation="kickoff")
        return self.random_scene(env)

    def random_scene(self, env: Engine) -> Scene:
        f, s, rng = env.field, self.spawn, env.np_random
        L2 = f.half_length
        goal = f.goal_center(+1)
        k = int(rng.integers(N_ATTACKERS))
        cx = rng.uniform(L2 - s.carrier_goal_dist[1], L2 - s.carrier_goal_dist[0])
        cy = rng.uniform(-s.carrier_abs_y, s.carrier_abs_y)
        ch = math.atan2(goal[1] - cy, goal[0] - cx) + rng.uniform(-s.carrier_heading_noise, s.carrier_heading_noise)
        d = rng.uniform(*s.ball_ahead_m)
        ball = np.array([cx + d * math.cos(ch), cy + d * math.sin(ch)])
        pose = np.zeros((len(env.possible_agents), 3))
        pose[0] = (-L2 + s.parked_inset_m, 0.0, 0.0)
        placed = [np.array([cx, cy])]
        mates = [j for j in range(N_ATTACKERS) if j != k]
        pose[1 + k] = (cx, cy, ch)
        for j in mates:
            for _ in range(200):
                p = np.array([rng.uniform(L2 - s.mate_goal_dist[1], L2 - s.mate_goal_dist[0]),
                              rng.uniform(-s.mate_abs_y, s.mate_abs_y)])
                if all(np.hypot(*(p - q)) >= s.mate_spacing_m for q in placed) and np.hypot(*(p - ball)) > 0.5:
                    break
            placed.append(p)
            pose[1 + j] = (p[0], p[1], rng.uniform(-math.pi, math.pi))
        gy = rng.uniform(-s.goalie_abs_y, s.goalie_abs_y)
        n_blue = N_ATTACKERS + 1
        pose[n_blue] = (L2 - s.goalie_inset_m, gy, math.pi)
        frac = rng.uniform(*s.defender_frac)
        u = goal - ball
        dist = float(np.hypot(*u))
        u = u / max(dist, 1e-9)
        normal = np.array([-u[1], u[0]])
        q = self._keep_out(f, ball + frac * dist * u + rng.uniform(-s.defender_side_m, s.defender_side_m) * normal)
        gap = float(np.hypot(*(q - ball)))
        if gap < s.defender_min_ball_m:  # push it along the ball-defender line (or the goal line of sight)
            v = (q - ball) / gap if gap > 1e-6 else u
            q = ball + s.defender_min_ball_m * v
            q[0] = min(q[0], L2 - f.defense_depth - s.defender_area_gap_m)
        for r in placed:  # do not stand on an attacker
            if np.hypot(*(q - r)) < CLEAR_M:
                q = q + 0.3 * normal
        pose[n_blue + 1] = _facing(q, ball)
        if len(pose) - n_blue > 2:
            self._place_more_defenders(env, pose, n_blue, ball, u, normal, placed[1:])
        self.carrier_robot = ATTACKER_ROBOTS[k]
        return Scene(pose, ball, np.zeros(2))

    def _keep_out(self, f, q: np.ndarray) -> np.ndarray:
        """``q`` (m, field frame) moved out of the +x defense area (``defender_area_gap_m`` before
        it) and 0.2 m inside the side lines, in place."""
        q[0] = min(q[0], f.half_length - f.defense_depth - self.spawn.defender_area_gap_m)
        q[1] = min(max(q[1], -f.half_width + 0.2), f.half_width - 0.2)
        return q

    def _place_more_defenders(self, env: Engine, pose: np.ndarray, n_blue: int, ball: np.ndarray, u: np.ndarray,
                              normal: np.ndarray, mates: list[np.ndarray]) -> None:
        """Rows ``n_blue + 2 ..`` of ``pose``: second defender, presser, marks on ``mates``
        (module docstring); ``u``: the unit vector from the ball to the goal centre, ``normal``: u turned left."""
        f, s, rng = env.field, self.spawn, env.np_random
        goal = f.goal_center(+1)
        first = pose[n_blue + 1, :2]
        side = -1.0 if float(np.dot(first - ball, normal)) > 0.0 else 1.0
        spots = [first + side * rng.uniform(*s.second_defender_gap_m) * normal]
        a = math.atan2(u[1], u[0]) + rng.uniform(-s.presser_angle, s.presser_angle)
        spots.append(ball + rng.uniform(*s.presser_ball_m) * np.array([math.cos(a), math.sin(a)]))
        for m in mates:
            v = goal - m
            v = v / max(float(np.hypot(*v)), 1e-9)
            spots.append(m + rng.uniform(*s.mark_goal_side_m) * v
                         + rng.uniform(-s.mark_side_m, s.mark_side_m) * np.array([-v[1], v[0]]))
        taken = [pose[i, :2].copy() for i in range(1, n_blue + 2)]
        for j, spot in enumerate(spots[:len(pose) - n_blue - 2]):
            best, best_gap = None, -1.0
            for step in (0.0, 0.3, -0.3, 0.6, -0.6, 0.9, -0.9):  # step sideways off a robot already placed
                q = self._keep_out(f, np.array(spot, float) + step * normal)
                gap = min(float(np.hypot(*(q - r))) for r in taken)
                if gap > best_gap:
                    best, best_gap = q, gap
                if gap >= CLEAR_M:
                    break
            taken.append(best)
            pose[n_blue + 2 + j] = _facing(best, ball)

    def start(self, env: Engine) -> None:
        self.outcome = None
        self.goal = 0
        self._scored = False
        if self.touch is not None:
            self.touch.reset()

    def begin_step(self, env: Engine) -> None:
        self._scored = False
        self._event_mark = 0

    def attacker_foul(self, env: Engine, events: list[dict]) -> str | None:
        """This tick's SSL foul of an attacker (its name), None without one or without ``rules.fouls``.
        Reads the step's kick events after the last call (``events``: the step's list)."""
        if self.touch is None:
            return None
        kicked = kicked_rows(events[self._event_mark:], env.agent_index)
        self._event_mark = len(events)
        w = env.world_state()
        foul = self.touch.update(w, self.touch.touching(w, kicked), env.field, True, kicked)
        if foul is None or self.touch.teams[foul[1]] != "blue":
            return None
        events.append({"type": "foul", "foul": foul[0], "team": "blue", "robot": int(foul[1]), "t": float(w.t)})
        return foul[0]

    # ------------------------------------------------------------------ judge
    def judge(self, env: Engine) -> str | None:
        """The outcome the world shows now (None: play on); module docstring."""
        w, f = env.world_state(), env.field
        r = env.config.ball.radius
        ball = np.asarray(w.ball_pos, float)
        side = f.in_goal(ball, r)
        if side > 0:
            return "goal"
        held = not (self.rules.contested_plays_on and bool(w.blue.ball_on_dribbler.any()))
        if held and bool(w.yellow.ball_on_dribbler[0]):
            return "lost_goalie"
        if held and w.yellow.n > 1 and bool(w.yellow.ball_on_dribbler[1:].any()):
            return "lost_defender"
        if (bool(f.in_defense_area(ball, +1)) and float(np.hypot(*w.ball_vel)) < self.rules.rest_speed):
            return "lost_goalie"
        if side < 0 or abs(ball[0]) >= f.half_length + r or abs(ball[1]) >= f.half_width + r or ball[0] < 0.0:
            return "out"
        if w.t >= self.rules.max_time_s - 1e-9:
            return "timeout"
        return None

    def after_tick(self, env: Engine, events: list[dict]) -> bool:
        if self.outcome is not None:
            return True
        out = self.judge(env)
        if out != "goal" and self.attacker_foul(env, events) is not None:
            out = "foul"
        if out is None:
            return False
        self.outcome = out
        if out == "goal":
            self.goal = 1
            self._scored = True
            events.append({"type": "goal", "team": "blue", "t": float(env.world_state().t)})
        return True

    def rewards(self, env: Engine) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
        g = 1.0 if self._scored else 0.0
        return ({a: (g if env.team_of(a) == "blue" else -g) for a in env.agents},
                {"blue": {"goal": g}, "yellow": {"goal": -g}})

    def end(self, env: Engine) -> tuple[bool, bool]:
        if self.outcome is None:
            return False, False
        return self.outcome != "timeout", self.outcome == "timeout"


__all__ = ["AttackTask", "AttackSpawn", "AttackRules", "OUTCOMES", "ATTACKER_ROBOTS", "N_ATTACKERS", "MAX_DEFENCE"]
