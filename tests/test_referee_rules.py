"""SSL game control (ssl_marl.envs.game_control, the match task): fouls, free kicks,
STOP, half-time, seeded restart placement; the statistics helper's intervals."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.envs.actions import make_action
from ssl_marl.envs.game_control import (DEFENDER_TOO_CLOSE_M, FREE_KICK, KICKOFF, RUNNING, STOP, RefereeState,
                                        TouchWatch, jittered_kickoff, too_close_to_kick_point)
from ssl_marl.envs.referee import kickoff_poses
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.state import WorldState, make_team_state, to_team_frame
from ssl_marl.plays.team import keep_clear
from ssl_marl.runners.statistics import series_statistics, t_interval, wilson_interval

FIELD = FieldGeometry.from_name("div_b")
R_ROBOT, R_BALL = 0.09, 0.0215


def world(blue_xy, yellow_xy, ball_xy, t=0.0) -> WorldState:
    def team(xy):
        n = len(xy)
        return make_team_state(np.array(xy, float).reshape(n, 2), np.zeros(n), np.zeros((n, 2)), np.zeros(n),
                               np.zeros(n, bool), np.ones(n, bool))
    return WorldState(t=t, ball_pos=np.array(ball_xy, float), ball_vel=np.zeros(2), blue=team(blue_xy),
                      yellow=team(yellow_xy))


def touch_step(watch, ws, fouls=True):
    return watch.update(ws, watch.touching(ws, []), FIELD, fouls)


def test_dribbling_1_2_m_is_a_foul_and_0_9_m_is_not():
    watch = TouchWatch(1, 1, R_ROBOT, R_BALL)
    calls = []
    for k in range(13):  # robot and ball move together 0.1 m per tick: 1.2 m in all
        x = -2.0 + 0.1 * k
        calls.append(touch_step(watch, world([(x, 0.0)], [(3.0, 2.0)], (x + 0.1, 0.0))))
    assert all(c is None for c in calls[:10])  # up to 0.9 m (and 1.0 m exactly) no foul
    assert calls[-1] == ("excessive_dribbling", 0)


def test_last_toucher_of_a_contested_tick_is_the_kicker_or_the_nearest_robot_not_the_last_row():
    """A blue and a yellow robot come into contact with the ball in the same tick: the
    last toucher (whose opponents get the free kick if the ball goes out) is the robot
    that kicked, else the one nearer the ball, whichever colour it is."""
    for blue_x, yellow_x, near in ((-0.10, 0.11, 0), (-0.11, 0.10, 1)):
        watch = TouchWatch(1, 1, R_ROBOT, R_BALL)
        ws = world([(blue_x, 0.0)], [(yellow_x, 0.0)], (0.0, 0.0))
        watch.update(ws, watch.touching(ws, []), FIELD, False)
        assert watch.last_robot == near and watch.last_team() == ("blue", "yellow")[near]
        for kicker in (0, 1):
            watch = TouchWatch(1, 1, R_ROBOT, R_BALL)
            watch.update(ws, watch.touching(ws, [kicker]), FIELD, False, [kicker])
            assert watch.last_robot == kicker


def test_double_touch_after_a_free_kick():
    watch = TouchWatch(2, 1, R_ROBOT, R_BALL)
    assert touch_step(watch, world([(0.0, 0.0), (2.0, 2.0)], [(3.0, 2.0)], (0.1, 0.0))) is None
    watch.taken_by(0)
    assert touch_step(watch, world([(0.0, 0.0), (2.0, 2.0)], [(3.0, 2.0)], (0.5, 0.0))) is None  # let go
    assert touch_step(watch, world([(0.4, 0.0), (2.0, 2.0)], [(3.0, 2.0)], (0.5, 0.0))) == ("double_touch", 0)
    # another robot touching first clears the guard
    watch = TouchWatch(2, 1, R_ROBOT, R_BALL)
    watch.taken_by(0)
    touch_step(watch, world([(0.0, 0.0), (2.0, 2.0)], [(3.0, 2.0)], (1.0, 0.0)))
    touch_step(watch, world([(0.0, 0.0), (1.1, 0.0)], [(3.0, 2.0)], (1.0, 0.0)))
    assert touch_step(watch, world([(0.9, 0.0), (2.0, 2.0)], [(3.0, 2.0)], (1.0, 0.0))) is None


def test_attacker_touching_the_ball_in_the_opponent_defense_area():
    watch = TouchWatch(1, 1, R_ROBOT, R_BALL)
    inside = (FIELD.half_length - 0.3, 0.0)  # blue attacks +x: the yellow defense area
    assert touch_step(watch, world([(inside[0] - 0.1, 0.0)], [(-3.0, 2.0)], inside)) == ("attacker_in_defense_area", 0)
    watch = TouchWatch(1, 1, R_ROBOT, R_BALL)  # the defender in its own area: no foul
    assert touch_step(watch, world([(-3.0, 2.0)], [(inside[0] + 0.1, 0.0)], inside)) is None
    watch = TouchWatch(1, 1, R_ROBOT, R_BALL)  # switched off
    assert touch_step(watch, world([(inside[0] - 0.1, 0.0)], [(-3.0, 2.0)], inside), fouls=False) is None


def _env(**rules):
    return parallel_env(n_blue=1, n_yellow=1, max_time_s=60.0, **rules)


def _idle(env):
    return {a: make_action() for a in env.agents}


def test_free_kick_goes_to_the_team_that_did_not_touch_last_after_a_stop():
    env = _env(ssl_restarts=True, stop_s=0.5)
    L2, W2 = FIELD.half_length, FIELD.half_width
    env.reset(seed=1, options={"ball": {"pos": (1.0, W2 - 0.12), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (1.0, W2 - 0.22, math.pi / 2), "yellow_0": (-3.0, 0.0, 0.0)}})
    events = []
    for _ in range(90):
        _, _, _, _, infos = env.step(_idle(env))
        events += infos["blue_0"]["events"]
        if env.task.referee_state.command == FREE_KICK:
            break
    outs = [e for e in events if e["type"] == "ball_out"]
    assert outs and outs[0]["free_kick_for"] == "yellow"
    commands = [e["command"] for e in events if e["type"] == "referee"]
    assert commands[-2:] == [STOP, FREE_KICK]
    stop = [e for e in events if e["type"] == "referee" and e["command"] == STOP][-1]
    assert (stop["next_command"], stop["next_team"]) == (FREE_KICK, "yellow")  # the STOP announces it
    st = env.task.referee_state
    assert st.team == "yellow" and np.allclose(st.position, outs[0]["placement"])
    assert st.next_command is None
    # the free kick times out into running play
    for _ in range(int(10.5 * 60)):
        env.step(_idle(env))
    assert env.task.referee_state.command == RUNNING


@pytest.mark.parametrize("ball, kw, spot", [
    ((3.6, 0.5), {}, (2.5, 0.5)),  # in the defense area: 1 m out of its front line
    ((2.8, -0.3), {}, (2.5, -0.3)),  # within 1 m of the front line
    ((4.0, 1.5), {}, (4.0, 2.0)),  # beside the area: 1 m out of its side line, the nearer one
    ((-3.9, -1.2), {}, (-3.9, -2.0)),
    ((1.0, 3.1), {}, (1.0, 2.8)),  # over the touch line: 0.2 m inside it
    ((4.6, 0.8), dict(goal_line=1), (4.3, 2.8)),  # corner kick
    ((-4.6, -0.2), dict(goal_line=-1, goal_kick=True), (-3.5, -2.8)),  # goal kick: 1 m from the goal line
])
def test_ssl_free_kick_spots(ball, kw, spot):
    from ssl_marl.envs.referee import free_kick_spot

    assert np.allclose(free_kick_spot(np.array(ball), FIELD, **kw), spot)
    with pytest.raises(ValueError, match="goal_line"):
        free_kick_spot(np.array(ball), FIELD, goal_line=2)


@pytest.mark.parametrize("toucher, over, spot", [("yellow", -1, (-3.5, 2.8)), ("blue", -1, (-4.3, 2.8)),
                                                  ("blue", 1, (3.5, 2.8))])
def test_ball_over_the_goal_line_gives_a_goal_kick_or_a_corner_kick(toucher, over, spot):
    """A ball out over a team's own goal line last touched by the opponents is that team's goal
    kick, 1 m from the line; last touched by the team itself, the opponents' corner kick."""
    env = _env(ssl_restarts=True, stop_s=0.5)
    L2 = FIELD.half_length
    x = over * (L2 - 0.05)
    heading = 0.0 if over > 0 else math.pi
    other_robot = "yellow_0" if toucher == "blue" else "blue_0"
    robots = {f"{toucher}_0": (x - over * 0.13, 2.0, heading), other_robot: (0.0, -2.0, 0.0)}
    env.reset(seed=1, options={"ball": {"pos": (x, 2.0)}, "robots": robots})
    for _ in range(60):  # the toucher pushes the ball over the line
        _, _, _, _, infos = env.step({f"{toucher}_0": make_action(vx=1.0), other_robot: make_action()})
        outs = [e for e in infos["blue_0"]["events"] if e["type"] == "ball_out"]
        if outs:
            break
    assert outs and outs[0]["free_kick_for"] == ("yellow" if toucher == "blue" else "blue")
    assert np.allclose(outs[0]["placement"], spot)


