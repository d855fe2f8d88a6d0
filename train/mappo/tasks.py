"""The multi-agent tasks MAPPO trains on, by name (``python -m train mappo --task NAME``).

Each entry builds a decision env (the interface of ``ssl_marl/decisions``: PettingZoo
``ParallelEnv`` with ``decision`` / ``action_mask`` / ``elapsed_s`` infos and ``state()``)
and names the final-info key that scores an episode. ``defaults`` are the run-config
overrides the task starts from (see :class:`train.mappo.loop.MAPPORunConfig`).
Factories are module-level functions so worker processes can build them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class MARLTask:
    """One trainable task: ``factory(**kwargs)`` -> env; ``score_key``: its episode score in the final infos."""

    factory: Callable[..., Any]
    score_key: str
    defaults: dict[str, Any] = field(default_factory=dict)
    description: str = ""


def _toy_signal(**kw: Any) -> Any:
    from train.mappo.toy_marl import ToySignal

    return ToySignal(**kw)


def _toy_tempo(**kw: Any) -> Any:
    from train.mappo.toy_marl import ToyTempo

    return ToyTempo(**kw)


@dataclass(frozen=True)
class DecisionTaskFactory:
    """Builds the decision task ``name`` of :data:`ssl_marl.decisions.DECISION_TASKS` (a
    picklable module-level callable, so env worker processes can build it)."""

    name: str

    def __call__(self, **kw: Any) -> Any:
        from ssl_marl.decisions import DECISION_TASKS

        return DECISION_TASKS[self.name](**kw)


#: the league of the attack-match task: the hand-coded anchors, all with the shipped learned skills
MATCH_LEAGUE = ("attack-learned", "passing-learned", "learned")


def _attack_match(opponents: tuple[str, ...] = MATCH_LEAGUE, **kw: Any) -> Any:
    """The attack-match task with ``opponents`` (team kinds) as the yellow league."""
    from ssl_marl.decisions.attack_match import AttackMatchEnv
    from ssl_marl.runners.controllers import team_spec

    league = {kind: (lambda k=kind: team_spec(k, where=f"opponent {k}")) for kind in opponents}
    return AttackMatchEnv(league, **kw)


def _pass_and_score(**kw: Any) -> Any:
    from ssl_marl.envs.tasks.pass_and_score import PassAndScoreEnv

    return PassAndScoreEnv(**kw)


#: the attack drills' run defaults (each adds its validation seed)
_DRILL_DEFAULTS: dict[str, Any] = {"num_envs": 4, "rollout_steps": 16, "total_decisions": 1_500, "checkpoint_every": 2,
                                   "val_every": 8, "val_episodes": 40,
                                   "algo": {"hidden": [64, 64], "lr": 1e-3, "epochs": 10, "minibatches": 2,
                                            "gamma": 0.99, "tau_s": 0.1}}

MARL_TASKS: dict[str, MARLTask] = {
    "toy-signal": MARLTask(_toy_signal, "success",
                           {"num_envs": 16, "rollout_steps": 16, "total_decisions": 6_000, "val_episodes": 30,
                            "algo": {"hidden": [64, 64], "lr": 3e-3, "ent_coef": 0.03, "minibatches": 2,
                                     "gamma": 0.99, "tau_s": 1.0}},
                           "two-agent signalling game (train/mappo/toy_marl.py)"),
    "toy-tempo": MARLTask(_toy_tempo, "success",
                          {"num_envs": 16, "rollout_steps": 16, "total_decisions": 6_000, "val_episodes": 10,
                           "algo": {"hidden": [64, 64], "lr": 3e-3, "minibatches": 2, "gamma": 0.9, "tau_s": 1.0}},
                          "asynchronous variable-duration jobs (train/mappo/toy_marl.py)"),
    "keepaway": MARLTask(DecisionTaskFactory("keepaway"), "duration_s",
                         {"val_seed": 45000, "num_envs": 4, "rollout_steps": 16, "total_decisions": 4_000,
                          "checkpoint_every": 2, "val_every": 8, "val_episodes": 30,
                          "algo": {"hidden": [64, 64], "lr": 1e-3, "epochs": 10, "minibatches": 2,
                                   "gamma": 0.99, "tau_s": 0.1}},
                         "keepaway 3v2 (ssl_marl.decisions)"),
    "attack-3v2": MARLTask(DecisionTaskFactory("attack-3v2"), "goal",
                           {"val_seed": 46000, "num_envs": 4, "rollout_steps": 16, "total_decisions": 1_500,
                            "checkpoint_every": 2, "val_every": 8, "val_episodes": 20,
                            "algo": {"hidden": [64, 64], "lr": 1e-3, "epochs": 10, "minibatches": 2,
                                     "gamma": 0.99, "tau_s": 0.1}},
                           "attack 3v2 (ssl_marl.decisions)"),
    "attack-drill": MARLTask(DecisionTaskFactory("attack-drill"), "goal", {"val_seed": 49000, **_DRILL_DEFAULTS},
                             "attack drill: the attacking plays' options, 3 attackers vs goalie and defender "
                             "(ssl_marl.decisions)"),
    "attack-drill-ssl": MARLTask(DecisionTaskFactory("attack-drill-ssl"), "goal", {"val_seed": 49600, **_DRILL_DEFAULTS},
                                 "the attack drill under SSL rules: the attackers' fouls end the attack, dribbles "
                                 "cut and masked as in matches (ssl_marl.decisions)"),
    "attack-drill-defended": MARLTask(DecisionTaskFactory("attack-drill-defended"), "goal",
                                      {**_DRILL_DEFAULTS, "val_seed": 48500, "val_every": 0},
                                      "the attack drill under SSL rules against the match's defence: goalie, two "
                                      "defenders, a presser and two marks (ssl_marl.decisions)"),
    "attack-drill-mix": MARLTask(DecisionTaskFactory("attack-drill-mix"), "goal",
                                 {**_DRILL_DEFAULTS, "val_seed": 47500, "val_every": 0},
                                 "the attack drill under SSL rules with its defence drawn per episode: a goalie and "
                                 "one defender, or the match's defence (ssl_marl.decisions.attack_drill_mix)"),
    "attack-match": MARLTask(_attack_match, "goal_diff",
                             {"val_seed": 49500, "num_envs": 2, "rollout_steps": 32, "total_decisions": 2_000,
                              "checkpoint_every": 2, "val_every": 0, "val_episodes": 4,
                              "algo": {"hidden": [64, 64], "lr": 1e-4, "epochs": 4, "minibatches": 2,
                                       "gamma": 0.99, "tau_s": 0.1}},
                             "full 6v6 matches of 120 s: the attacking team's carrier decisions against a league "
                             "drawn by PFSP (ssl_marl.decisions.attack_match)"),
    "pass-and-score": MARLTask(_pass_and_score, "success",
                               {"val_seed": 47000, "num_envs": 8, "rollout_steps": 128, "val_every": 25, "val_episodes": 20,
                                "total_decisions": 300_000,
                                "algo": {"continuous": True, "gamma": 0.99, "tau_s": 1 / 60, "lam": 0.95,
                                         "ent_coef": 0.0, "lr": 3e-4, "epochs": 5, "minibatches": 4}},
                               "2v0 pass-then-score drill, continuous (vx, vy, omega, dribble, kick) at 60 Hz"),
}


def get_task(name: str) -> MARLTask:
    try:
        return MARL_TASKS[name]
    except KeyError:
        raise ValueError(f"unknown MAPPO task {name!r}; expected one of {sorted(MARL_TASKS)}") from None
