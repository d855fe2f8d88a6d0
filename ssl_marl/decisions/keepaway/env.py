"""Keepaway 3v2 as a decision-level PettingZoo ParallelEnv (:class:`KeepawayEnv`).

Scene, judge, square size and its justification: :mod:`ssl_marl.envs.tasks.keepaway`
(3 keepers = blue, 2 takers = yellow, 5 x 5 m square, end on taker control or the
ball leaving the square, truncation at 60 s, score = duration).

Agents ``keeper_0..2`` drive ``blue_0..2``. Options (``KeepawayEnv.option_names``):

* 0 ``hold``: keep the ball on the dribbler for ``hold_s`` (0.2 s), shielding it:
  the keeper faces and drifts (``hold_speed``, 0.5 m/s) away from the nearest taker,
  bent towards the square's centre near a side (turning at most ``hold_turn_rate``,
  the turn rate changed gently so the dribbler keeps the ball), so its body stays
  between the taker and the ball; then it decides again (if it still controls it).
* 1 ``pass_to_1`` / 2 ``pass_to_2``: pass to teammate ``(i + 1) % 3`` / ``(i + 2) % 3``
  (teammates ordered relative to self, as in the observation). The passer runs the
  project's :class:`~ssl_marl.plays.pass_tactic.Pass` tactic and the receiver the
  :class:`~ssl_marl.plays.receive_tactic.Receive` tactic on the point where it can
  stop when the pass is chosen (its position plus its braking distance at 3.6 m/s^2;
  clamped 0.4 m inside the square; the Receive tactic and
  its skills are given the square as their field, so the receive skill's cushion,
  which backs away along the ball's path, stops 0.25 m before the square's side
  instead of the field's); the passer kicks once
  the receiver reports READY (the handshake, ``receiver_ready``). The pass ends when a
  keeper controls the ball (the next decision point), when the Receive tactic gives
  up or the Pass tactic fails (ball loose, see below), or ``max_interval_s`` (4 s)
  after the choice.

All options are always legal (``action_mask`` all ones for the deciding keeper).

**Keeper control** (a decision point): the ball within ``control_m`` (35 mm, the
tactics' "near the dribbler") of the keeper's dribbler (d_{d-b}) and moving with it
(relative speed <= ``control_rel_speed`` = 0.5 m/s) for ``control_ticks`` (3) ticks
in a row, judged on the ground truth. Only a keeper that controls the ball and is
not executing an option decides: the flags are honest (one decider at most).

**Timing**: a step runs until a keeper decides, the episode ends, or
``max_interval_s`` passes. Reward per step = its simulated duration (the task gives
+dt per tick), so a keeper's undiscounted return equals the episode duration,
including the ticks before the first decision (the first keeper starts with the
ball, so it decides at t = 0).

What the keepers do between decisions and the fixed behaviours: :mod:`.keepers`; the
takers: :mod:`.takers`; observations and the global state: :mod:`.observation`;
benchmark policies: :mod:`.policies`; parameters: :mod:`.params`.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Mapping

import numpy as np

from ...envs.tasks.keepaway import KeepawayRules, KeepawayTask
from ...physics.field import FieldGeometry
from ...plays.pass_tactic import Pass, PassState
from ...plays.receive_tactic import Receive, ReceiveState
from ...skills.baseline import GoToBallBaseline
from ...skills.batched_features import dribbler_ball_distance_batch
from ...skills.navigation import NavigateToPoint
from ..base import DecisionEnv
from .keepers import KeeperBehaviours
from .observation import KeepawayObservation
from .params import HOLD, KeepawayParams
from .takers import TakerBehaviours


class KeepawayEnv(KeeperBehaviours, TakerBehaviours, KeepawayObservation, DecisionEnv):
    """Keepaway 3v2 (module docstring). Keyword arguments: see :class:`DecisionEnv`,
    plus ``rules`` (:class:`KeepawayRules`) and ``params`` (:class:`KeepawayParams`)."""

    metadata = {"name": "ssl_marl_keepaway_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}
    task_name = "keepaway"
    option_names = ("hold", "pass_to_1", "pass_to_2")
    agent_prefix = "keeper"
    n_agents = 3
    team = "blue"
    default_option = HOLD
    engine_observations = False  # observations from vision_state: skip the engine's per-robot pass

    def __init__(self, rules: KeepawayRules | None = None, params: KeepawayParams | None = None,
                 **kwargs: Any) -> None:
        self.rules = rules or KeepawayRules()
        self.params = params or KeepawayParams()
        super().__init__(**kwargs)
        cfg = self.engine.config
        self.rp, self.bp = cfg.robot, cfg.ball
        f, rp, bp, p = self.field, self.rp, self.bp, self.params
        self.pass_tactics = [Pass(f, rp, bp, skills=p.skills, dt=self.dt) for _ in range(3)]
        side = self.rules.side_m
        # the receivers (and their receive / go-to-ball skills) see the square as their field, so
        # the receive skill's cushion stops before the ball would leave the square (not the field)
        self.square = FieldGeometry(name="keepaway_square", length=side, width=side, goal_width=0.02,
                                    defense_width=0.02, defense_depth=0.02, boundary_width=0.3,
                                    center_circle_radius=0.5, max_robots_per_team=3)
        self.receive_tactics = [Receive(self.square, rp, bp, skills=p.skills, dt=self.dt) for _ in range(3)]
        for rt in self.receive_tactics:
            rt.nav.field = f
            rt.nav.params = dataclasses.replace(rt.nav.params, avoid_own_defense=False, avoid_opp_defense=False)
        self.keeper_fetch = [GoToBallBaseline(f, rp, bp) for _ in range(3)]
        self.keeper_nav = [NavigateToPoint(f, rp, bp, tolerance=0.05) for _ in range(3)]
        self.taker_chase = [GoToBallBaseline(f, rp, bp) for _ in range(2)]
        self.taker_nav = [NavigateToPoint(f, rp, bp, tolerance=0.05) for _ in range(2)]
        g = np.linspace(-1.0, 1.0, p.getopen_grid) * (self.rules.half - p.getopen_inset_m)
        self._grid = np.array([(x, y) for x in g for y in g])
        self._replan_ticks = max(1, int(round(p.getopen_replan_s / self.dt)))
        self._hold_ticks = max(1, int(round(p.hold_s / self.dt)))
        self._max_option_ticks = max(1, int(round(self.max_interval_s / self.dt)))
        self._half = self.rules.half

    # --------------------------------------------------------------- hooks
    def make_task(self) -> KeepawayTask:
        return KeepawayTask(self.rules)

    def engine_kwargs(self) -> dict:
        return {"n_blue": 3, "n_yellow": 2}

    def on_reset(self) -> None:
        for t in self.pass_tactics + self.receive_tactics:
            t.reset()
        self.holder: int | None = None  # keeper executing an option with the ball
        self.option: int | None = None
        self.option_ticks = 0
        self.receiver: int | None = None
        self.kicked = False
        self.fetcher: int | None = None
        self.chaser = 0
        self.block_target: int | None = None
        self.spots = np.zeros((3, 2))
        self._spot_age = self._replan_ticks  # re-plan on the first tick
        self._pos_cmd: dict = {}  # positioning commands (get-open, blocker), refreshed every positioning_every ticks
        self._ctrl_ticks = np.zeros(3, np.int64)
        self.option_counts = np.zeros(3, np.int64)
        self.passes_kicked = 0
        self.passes_completed = 0
        self._truth = self.engine.world_state()
        self._update_control()

    def decision_agents(self) -> frozenset[str]:
        if self.holder is not None:
            return frozenset()
        c = self.controller()
        return frozenset() if c is None else frozenset({self.possible_agents[c]})

    def start_options(self, chosen: Mapping[str, int]) -> None:
        for agent, opt in chosen.items():
            i = int(agent.rsplit("_", 1)[1])
            self.option_counts[opt] += 1
            self.holder, self.option, self.option_ticks = i, opt, 0
            self.fetcher = None
            if opt == HOLD:
                self.receiver = None
                continue
            r = (i + opt) % 3
            self.receiver, self.kicked = r, False
            w = self._truth
            h = self._half - self.params.receive_inset_m
            v = w.blue.vel[r]  # where the receiver can stop (braking at 3.6 m/s^2, 0.6 x the limit)
            point = np.clip(w.blue.pos[r] + v * (math.hypot(v[0], v[1]) / (2.0 * 0.6 * self.rp.max_brake)), -h, h)
            self.pass_tactics[i].reset()
            self.pass_tactics[i].set_params(target_robot=r, target_point=(float(point[0]), float(point[1])),
                                            receiver_ready=False, arrival_speed=self.params.pass_arrival_speed)
            self.receive_tactics[r].reset()
            self.receive_tactics[r].set_params(receive_point=(float(point[0]), float(point[1])),
                                               ball_from=(float(w.ball_pos[0]), float(w.ball_pos[1])))

    def after_tick(self) -> None:
        self._truth = self.engine.world_state()
        self._update_control()
        if self.holder is None:
            return
        self.option_ticks += 1
        i = self.holder
        if self.option == HOLD:
            if self.option_ticks >= self._hold_ticks:
                self._end_option()
            elif self._ctrl_ticks[i] == 0 and self._dribbler_distances()[i] > 0.05:
                self._end_option()  # ball lost while holding: loose
            return
        # a pass
        pt, rt = self.pass_tactics[i], self.receive_tactics[self.receiver]
        if not self.kicked:
            if pt.state is PassState.DONE:
                self.kicked = True
                self.passes_kicked += 1
            elif pt.state is PassState.FAILED or (pt.state is PassState.GET_BALL and pt.status.transitions > 0):
                self._end_option()  # handshake timed out / ball lost before the kick
                return
        if self.kicked:
            c = self.controller()
            if c is not None and c != i:
                self.passes_completed += int(c == self.receiver)
                self._end_option()
                return
            if rt.state is ReceiveState.FAILED or rt.state is ReceiveState.CONTROLLED:
                self._end_option()
                return
        if self.option_ticks >= self._max_option_ticks:
            self._end_option()

    def _end_option(self) -> None:
        self.holder, self.option, self.receiver, self.kicked = None, None, None, False

    # ------------------------------------------------------------- control
    def _dribbler_distances(self) -> np.ndarray:
        """(3,) m: each keeper's d_{d-b} (the skills' dribbler-ball distance)."""
        b, ball = self._truth.blue, self._truth.ball_pos
        return dribbler_ball_distance_batch(b.pos, b.heading, np.broadcast_to(ball, b.pos.shape), self.rp, self.bp)

    def _update_control(self) -> None:
        w, p = self._truth, self.params
        b = w.blue
        d = self._dribbler_distances()
        rel = np.sqrt(((w.ball_vel - b.vel) ** 2).sum(axis=1))
        ok = (d <= p.control_m) & (rel <= p.control_rel_speed)
        self._ctrl_ticks = np.where(ok, self._ctrl_ticks + 1, 0)
        if self.t == 0.0:  # the start: the first keeper's ball rests on its dribbler
            self._ctrl_ticks = np.where(ok, p.control_ticks, 0)

    def controller(self) -> int | None:
        """The keeper that controls the ball now (module docstring), or None."""
        n = self._ctrl_ticks
        if n.max() < self.params.control_ticks:
            return None
        return int(np.argmax(n))

    @property
    def phase(self) -> str:
        """"hold" (a keeper executes hold, or controls the ball), "pass" or "loose"."""
        if self.holder is not None:
            return "hold" if self.option == HOLD else "pass"
        return "hold" if self.controller() is not None else "loose"

    def episode_info(self) -> dict:
        task = self.task
        return {"outcome": task.outcome, "duration_s": float(task.duration_s),
                "options": {n: int(c) for n, c in zip(self.option_names, self.option_counts)},
                "passes_kicked": int(self.passes_kicked), "passes_completed": int(self.passes_completed)}


__all__ = ["KeepawayEnv"]