def test_a_foul_in_the_defense_area_is_a_free_kick_1_m_outside_it():
    """blue_0 takes the kickoff with a kick into the yellow defense area, where blue_1
    touches it: attacker_in_defense_area, yellow's free kick 1 m outside the area."""
    env = parallel_env(n_blue=2, n_yellow=1, max_time_s=60.0, ssl_restarts=True, fouls=True, stop_s=0.5)
    L2 = FIELD.half_length
    env.reset(seed=1, options={"ball": {"pos": (3.0, 0.3)},
                               "robots": {"blue_0": (2.885, 0.3, 0.0), "blue_1": (L2 - 0.5, 0.3, math.pi),
                                          "yellow_0": (-3.0, 0.0, 0.0)}})
    fouls = []
    for k in range(60):
        kick = make_action(vx=0.3, kick=0.3) if k < 10 else make_action()
        _, _, _, _, infos = env.step({"blue_0": kick, "blue_1": make_action(), "yellow_0": make_action()})
        fouls += [e for e in infos["blue_0"]["events"] if e["type"] == "foul"]
        if fouls:
            break
    assert fouls and (fouls[0]["foul"], fouls[0]["agent"]) == ("attacker_in_defense_area", "blue_1")
    assert np.allclose(fouls[0]["placement"][0], L2 - FIELD.defense_depth - 1.0)
    assert env.task.referee_state.next_team == "yellow"


