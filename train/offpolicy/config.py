"""Off-policy training config: one run dataclass with one nested dataclass per algorithm.

:class:`TrainConfig` holds what the loop (:mod:`train.offpolicy.loop`) reads: the task,
the replay and update schedule, evaluation, checkpoints and speed options. The
hyperparameters of each part sit in their own section:

* ``ddpg`` -- :class:`DDPGConfig`, the actor-critic update (networks, learning rates,
  ``gamma``, ``tau``, behaviour cloning); TD3 reads it too (TD3 is DDPG plus three changes);
* ``td3`` -- :class:`TD3Config`, the three TD3 additions (read when ``algo`` is ``"td3"``);
* ``exploration`` -- :class:`ExplorationConfig`, the action noise during collection.

JSON files (``train/configs/``) and ``--set`` use the same layout::

    {"algo": "td3", "skill": "receive", ..., "ddpg": {"actor_lr": 3e-4}, "td3": {"policy_delay": 2},
     "exploration": {"kind": "gaussian", "gaussian_sigma": 0.1}}

    --set ddpg.actor_lr=3e-4 --set exploration.kind=gaussian --set total_samples=20000

A section in a file may give only some of its keys (the rest keep their defaults).
Keys starting with ``_`` are comments; any other unknown key is an error (a typo must
not fall back to a default), and a section key written at the top level gets an
error naming its place (``actor_lr`` -> ``ddpg.actor_lr``).
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

CONFIG_DIR = Path(__file__).resolve().parent.parent / "configs"

#: configs that belong to no registered skill (the Pendulum check)
EXTRA_CONFIGS = {"pendulum": "pendulum.json"}

#: ``algo`` names; :data:`train.offpolicy.algos.ALGOS` maps each to its agent class
ALGO_NAMES = ("ddpg", "td3")

#: ``exploration.kind`` names; :func:`train.offpolicy.exploration.make_exploration` builds each
EXPLORATION_KINDS = ("ou", "gaussian")

#: ``vector_mode`` names (see :class:`TrainConfig`)
VECTOR_MODES = ("sync", "async", "batched")


def _skill_configs() -> dict[str, str]:
    """CLI skill name -> default config file in :data:`CONFIG_DIR`: every registered skill
    whose task names a training config (``SkillTaskDef.train_config``), plus the extra ones."""
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


def _coerce_numbers(obj: Any, section: str) -> list[str]:
    """JSON and ``--set`` give 2e4 for ints and 1 for floats: convert such values in place
    (frozen dataclass) to the declared type; return the problems with non-numbers."""
    problems = []
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if f.type in ("int", "int | None") and isinstance(v, float) and v.is_integer():
            object.__setattr__(obj, f.name, int(v))
        elif f.type == "float" and isinstance(v, int) and not isinstance(v, bool):
            object.__setattr__(obj, f.name, float(v))
        elif f.type in ("int", "float", "bool") and not isinstance(v, (int, float)):
            problems.append(f"{section}{f.name} must be {f.type} (got {v!r})")
    return problems


def _check(problems: list[str]) -> None:
    if problems:
        raise ValueError("invalid training config: " + "; ".join(problems))


@dataclass(frozen=True)
class DDPGConfig:
    """Actor-critic hyperparameters of DDPG (Lillicrap et al. 2016), also used by TD3.

    From the paper (Tables 1 and 2): learning rates and layer sizes. ``gamma`` 0.99 is
    a ~100-step (1.7 s at 60 Hz) horizon, long enough for the go-to-ball contact bonus
    to propagate; ``tau`` 0.005 is the Polyak rate of the target networks (the original
    DDPG's 0.001 learns slower in our tests). Learning rates per Adam step.
    """

    actor_hidden: tuple[int, ...] = (300, 400)  #: actor hidden layer sizes
    critic_hidden: tuple[int, ...] = (300, 400)  #: critic hidden layer sizes
    layer_norm: bool = True  #: layer normalisation after each hidden layer
    actor_lr: float = 1e-4
    critic_lr: float = 1e-3
    critic_weight_decay: float = 0.0  #: Adam L2 on the critic (original DDPG: 1e-2)
    gamma: float = 0.99  #: discount per env step
    tau: float = 0.005  #: Polyak rate of the target networks
    bc_weight: float = 0.0  #: DDPGfD-style behaviour cloning: + bc_weight * MSE(mu(s_d), a_d) on demo rows (0: none)

    def __post_init__(self) -> None:
        object.__setattr__(self, "actor_hidden", tuple(int(h) for h in self.actor_hidden))
        object.__setattr__(self, "critic_hidden", tuple(int(h) for h in self.critic_hidden))
        problems = _coerce_numbers(self, "ddpg.")
        for name in ("actor_lr", "critic_lr"):
            if not getattr(self, name) > 0:
                problems.append(f"ddpg.{name} must be > 0 (got {getattr(self, name)!r})")
        for name in ("critic_weight_decay", "bc_weight"):
            if getattr(self, name) < 0:
                problems.append(f"ddpg.{name} must be >= 0 (got {getattr(self, name)!r})")
        if not 0.0 <= self.gamma <= 1.0:
            problems.append(f"ddpg.gamma must be in [0, 1] (got {self.gamma})")
        if not 0.0 < self.tau <= 1.0:
            problems.append(f"ddpg.tau must be in (0, 1] (got {self.tau})")
        if not self.actor_hidden or not self.critic_hidden or min(self.actor_hidden + self.critic_hidden) <= 0:
            problems.append("ddpg.actor_hidden and ddpg.critic_hidden need at least one positive size")
        _check(problems)


@dataclass(frozen=True)
class TD3Config:
    """The TD3 additions to DDPG (Fujimoto et al. 2018, the paper's values), in the actor's
    normalised action units ([-1, 1])."""

    policy_noise: float = 0.2  #: std of the target policy smoothing noise
    noise_clip: float = 0.5  #: the smoothing noise is clipped to +-this
    policy_delay: int = 2  #: critic updates per actor (and target) update

    def __post_init__(self) -> None:
        problems = _coerce_numbers(self, "td3.")
        for name in ("policy_noise", "noise_clip"):
            if getattr(self, name) < 0:
                problems.append(f"td3.{name} must be >= 0 (got {getattr(self, name)!r})")
        if self.policy_delay < 1:
            problems.append(f"td3.policy_delay must be >= 1 (got {self.policy_delay})")
        _check(problems)


@dataclass(frozen=True)
class ExplorationConfig:
    """Action noise added during collection, in the actor's normalised action units.

    ``kind`` "ou": the Ornstein-Uhlenbeck process of DDPG and of the paper (Tables 1 and
    2: theta 0.15, mu 0, sigma 0.3); ``ou_dt`` in noise-process time units per env step
    (1.0 = the textbook discrete process). ``kind`` "gaussian": independent
    N(0, ``gaussian_sigma``) each step (TD3 paper: 0.1).
    """

    kind: str = "ou"  #: "ou" or "gaussian"
    ou_theta: float = 0.15
    ou_mu: float = 0.0
    ou_sigma: float = 0.3
    ou_sigma_per_dim: tuple[float, ...] | None = None  #: one sigma per action dimension; replaces ou_sigma when set
    ou_dt: float = 1.0
    gaussian_sigma: float = 0.1  #: std of the Gaussian noise

    def __post_init__(self) -> None:
        problems = _coerce_numbers(self, "exploration.")
        if self.ou_sigma_per_dim is not None:
            object.__setattr__(self, "ou_sigma_per_dim", tuple(float(v) for v in self.ou_sigma_per_dim))
            if any(v < 0 for v in self.ou_sigma_per_dim):
                problems.append(f"exploration.ou_sigma_per_dim must be >= 0 (got {self.ou_sigma_per_dim})")
        for name in ("ou_sigma", "ou_theta", "gaussian_sigma"):
            if getattr(self, name) < 0:
                problems.append(f"exploration.{name} must be >= 0 (got {getattr(self, name)!r})")
        if self.ou_dt <= 0:
            problems.append(f"exploration.ou_dt must be > 0 (got {self.ou_dt})")
        if self.kind not in EXPLORATION_KINDS:
            problems.append(f"exploration.kind must be one of {list(EXPLORATION_KINDS)} (got {self.kind!r})")
        _check(problems)


#: section name -> its dataclass
SECTIONS: dict[str, type] = {"ddpg": DDPGConfig, "td3": TD3Config, "exploration": ExplorationConfig}


@dataclass(frozen=True)
class TrainConfig:
    """Everything that defines an off-policy run except the seed and the output folder.

    Our choices where the paper is silent (all overridable): ``batch_size`` 256 and
    ``updates_per_sample`` 1.0 (one gradient update per env sample, the usual DDPG ratio);
    ``n_step`` 1 (one-step targets, the paper's; n > 1 stores n-step returns,
    :mod:`train.offpolicy.nstep`, windows truncated at episode ends); ``warmup_samples``
    1,000 env samples collected by actor + noise after the demo burn-in before updates
    start; ``total_samples`` 500,000 env samples (paper Fig. 3: "about 500,000 training
    samples"; demonstration transitions count separately); ``eval_interval`` 25,000 samples
    with ``eval_episodes`` 10 deterministic episodes; ``checkpoint_interval`` 50,000.
    ``autocast_bf16`` is on by default only where the CPU has native bfloat16
    (:func:`cpu_has_fast_bf16`); ``compile`` is off by default (~30 s of start-up).
    ``torch_threads`` 1: two 2-thread trainers sharing 2 cores slow each other down
    several-fold (OpenMP spin-waiting), see ``benchmarks/bench_ddpg.py``.
    Intervals are in env samples.
    """

    # --- algorithm and its hyperparameters ----------------------------------
    algo: str = "ddpg"  #: "ddpg" or "td3" (train.offpolicy.algos.ALGOS)
    ddpg: DDPGConfig = field(default_factory=DDPGConfig)
    td3: TD3Config = field(default_factory=TD3Config)
    exploration: ExplorationConfig = field(default_factory=ExplorationConfig)
    # --- task ------------------------------------------------------------------
    skill: str = "go_to_ball"  #: skill name stored in the exported actor's metadata
    env_id: str = "ssl_marl/GoToBall-v0"  #: Gymnasium id ("module:id" imports module first)
    env_kwargs: dict[str, Any] = field(default_factory=dict)  #: passed to gym.make and the demo function
    env_variants: list[dict[str, Any]] = field(default_factory=list)  #: overrides of env_kwargs, one per block of sub-envs (e.g. [{"field": "div_a"}, {"field": "div_b"}]): the num_envs sub-envs, the demo steps and the evaluation episodes are split evenly across them; [] = one configuration
    max_episode_steps: int | None = None  #: TimeLimit override for gym.make (None: the env's own)
    demo_fn: str | None = None  #: "module:function" yielding Transition(obs, action, reward, ...)
    demo_steps: int = 0  #: demonstration transitions put in the replay before training (burn-in)
    # --- replay and update schedule --------------------------------------------
    batch_size: int = 256
    buffer_size: int = 1_000_000
    total_samples: int = 500_000
    warmup_samples: int = 1_000
    random_warmup: bool = False  #: uniform-random actions (not actor + noise) during warm-up
    updates_per_sample: float = 1.0
    n_step: int = 1  #: n-step returns: rewards of up to n steps summed per row, bootstrap with gamma**k
    bc_batch_size: int = 64  #: demonstration rows per update for the behaviour-cloning term (ddpg.bc_weight)
    bc_anneal_samples: int = 0  #: > 0: ddpg.bc_weight falls linearly to 0 over this many env samples after warm-up (0: constant)
    reward_scale: float = 1.0  #: rewards are multiplied by this before storage (logs show raw)
    # --- envs, evaluation, logging ----------------------------------------------
    num_envs: int = 1
    vector_mode: str = "sync"  #: "sync" (SyncVectorEnv), "async" (AsyncVectorEnv) or "batched" (ssl_marl SkillVectorEnv)
    eval_interval: int = 25_000  #: env samples between deterministic evaluations (0: none)
    eval_episodes: int = 10
    checkpoint_interval: int = 50_000  #: env samples between resumable checkpoints
    log_interval: int = 100  #: updates between loss read-outs (avoids a .item() sync per update)
    # --- speed -------------------------------------------------------------------
    torch_threads: int = 1  #: torch.set_num_threads; 0 leaves torch's default
    autocast_bf16: bool = field(default_factory=cpu_has_fast_bf16)  #: bfloat16 autocast of the forward passes (less precise); default: on where the CPU has native bf16
    compile: bool = False  #: torch.compile the loss functions (~30 s start-up; see docs/BENCHMARKS.md)

    def __post_init__(self) -> None:
        for name, cls in SECTIONS.items():
            value = getattr(self, name)
            if isinstance(value, Mapping):
                object.__setattr__(self, name, _section(name, value))
            elif not isinstance(value, cls):
                raise ValueError(f"invalid training config: {name} must be a section (a JSON object of "
                                 f"{cls.__name__} keys such as {_example(name)}), got {value!r}")
        problems = _coerce_numbers(self, "")
        object.__setattr__(self, "env_kwargs", dict(self.env_kwargs))
        object.__setattr__(self, "env_variants", [dict(v) if isinstance(v, dict) else v for v in self.env_variants])
        if not all(isinstance(v, dict) for v in self.env_variants):
            problems.append(f"env_variants must be a list of dicts (got {self.env_variants!r})")
        elif self.env_variants and self.num_envs % len(self.env_variants):
            problems.append(f"num_envs ({self.num_envs}) must be a multiple of the number of env_variants "
                            f"({len(self.env_variants)})")
        for name in ("batch_size", "buffer_size", "num_envs", "eval_episodes", "checkpoint_interval", "log_interval"):
            if not getattr(self, name) > 0:
                problems.append(f"{name} must be > 0 (got {getattr(self, name)!r})")
        for name in ("total_samples", "warmup_samples", "demo_steps", "eval_interval", "torch_threads",
                     "updates_per_sample", "bc_anneal_samples"):
            if getattr(self, name) < 0:
                problems.append(f"{name} must be >= 0 (got {getattr(self, name)!r})")
        if self.n_step < 1:
            problems.append(f"n_step must be >= 1 (got {self.n_step})")
        if self.algo not in ALGO_NAMES:
            problems.append(f"algo must be one of {list(ALGO_NAMES)} (got {self.algo!r})")
        if self.vector_mode not in VECTOR_MODES:
            problems.append(f"vector_mode must be one of {list(VECTOR_MODES)} (got {self.vector_mode!r})")
        if self.demo_steps > 0 and not self.demo_fn:
            problems.append("demo_steps > 0 needs demo_fn ('module:function')")
        if self.demo_steps > self.buffer_size:
            problems.append(f"demo_steps ({self.demo_steps}) exceeds buffer_size ({self.buffer_size})")
        _check(problems)

    def variant_kwargs(self) -> list[dict[str, Any]]:
        """The env keyword arguments of each block of sub-envs (``[env_kwargs]`` without variants)."""
        return [{**self.env_kwargs, **v} for v in self.env_variants] or [dict(self.env_kwargs)]

    def to_dict(self) -> dict[str, Any]:
        """JSON-safe nested dict (tuples as lists), the layout of the config files."""
        return _plain(dataclasses.asdict(self))


def _plain(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _example(section: str) -> str:
    name = dataclasses.fields(SECTIONS[section])[0].name
    return "{" + json.dumps(name) + ": ...}"


def _section(name: str, data: Mapping[str, Any]) -> Any:
    """Build section ``name`` from ``data`` (missing keys: defaults); unknown keys raise ValueError."""
    cls = SECTIONS[name]
    keys = {f.name for f in dataclasses.fields(cls)}
    unknown = sorted(k for k in data if k not in keys)
    if unknown:
        raise ValueError(f"unknown training config key(s) {[f'{name}.{k}' for k in unknown]}; "
                         f"valid {name} keys: {sorted(keys)}")
    return cls(**data)


def _run_keys() -> set[str]:
    return {f.name for f in dataclasses.fields(TrainConfig)}


def section_of(key: str) -> str | None:
    """The section holding field ``key`` (e.g. ``"actor_lr"`` -> ``"ddpg"``), None if none does;
    ``td3_NAME`` names ``td3.NAME``."""
    if key.startswith("td3_") and key[4:] in {f.name for f in dataclasses.fields(TD3Config)}:
        return "td3"
    for name, cls in SECTIONS.items():
        if key in {f.name for f in dataclasses.fields(cls)}:
            return name
    return None


def _misplaced(key: str) -> str:
    """Error text for a top-level key that belongs in a section, naming its place."""
    section = section_of(key)
    if section is None:
        return ""
    inner = key[4:] if key.startswith("td3_") else key
    return f"{key!r} belongs in the {section!r} section: {section}.{inner}"


def config_from_dict(data: Mapping[str, Any], base: TrainConfig | None = None) -> TrainConfig:
    """Build a config from nested ``data`` over ``base`` (or the defaults). A section given
    as a dict updates only its keys. Unknown keys raise ValueError (a section key at the top
    level names its section)."""
    data = {k: v for k, v in data.items() if not k.startswith("_")}
    unknown = sorted(k for k in data if k not in _run_keys())
    if unknown:
        misplaced = [m for m in map(_misplaced, unknown) if m]
        raise ValueError(f"unknown training config key(s) {unknown}"
                         + (f" ({'; '.join(misplaced)})" if misplaced else "")
                         + f"; valid top-level keys: {sorted(_run_keys())}")
    if isinstance(data.get("exploration"), str):
        raise ValueError(f"invalid training config: exploration is a section; the noise kind is exploration.kind "
                         f"(e.g. {{\"exploration\": {{\"kind\": {json.dumps(data['exploration'])}}}}})")
    values = base.to_dict() if base is not None else TrainConfig().to_dict()
    for k, v in data.items():
        if k in SECTIONS and isinstance(v, Mapping):
            values[k] = {**values[k], **v}
        else:
            values[k] = v
    return TrainConfig(**values)


def load_config(path: str | Path) -> TrainConfig:
    """Read a JSON config file (layout: the module docstring)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise FileNotFoundError(f"config file not found: {path}") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from exc
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object at top level")
    try:
        return config_from_dict(data)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def default_config(skill: str) -> TrainConfig:
    """The shipped config for a CLI skill name ("go-to-ball", "aim-to-shoot", "pendulum", ...)."""
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
    """A new config with ``--set key=value`` overrides applied (validated); ``SECTION.key=value``
    sets one key of a section (``ddpg.actor_lr=3e-4``)."""
    data: dict[str, Any] = {}
    for text in overrides:
        key, value = parse_override(text)
        section, dot, inner = key.partition(".")
        if dot:
            if section not in SECTIONS:
                raise ValueError(f"unknown config section {section!r} in --set {key}; sections: {sorted(SECTIONS)}")
            data.setdefault(section, {})[inner] = value
        else:
            data[key] = value
    return config_from_dict(data, base=cfg) if data else cfg
