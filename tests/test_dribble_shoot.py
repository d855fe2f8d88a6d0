"""DribbleAndShoot: each transition on hand-built inputs and scenes, the shooting
window geometry, the approach gates, and short physics runs that check the ball is kept."""

import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry
from ssl_marl.plays.dribble_shoot import DribbleAndShoot, DribbleInputs, DribbleParams, DribbleState, shooting_point
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.skills.base import SkillStatus

F = FieldGeometry.div_b()
FA = FieldGeometry.div_a()
DT = 1.0 / 60.0
S = DribbleState
P = DribbleParams()


def scene(robot=(0.0, 0.0, 0.0), ball=None, gap=0.0, t=0.0, **kw):
    if ball is None:
        ball = ball_in_front(*robot, gap=gap)
    return make_world(blue=[robot], ball=ball, t=t, frame="blue", **kw)


# ------------------------------------------------------------- transitions
@pytest.mark.parametrize("state,inputs,expected", [
    # GO_TO_BALL: the 35 mm test or the dribbler flag
    (S.GO_TO_BALL, DribbleInputs(d_db=0.036), S.GO_TO_BALL),
    (S.GO_TO_BALL, DribbleInputs(d_db=0.035), S.CONTROL),
    (S.GO_TO_BALL, DribbleInputs(d_db=0.5, held=True), S.CONTROL),
    (S.GO_TO_BALL, DribbleInputs(d_db=0.5, stalled=True), S.RECOVER),
    # RECOVER: reach the ball or give the skill another go
    (S.RECOVER, DribbleInputs(d_db=0.02), S.CONTROL),
    (S.RECOVER, DribbleInputs(d_db=0.5, time_in_state=1.0), S.RECOVER),
    (S.RECOVER, DribbleInputs(d_db=0.5, time_in_state=2.1), S.GO_TO_BALL),
    # CONTROL: secure (held long enough, slow) -> DRIBBLE or AIM; lost -> GO_TO_BALL
    (S.CONTROL, DribbleInputs(d_db=0.0, held=True, held_s=0.05, speed=0.1), S.CONTROL),
    (S.CONTROL, DribbleInputs(d_db=0.0, held=True, held_s=0.1, speed=0.5), S.CONTROL),
    (S.CONTROL, DribbleInputs(d_db=0.0, held=True, held_s=0.1, speed=0.1), S.DRIBBLE),
    (S.CONTROL, DribbleInputs(d_db=0.0, held=True, held_s=0.1, speed=0.1, in_window=True), S.AIM),
    (S.CONTROL, DribbleInputs(d_db=0.07), S.GO_TO_BALL),
    (S.CONTROL, DribbleInputs(d_db=0.05), S.CONTROL),  # hysteresis: 35 mm in, 60 mm out
    (S.CONTROL, DribbleInputs(d_db=0.02, time_in_state=1.1), S.GO_TO_BALL),
    # DRIBBLE: arrive slowly -> AIM; ball off the dribbler -> GO_TO_BALL
    (S.DRIBBLE, DribbleInputs(d_db=0.0, held=True, to_target_m=1.0, speed=2.0), S.DRIBBLE),
    (S.DRIBBLE, DribbleInputs(d_db=0.0, held=True, to_target_m=0.1, speed=0.5), S.DRIBBLE),
    (S.DRIBBLE, DribbleInputs(d_db=0.0, held=True, to_target_m=0.1, speed=0.2), S.AIM),
    (S.DRIBBLE, DribbleInputs(d_db=0.0, held=True, to_target_m=1.0, in_window=True, speed=0.2), S.AIM),
    (S.DRIBBLE, DribbleInputs(d_db=0.051, to_target_m=0.1, speed=0.2), S.GO_TO_BALL),
    # AIM: kick -> GO_TO_BALL; the skill gives up: ball still here -> DRIBBLE closer, else GO_TO_BALL
    (S.AIM, DribbleInputs(d_db=0.0), S.AIM),
    (S.AIM, DribbleInputs(d_db=0.0, kicked=True), S.GO_TO_BALL),
    (S.AIM, DribbleInputs(d_db=0.0, skill_status=SkillStatus.SUCCEEDED), S.GO_TO_BALL),
    (S.AIM, DribbleInputs(d_db=0.01, skill_status=SkillStatus.FAILED), S.DRIBBLE),
    (S.AIM, DribbleInputs(d_db=0.2, skill_status=SkillStatus.FAILED), S.GO_TO_BALL),
])
def test_transitions(state, inputs, expected):
    assert DribbleAndShoot.transition(state, inputs, P) is expected