def test_defender_too_close_to_kick_point_helper():
    spot = np.array([1.0, 0.5])
    pos = np.array([[1.0, 1.2], [1.3, 0.5 + 0.35], [3.0, 0.0]])  # 0.70 m, 0.46 m, far
    assert too_close_to_kick_point(pos, spot) == 1
    assert too_close_to_kick_point(pos[[0, 2]], spot) is None
    assert too_close_to_kick_point(np.array([[1.0, 0.5 + DEFENDER_TOO_CLOSE_M + 1e-6]]), spot) is None
    assert too_close_to_kick_point(np.zeros((0, 2)), spot) is None


def _walk_in(env, mover: str, max_steps: int = 240):
    """Step ``env`` with ``mover`` driving forward at 0.3 (normalised) until a foul event;
    returns (the foul events, all referee commands seen)."""
    fouls, commands = [], []
    for _ in range(max_steps):
        actions = _idle(env)
        actions[mover] = make_action(vx=0.3)
        _, _, _, _, infos = env.step(actions)
        for e in infos[env.agents[0]]["events"]:
            fouls += [e] if e["type"] == "foul" else []
            commands += [e["command"]] if e["type"] == "referee" else []
        if fouls:
            return fouls, commands
    return fouls, commands


@pytest.mark.parametrize("fouls_on", [True, False])
def test_a_defender_walking_into_the_kickoff_gets_the_kickoff_taken_again(fouls_on):
    """Yellow drives at the ball during blue's kickoff: with fouls on, the referee calls
    ``defender_too_close`` on yellow once it is within 0.48 m of the ball (centre), stops the
    game, moves yellow out to 0.5 m and gives blue the kickoff again at the centre mark;
    with fouls off nothing is called."""
    env = _env(ssl_restarts=True, fouls=fouls_on, stop_s=0.5)
    env.reset(seed=2, options={"ball": {"pos": (0.0, 0.0)},
                               "robots": {"blue_0": (-1.0, 0.0, 0.0), "yellow_0": (0.7, 0.0, math.pi)}})
    assert env.task.referee_state.command == KICKOFF and env.task.referee_state.team == "blue"
    fouls, _ = _walk_in(env, "yellow_0")
    if not fouls_on:
        assert fouls == []
        return
    assert [(e["foul"], e["team"], e["agent"]) for e in fouls] == [("defender_too_close", "yellow", "yellow_0")]
    w = env.world_state()
    assert env.task.referee_state.command == STOP
    assert np.hypot(*w.yellow.pos[0]) >= 0.5 - 1e-6 and np.allclose(w.ball_pos, 0.0, atol=1e-6)
    commands = []
    for _ in range(40):
        _, _, _, _, infos = env.step(_idle(env))
        commands += [e["command"] for e in infos["blue_0"]["events"] if e["type"] == "referee"]
    assert commands == [KICKOFF] and env.task.referee_state.team == "blue"
    assert env.task.referee_state.position == (0.0, 0.0)


