"""Training hyperparameters: one documented dataclass, loaded from JSON, overridable by ``--set``.

One flat dataclass for every algorithm (``algo``: ``ddpg`` or ``td3``, see
:mod:`train.algos`); an algorithm's own keys carry its name (``td3_*``).

JSON files live in ``train/configs/``; keys starting with ``_`` are comments and
ignored; any other unknown key is an error (a typo must not silently fall back
to a default).
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

CONFIG_DIR = Path(__file__).resolve().parent / "configs"

#: configs that belong to no registered skill (the toy check)
EXTRA_CONFIGS = {"pendulum": "pendulum.json"}


def _skill_configs() -> dict[str, str]:
    """CLI skill name -> default config file in :data:`CONFIG_DIR`: every registered skill
    whose task names a training config (``SkillTaskDef.train_config``), plus the toy ones."""
    from ssl_marl.skills.registry import task_skills

    out = {s.cli_name: f"{s.task.train_config}.json" for s in task_skills() if s.task.train_config}
    out.update(EXTRA_CONFIGS)
    return out


#: CLI skill name -> default config file in :data:`CONFIG_DIR`.
SKILL_CONFIGS = _skill_configs()


def cpu_has_fast_bf16(cpuinfo: str | Path = "/proc/cpuinfo") -> bool:
    """True when this CPU computes bfloat16 matrix products natively: AMX (``amx_bf16``,
    Intel Sapphire Rapids and later) or AVX512-BF16 (``avx512_bf16``: Intel Cooper Lake,
    AMD Zen 4 and later), read from the ``flags`` line of ``cpuinfo`` (Linux x86); False
    where that file is missing or names neither. Without them torch emulates bfloat16
    and autocast does not pay (docs/BENCHMARKS.md)."""
    try:
        with open(cpuinfo) as f:
            for line in f:
                if line.startswith("flags"):
                    return bool(set(line.split(":", 1)[1].split()) & {"amx_bf16", "avx512_bf16"})
    except OSError:
        pass
    return False


@dataclass
class TrainConfig:
    """Everything that defines a training run except the seed and the output folder.

    From the paper (Tables 1 and 2): learning rates, layer sizes, replay size,
    OU noise (theta 0.15, mu 0, sigma 0.3) and the number of demonstration
    steps. The paper's Table 2 "Actor sizes" entry for aim-to-shoot is garbled
    ("200—300, 300, 300"); we use the critic's 200, 300, 300, 300.

    Chosen here because the paper leaves them out (all overridable):

    * ``gamma`` 0.99 -- a ~100-step (1.7 s at 60 Hz) horizon, long enough for the
      go-to-ball contact bonus to propagate.
    * ``tau`` 0.005 -- Polyak rate of the target networks (SB3/TD3 default; the
      original DDPG's 0.001 learns slower in our tests).
    * ``batch_size`` 256, ``updates_per_sample`` 1.0 (one gradient update per
      environment sample, the usual DDPG ratio).
    * ``n_step`` 1 (one-step targets, the paper's); n > 1 stores n-step returns
      (:mod:`train.nstep`), windows truncated at episode ends.
    * ``warmup_samples`` 1,000 -- env samples collected by actor + noise after
      the demo burn-in before updates start.
    * ``total_samples`` 500,000 env samples (paper Fig. 3: "about 500,000
      training samples"); demonstration transitions are counted separately.
    * ``num_envs`` 1 synchronous env; ``eval_interval`` 25,000 samples with
      ``eval_episodes`` 10 deterministic episodes; ``checkpoint_interval`` 50,000.
    * ``algo`` "ddpg" (the paper's); "td3" adds twin critics, target policy
      smoothing and delayed actor updates (``td3_*`` keys, the TD3 paper's values).
    * ``exploration`` "ou" (the paper's OU noise); "gaussian" draws independent
      N(0, ``gaussian_sigma``) noise each step (TD3 paper: 0.1).
    * ``autocast_bf16``: on by default only where the CPU has native bfloat16
      (:func:`cpu_has_fast_bf16`); ``compile`` off by default (~30 s of start-up).
    * ``torch_threads`` 1: 2 threads are ~1.4x faster on an idle 2-core
      machine, but two 2-thread trainers sharing 2 cores slow each other down
      several-fold (OpenMP spin-waiting); 1 is the safe default (see
      ``benchmarks/bench_ddpg.py``).

    Units: learning rates per Adam step; ``ou_dt`` in noise-process time units
    per env step (1.0 = the textbook discrete OU); intervals in env samples.
    """

    # --- algorithm ----------------------------------------------------------
    algo: str = "ddpg"  #: learning algorithm, a key of train.algos.ALGOS ("ddpg", "td3")
    # --- task --------------------------------------------------------------
    skill: str = "go_to_ball"  #: skill name stored in the exported actor's metadata
    env_id: str = "ssl_marl/GoToBall-v0"  #: Gymnasium id ("module:id" imports module first)
    env_kwargs: dict[str, Any] = field(default_factory=dict)  #: passed to gym.make and the demo function
    env_variants: list[dict[str, Any]] = field(default_factory=list)  #: overrides of env_kwargs, one per block of sub-envs (e.g. [{"field": "div_a"}, {"field": "div_b"}]): the num_envs sub-envs, the demo steps and the trainer's evaluation episodes are split evenly across them; [] = one configuration
    max_episode_steps: int | None = None  #: TimeLimit override for gym.make (None: the env's own)
    demo_fn: str | None = None  #: "module:function" yielding Transition(obs, action, reward, ...)
    demo_steps: int = 0  #: demonstration transitions put in the replay before training (burn-in)
    # --- networks ----------------------------------------------------------
    actor_hidden: tuple[int, ...] = (300, 400)
    critic_hidden: tuple[int, ...] = (300, 400)
    layer_norm: bool = True
    actor_lr: float = 1e-4
    critic_lr: float = 1e-3
    critic_weight_decay: float = 0.0  #: Adam L2 on the critic (original DDPG: 1e-2)
    # --- learning (every algorithm) ------------------------------------------
    gamma: float = 0.99
    tau: float = 0.005
    batch_size: int = 256
    buffer_size: int = 1_000_000
    total_samples: int = 500_000
    warmup_samples: int = 1_000
    random_warmup: bool = False  #: uniform-random actions (not actor + noise) during warm-up
    updates_per_sample: float = 1.0
    n_step: int = 1  #: n-step returns (train.nstep): rewards of up to n steps summed per transition, bootstrap with gamma**k; 1 = one-step DDPG
    bc_weight: float = 0.0  #: DDPGfD-style behaviour cloning: + bc_weight * MSE(mu(s_d), a_d) on demo rows (0: plain DDPG)
    bc_batch_size: int = 64  #: demonstration rows per update for the behaviour-cloning term
    bc_anneal_samples: int = 0  #: > 0: the behaviour-cloning weight falls linearly from bc_weight to 0 over this many env samples after warm-up (0: constant)
    reward_scale: float = 1.0  #: rewards are multiplied by this before storage (logs show raw)
    # --- TD3 (Fujimoto et al. 2018; in the actor's [-1, 1] action units) ------
    td3_policy_noise: float = 0.2  #: std of the target policy smoothing noise
    td3_noise_clip: float = 0.5  #: the smoothing noise is clipped to +-this
    td3_policy_delay: int = 2  #: critic updates per actor (and target) update
    # --- exploration (in the actor's [-1, 1] action units) --------------------
    exploration: str = "ou"  #: "ou" (Ornstein-Uhlenbeck, ou_* keys) or "gaussian" (gaussian_sigma)
    gaussian_sigma: float = 0.1  #: std of the Gaussian exploration noise
    ou_theta: float = 0.15
    ou_mu: float = 0.0
    ou_sigma: float = 0.3
    ou_sigma_per_dim: tuple[float, ...] | None = None  #: per action dimension; overrides ou_sigma when set
    ou_dt: float = 1.0
    # --- envs, evaluation, logging -------------------------------------------
    num_envs: int = 1
    vector_mode: str = "sync"  #: "sync" (SyncVectorEnv), "async" (AsyncVectorEnv) or "batched" (ssl_marl SkillVectorEnv)
    eval_interval: int = 25_000  #: env samples between deterministic evaluations (0: none)
    eval_episodes: int = 10
    checkpoint_interval: int = 50_000  #: env samples between resumable checkpoints
    log_interval: int = 100  #: updates between loss read-outs (avoids a .item() sync per update)
    # --- speed -------------------------------------------------------------
    torch_threads: int = 1  #: torch.set_num_threads; 0 leaves torch's default
    autocast_bf16: bool = field(default_factory=cpu_has_fast_bf16)  #: bfloat16 autocast of the forward passes (matrix products in bf16; less precise); default: on where the CPU has native bf16
    compile: bool = False  #: torch.compile the loss functions (~30 s start-up; with autocast_bf16 see BENCHMARKS.md)

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):  # JSON / --set give 2e4 for ints, 1 for floats, ...
            v = getattr(self, f.name)
            if f.type in ("int", "int | None") and isinstance(v, float) and v.is_integer():
                setattr(self, f.name, int(v))
            elif f.type == "float" and isinstance(v, int) and not isinstance(v, bool):
                setattr(self, f.name, float(v))
            elif f.type in ("int", "float", "bool") and not isinstance(getattr(self, f.name), (int, float)):
                raise ValueError(f"invalid training config: {f.name} must be {f.type} (got {v!r})")
        if self.ou_sigma_per_dim is not None:
            self.ou_sigma_per_dim = tuple(float(v) for v in self.ou_sigma_per_dim)
            if any(v < 0 for v in self.ou_sigma_per_dim):
                raise ValueError(f"invalid training config: ou_sigma_per_dim must be >= 0 (got {self.ou_sigma_per_dim})")
        self.actor_hidden = tuple(int(h) for h in self.actor_hidden)
        self.critic_hidden = tuple(int(h) for h in self.critic_hidden)
        self.env_kwargs = dict(self.env_kwargs)
        self.env_variants = [dict(v) if isinstance(v, dict) else v for v in self.env_variants]
        problems = []
        if not all(isinstance(v, dict) for v in self.env_variants):
            problems.append(f"env_variants must be a list of dicts (got {self.env_variants!r})")
        elif self.env_variants and self.num_envs % len(self.env_variants):
            problems.append(f"num_envs ({self.num_envs}) must be a multiple of the number of env_variants "
                            f"({len(self.env_variants)})")
        for name in ("actor_lr", "critic_lr", "batch_size", "buffer_size", "num_envs", "eval_episodes",
                     "checkpoint_interval", "log_interval"):
            if not getattr(self, name) > 0:
                problems.append(f"{name} must be > 0 (got {getattr(self, name)!r})")
        for name in ("total_samples", "warmup_samples", "demo_steps", "eval_interval", "critic_weight_decay",
                     "torch_threads", "updates_per_sample", "ou_sigma", "ou_theta", "bc_weight", "bc_anneal_samples",
                     "gaussian_sigma",
                     "td3_policy_noise", "td3_noise_clip"):
            if getattr(self, name) < 0:
                problems.append(f"{name} must be >= 0 (got {getattr(self, name)!r})")
        if not 0.0 <= self.gamma <= 1.0:
            problems.append(f"gamma must be in [0, 1] (got {self.gamma})")
        if not 0.0 < self.tau <= 1.0:
            problems.append(f"tau must be in (0, 1] (got {self.tau})")
        if self.ou_dt <= 0:
            problems.append(f"ou_dt must be > 0 (got {self.ou_dt})")
        if not self.actor_hidden or not self.critic_hidden or min(self.actor_hidden + self.critic_hidden) <= 0:
            problems.append("actor_hidden and critic_hidden need at least one positive size")
        if self.n_step < 1:
            problems.append(f"n_step must be >= 1 (got {self.n_step})")
        if self.td3_policy_delay < 1:
            problems.append(f"td3_policy_delay must be >= 1 (got {self.td3_policy_delay})")
        from .algos import ALGOS  # late: the algorithms import this module
        from .exploration import EXPLORATIONS

        if self.algo not in ALGOS:
            problems.append(f"algo must be one of {sorted(ALGOS)} (got {self.algo!r})")
        if self.exploration not in EXPLORATIONS:
            problems.append(f"exploration must be one of {sorted(EXPLORATIONS)} (got {self.exploration!r})")
        if self.vector_mode not in ("sync", "async", "batched"):
            problems.append(f"vector_mode must be 'sync', 'async' or 'batched' (got {self.vector_mode!r})")
        if self.demo_steps > 0 and not self.demo_fn:
            problems.append("demo_steps > 0 needs demo_fn ('module:function')")
        if self.demo_steps > self.buffer_size:
            problems.append(f"demo_steps ({self.demo_steps}) exceeds buffer_size ({self.buffer_size})")
        if problems:
            raise ValueError("invalid training config: " + "; ".join(problems))

    def variant_kwargs(self) -> list[dict[str, Any]]:
        """The env keyword arguments of each block of sub-envs (``[env_kwargs]`` without variants)."""
        return [{**self.env_kwargs, **v} for v in self.env_variants] or [dict(self.env_kwargs)]

    def to_dict(self) -> dict[str, Any]:
        """JSON-safe dict (tuples as lists)."""
        d = dataclasses.asdict(self)
        return {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}


#: the name this dataclass had while DDPG was the only algorithm (kept for existing code)
DDPGConfig = TrainConfig


def _field_names() -> set[str]:
    return {f.name for f in dataclasses.fields(TrainConfig)}


def config_from_dict(data: Mapping[str, Any], base: TrainConfig | None = None) -> TrainConfig:
    """Build a config from ``data`` (over ``base`` or the defaults); unknown keys raise ValueError."""
    unknown = sorted(k for k in data if not k.startswith("_") and k not in _field_names())
    if unknown:
        raise ValueError(f"unknown training config key(s) {unknown}; valid keys: {sorted(_field_names())}")
    values = base.to_dict() if base is not None else {}
    values.update({k: v for k, v in data.items() if not k.startswith("_")})
    return TrainConfig(**values)


def load_config(path: str | Path) -> TrainConfig:
    """Read a JSON config file (see :class:`TrainConfig` for the keys)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise FileNotFoundError(f"config file not found: {path}") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from exc
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object at top level")
    return config_from_dict(data)


def default_config(skill: str) -> TrainConfig:
    """The shipped config for a CLI skill name ("go-to-ball", "aim-to-shoot", "pendulum")."""
    if skill not in SKILL_CONFIGS:
        raise ValueError(f"unknown skill {skill!r}; expected one of {sorted(SKILL_CONFIGS)}")
    return load_config(CONFIG_DIR / SKILL_CONFIGS[skill])


def parse_override(text: str) -> tuple[str, Any]:
    """``"key=value"`` -> (key, value); value parsed as JSON when it can be, else kept as a string."""
    if "=" not in text:
        raise ValueError(f"override {text!r} must look like key=value")
    key, raw = text.split("=", 1)
    key = key.strip()
    try:
        value: Any = json.loads(raw)
    except json.JSONDecodeError:
        value = raw
    return key, value


def apply_overrides(cfg: TrainConfig, overrides: Iterable[str]) -> TrainConfig:
    """Return a new config with ``--set key=value`` overrides applied (validated)."""
    data = dict(parse_override(o) for o in overrides)
    return config_from_dict(data, base=cfg) if data else cfg
