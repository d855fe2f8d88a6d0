"""The vision tracker (ssl_marl.envs.tracking): filter error against a derived bound,
latency compensation, outlier gates, ball on the dribbler, determinism, bad input."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs.tracking import (
    TrackedVisionEnv,
    TrackerParams,
    VisionTracker,
    resolve_tracker,
    with_tracker,
)
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import (
    WorldState,
    make_team_state,
    to_team_frame,
    wrap_angle,
)

DT = 1.0 / 60.0
RP, BP = RobotParams(), BallParams()


def _team(pos, heading=0.0, vel=(0.0, 0.0), omega=0.0, on=False):
    return make_team_state(np.asarray(pos, float).reshape(1, 2), [heading], np.asarray(vel, float).reshape(1, 2),
                           [omega], [on], [True])


def _frame(t, blue, yellow, ball=(0.0, 0.0), ball_vel=(0.0, 0.0), visible=True):
    return WorldState(t=t, ball_pos=np.asarray(ball, float), ball_vel=np.asarray(ball_vel, float), blue=blue,
                      yellow=yellow, ball_visible=visible, frame="blue")


# ----------------------------------------------------------- filter accuracy
def _expected_cv_error(q: float, r_p: float, r_v: float, dt: float) -> float:
    """RMS 2-D position error of the tracker's filter on a true constant-velocity
    target: the filter's steady-state gain K from the Riccati recursion with its own
    white-noise-acceleration model (q), then the actual error covariance for a target
    with no acceleration, Sigma = A Sigma A^T + K R K^T, A = (I - K H) F, H = I."""
    F = np.array([[1.0, dt], [0.0, 1.0]])
    Q = q * q * np.array([[dt ** 4 / 4, dt ** 3 / 2], [dt ** 3 / 2, dt * dt]])
    R = np.diag([r_p * r_p, r_v * r_v])
    P = R.copy()
    for _ in range(5000):
        Pp = F @ P @ F.T + Q
        K = Pp @ np.linalg.inv(Pp + R)
        P = (np.eye(2) - K) @ Pp
    A = (np.eye(2) - K) @ F
    S = np.zeros((2, 2))
    for _ in range(5000):
        S = A @ S @ A.T + K @ R @ K.T
    return math.sqrt(2.0 * S[0, 0])  # x and y axes


def test_constant_velocity_target_error_within_derived_bound():
    r_p, r_v = 0.01, 0.05
    params = TrackerParams(robot_pos_sigma=r_p, vel_sigma=r_v)
    tr = VisionTracker("blue", RP, BP, DT, params=params)
    rng = np.random.default_rng(0)
    v = np.array([1.2, -0.7])
    p0 = np.array([-3.0, 1.5])
    errs, raw = [], []
    n = 3000
    for k in range(n):
        t = k * DT
        truth = p0 + v * t
        z = truth + rng.normal(0.0, r_p, 2)
        zv = v + rng.normal(0.0, r_v, 2)
        yellow = _team(z, 0.3, zv)  # the opponent: no commands, white-noise-acceleration model
        tr.update(_frame(t, _team((4.0, 2.0)), yellow, ball=(0.0, -2.0)))
        est = tr.predict(t).yellow.pos[0]
        if k >= 120:  # after the transient
            errs.append(np.sum((est - truth) ** 2))
            raw.append(np.sum((z - truth) ** 2))
    rms, rms_raw = math.sqrt(np.mean(errs)), math.sqrt(np.mean(raw))
    expected = _expected_cv_error(params.opp_accel_sigma, r_p, r_v, DT)
    assert expected < 0.8 * r_p * math.sqrt(2)  # filtering pays: the bound is below the raw noise
    assert 0.85 * expected < rms < 1.15 * expected
    assert rms < 0.8 * rms_raw


# ---------------------------------------------------------- latency, tactic
def _run_tactic(seed: int, steps: int = 400):
    from ssl_marl.plays.shoot import GoToBallAndShoot

    env = TrackedVisionEnv(parallel_env(n_blue=1, n_yellow=0, realism="realistic", referee=True,
                                        after_goal="terminate", max_time_s=steps * DT))
    rng = np.random.default_rng(seed)
    ball = rng.uniform((-3.0, -2.0), (3.0, 2.0))
    env.reset(seed=seed, options={"ball": {"pos": ball.tolist()},
                                  "robots": {"blue_0": [ball[0] - 1.5, ball[1] + 0.8, rng.uniform(-3, 3)]}})
    tac = GoToBallAndShoot(env.field, env.config.robot, env.config.ball, skills="baseline")
    rows = []
    while env.agents:
        tracked, raw = env.vision_state("blue"), env.raw_vision_state("blue")
        env.step({"blue_0": tac.act(tracked, 0)})
        truth = to_team_frame(env.world_state(), "blue")  # the time the command starts to act
        assert tracked.t == pytest.approx(truth.t)
        rows.append((tracked, raw, truth))
    return rows


def test_latency_compensation_reduces_error_along_the_run_and_at_contact():
    rows = []
    for seed in (1, 2):
        rows += _run_tactic(seed)
    err = lambda a, b: float(np.hypot(*(a - b)))
    trk = [err(tr.blue.pos[0], tru.blue.pos[0]) for tr, _, tru in rows]
    raw = [err(rw.blue.pos[0], tru.blue.pos[0]) for _, rw, tru in rows]
    assert np.sqrt(np.mean(np.square(trk))) < 0.3 * np.sqrt(np.mean(np.square(raw)))
    # at contact (the first step the robot truly has the ball on its dribbler): the
    # robot-to-ball vector the tactic's 35 mm test reads
    contact = [k for k in range(1, len(rows)) if rows[k][2].blue.ball_on_dribbler[0]
               and not rows[k - 1][2].blue.ball_on_dribbler[0]]
    assert contact
    rel = lambda w: w.ball_pos - w.blue.pos[0]
    e_trk = np.mean([err(rel(rows[k][0]), rel(rows[k][2])) for k in contact])
    e_raw = np.mean([err(rel(rows[k][1]), rel(rows[k][2])) for k in contact])
    assert e_trk < 0.5 * e_raw
    e_trk_pos = np.mean([err(rows[k][0].blue.pos[0], rows[k][2].blue.pos[0]) for k in contact])
    e_raw_pos = np.mean([err(rows[k][1].blue.pos[0], rows[k][2].blue.pos[0]) for k in contact])
    assert e_trk_pos < 0.3 * e_raw_pos


def test_commands_drive_the_prediction_ahead_of_vision():
    """A robot at rest is commanded forward: the tracker moves it before vision does."""
    env = TrackedVisionEnv(parallel_env(n_blue=1, n_yellow=0, realism="realistic", referee=False))
    env.reset(seed=0, options={"robots": {"blue_0": (0.0, 0.0, 0.0)}, "ball": {"pos": (3.0, 2.0)}})
    for _ in range(4):
        env.step({"blue_0": np.array([1.0, 0, 0, 0, 0], np.float32)})
    truth = env.world_state()
    env.step({"blue_0": np.array([1.0, 0, 0, 0, 0], np.float32)})
    tracked, raw = env.vision_state("blue"), env.raw_vision_state("blue")
    nxt = env.world_state()  # vision still shows the robot (almost) at rest
    assert raw.blue.vel[0, 0] < 0.1 < truth.blue.vel[0, 0]
    assert abs(tracked.blue.vel[0, 0] - nxt.blue.vel[0, 0]) < 0.05 + abs(nxt.blue.vel[0, 0] - truth.blue.vel[0, 0])


# ------------------------------------------------------------------ outliers
def test_single_outlier_is_ignored_and_repeated_ones_restart_the_filter():
    params = TrackerParams()
    tr = VisionTracker("blue", RP, BP, DT, params=params)
    p = np.array([1.0, 1.0])
    k = 0

    def feed(pos, ball=(0.0, 0.0)):
        nonlocal k
        tr.update(_frame(k * DT, _team(pos), _team((-2.0, 0.0)), ball=ball))
        k += 1
        return tr.predict((k - 1) * DT)

    for _ in range(20):
        feed(p)
    ws = feed(p + (1.0, 0.0), ball=(0.0, 1.0))  # one wild robot and ball detection
    assert np.hypot(*(ws.blue.pos[0] - p)) < 0.01
    assert np.hypot(*ws.ball_pos) < 0.01
    ws = feed(p)
    assert np.hypot(*(ws.blue.pos[0] - p)) < 0.01
    jumped = p + (1.0, 0.0)
    for i in range(params.max_outliers):  # a real jump: held off max_outliers frames ...
        ws = feed(jumped, ball=(0.0, 1.0))
        assert np.hypot(*(ws.blue.pos[0] - p)) < 0.02, i
    ws = feed(jumped, ball=(0.0, 1.0))  # ... then the filter restarts at the detection
    assert np.hypot(*(ws.blue.pos[0] - jumped)) < 0.01
    assert np.hypot(*(ws.ball_pos - (0.0, 1.0))) < 0.01


def test_referee_teleport_is_accepted_at_once():
    tr = VisionTracker("blue", RP, BP, DT)
    for k in range(10):
        tr.update(_frame(k * DT, _team((1.0, 1.0)), _team((-2.0, 0.0))))
    tr.expect_jump(3)
    tr.update(_frame(10 * DT, _team((-1.0, 0.0)), _team((2.0, 0.0)), ball=(0.5, 0.5)))
    ws = tr.predict(10 * DT)
    np.testing.assert_allclose(ws.blue.pos[0], (-1.0, 0.0), atol=1e-3)
    np.testing.assert_allclose(ws.yellow.pos[0], (2.0, 0.0), atol=1e-3)
    np.testing.assert_allclose(ws.ball_pos, (0.5, 0.5), atol=1e-3)


# ------------------------------------------------------- ball on the dribbler
def _holding_run(hide_from: int, steps: int = 90, kick_at: int | None = None):
    """A robot with the ball on its dribbler drives forward and turns gently; vision
    frames come from the realistic env; the ball is hidden from frame ``hide_from`` on."""
    env = parallel_env(n_blue=1, n_yellow=0, realism="realistic", referee=False)
    reach = RP.front_distance + BP.radius
    env.reset(seed=3, options={"robots": {"blue_0": (-1.0, 0.0, 0.0)}, "ball": {"pos": (-1.0 + reach, 0.0)}})
    tr = VisionTracker("blue", env.config.robot, env.config.ball, DT, params=TrackerParams.for_realism("realistic", DT))
    out = []
    last_seen = None
    for k in range(steps):
        frame = env.vision_state("blue")
        if k >= hide_from:
            last_seen = frame.ball_pos if last_seen is None else last_seen
            frame = replace(frame, ball_visible=False, ball_pos=last_seen)
        ws = tr.track(frame, env.world_state().t)
        a = np.array([0.3, 0.0, 0.15, 1.0, 1.0 if k == kick_at else 0.0])
        env.step({"blue_0": a})
        tr.record_command(round(env.world_state().t / DT), a[None])
        out.append((ws, to_team_frame(env.world_state(), "blue")))
    return out


def test_hidden_ball_is_pinned_to_the_dribbler():
    rows = _holding_run(hide_from=10)
    for ws, truth in rows[30:]:
        assert truth.blue.ball_on_dribbler[0]
        assert not ws.ball_visible
        assert ws.blue.ball_on_dribbler[0]
        assert np.hypot(*(ws.ball_pos - truth.ball_pos)) < 0.02
    # raw vision would hold the ball where it was last seen: far behind by now
    assert np.hypot(*(rows[-1][1].ball_pos - rows[10][1].ball_pos)) > 0.3


def test_sent_kick_releases_the_ball_in_the_prediction():
    rows = _holding_run(hide_from=10_000, steps=40, kick_at=20)
    # one step after the kick command, vision (50 ms old) still shows the ball held; the
    # prediction already has it flying at the kick speed
    ws, truth = rows[21]
    assert not ws.blue.ball_on_dribbler[0]
    assert np.hypot(*ws.ball_vel) > 0.9 * RP.kick_speed_max
    assert np.hypot(*(ws.ball_vel - truth.ball_vel)) < 0.3


# -------------------------------------------------------------- determinism
def test_tracked_runs_are_deterministic():
    a = _run_tactic(7, steps=120)
    b = _run_tactic(7, steps=120)
    for (ta, _, _), (tb, _, _) in zip(a, b):
        np.testing.assert_array_equal(ta.blue.pos, tb.blue.pos)
        np.testing.assert_array_equal(ta.ball_pos, tb.ball_pos)
        assert ta.blue.ball_on_dribbler[0] == tb.blue.ball_on_dribbler[0]


# ------------------------------------------------------------- env layer
def test_without_realism_the_tracker_reproduces_vision():
    env = TrackedVisionEnv(parallel_env(n_blue=2, n_yellow=2, realism="none"))
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    for _ in range(60):
        for team in ("blue", "yellow"):
            tracked, raw = env.vision_state(team), env.raw_vision_state(team)
            assert tracked.frame == raw.frame == team
            np.testing.assert_allclose(tracked.blue.pos, raw.blue.pos, atol=2e-3)
            assert np.abs(wrap_angle(tracked.yellow.heading - raw.yellow.heading)).max() < 3e-2
        env.step({a: rng.uniform(-1, 1, 5).astype(np.float32) for a in env.agents})
    assert env.score == env.env.score  # everything else is the env's


def test_realtime_mode_runs_through_the_tracker():
    env = TrackedVisionEnv(parallel_env(n_blue=1, n_yellow=1, realism="realistic", realtime=True))
    env.reset(seed=0)
    for _ in range(5):
        ws = env.vision_state("yellow")
        assert ws.frame == "yellow"
        assert ws.t == pytest.approx(env.world_state().t + DT)
        env.step({"blue_0": np.zeros(5, np.float32), "yellow_0": np.array([0.5, 0, 0, 0, 0], np.float32)})


def test_resolve_tracker_defaults_follow_realism():
    assert resolve_tracker("auto", "realistic") is True
    assert resolve_tracker("auto", "none") is False
    assert resolve_tracker(None, "none") is False
    assert resolve_tracker("on", "none") is True
    assert resolve_tracker("off", "realistic") is False
    env = parallel_env(n_blue=1, n_yellow=0)
    assert with_tracker(env, "auto") is env
    assert isinstance(with_tracker(env, "on"), TrackedVisionEnv)


# ------------------------------------------------------------------ errors
def test_bad_input_gives_clear_errors():
    with pytest.raises(ValueError, match="robot_pos_sigma"):
        TrackerParams(robot_pos_sigma=-1.0)
    with pytest.raises(ValueError, match="max_outliers"):
        TrackerParams(max_outliers=0)
    with pytest.raises(ValueError, match="release_gate"):
        TrackerParams(release_gate=0.01, dribbler_gate=0.02)
    with pytest.raises(ValueError, match="team"):
        VisionTracker("green")
    with pytest.raises(ValueError, match="dt"):
        VisionTracker("blue", dt=0.0)
    tr = VisionTracker("blue")
    with pytest.raises(RuntimeError, match="no vision frame"):
        tr.predict(0.0)
    with pytest.raises(ValueError, match="WorldState"):
        tr.update("frame")
    good = _frame(0.0, _team((0.0, 0.0)), _team((1.0, 0.0)))
    with pytest.raises(ValueError, match="'yellow'"):
        VisionTracker("yellow").update(good)
    with pytest.raises(ValueError, match="ball_pos"):
        tr.update(replace(good, ball_pos=np.array([np.nan, 0.0])))
    with pytest.raises(ValueError, match="blue.pos"):
        tr.update(replace(good, blue=_team((np.inf, 0.0))))
    tr.update(good)
    with pytest.raises(ValueError, match="before the last capture"):
        tr.predict(-1.0)
    with pytest.raises(ValueError, match=r"shape \(n, 5\)"):
        tr.record_command(1, np.zeros(5))
    with pytest.raises(ValueError, match="NaN"):
        tr.record_command(1, np.full((1, 5), np.nan))
    with pytest.raises(ValueError, match="robots"):
        tr.update(replace(good, t=DT, blue=make_team_state(np.zeros((2, 2)), [0, 0], np.zeros((2, 2)), [0, 0],
                                                            [False, False], [True, True])))
    with pytest.raises(ValueError, match="tracker"):
        resolve_tracker("maybe", "none")
    with pytest.raises(ValueError, match="SSLParallelEnv"):
        TrackedVisionEnv(object())


def test_cli_exposes_the_tracker_option():
    from ssl_marl.cli import build_parser

    p = build_parser()
    for cmd in (["eval-skill", "go-to-ball"], ["eval-tactic"], ["match"]):
        assert p.parse_args(cmd).tracker == "auto"
        assert p.parse_args(cmd + ["--tracker", "off"]).tracker == "off"
    with pytest.raises(SystemExit):
        p.parse_args(["eval-tactic", "--tracker", "maybe"])


def test_evaluations_run_through_the_tracker(tmp_path):
    from ssl_marl.runners.tactic_eval import evaluate_tactic
    from ssl_marl.runners.skill_eval import evaluate_skill

    r = evaluate_tactic(skills="baseline", episodes=1, seed=20000, realism="realistic", progress=False,
                        max_time_s=2.0)
    assert r["config"]["tracker"] is True
    s = evaluate_skill("go-to-ball", "baseline", episodes=2, seed=10000, realism="realistic", progress=False,
                       tracker="on")
    assert s["config"]["tracker"] is True and s["episodes"] == 2


def test_skill_task_env_trains_through_the_tracker():
    """``tracker=True`` on a skill task env: the robot's features come from the tracker's
    estimate (not the raw delayed frame), the env passes Gymnasium's checker, and a bad
    value is refused by name."""
    from gymnasium.utils.env_checker import check_env

    from ssl_marl.envs.tracking import TrackedVisionEnv
    from ssl_marl.skills.features import go_to_ball_features
    from ssl_marl.skills.wrappers import GoToBallEnv

    env = GoToBallEnv(realism="randomized", tracker=True)
    assert isinstance(env.env, TrackedVisionEnv)
    check_env(env, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    for _ in range(30):
        obs, *_ = env.step(np.array([1.0, 0.0, 0.5], np.float32))
    np.testing.assert_allclose(obs, go_to_ball_features(env.env.vision_state("blue"), 0, env.field), rtol=1e-6)
    raw = go_to_ball_features(env.env.env.vision_state("blue"), 0, env.field)
    assert not np.allclose(obs, raw)  # the raw frame is older: the tracker predicts ahead
    with pytest.raises(ValueError, match="tracker: expected one of"):
        GoToBallEnv(tracker="yes")
    assert not isinstance(GoToBallEnv(realism="realistic").env, TrackedVisionEnv)  # skill tasks: off by default
    assert isinstance(GoToBallEnv(realism="realistic", tracker="auto").env, TrackedVisionEnv)
    from ssl_marl.skills.vector import SkillVectorEnv

    with pytest.raises(ValueError, match="tracker: not supported by the vector env"):
        SkillVectorEnv("go-to-ball", 2, realism="realistic", tracker="auto")


@pytest.mark.parametrize("env_id", ["ssl_marl/Pass-v0", "ssl_marl/Receive-v0"])
def test_passing_task_envs_take_the_tracker_option(env_id):
    """Pass and receive take ``tracker=`` like the one-robot tasks: on, the robot's features
    come from the tracker's estimate; "auto" follows the realism preset."""
    import gymnasium as gym

    import ssl_marl  # noqa: F401  (registers the ids)

    env = gym.make(env_id, realism="realistic", tracker="on").unwrapped
    assert isinstance(env.env, TrackedVisionEnv)
    obs, _ = env.reset(seed=5)
    for _ in range(20):
        obs, _, term, trunc, _ = env.step(np.zeros(3, np.float32))
        if term or trunc:
            break
    np.testing.assert_allclose(obs, env.task.observe(env.env.vision_state("blue"), 0), rtol=1e-6)
    assert not isinstance(gym.make(env_id, tracker="auto").unwrapped.env, TrackedVisionEnv)


def test_decision_tasks_read_the_tracker_under_realism():
    """Decision task envs: ``tracker`` "auto" (default) runs the tracker exactly when
    realism is on; "off" keeps the raw vision."""
    from ssl_marl.decisions import make_decision_env

    for task in ("keepaway", "attack-3v2"):
        assert not isinstance(make_decision_env(task).engine, TrackedVisionEnv)
        assert isinstance(make_decision_env(task, realism="realistic").engine, TrackedVisionEnv)
        assert not isinstance(make_decision_env(task, realism="realistic", tracker="off").engine, TrackedVisionEnv)
    env = make_decision_env("keepaway", realism="realistic")
    obs, infos = env.reset(seed=1)
    obs, *_ = env.step({a: 0 for a, i in infos.items() if i["decision"]})
    assert env.engine.env._observations is dict  # the keepaway env builds its own observations