def test_a_defender_walking_into_a_free_kick_gets_it_taken_again():
    env = _env(ssl_restarts=True, fouls=True, stop_s=0.5)
    W2 = FIELD.half_width
    env.reset(seed=1, options={"ball": {"pos": (1.0, W2 - 0.12), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (1.0, W2 - 0.22, math.pi / 2), "yellow_0": (-3.0, 0.0, 0.0)}})
    for _ in range(120):  # blue kicks the ball out: STOP, free kick for yellow
        env.step(_idle(env))
        if env.task.referee_state.command == FREE_KICK:
            break
    st = env.task.referee_state
    assert st.command == FREE_KICK and st.team == "yellow"
    spot = np.array(st.position)
    w = env.world_state()
    # turn blue_0 to face the ball, then walk it in
    d = spot - w.blue.pos[0]
    env.unwrapped.place_robots(np.array([[*w.blue.pos[0], math.atan2(d[1], d[0])], [*w.yellow.pos[0], 0.0]]))
    fouls, commands = _walk_in(env, "blue_0")
    assert [(e["foul"], e["team"]) for e in fouls] == [("defender_too_close", "blue")]
    assert np.allclose(fouls[0]["placement"], spot)
    for _ in range(40):
        _, _, _, _, infos = env.step(_idle(env))
        commands += [e["command"] for e in infos["blue_0"]["events"] if e["type"] == "referee"]
    assert commands[-2:] == [STOP, FREE_KICK]
    st = env.task.referee_state
    assert st.team == "yellow" and np.allclose(st.position, spot)
    assert np.hypot(*(env.world_state().blue.pos[0] - spot)) >= 0.5 - 1e-6


def test_stop_keep_clear_moves_robots_away_and_the_kicker_plays():
    st = RefereeState(STOP, None, (0.0, 0.0))
    assert st.must_keep_clear("blue") and st.must_keep_clear("yellow")
    fk = RefereeState(FREE_KICK, "blue", (0.0, 0.0))
    assert not fk.must_keep_clear("blue") and fk.must_keep_clear("yellow")
    ws = to_team_frame(world([(-0.3, 0.0), (-0.7, 0.0), (-2.0, 0.0)], [(2.0, 0.0)], (0.0, 0.0)), "blue")
    actions = {f"blue_{i}": make_action(vx=1.0, kick=1.0, dribble=True) for i in range(3)}  # all drive at the ball
    keep_clear(actions, list(actions), ws, "blue", max_speed=3.0)
    assert actions["blue_0"][0] < 0 and actions["blue_0"][4] == -1.0  # within 0.6 m: backs off, no kick
    assert 0 < actions["blue_1"][0] * 3.0 <= np.sqrt(2 * 2.0 * 0.1) + 1e-6  # slows down to stop at 0.6 m
    far = {"blue_0": make_action(vx=1.0)}
    keep_clear(far, ["blue_0"], to_team_frame(world([(-4.0, 0.0)], [(2.0, 0.0)], (0.0, 0.0)), "blue"), "blue", 3.0)
    assert far["blue_0"][0] == 1.0  # far away: untouched


def test_keep_clear_brakes_a_robot_running_at_the_ball_whatever_its_sideways_command():
    """A robot running at the ball at full speed when it must keep clear, its tactic asking
    for a sideways turn (0.6, -0.8 of full speed in its body frame): ``keep_clear`` stops it
    outside 0.5 m. (Capping only the command's speed towards the ball let the sideways part
    take the acceleration: it stopped 0.43 m from the ball.)"""
    env = parallel_env(n_blue=1, n_yellow=1, max_time_s=60.0, referee=False)
    env.reset(seed=0, options={"ball": {"pos": (1.5, 0.0)},
                               "robots": {"blue_0": (-2.5, 0.0, 0.0), "yellow_0": (-3.5, 2.0, 0.0)}})
    worst, braking_from = np.inf, None
    for _ in range(300):
        w = env.world_state()
        d = float(np.hypot(*(w.blue.pos[0] - w.ball_pos)))
        worst = min(worst, d)
        actions = {"blue_0": make_action(vx=1.0), "yellow_0": make_action()}
        if d < 1.6:
            braking_from = braking_from or float(np.hypot(*w.blue.vel[0]))
            actions["blue_0"] = make_action(vx=0.6, vy=-0.8)
            keep_clear(actions, ["blue_0"], to_team_frame(w, "blue"), "blue", env.config.robot.max_speed)
        env.step(actions)
    assert braking_from > 2.5  # it came in fast
    assert worst >= 0.5