def test_params_are_checked_by_name():
    with pytest.raises(ValueError, match="dribble_speed"):
        DribbleParams(dribble_speed=-1.0)
    with pytest.raises(ValueError, match="control_lost_m"):
        DribbleParams(control_lost_m=0.01)
    with pytest.raises(ValueError, match="window_max_angle_rad"):
        DribbleParams(window_max_angle_rad=2.0)
    with pytest.raises(ValueError, match="unknown parameter"):
        DribbleAndShoot(F, bogus=1)
    import dataclasses

    with pytest.raises(dataclasses.FrozenInstanceError):
        DribbleParams().touch_speed = 1.0


# ------------------------------------------------------------ geometry
def test_shooting_point_on_the_ray_outside_the_defense_area():
    g = F.goal_center(+1)
    pt, inside = shooting_point(F, np.array([-3.0, 0.0]), P)
    assert not inside
    assert pt[1] == pytest.approx(0.0) and math.hypot(*(pt - g)) == pytest.approx(1.8 * F.goal_width)
    # a ball at a steep angle: clamped to window_max_angle_rad, pushed out of the defense area
    pt, _ = shooting_point(F, np.array([4.0, -2.8]), P)
    ang = math.atan2(pt[1] - g[1], g[0] - pt[0])
    assert ang == pytest.approx(-P.window_max_angle_rad)
    assert not F.in_defense_area(pt, +1, margin=P.defense_margin_m - 1e-6)
    # Division A: 1.8 goal widths of a 1.8 m goal, and outside its larger defense area
    pta, _ = shooting_point(FA, np.array([-5.0, 3.0]), P)
    assert math.hypot(*(pta - FA.goal_center(+1))) >= 1.8 * FA.goal_width - 1e-9
    assert not FA.in_defense_area(pta, +1)
    # a closer, explicit distance is still kept out of the defense area
    ptc, _ = shooting_point(F, np.array([0.0, 0.0]), P, distance=0.2)
    assert not F.in_defense_area(ptc, +1)


def test_ball_in_the_window_is_aimed_from_where_it_is():
    _, inside = shooting_point(F, np.array([2.6, 0.2]), P)
    assert inside
    _, behind_goal_line_side = shooting_point(F, np.array([4.3, 2.5]), P)  # outside the angle
    assert not behind_goal_line_side


def test_retries_shorten_the_shooting_distance():
    tac = DribbleAndShoot(F)
    d0 = tac.shoot_distance()
    tac._retries = 2
    assert tac.shoot_distance() == pytest.approx(d0 - 2 * P.retry_step_m)
    tac._retries = 100
    assert tac.shoot_distance() == pytest.approx(P.min_shoot_distance_m)


