"""Attack 3v2: the ball carrier's shoot / pass / dribble decision as a PettingZoo task.

:class:`Attack3v2Env` is a :class:`~ssl_marl.decisions.base.DecisionEnv` over the
engine with :class:`~ssl_marl.envs.tasks.attack.AttackTask` (scene and judge: spawn
ranges, outcomes, 15 s, reward +1 for a goal, all documented there). Agents
``attacker_0..2`` drive ``blue_1..3`` (``blue_0`` is the attacking team's goalie,
parked in its own goal: the passing play's team layout, robot 0 = goalie).

**Who plays what.** The attackers are one :class:`~ssl_marl.plays.team.TeamController`
running the passing play's roles (:mod:`ssl_marl.plays.passing_roles`: attacker,
passer / receiver with the handshake, two supports that move to open spots rated by
their pass lanes, the goalie) with the play's :class:`~ssl_marl.plays.pass_coordinator.PassCoordinator`;
the only change from a match is that the coordinator's carrier decision comes from the
agents (the :class:`~ssl_marl.plays.pass_coordinator.CarrierDecider` hook) and that it asks
every tick (``decide_every=1``, matches: 3) so a decision is not delayed. The defence
is a TeamController with the project's :class:`~ssl_marl.plays.defense.Goalie` and
:class:`~ssl_marl.plays.defense.Defender` tactics (``goalie_role``, ``defender_role``).
Both teams use ``skills`` (default "learned": the shipped actors where they exist,
as the passing-learned team).

**Decision points.** When the passing play asks for the carrier's decision (the carrier
has settled the ball on its dribbler: attacker state KEEP or AIM_TO_SHOOT, no pass
running), the carrier's agent gets ``infos[agent]["decision"] = True`` with the legal
options; its observation at that step is the one computed on the world the play asked
on (:func:`~ssl_marl.decisions.attack_features.attack_observation`, the same function
as in matches). Until the next step the carrier holds its previous dribble (one tick).
The chosen option becomes the play's decision
(:func:`~ssl_marl.decisions.attack_features.option_decision`): ``shoot`` (the attacker
aims and kicks), ``pass_1`` / ``pass_2`` (a pass plan to that teammate slot: passer
and receiver tactics, the receiver's READY before the kick), ``dribble_goal`` /
``dribble_left`` / ``dribble_right`` (the attacker's KEEP towards the option's point at
0.5 m/s for 0.6 s). After a shot the ball is loose until the episode ends or an
attacker settles it again; after a completed pass the receiver settles and decides.

Only one agent decides at a time (the carrier). Options, observation (40 values) and
mask: :mod:`ssl_marl.decisions.attack_features`. An illegal option (a pass whose mask
entry is 0) raises ValueError (``illegal_option="raise"``) or becomes ``shoot``
(``illegal_option="default"``; shoot is always legal).

**State** (:meth:`Attack3v2Env.global_state`, 36 values for a centralised critic):
per attacker (x / (L/2), y / (W/2), cos, sin, vx / 3, vy / 3, ball on its dribbler),
goalie and defender (x, y, vx, vy, scaled alike; 4 values more for each further defender
of a larger defence, ``n_defence``), the ball (x, y, vx / 6.5, vy / 6.5),
the shot value from the ball, elapsed time / 15 s, and whether a pass is running.

**Benchmark.** :class:`HandcodedAttackPolicy` is the passing play's cost decision
(:class:`~ssl_marl.plays.pass_coordinator.CostDecider`, the same function as in matches)
on the same request, mapped to the options: SHOOT -> shoot, PASS to k -> the slot of
k, KEEP -> ``dribble_goal`` (the match's KEEP creeps towards the goal too); as in the
play, a carrier that has kept the ball for more than ``max_keep_s`` (0.8 s) shoots.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Any, Mapping

import numpy as np

from ..envs.tasks.attack import ATTACKER_ROBOTS, N_ATTACKERS, AttackRules, AttackSpawn, AttackTask
from ..plays.pass_decision import Choice, Decision
from ..physics.params import BallParams
from ..plays.pass_coordinator import CarrierDecider, CarrierRequest, CostDecider, PassCoordinator, PassingParams
from ..plays.passing_play import PrepareHook, coordinator_of
from ..plays.passing_roles import passer_role, passing_attacker_role, passing_support_role, receiver_role
from ..plays.play import Play, defender_role, goalie_role
from ..plays.skillset import TEAM_SKILLS, team_skill_set
from ..plays.team import TeamSpec, build_team
from ..plays.pass_decision import shot_value
from .attack_features import (ATTACK_OBS_DIM, ATTACK_OPTIONS, OBS_BOUND, SHOOT, attack_action_mask,
                              attack_observation, decision_option, option_decision)
from .base import DecisionEnv

STATE_DIM = 36
STALE_REQUEST_S = 0.1  # s: an answer is dropped if the play has not taken it within this time


class DrillDecider:
    """The drill's :class:`~ssl_marl.plays.pass_coordinator.CarrierDecider`: records the
    play's request for the env (the agent answers at its next step) and hands the
    answer to the play on the next tick; until then the carrier holds its dribble. An
    answer may carry a payload for the play's roles (:meth:`accept`)."""

    def __init__(self) -> None:
        self.coordinator: PassCoordinator | None = None
        self.reset()

    def reset(self) -> None:
        self.request: CarrierRequest | None = None
        self.answer: tuple[int, float, Decision, Any] | None = None  # (carrier, request time, decision, payload)

    def accept(self, payload: Any) -> None:
        """The answer's payload reaches the play with its decision (nothing to hand on here)."""

    def decide(self, request: CarrierRequest) -> Decision:
        if self.answer is not None:
            carrier, t_req, d, payload = self.answer
            self.answer = None
            if carrier == request.carrier and request.t - t_req <= STALE_REQUEST_S + 1e-9:
                self.request = None
                self.accept(payload)
                return d
        self.request = request
        cur = self.coordinator.decision if self.coordinator is not None else None
        if cur is not None and cur.choice is Choice.KEEP:  # hold the dribble until the answer comes
            return dataclasses.replace(cur, commit_s=0.0)
        return Decision(Choice.KEEP, 0.0, 0.0, dribble_speed=0.0)

    def answer_with(self, decision: Decision, payload: Any = None) -> None:
        req = self.request
        if req is None:
            raise RuntimeError(f"{type(self).__name__}: no request to answer")
        self.answer = (req.carrier, req.t, decision, payload)
        self.request = None