def _played(env, ctrls):
    """Step ``env`` to its end with the team controllers ``ctrls`` (actions fitted to the env's
    action size); yield each step's infos."""
    from ssl_marl.envs.actions import fit_action

    dim = env.action_space(env.possible_agents[0]).shape[0]
    while env.agents:
        actions = {}
        for c in ctrls:
            actions.update({k: fit_action(v, dim) for k, v in c.act(env).items()})
        yield env.step(actions)[4]


def test_stop_is_obeyed_by_the_team_controller_in_a_match():
    """Once a STOP is 1 s old no robot is within 0.45 m of the ball. The placement is
    instant: a robot running at the ball at 3 m/s when it went out needs up to about 1 s
    to brake (about 4 m/s^2) and back out (seed 3 has one that comes to 0.18 m 0.5 s in)."""
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=30.0, ssl_restarts=True, fouls=True, stop_s=2.0)
    ctrls = [make_controller("baseline", t, 3, env.field) for t in ("blue", "yellow")]
    env.reset(seed=3)
    worst, free_kicks = np.inf, 0
    for infos in _played(env, ctrls):
        free_kicks += sum(e["type"] == "referee" and e["command"] == FREE_KICK for e in infos["blue_0"]["events"]
                          if "command" in e)
        st = env.task.referee_state
        w = env.world_state()
        if st.command == STOP and w.t - st.since > 1.0:
            pos = np.concatenate([w.blue.pos, w.yellow.pos])
            worst = min(worst, float(np.min(np.hypot(*(pos - w.ball_pos).T))))
    assert free_kicks > 0
    if np.isfinite(worst):
        assert worst >= 0.45


def test_the_attacking_team_keeps_clear_of_the_opponents_free_kicks_in_a_match():
    """The attacking plays (both sides, chip env, SSL game control): while a kickoff or free
    kick for the other team is not taken yet, no robot of the defending side comes within
    0.45 m of the ball (SSL's 0.5 m less 0.05 m of slack) once the command is 0.5 s old, and
    the referee never calls ``defender_too_close`` (DESIGN.md, "Referee")."""
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=6, n_yellow=6, max_time_s=60.0, ssl_restarts=True, fouls=True, chip_kicks=True)
    ctrls = [make_controller("attack-baseline", t, 6, env.field) for t in ("blue", "yellow")]
    env.reset(seed=1)
    worst, ticks, fouls = np.inf, 0, []
    for infos in _played(env, ctrls):
        fouls += [e["foul"] for e in infos["blue_0"]["events"] if e["type"] == "foul"]
        st, w = env.task.referee_state, env.world_state()
        if st.command in (FREE_KICK, KICKOFF) and w.t - st.since > 0.5:
            defending = w.yellow.pos if st.team == "blue" else w.blue.pos
            worst = min(worst, float(np.min(np.hypot(*(defending - w.ball_pos).T))))
            ticks += 1
    assert ticks > 60  # set pieces were played (1 s or more of them)
    assert worst >= 0.45
    assert "defender_too_close" not in fouls


def test_every_kickoff_command_is_among_the_step_events():
    """The match's first kickoff (with the first step's events), the kickoff after a goal (with the
    goal's step) and the second half's (with the half-time step) are reported as ``referee``
    events, so the statistics count them among the set pieces."""
    from ssl_marl.plays.stats import MatchStatsTracker

    env = parallel_env(n_blue=1, n_yellow=1, max_time_s=3.0, ssl_restarts=True, half_time_s=2.0)
    L2 = FIELD.half_length
    env.reset(seed=0, options={"ball": {"pos": (L2 - 0.3, 0.0), "vel": (3.0, 0.0)},
                               "robots": {"blue_0": (-1.0, 0.0, 0.0), "yellow_0": (-3.0, 1.0, 0.0)}})
    stats = MatchStatsTracker(env.field, env.config.ball)
    seen = []
    while env.agents:
        _, _, _, _, infos = env.step(_idle(env))
        ev = infos["blue_0"]["events"]
        stats.observe(env.world_state(), ev)
        seen += [(e["type"], e.get("command"), e.get("team")) for e in ev if e["type"] in ("referee", "goal", "half_time")]
    kickoffs = [x for x in seen if x[1] == KICKOFF]
    assert kickoffs == [("referee", KICKOFF, "blue"), ("referee", KICKOFF, "yellow"), ("referee", KICKOFF, "yellow")]
    assert seen.index(("goal", None, "blue")) < seen.index(kickoffs[1])
    assert stats.teams["yellow"].set_pieces == 2 and stats.teams["blue"].set_pieces == 1