# ------------------------------------------------------- executed actions
def test_go_to_ball_is_governed_and_does_not_push_sideways():
    tac = DribbleAndShoot(F, skills="baseline")
    # ball 5 cm beside the face: no velocity component towards the ball
    ws = scene(robot=(0.0, 0.0, 0.0), ball=(0.05, 0.14), t=0.0)
    a = tac.act(ws, 0)
    assert tac.state is S.GO_TO_BALL
    h = 0.0
    v_field = np.array([a[0] * math.cos(h) - a[1] * math.sin(h), a[0] * math.sin(h) + a[1] * math.cos(h)])
    u = np.array([0.05, 0.14]) / math.hypot(0.05, 0.14)
    assert float(v_field @ u) <= 1e-6 and a[3] > 0
    # far ball: the governor caps the speed at sqrt(v_touch^2 + 2 a gap)
    tac2 = DribbleAndShoot(F, skills="baseline", touch_speed=0.2, approach_decel=1.0)
    ws = scene(robot=(0.0, 0.0, 0.0), ball=(0.4, 0.0))
    a = tac2.act(ws, 0)
    gap = 0.4 - 0.08 - 0.0215
    assert math.hypot(a[0], a[1]) * 3.0 <= math.sqrt(0.04 + 2.0 * gap) + 1e-5


def test_control_brakes_gently_then_dribbles_towards_the_window():
    tac = DribbleAndShoot(F, skills="baseline")
    # robot moving at 2 m/s with the ball on the face: CONTROL may shed at most control_decel * dt per tick
    ws = scene(robot=(-2.0, 0.0, 0.0), t=0.0, blue_vel=[(2.0, 0.0)], blue_on_dribbler=[True])
    a = tac.act(ws, 0)
    assert tac.state is S.CONTROL
    assert a[0] * 3.0 == pytest.approx(2.0 - P.control_decel * DT, abs=1e-4) and a[3] > 0
    # at rest, held for secure_s: DRIBBLE, heading at the window (+x): forward, dribbler on
    tac = DribbleAndShoot(F, skills="baseline")
    t = 0.0
    for _ in range(8):
        a = tac.act(scene(robot=(-2.0, 0.0, 0.0), t=t, blue_on_dribbler=[True]), 0)
        t += DT
    assert tac.state is S.DRIBBLE
    assert a[0] > 0 and abs(a[1]) < 1e-6 and a[3] > 0 and a[4] < 0
    assert a[0] * 3.0 <= P.dribble_accel * DT * 9 + 1e-6  # ramped up, not a jump to full speed


def test_dribble_turns_in_place_when_facing_away():
    tac = DribbleAndShoot(F, skills="baseline")
    t = 0.0
    for _ in range(8):
        a = tac.act(scene(robot=(-2.0, 0.0, math.pi), t=t, blue_on_dribbler=[True]), 0)
        t += DT
    assert tac.state is S.DRIBBLE
    assert abs(a[2]) * 10.0 == pytest.approx(P.dribble_turn_rate, rel=1e-4)
    assert math.hypot(a[0], a[1]) < 1e-6


def test_in_window_with_the_ball_aims_and_the_baseline_shoots():
    tac = DribbleAndShoot(F, skills="baseline")
    t = 0.0
    kicked = False
    for _ in range(30):
        a = tac.act(scene(robot=(2.6, 0.0, 0.0), t=t, blue_on_dribbler=[True]), 0)
        t += DT
        if a[4] > 0:
            kicked = True
            break
    assert kicked and tac.status.kicks == 1
    a = tac.act(scene(robot=(2.6, 0.0, 0.0), ball=(3.5, 0.0), t=t), 0)
    assert tac.state is S.GO_TO_BALL


def test_stall_triggers_recover_and_reset_clears_it():
    tac = DribbleAndShoot(F, skills="baseline")
    # the ball never gets closer (the robot does not move): after stall_s, RECOVER
    t = 0.0
    states = []
    for _ in range(int(1.3 / DT)):
        tac.act(scene(robot=(0.0, 0.0, math.pi / 2), ball=(1.0, 0.0), t=t), 0)
        states.append(tac.state)
        t += DT
    assert S.RECOVER in states and tac.stalls == 1
    tac.reset()
    assert tac.state is S.GO_TO_BALL and tac.stalls == 0


