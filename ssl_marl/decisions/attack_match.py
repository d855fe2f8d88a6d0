"""Full matches as a decision task: the attacking team's carrier decisions against opponents drawn from a league.

:class:`AttackMatchEnv` is a :class:`~ssl_marl.decisions.base.DecisionEnv` over the full-field
match (:class:`~ssl_marl.envs.tasks.match.MatchTask`: referee, kickoffs after goals, no-progress
restarts with seeded placement; chip kicks on). Blue is the attacking team
(:mod:`ssl_marl.plays.attack_play`, with ``skills``); the carrier decisions of its open play are
the agents' (``attacker_0..n-2`` drive ``blue_1..blue_{n-1}``; ``blue_0`` is the goalie and never
carries), everything else (set pieces, supports, defence) is the play's own. Options, mask and
observation are those of the attack drill (:mod:`ssl_marl.decisions.attack_drill_features`), so
an actor trained in the drill continues here and plays the same way in ``ssl-marl match``
(:class:`~ssl_marl.decisions.match_decider.PolicyAttackDecider`).

* **Decision points.** The attacking plays' coordinator asks for the carrier's decision at its
  match rate (``ATTACK_PASSING``, every 3rd tick once the carrier has settled the ball); the
  carrier's agent decides at its next step, and its option reaches the play on the coordinator's
  next request (at most 3 ticks, 50 ms, later; until then the carrier holds the ball). Restarts
  stay with the cost decision, as in matches.
* **Observations.** The deciding agent gets the drill's 48 values; the others get the 40 values
  of :func:`~ssl_marl.decisions.attack_features.attack_observation` and zeros for the pass values
  (their observations are not used to decide; :class:`~ssl_marl.decisions.attack_drill.AttackOptionsMixin`).
* **Reward.** The match task's team reward (``reward_scales``, default goals only): +1 to every
  blue agent for a goal scored, -1 for one conceded. An episode is ``seconds`` of play (default
  120 s, truncated); its score is the goal difference (``goal_diff``), reported with
  ``goals_for``, ``goals_against`` and ``opponent``.
* **Opponents: a league with prioritized fictitious self-play.** ``opponents`` names the yellow
  teams (``{name: TeamSpec}``, e.g. the hand-coded anchors). With ``pfsp`` each reset draws one
  with probability proportional to ``(1 - p) ** 2`` (:mod:`ssl_marl.decisions.pfsp`, "hard"),
  ``p`` this env's estimate of its chance to beat it (wins, draws 0.5, with a one-win-one-loss
  prior), so harder opponents come more often; without it, uniformly.
  ``snapshot_dir`` adds the learner's own snapshots: the actors of a MAPPO run folder's
  ``val.csv`` whose validation score beat every earlier one (the last ``max_snapshots``), each
  playing the attacking plays with that decision. Episodes are deterministic under the seed for a
  given opponent; the draw depends on this env's earlier results.
* **Rules.** The plain format by default; ``ssl_rules`` plays SSL game control (commands, free
  kicks, fouls) with the learned decider's dribble mask, so what is learned is what plays in
  ``ssl-marl match --format ssl``.
* **State** (:meth:`global_state`, ``4 + 8 n + 2`` values): the ball (x, y, vx, vy), every robot
  of both teams (x, y, vx, vy), the goal difference / 5 and the elapsed fraction.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..envs.game_control import SSL_GAME_CONTROL
from ..envs.referee import match_start_options
from ..envs.tasks.match import MatchTask
from ..plays.attack_decision import AttackParams
from ..plays.attack_play import AttackDecider, attack_plays
from ..plays.pass_coordinator import CarrierRequest
from ..plays.pass_decision import Decision
from ..plays.passing_play import coordinator_of
from ..plays.skillset import ATTACK_SKILLS, team_skill_set
from ..plays.team import TeamController, TeamSpec, build_team
from .attack_drill import AttackOptionsMixin, DrillAttackDecider
from .attack_drill_features import ATTACK_DRILL_OPTIONS, SHOOT, SlotPasses
from .attack_features import OBS_BOUND
from .base import DecisionEnv
from . import long_shot
from .dribble_limit import DRIBBLE_MASK_M
from .pfsp import pfsp_weights, win_probability

class MatchAttackDecider(DrillAttackDecider):
    """:class:`~ssl_marl.decisions.attack_drill.DrillAttackDecider` for matches: restarts
    (set pieces) are decided by the cost decision, open play by the agents."""

    def decide(self, request: CarrierRequest) -> Decision:
        if request.restart or not request.on_ball:
            return AttackDecider.decide(self, request)
        return super().decide(request)


def improving_snapshots(run_dir: str | Path, max_snapshots: int = 3) -> list[Path]:
    """The actors of a MAPPO run folder whose validation score beat every earlier one
    (``val.csv``), the last ``max_snapshots`` of them; [] while there is none."""
    path = Path(run_dir) / "val.csv"
    if not path.is_file():
        return []
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    best, out = -math.inf, []
    for r in rows:
        score = float(r["val_score"])
        if score > best and (Path(run_dir) / r["actor"]).is_file():
            best = score
            out.append(Path(run_dir) / r["actor"])
    return out[-max_snapshots:] if max_snapshots > 0 else []


class AttackMatchEnv(AttackOptionsMixin, DecisionEnv):
    """Full matches as the attacking team's decision task (module docstring).

    Args:
        opponents: ``{name: TeamSpec or a callable returning one}``: the yellow league (at
            least one).
        skills: the blue attacking team's skills ("learned" or "baseline").
        robots: robots per team (2-11).
        seconds: simulated seconds per episode.
        pfsp: draw opponents by prioritized fictitious self-play (else uniformly).
        snapshot_dir, max_snapshots: the learner's improving snapshots as further opponents.
        snapshot_spec: ``actor path -> TeamSpec`` of a snapshot opponent (default: the
            attacking plays with ``skills`` and that actor's decision).
        start_jitter_m, restart_jitter_m: the match's kickoff and restart placement jitter (m).
        reward_scales: the match task's reward terms (default ``{"goal": 1.0}``; e.g.
            ``"ball_progress"`` adds the ball's progress towards the opponent goal).
        ssl_rules: SSL game control (:data:`~ssl_marl.envs.game_control.SSL_GAME_CONTROL`: referee
            commands, free kicks, fouls) as in ``ssl-marl match --format ssl`` (one period: no
            half-time), and the learned decider's dribble mask
            (:data:`~ssl_marl.decisions.dribble_limit.DRIBBLE_MASK_M`), as the match's
            :class:`~ssl_marl.decisions.match_decider.PolicyAttackDecider` plays.
            The learner's and its snapshots' shots follow the long-shot rule of the match's learned
            decider (:data:`~ssl_marl.decisions.long_shot.LONG_SHOT_MASK_M`) with or without.
        kwargs: :class:`~ssl_marl.decisions.base.DecisionEnv` options (field, realism,
            max_interval_s, illegal_option, render_mode, tracker).
    """

    task_name = "attack-match"
    option_names = ATTACK_DRILL_OPTIONS
    agent_prefix = "attacker"
    team = "blue"
    default_option = SHOOT
    engine_observations = False

    def __init__(self, opponents: Mapping[str, TeamSpec | Callable[[], TeamSpec]], skills: str = "learned",
                 robots: int = 6, seconds: float = 120.0, pfsp: bool = True, snapshot_dir: str | None = None,
                 max_snapshots: int = 3, snapshot_spec: Callable[[str], TeamSpec] | None = None,
                 start_jitter_m: float = 0.1, restart_jitter_m: float = 0.1,
                 reward_scales: Mapping[str, float] | None = None, ssl_rules: bool = False, **kwargs: Any) -> None:
        if not opponents:
            raise ValueError("AttackMatchEnv needs at least one opponent")
        if not (isinstance(robots, int) and 2 <= robots <= 11):
            raise ValueError(f"robots must be an integer in 2..11, got {robots!r}")
        if not (isinstance(seconds, (int, float)) and math.isfinite(seconds) and seconds > 0):
            raise ValueError(f"seconds must be a positive number, got {seconds!r}")
        self.n_agents = robots - 1
        self.robots, self.seconds, self.pfsp = robots, float(seconds), bool(pfsp)
        self.skills = team_skill_set(skills, ATTACK_SKILLS, where="AttackMatchEnv")
        self.opponent_specs = dict(opponents)
        self.snapshot_dir, self.max_snapshots = snapshot_dir, int(max_snapshots)
        self.snapshot_spec = snapshot_spec or self._snapshot_spec
        self.start_jitter_m, self.restart_jitter_m = float(start_jitter_m), float(restart_jitter_m)
        self.reward_scales = dict(reward_scales or {"goal": 1.0})
        self.ssl_rules = bool(ssl_rules)
        self.dribble_mask_m = DRIBBLE_MASK_M if self.ssl_rules else None
        self.long_shot_m = long_shot.LONG_SHOT_MASK_M
        self.results: dict[str, list[float]] = {}  # opponent -> [wins (draw 0.5), games]
        self._teams: dict[str, TeamController] = {}
        super().__init__(**kwargs)
        cfg = self.engine.config
        self.rp, self.bp = cfg.robot, cfg.ball
        self.attack = AttackParams()
        self.decider = MatchAttackDecider(self.attack)
        spec = TeamSpec(plays=attack_plays, skills=self.skills, decider=self.decider)
        self.blue = build_team(spec, "blue", robots, self.field, self.rp, self.bp, dt=self.dt)
        self.decider.coordinator = coordinator_of(self.blue.selector.plays)  # the carrier holds its dribble
        self.opponent: str | None = None
        self.yellow: TeamController | None = None
        self._passes: SlotPasses = {}
        self._request_obs: np.ndarray | None = None
        self._request_mask: np.ndarray | None = None

    # ------------------------------------------------------------ league
    def _snapshot_spec(self, actor: str) -> TeamSpec:
        from .learned import LearnedDecisionPolicy
        from .match_decider import PolicyAttackDecider

        decider = PolicyAttackDecider(LearnedDecisionPolicy(actor, task="attack-drill"), long_shot_m=self.long_shot_m)
        return TeamSpec(plays=attack_plays, skills=self.skills, decider=decider)

    def league(self) -> list[str]:
        """The opponents' names now: ``opponents`` then ``snapshot:<actor path>`` entries."""
        names = list(self.opponent_specs)
        if self.snapshot_dir is not None:
            names += [f"snapshot:{p}" for p in improving_snapshots(self.snapshot_dir, self.max_snapshots)]
        return names

    def _team(self, name: str) -> TeamController:
        team = self._teams.get(name)
        if team is None:
            if name.startswith("snapshot:"):
                spec = self.snapshot_spec(name.split(":", 1)[1])
            else:
                spec = self.opponent_specs[name]
                spec = spec() if callable(spec) and not isinstance(spec, TeamSpec) else spec
            team = self._teams[name] = build_team(spec, "yellow", self.robots, self.field, self.rp, self.bp,
                                                  dt=self.dt)
        return team

    def draw_opponent(self) -> str:
        """The next episode's opponent (module docstring), drawn from ``self.np_random``."""
        names = self.league()
        if not self.pfsp or len(names) == 1:
            return names[int(self.np_random.integers(len(names)))]
        wins = [self.results.get(n, [0.0, 0.0])[0] for n in names]
        games = [self.results.get(n, [0.0, 0.0])[1] for n in names]
        return names[int(self.np_random.choice(len(names), p=pfsp_weights(win_probability(wins, games))))]

    # ------------------------------------------------------------ hooks
    def make_task(self) -> MatchTask:
        return MatchTask()

    def engine_kwargs(self) -> dict:
        return {"n_blue": self.robots, "n_yellow": self.robots, "chip_kicks": True, "referee": True,
                "after_goal": "kickoff", "max_time_s": self.seconds, "restart_jitter_m": self.restart_jitter_m,
                "reward_scales": self.reward_scales, **(SSL_GAME_CONTROL if self.ssl_rules else {})}

    def agent_robot(self, agent: str) -> str:
        return f"blue_{int(agent.rsplit('_', 1)[1]) + 1}"

    def agent_of(self, robot: int) -> str:
        return f"{self.agent_prefix}_{robot - 1}"

    def reset(self, seed: int | None = None, options: dict | None = None):
        if options is None and seed is not None and self.start_jitter_m > 0:
            options = match_start_options(self.engine, seed, self.start_jitter_m)
        return super().reset(seed=seed, options=options)

    def on_reset(self) -> None:
        self.opponent = self.draw_opponent()
        self.yellow = self._team(self.opponent)
        self.decider.reset()
        self.blue.reset()
        self.yellow.reset()
        self._request_obs = self._request_mask = None

    def _goals(self) -> tuple[int, int]:
        score = self.engine.score
        return int(score["blue"]), int(score["yellow"])

    def global_state(self) -> np.ndarray:
        w = self.engine.world_state()
        L2, W2, sv, bv = self.field.half_length, self.field.half_width, self.rp.max_speed, self.rp.kick_speed_max
        parts = [np.array([w.ball_pos[0] / L2, w.ball_pos[1] / W2, w.ball_vel[0] / bv, w.ball_vel[1] / bv])]
        for t in (w.blue, w.yellow):
            parts.append(np.column_stack([t.pos[:, 0] / L2, t.pos[:, 1] / W2, t.vel[:, 0] / sv, t.vel[:, 1] / sv])
                         .ravel())
        gf, ga = self._goals()
        parts.append(np.array([(gf - ga) / 5.0, self.t / self.seconds]))
        return np.clip(np.concatenate(parts), -OBS_BOUND, OBS_BOUND).astype(np.float32)

    def state_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        n = 4 + 8 * self.robots + 2
        return np.full(n, -OBS_BOUND, np.float32), np.full(n, OBS_BOUND, np.float32)

    def episode_info(self) -> dict:
        gf, ga = self._goals()
        rec = self.results.setdefault(self.opponent, [0.0, 0.0])
        rec[0] += 1.0 if gf > ga else 0.5 if gf == ga else 0.0
        rec[1] += 1.0
        return {"outcome": "win" if gf > ga else "draw" if gf == ga else "loss", "goal_diff": float(gf - ga),
                "goals_for": gf, "goals_against": ga, "opponent": self.opponent}


__all__ = ["AttackMatchEnv", "MatchAttackDecider", "improving_snapshots"]