def test_half_time_keeps_the_score_and_swaps_ends():
    env = parallel_env(n_blue=2, n_yellow=2, max_time_s=2.0, ssl_restarts=True, half_time_s=1.0)
    env.reset(seed=0)
    env.score["blue"] = 2
    events = []
    while env.agents:
        _, _, _, _, infos = env.step(_idle(env))
        events += infos["blue_0"]["events"]
        if any(e["type"] == "half_time" for e in events) and env.task.half == 2:
            break
    ht = [e for e in events if e["type"] == "half_time"]
    assert len(ht) == 1 and abs(ht[0]["t"] - 1.0) < 0.02 and ht[0]["score"]["blue"] == 2
    assert env.score == {"blue": 2, "yellow": 0} and env.task.sides_swapped
    st = env.task.referee_state
    assert st.command == KICKOFF and st.team == "yellow"
    w = env.world_state()
    assert np.allclose(w.ball_pos, 0.0)
    for team in ("blue", "yellow"):  # each team's own goal at -x of its frame in both halves
        assert np.all(to_team_frame(w, team).team(team).pos[:, 0] < 0)


@pytest.mark.parametrize("clock_stops", [False, True])
def test_the_match_clock_stops_during_stop_only_when_asked(clock_stops):
    """SSL's clock stops during STOP: with ``clock_stops`` the halves and the match last their
    seconds of play, the STOPs added on top; without it the simulated time is the clock."""
    env = parallel_env(n_blue=1, n_yellow=1, max_time_s=4.0, half_time_s=2.0, ssl_restarts=True, stop_s=1.0,
                       clock_stops=clock_stops)
    env.reset(seed=0, options={"ball": {"pos": (0.5, FIELD.half_width - 0.05), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (-1.0, 0.0, 0.0), "yellow_0": (-3.0, 1.0, 0.0)}})
    dt, steps, stop_steps, half_t = env.config.dt, 0, 0, None
    while env.agents:
        stop_steps += env.task.referee_state.command == STOP
        _, _, _, _, infos = env.step(_idle(env))
        steps += 1
        half_t = next((e["t"] for e in infos["blue_0"]["events"] if e["type"] == "half_time"), half_t)
    assert stop_steps >= 60  # the ball out over the touch line: a STOP of 1 s
    sim_t = env.world_state().t
    assert env.task.clock_s(env) == pytest.approx(4.0, abs=1.5 * dt)
    if clock_stops:
        assert sim_t == pytest.approx(4.0 + stop_steps * dt, abs=1.5 * dt)
        assert half_t == pytest.approx(2.0 + stop_steps * dt, abs=1.5 * dt)  # the STOP came in the first half
    else:
        assert sim_t == pytest.approx(4.0, abs=1.5 * dt) and half_t == pytest.approx(2.0, abs=1.5 * dt)


def test_the_ssl_format_stops_the_clock_and_reports_the_played_time():
    from ssl_marl.runners.match import format_options, play_match
    from ssl_marl.runners.result import summarize

    assert format_options("ssl", 600)["clock_stops"] and "clock_stops" not in format_options("plain", 600)
    r = play_match(blue="idle", yellow="idle", robots=1, seconds=2.0, seed=0, progress=False,
                   env_kwargs={**format_options("ssl", 2.0), "stop_s": 0.5}, start_jitter_m=0.0)
    assert r.played_s == pytest.approx(2.0, abs=0.02) and r.config["rules"]["clock_stops"] is True
    assert summarize([r])["statistics"]["matches"] == 1


def _forced_goal_kickoffs(seed, jitter, goals=6):
    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=600.0, restart_jitter_m=jitter, ssl_restarts=jitter > 0)
    env.reset(seed=seed)
    poses = [env.robot_poses()]
    while len(poses) <= goals:
        env.place_ball(np.array([FIELD.half_length + 0.1, 0.0]))  # the ball into yellow's goal: a goal
        env.step(_idle(env))
        poses.append(env.robot_poses())
        for _ in range(30):  # play on a little
            env.step(_idle(env))
    assert env.score["blue"] == goals
    return np.array(poses)


def test_no_restart_repeats_an_earlier_world_state():
    a = _forced_goal_kickoffs(5, 0.1)
    for i in range(1, len(a)):
        for j in range(i):
            assert not np.allclose(a[i], a[j], atol=1e-3), (i, j)
    assert np.array_equal(a, _forced_goal_kickoffs(5, 0.1))  # same seed, same match
    fixed = _forced_goal_kickoffs(5, 0.0, goals=3)  # without jitter every kickoff is the same formation
    assert np.allclose(fixed[1], fixed[2]) and np.allclose(fixed[2], fixed[3])