def drill_attack_play(coord: PassCoordinator) -> Play:
    """The attackers' one play: the passing play's offense roles (goalie, passer,
    receiver, attacker, two supports), always applicable."""
    roles = (goalie_role(100), passer_role(coord, 95), receiver_role(coord, 94), passing_attacker_role(coord, 90),
             passing_support_role(0, 80), passing_support_role(1, 70))
    return Play("attack_3v2", lambda ctx: True, roles, prepare=PrepareHook(coord))


def drill_defence_play() -> Play:
    """The defence's one play: goalie and one defender, always applicable."""
    return Play("defence_2", lambda ctx: True, (goalie_role(100), defender_role(0, 80)))


def drill_attack_plays(passing: PassingParams, *, ball: BallParams | None,
                       decider: CarrierDecider | None) -> tuple[Play, ...]:
    """The attackers' plays (a :class:`~ssl_marl.plays.team.PlaysFactory` once
    ``passing`` is bound): :func:`drill_attack_play` with a new coordinator."""
    return (drill_attack_play(PassCoordinator(passing, ball, decider)),)


def drill_defence_plays(*, ball: BallParams | None, decider: CarrierDecider | None) -> tuple[Play, ...]:
    """The defence's plays (a :class:`~ssl_marl.plays.team.PlaysFactory`): :func:`drill_defence_play`."""
    return (drill_defence_play(),)


class CarrierRequestHooks:
    """:class:`~ssl_marl.decisions.base.DecisionEnv` hooks of the drills whose decision point is
    the play's open carrier request (``self.decider.request``): the carrier's agent decides
    when the carrier is a field robot 1..``n_agents``, with the observation and mask of
    :meth:`request_features`, computed once per request."""

    _request_obs: np.ndarray | None
    _request_mask: np.ndarray | None

    @property
    def pending_request(self) -> CarrierRequest | None:
        """The play's open request for the carrier's decision (None: nobody decides)."""
        return self.decider.request

    def request_features(self, req: CarrierRequest) -> tuple[np.ndarray, np.ndarray]:
        """(observation, legal-option mask) of the carrier's agent for request ``req``."""
        raise NotImplementedError

    def decision_agents(self) -> frozenset[str]:
        req = self.decider.request
        if req is None or not 1 <= req.carrier <= self.n_agents:
            return frozenset()
        self._request_obs, self._request_mask = self.request_features(req)
        return frozenset({self.agent_of(req.carrier)})

    def action_mask(self, agent: str) -> np.ndarray:
        return self._request_mask