# ------------------------------------------------------------ physics
def _run(env, tac, steps):
    out = []
    for _ in range(steps):
        if not env.agents:
            break
        a = tac.act(env.vision_state("blue"), 0)
        _, _, _, _, infos = env.step({"blue_0": a})
        out.append((tac.state, env.world_state(), infos["blue_0"]["events"] if infos else []))
    return out


def test_dribble_keeps_the_ball_over_the_field_and_scores():
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=1, n_yellow=0, field="div_b", referee=True, after_goal="terminate", max_time_s=10.0)
    # ball on the dribbler of a robot in its own half facing its own goal: turn, carry, shoot
    pose = (-2.5, 1.0, math.pi)
    env.reset(seed=1, options={"robots": {"blue_0": list(pose)}, "ball": {"pos": list(ball_in_front(*pose))}})
    tac = DribbleAndShoot(env.field, env.config.robot, env.config.ball, skills="baseline", dt=env.config.dt)
    trace = _run(env, tac, 600)
    states = [s for s, _, _ in trace]
    assert S.DRIBBLE in states and S.AIM in states
    first_aim = states.index(S.AIM)
    # from the first CONTROL to the aim, the ball never left the dribbler zone (no GO_TO_BALL in between)
    assert S.GO_TO_BALL not in states[states.index(S.CONTROL):first_aim]
    ball_at_aim = trace[first_aim][1].ball_pos
    assert ball_at_aim[0] > 1.5  # carried from x = -2.6 into the attacking third
    goals = [e for _, _, ev in trace for e in ev if e["type"] == "goal"]
    assert goals and goals[0]["team"] == "blue"


def test_learned_go_to_ball_takes_the_ball_gently():
    """The learned go-to-ball alone hits the ball at ~2.6 m/s; under the tactic's governor
    the first contact happens at low robot speed."""
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=1, n_yellow=0, field="div_b", referee=True, after_goal="terminate", max_time_s=6.0)
    speeds = []
    for seed, (ball, pose) in enumerate([((1.0, 0.5), (-1.0, -0.5, 0.3)), ((-2.0, 1.5), (0.5, -1.0, 2.5))]):
        env.reset(seed=seed, options={"robots": {"blue_0": list(pose)}, "ball": {"pos": list(ball)}})
        tac = DribbleAndShoot(env.field, env.config.robot, env.config.ball, skills="learned", dt=env.config.dt)
        for state, world, _ in _run(env, tac, 360):
            if world.blue.ball_on_dribbler[0]:
                speeds.append(float(np.hypot(*world.blue.vel[0])))
                break
    assert len(speeds) == 2 and max(speeds) < 1.0, speeds


# ------------------------------------------------------------- runner / CLI
def test_eval_tactic_runs_the_chosen_tactic(tmp_path):
    from ssl_marl.runners.tactic_eval import evaluate_tactic, run_episode

    r = evaluate_tactic(skills="baseline", episodes=2, seed=123, workers=1, progress=False,
                        tactic="dribble-and-shoot", out=tmp_path)
    assert r["tactic"] == "dribble-and-shoot" and "dribble-and-shoot" in r["protocol"]
    assert "go_to_ball_stalls" in r and (tmp_path / "results.json").is_file()
    # the same episode under the paper's tactic is a different run (no stall counter)
    e = run_episode(0, 123, "baseline", tactic="go-to-ball-and-shoot", max_time_s=1.0)
    assert "stalls" not in e
    with pytest.raises(ValueError, match="unknown tactic"):
        evaluate_tactic(skills="baseline", episodes=1, tactic="dribble", progress=False)


def test_cli_eval_tactic_has_tactic_and_realtime(capsys):
    from ssl_marl.cli import main

    rc = main(["eval-tactic", "--tactic", "dribble-and-shoot", "--skills", "baseline", "--episodes", "1",
               "--seed", "5", "--realtime", "--quiet"])
    out = capsys.readouterr().out
    assert rc == 0 and out.startswith("dribble-and-shoot (baseline skills)") and "missed deadlines" in out
