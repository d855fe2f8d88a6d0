"""Learned skills: a trained DDPG actor run through the same skill protocol and the
same feature functions as the baselines (a tactic cannot tell them apart).

The actor's forward pass is re-implemented in numpy (Linear -> LayerNorm -> ReLU,
tanh head), which is several times faster than calling torch for one observation
(measured in ``docs/BENCHMARKS.md``) and gives the same numbers to float32 precision.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import WorldState
from .base import AimToShootSkill, GoToBallSkill
from .features import (aim_to_shoot_env_action, aim_to_shoot_features, check_go_to_ball_state, go_to_ball_env_action,
                       go_to_ball_features)
from .registry import get_skill, learned_skills


class NumpyActor:
    """Inference-only copy of :class:`ssl_marl.skills.networks.Actor` in numpy."""

    def __init__(self, actor) -> None:
        sd = {k: v.detach().cpu().numpy().astype(np.float64) for k, v in actor.state_dict().items()}
        self.layers: list[tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None]] = []
        mods = list(actor.trunk)
        i = 0
        while i < len(mods):
            lin = f"trunk.{i}"
            w, b = sd[f"{lin}.weight"].T.copy(), sd[f"{lin}.bias"]
            g = beta = None
            i += 1
            if i < len(mods) and type(mods[i]).__name__ == "LayerNorm":
                g, beta = sd[f"trunk.{i}.weight"], sd[f"trunk.{i}.bias"]
                self.eps = float(mods[i].eps)
                i += 1
            i += 1  # ReLU
            self.layers.append((w, b, g, beta))
        self.head_w, self.head_b = sd["head.weight"].T.copy(), sd["head.bias"]

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        x = np.asarray(obs, dtype=np.float64)
        for w, b, g, beta in self.layers:
            x = x @ w + b
            if g is not None:  # LayerNorm: the sums and quotients of x.mean(-1) and x.var(-1), done once
                n = x.shape[-1]
                d = x - np.add.reduce(x, axis=-1, keepdims=True) / n
                var = np.add.reduce(np.square(d), axis=-1, keepdims=True) / n
                x = d / np.sqrt(var + self.eps) * g + beta
            np.maximum(x, 0.0, out=x)
        return np.tanh(x @ self.head_w + self.head_b).astype(np.float32)


def load_policy(skill: str, checkpoint: str | Path | None = None) -> tuple[NumpyActor, dict]:
    """Load a checkpoint (default: the shipped actor) for registered learned ``skill``
    ("go_to_ball", "aim_to_shoot", ...), checking its skill name and observation spec
    against every spec version the skill's task accepts."""
    from .checkpoint import load_actor

    known = {s.name: s for s in learned_skills() if s.task is not None}
    if skill not in known:
        raise ValueError(f"unknown learned skill {skill!r}; expected one of {sorted(known)}")
    entry = known[skill]
    if checkpoint is None and entry.actor is None:
        raise FileNotFoundError(f"skill {skill!r} ships no learned actor; pass a checkpoint")
    path = Path(checkpoint) if checkpoint is not None else entry.actor
    specs = entry.task.specs
    actor, meta = load_actor(path, expected_skill=skill, expected_spec=specs[0] if len(specs) == 1 else specs)
    return NumpyActor(actor), meta


class LearnedGoToBall(GoToBallSkill):
    """Learned go-to-ball (paper's DDPG skill). Succeeds when the ball is on the dribbler.
    The actor reads the state it was trained on: the checkpoint's spec (``go_to_ball/v1``:
    the paper's state, ``go_to_ball/v2``: with the ball's velocity) picks it; with
    ``policy`` given directly, ``state`` does."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 checkpoint: str | Path | None = None, policy: NumpyActor | None = None,
                 state: str = "default") -> None:
        super().__init__(field, robot, ball)
        if policy is None:
            policy, meta = load_policy("go_to_ball", checkpoint)
            state = get_skill("go_to_ball").task.mapping_of(meta["obs_spec"])
        self.policy, self.state = policy, check_go_to_ball_state(state)

    def approach(self, world: WorldState, robot: int) -> np.ndarray:
        return go_to_ball_env_action(self.policy(go_to_ball_features(world, robot, self.field, self.state)))


class LearnedAimToShoot(AimToShootSkill):
    """Learned aim-to-shoot (paper's DDPG skill). Succeeds when it kicks; fails if the
    ball leaves the dribbler before the kick, or after ``max_time_s`` (1.6 s, its
    training episode length) without a kick: beyond that horizon the policy was never
    trained, and a tactic should try something else (e.g. drive closer and aim again).
    The kick action means what it meant in training: the checkpoint's spec
    (``aim_to_shoot/v1``: kick strength, ``v2``: full-strength kick) picks the mapping;
    with ``policy`` given directly, ``kick_action`` does."""

    def __init__(self, field: FieldGeometry, robot: RobotParams | None = None, ball: BallParams | None = None,
                 checkpoint: str | Path | None = None, policy: NumpyActor | None = None,
                 max_time_s: float | None = 1.6, kick_action: str = "strength") -> None:
        super().__init__(field, robot, ball, max_time_s)
        if policy is None:
            policy, meta = load_policy("aim_to_shoot", checkpoint)
            kick_action = get_skill("aim_to_shoot").task.mapping_of(meta["obs_spec"])
        self.policy, self.kick_action = policy, kick_action

    def aim(self, world: WorldState, robot: int) -> tuple[np.ndarray, bool]:
        a = aim_to_shoot_env_action(self.policy(aim_to_shoot_features(world, robot, self.field)), self.kick_action)
        team = world.team(world.frame)
        return a, bool(a[4] > 0 and team.kick_ready[robot] and team.ball_on_dribbler[robot])