def _forced_ball_out_placements(seed, jitter, outs=5):
    """The same crowded ball-out, ``outs`` times over: blue_1 and yellow_1 next to the ball
    as it rolls over the touch line; the robots' poses after each restart."""
    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=600.0, restart_jitter_m=jitter)
    env.reset(seed=seed)
    placed = []
    for _ in range(outs):
        pose = env.robot_poses()
        pose[1], pose[4] = (1.0, FIELD.half_width - 0.25, 0.0), (1.2, FIELD.half_width - 0.3, np.pi)
        env.place_robots(pose)
        env.place_ball(np.array([1.1, FIELD.half_width + 0.01]), np.array([0.0, 1.0]))
        _, _, _, _, infos = env.step(_idle(env))
        assert any(e["type"] == "ball_out" for e in infos["blue_0"]["events"])
        placed.append(env.robot_poses())
    return np.array(placed)


def test_repeated_ball_out_restarts_place_the_robots_anew_each_time():
    """The no-replay rule for free kicks / ball placement: the same crowded ball-out restarted
    five times puts the two robots near the ball somewhere new each time (the match's seeded
    RNG), the same seed gives the same placements, and without jitter they are the same."""
    a = _forced_ball_out_placements(7, 0.1)
    for i in range(1, len(a)):
        for j in range(i):
            assert not np.allclose(a[i][[1, 4]], a[j][[1, 4]], atol=1e-3), (i, j)
    np.testing.assert_array_equal(a, _forced_ball_out_placements(7, 0.1))
    fixed = _forced_ball_out_placements(7, 0.0, outs=3)
    np.testing.assert_allclose(fixed[1][[1, 4]], fixed[2][[1, 4]], atol=1e-6)


def test_jittered_kickoff_stays_legal():
    rng = np.random.default_rng(0)
    base = kickoff_poses(FIELD, 6, 6)
    for _ in range(200):
        p = jittered_kickoff(base, 6, FIELD, 0.5, rng, R_ROBOT)
        for i, (x, y, _) in enumerate(p):
            side = -1 if i < 6 else 1
            assert side * x > 0 and abs(y) <= FIELD.half_width
            if i not in (0, 6):
                assert np.hypot(x, y) >= FIELD.center_circle_radius + R_ROBOT
                assert not FIELD.in_defense_area(np.array([x, y]), side)


def test_batched_env_refuses_game_control():
    from ssl_marl.envs.batched_env import BatchedSSLEnv

    with pytest.raises(ValueError, match="game control"):
        BatchedSSLEnv(2, n_blue=1, n_yellow=1, fouls=True)


def test_t_interval_against_scipy_and_wilson_against_hand_values():
    from scipy import stats

    vals = [1.0, -2.0, 0.0, 3.0, 1.0]
    lo, hi = t_interval(vals)
    ref = stats.t.interval(0.95, len(vals) - 1, loc=np.mean(vals), scale=stats.sem(vals))
    assert lo == pytest.approx(ref[0]) and hi == pytest.approx(ref[1])
    assert t_interval([1.0, 2.0, 3.0]) == pytest.approx((-0.4841377, 4.4841377))
    assert wilson_interval(755, 1000) == pytest.approx((0.7274, 0.7806), abs=1e-4)  # by hand, z = 1.96
    assert wilson_interval(0, 0) == (0.0, 1.0)
    s = series_statistics([2, 0, 1], [0, 0, 3], seconds=300.0)
    assert (s["wins"], s["draws"], s["losses"]) == (1, 1, 1)
    assert s["goal_diff_per_match"] == pytest.approx(0.0) and s["goal_diff_per_600s"] == pytest.approx(0.0)
    assert s["goal_diff_per_600s_ci95"][1] == pytest.approx(2 * s["goal_diff_per_match_ci95"][1])


def _ball_world(ball_xy, ball_vel, blue_xy, t, ball_vz=0.0):
    w = world(blue_xy, [(-4.0, 2.5)], ball_xy, t)
    return WorldState(t=t, ball_pos=w.ball_pos, ball_vel=np.array(ball_vel, float), blue=w.blue, yellow=w.yellow,
                      ball_vz=ball_vz, ball_height=0.05 if ball_vz > 0 else 0.0)