class Attack3v2Env(CarrierRequestHooks, DecisionEnv):
    """Attack 3v2 (module docstring).

    Args:
        skills: "learned" (default) or "baseline": both teams' skills.
        rules, spawn: :class:`~ssl_marl.envs.tasks.attack.AttackRules` / ``AttackSpawn``.
        passing: the attackers' :class:`~ssl_marl.plays.pass_coordinator.PassingParams`
            (default: the match's, with ``decide_every=1``).
        kwargs: :class:`~ssl_marl.decisions.base.DecisionEnv` options (field,
            realism, max_interval_s, illegal_option, render_mode).
    """

    task_name = "attack-3v2"
    option_names = ATTACK_OPTIONS
    agent_prefix = "attacker"
    n_agents = N_ATTACKERS
    team = "blue"
    default_option = SHOOT
    #: yellow robots: the goalie and the defender (a subclass may field the match's defence)
    n_defence = 2
    #: the skills the attackers' tactics build (those of the passing plays); the defence builds the passing team's
    attacker_skills: tuple[str, ...] = TEAM_SKILLS

    def __init__(self, skills: str = "learned", rules: AttackRules | None = None, spawn: AttackSpawn | None = None,
                 passing: PassingParams | None = None, **kwargs: Any) -> None:
        self.skills = team_skill_set(skills, self.attacker_skills, where=type(self).__name__)
        self.defence_skills = team_skill_set(skills, where=type(self).__name__)
        self.skills_kind = skills
        self.rules, self.spawn = rules or AttackRules(), spawn or AttackSpawn()
        self.passing = passing or PassingParams(decide_every=1)
        super().__init__(**kwargs)
        cfg = self.engine.config
        self.rp, self.bp = cfg.robot, cfg.ball
        self.decision_params = self.passing.decision
        self.decider = self.make_decider()
        attack = TeamSpec(plays=self.attack_plays_factory(), skills=self.skills, decider=self.decider)
        self.blue = build_team(attack, "blue", N_ATTACKERS + 1, self.field, self.rp, self.bp, dt=self.dt)
        self.coordinator = coordinator_of(self.blue.selector.plays)
        self.decider.coordinator = self.coordinator
        self.yellow = build_team(TeamSpec(plays=self.defence_plays_factory(), skills=self.defence_skills), "yellow",
                                 self.n_defence, self.field, self.rp, self.bp, dt=self.dt)
        self._request_obs: np.ndarray | None = None
        self._request_mask: np.ndarray | None = None

    # ------------------------------------------------------------ hooks
    def make_decider(self) -> DrillDecider:
        """The attackers' carrier decider, answered by the agents."""
        return DrillDecider()

    def attack_plays_factory(self) -> Any:
        """The attackers' :class:`~ssl_marl.plays.team.PlaysFactory` (``ball``, ``decider`` keywords)."""
        return functools.partial(drill_attack_plays, self.passing)

    def defence_plays_factory(self) -> Any:
        """The defence's :class:`~ssl_marl.plays.team.PlaysFactory` (``ball``, ``decider`` keywords)."""
        return drill_defence_plays

    def make_task(self) -> AttackTask:
        return AttackTask(self.rules, self.spawn)

    def engine_kwargs(self) -> dict:
        return {"n_blue": N_ATTACKERS + 1, "n_yellow": self.n_defence}

    def agent_robot(self, agent: str) -> str:
        return ATTACKER_ROBOTS[int(agent.rsplit("_", 1)[1])]

    def robot_index(self, agent: str) -> int:
        """The attacker's robot index in the blue team (1..3)."""
        return int(agent.rsplit("_", 1)[1]) + 1

    def agent_of(self, robot: int) -> str:
        return f"{self.agent_prefix}_{robot - 1}"

    def on_reset(self) -> None:
        self.decider.reset()
        self.blue.reset()
        self.yellow.reset()
        self._request_obs = self._request_mask = None

    def request_features(self, req: CarrierRequest) -> tuple[np.ndarray, np.ndarray]:
        args = (req.ctx.world, "blue", req.carrier, self.field, self.rp, self.bp, req.params)
        return (attack_observation(*args, candidates=req.candidates),
                attack_action_mask(*args, candidates=req.candidates))

    def start_options(self, chosen: Mapping[str, int]) -> None:
        req = self.decider.request
        for agent, option in chosen.items():
            d = option_decision(option, req.ctx.world, "blue", req.carrier, self.field, self.rp, self.bp, req.params,
                                candidates=req.candidates)
            self.decider.answer_with(d)

    def tick_actions(self) -> dict[str, np.ndarray]:
        actions = self.blue.act(self.engine)
        actions.update(self.yellow.act(self.engine))
        return actions

    def observe(self) -> dict[str, np.ndarray]:
        world = self.engine.vision_state("blue")
        out = {}
        for a in self.possible_agents:
            if a in self._deciding and self._request_obs is not None:
                out[a] = self._request_obs
            else:
                out[a] = attack_observation(world, "blue", self.robot_index(a), self.field, self.rp, self.bp,
                                            self.decision_params)
        return out

    def observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(ATTACK_OBS_DIM, -OBS_BOUND, np.float32), np.full(ATTACK_OBS_DIM, OBS_BOUND, np.float32)

    def global_state(self) -> np.ndarray:
        w = self.engine.vision_state("blue")
        L2, W2, sv, bv = self.field.half_length, self.field.half_width, self.rp.max_speed, self.rp.kick_speed_max
        s = np.zeros(self.state_dim)
        b, y = w.blue, w.yellow
        for j in range(N_ATTACKERS):
            k = j + 1
            h = float(b.heading[k])
            s[7 * j:7 * j + 7] = (b.pos[k, 0] / L2, b.pos[k, 1] / W2, math.cos(h), math.sin(h), b.vel[k, 0] / sv,
                                  b.vel[k, 1] / sv, float(bool(b.ball_on_dribbler[k])))
        for j in range(y.n):
            s[21 + 4 * j:25 + 4 * j] = (y.pos[j, 0] / L2, y.pos[j, 1] / W2, y.vel[j, 0] / sv, y.vel[j, 1] / sv)
        i = 21 + 4 * y.n
        s[i:i + 4] = (w.ball_pos[0] / L2, w.ball_pos[1] / W2, w.ball_vel[0] / bv, w.ball_vel[1] / bv)
        s[i + 4] = shot_value(w.ball_pos, y.pos, b.pos[1:], self.field, self.rp, self.bp, self.decision_params)
        s[i + 5] = self.t / self.rules.max_time_s
        s[i + 6] = float(self.coordinator.active)
        return np.clip(s, -OBS_BOUND, OBS_BOUND).astype(np.float32)

    @property
    def state_dim(self) -> int:
        """Length of :meth:`global_state`: :data:`STATE_DIM` with two defenders, 4 more per further defender."""
        return STATE_DIM + 4 * (self.n_defence - 2)

    def state_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(self.state_dim, -OBS_BOUND, np.float32), np.full(self.state_dim, OBS_BOUND, np.float32)

    def episode_info(self) -> dict:
        return {"outcome": self.task.outcome, "goal": int(self.task.goal)}