def test_match_statistics_by_kind():
    from ssl_marl.plays.stats import MatchStatsTracker

    tr = MatchStatsTracker(FIELD)
    mates = [(1.0, 0.0), (3.0, 0.0)]
    tr.observe(_ball_world((1.1, 0.0), (0.0, 0.0), mates, 0.0))
    # blue_0 chips a pass to blue_1: a chip pass
    tr.observe(_ball_world((1.2, 0.0), (4.0, 0.0), mates, 1 / 60, ball_vz=2.0), [{"type": "kick", "agent": "blue_0", "speed": 4.0}])
    for k in range(2, 9):  # blue_1 controls it: completed
        w = _ball_world((2.9, 0.0), (0.0, 0.0), mates, k / 60)
        tr.observe(WorldState(t=w.t, ball_pos=w.ball_pos, ball_vel=w.ball_vel,
                              blue=make_team_state(w.blue.pos, w.blue.heading, w.blue.vel, w.blue.omega,
                                                   [False, True], w.blue.kick_ready), yellow=w.yellow))
    # blue_1 shoots at the goal after receiving the chip pass
    tr.observe(_ball_world((3.1, 0.0), (5.0, 0.0), mates, 10 / 60), [{"type": "kick", "agent": "blue_1", "speed": 5.0}])
    tr.observe(_ball_world((4.6, 0.0), (5.0, 0.0), mates, 11 / 60), [{"type": "goal", "team": "blue", "t": 11 / 60}])
    # a redirect: the ball arrives at 3 m/s and blue_0 kicks it on at the goal
    tr.observe(_ball_world((0.9, 0.0), (3.0, 0.0), mates, 12 / 60))
    tr.observe(_ball_world((1.2, 0.0), (5.0, 0.0), [(1.0, 0.0), (3.0, 2.0)], 13 / 60),
               [{"type": "kick", "agent": "blue_0", "speed": 5.0}])
    s = tr.summary()["blue"]
    assert (s["passes_chip_attempted"], s["passes_chip_completed"], s["passes_flat_attempted"]) == (1, 1, 0)
    assert s["pass_completion_chip"] == 1.0 and s["pass_completion_flat"] is None
    assert (s["shots_after_chip_pass"], s["shots_redirect"], s["shots_direct"]) == (1, 1, 0)
    assert (s["goals"], s["goals_after_chip_pass"]) == (1, 1)


@pytest.mark.parametrize("jitter", [0.0, 0.1])
def test_a_restart_never_places_a_robot_on_another(jitter):
    """Robots crowding the ball at a restart are moved out to 0.5 m (plus the jitter) without
    landing on each other or on a robot already standing on that ring: two robots on the same
    side of the ball, a third just beyond where they would go, the ball near a touch line."""
    from ssl_marl.envs.game_control import jittered_clearance
    from ssl_marl.envs.referee import PLACEMENT_GAP_M, clear_robots_from

    f = FieldGeometry.div_b()
    ball = np.array([1.0, f.half_width - 0.2])
    pos = np.array([[1.2, 2.5], [1.25, 2.45], [1.5, 2.35], [-3.0, 0.0], [1.0, 2.75]])
    for seed in range(20):
        if jitter:
            new = jittered_clearance(ball, pos, f, 0.5, jitter, np.random.default_rng(seed), 0.09)
        else:
            new = clear_robots_from(ball, pos, f, robot_radius=0.09)
        d_ball = np.hypot(*(new - ball).T)
        assert np.all(d_ball >= 0.5 - 1e-9)
        gaps = np.hypot(*(new[:, None] - new[None]).transpose(2, 0, 1)) + 9 * np.eye(len(new))
        assert gaps.min() >= 2 * 0.09 + PLACEMENT_GAP_M - 1e-9, (seed, new)
        assert all(f.in_field(p, margin=-f.boundary_width + 0.1) for p in new)
        np.testing.assert_array_equal(new[3], pos[3])  # robots far from the ball stay
        if not jitter:
            break


def test_no_two_robots_overlap_after_the_restarts_of_a_match():
    """A 60 s plain-format match (attacking plays against the standard plays): after no
    restart (ball out, no progress) do two robots' bodies overlap by more than 2 cm."""
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=6, n_yellow=6, max_time_s=60.0, chip_kicks=True, restart_jitter_m=0.1,
                       after_goal="kickoff")
    ctrls = [make_controller(k, t, 6, env.field) for t, k in (("blue", "attack-baseline"), ("yellow", "baseline"))]
    env.reset(seed=5)
    restarts, r = 0, env.config.robot.radius
    for infos in _played(env, ctrls):
        if any(e["type"] in ("ball_out", "no_progress", "goal") for e in infos["blue_0"]["events"]):
            restarts += 1
            w = env.world_state()
            p = np.concatenate([w.blue.pos, w.yellow.pos])
            gaps = np.hypot(*(p[:, None] - p[None]).transpose(2, 0, 1)) + 9 * np.eye(len(p))
            assert gaps.min() >= 2 * r - 0.02, (w.t, gaps.min())
    assert restarts >= 5