class KeepClock:
    """The play's ``max_keep_s`` rule for a hand-coded decision policy: a carrier that has
    kept (dribbled) the ball for more than ``max_keep_s`` since its first keep shoots."""

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self._keep_since: float | None = None
        self._carrier: int | None = None

    def expired(self, carrier: int, t: float, keeping: bool, max_keep_s: float) -> bool:
        """Record the decision of ``carrier`` at time ``t`` (s; ``keeping``: a keep / dribble);
        True when a keep has lasted longer than ``max_keep_s``."""
        if carrier != self._carrier:
            self._carrier, self._keep_since = carrier, None
        if not keeping:
            self._keep_since = None
            return False
        if self._keep_since is None:
            self._keep_since = t
        return t - self._keep_since > max_keep_s


class HandcodedCarrierPolicy:
    """A hand-coded carrier-decision policy of the attack drills: :meth:`choose` maps the
    play's open request to an option; as in the play, a carrier that has kept (dribbled)
    the ball for more than ``max_keep_s`` (default the env's ``passing.max_keep_s``) shoots,
    and an option the mask refuses becomes a shot (option 0 in both drills)."""

    name = "handcoded"

    def __init__(self, max_keep_s: float | None = None) -> None:
        self.max_keep_s = max_keep_s
        self.clock = KeepClock()

    def reset(self, env: Any) -> None:
        self.clock.reset()

    def choose(self, env: Any, request: CarrierRequest) -> tuple[int, bool]:
        """(option, whether it keeps the ball) for ``request``."""
        raise NotImplementedError

    def act(self, env: Any, agent: str, obs: np.ndarray, info: dict) -> int:
        req = env.pending_request
        if req is None:
            raise ValueError(f"{type(self).__name__}: agent {agent!r} has no open decision request")
        option, keeping = self.choose(env, req)
        max_keep = self.max_keep_s if self.max_keep_s is not None else env.passing.max_keep_s
        if self.clock.expired(req.carrier, req.t, keeping, max_keep):
            option = SHOOT
        mask = info.get("action_mask")
        if mask is not None and not mask[option]:
            return SHOOT
        return option


class HandcodedAttackPolicy(HandcodedCarrierPolicy):
    """The passing play's cost decision as an Attack 3v2 policy (module docstring)."""

    def __init__(self, max_keep_s: float | None = None) -> None:
        super().__init__(max_keep_s)
        self.cost = CostDecider()

    def choose(self, env: Any, request: CarrierRequest) -> tuple[int, bool]:
        d = self.cost.decide(request)
        return decision_option(d, request.ctx.world, "blue", request.carrier), d.choice is Choice.KEEP


__all__ = ["Attack3v2Env", "CarrierRequestHooks", "HandcodedAttackPolicy", "HandcodedCarrierPolicy", "KeepClock", "DrillDecider",
           "drill_attack_play", "drill_defence_play",
           "drill_attack_plays", "drill_defence_plays", "STATE_DIM"]
