"""Set pieces taken with one kick (ssl_marl.plays.set_piece_kick), the kicker kept off the
ball afterwards (TeamController.set_piece_guard), and the referee's double touch for a
kicker that stays in contact while the ball moves 0.05 m."""

from __future__ import annotations

import math

import numpy as np

from ssl_marl.envs import parallel_env
from ssl_marl.envs.actions import make_action
from ssl_marl.envs.game_control import FREE_KICK, KICKOFF, RUNNING, TouchWatch
from ssl_marl.physics.field import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.physics.state import WorldState, make_team_state, to_team_frame
from ssl_marl.plays.set_piece_kick import SetPieceKick, SetPieceState, set_piece_choice

F = FieldGeometry.from_name("div_b")
RP, BP = RobotParams(), BallParams()


def test_choice_shoots_at_an_open_goal_passes_round_a_closed_one_and_avoids_a_blocked_lane():
    ball = np.array([2.0, 0.0])
    goalie, kicker = (-4.0, 0.0), (1.8, 0.0)
    c = set_piece_choice(ball, 1, np.array([goalie, kicker, (1.0, 2.0)]), np.array([(0.0, -2.0)]), F, RP, BP)
    assert c.kind == "shot" and c.strength == 1.0 and c.target[0] >= F.half_length - 1e-9
    assert abs(c.target[1]) < F.goal_width / 2  # at the goal mouth
    # a robot 0.4 m in front of the ball shadows the whole mouth: the free teammate gets a pass
    wall = (2.4, 0.0)
    c = set_piece_choice(ball, 1, np.array([goalie, kicker, (1.0, 2.0)]), np.array([wall]), F, RP, BP)
    assert c.kind == "pass" and c.teammate == 2 and np.allclose(c.target, (1.0, 2.0)) and 0 < c.strength < 1
    # of two teammates, the one whose lane an opponent stands in is not chosen
    ours = np.array([goalie, kicker, (1.0, 2.0), (3.5, -1.5)])
    c = set_piece_choice(ball, 1, ours, np.array([wall, (1.5, 1.0)]), F, RP, BP)
    assert c.kind == "pass" and c.teammate == 3
    # every lane blocked: the shot at the goal centre, whatever it meets
    c = set_piece_choice(ball, 1, ours, np.array([wall, (1.5, 1.0), (2.75, -0.75)]), F, RP, BP)
    assert c.kind == "shot" and c.teammate is None


def test_a_kicker_beside_the_ball_at_the_goal_line_walks_round_it_and_kicks_without_touching_it_first():
    """The ball 0.2 m inside the own goal line (a free kick's spot), the kicker on the line
    beside it: it steps out into the run-off behind the ball (a target inside the lines
    only would leave it standing there), and the ball lies untouched until it is kicked
    towards the target."""
    env = parallel_env(n_blue=1, n_yellow=1, max_time_s=10.0, referee=False)
    spot = np.array([-F.half_length + 0.2, 2.01])
    env.reset(seed=0, options={"ball": {"pos": tuple(spot)},
                               "robots": {"blue_0": (-F.half_length, 1.71, -0.22), "yellow_0": (3.0, -2.0, math.pi)}})
    tactic = SetPieceKick(F, env.config.robot, env.config.ball, target_point=(F.half_length, 0.0))
    kicked_at = None
    for k in range(300):
        w = env.world_state()
        if kicked_at is None:
            assert np.hypot(*(w.ball_pos - spot)) < 0.01  # not pushed before the kick
        a = tactic.act(to_team_frame(w, "blue"), 0)
        _, _, _, _, infos = env.step({"blue_0": a, "yellow_0": make_action()})
        if any(e["type"] == "kick" for e in infos["blue_0"]["events"]):
            kicked_at = k
            break
    assert kicked_at is not None
    v = env.world_state().ball_vel
    assert np.hypot(*v) > 5.0 and abs(math.atan2(v[1], v[0]) - math.atan2(-spot[1], F.half_length - spot[0])) < 0.1


def test_set_piece_kick_states():
    S = SetPieceKick.Inputs
    T = SetPieceKick.transition
    p = SetPieceKick.Params()
    assert T(SetPieceState.APPROACH, S(behind=True), p) is SetPieceState.KICK
    assert T(SetPieceState.APPROACH, S(behind=False), p) is SetPieceState.APPROACH
    assert T(SetPieceState.KICK, S(off_line=True), p) is SetPieceState.APPROACH
    assert T(SetPieceState.KICK, S(ball_left=True, off_line=True), p) is SetPieceState.DONE
    assert T(SetPieceState.DONE, S(behind=True), p) is SetPieceState.DONE


def _world(blue_xy, ball_xy, ball_vel=(0.0, 0.0), on_dribbler=False):
    n = len(blue_xy)
    blue = make_team_state(np.array(blue_xy, float), np.zeros(n), np.zeros((n, 2)), np.zeros(n),
                           np.array([on_dribbler] + [False] * (n - 1)), np.ones(n, bool))
    yellow = make_team_state(np.array([(3.0, 2.0)]), np.zeros(1), np.zeros((1, 2)), np.zeros(1), np.zeros(1, bool),
                             np.ones(1, bool))
    return WorldState(t=0.0, ball_pos=np.array(ball_xy, float), ball_vel=np.array(ball_vel, float), blue=blue,
                      yellow=yellow)


def test_carries_the_ball_on_the_dribbler_or_in_contact_but_not_when_it_leaves():
    watch = TouchWatch(1, 1, RP.radius, BP.radius)
    touching = (0.11, 0.0)  # 0.11 m from the robot centre: within reach
    assert watch.carries(_world([(0.0, 0.0)], touching), 0)
    assert watch.carries(_world([(0.0, 0.0)], (0.3, 0.0), on_dribbler=True), 0)
    assert not watch.carries(_world([(0.0, 0.0)], touching, ball_vel=(1.0, 0.0)), 0)  # leaving at 1 m/s
    assert not watch.carries(_world([(0.0, 0.0)], touching), 0, kicked=[0])
    assert not watch.carries(_world([(0.0, 0.0)], (0.3, 0.0)), 0)


def _yellow_free_kick():
    """A 1v1 env under SSL game control with a free kick for yellow at a spot near the
    touch line (blue touched the ball last); returns env and the spot."""
    env = parallel_env(n_blue=1, n_yellow=1, max_time_s=30.0, ssl_restarts=True, fouls=True, stop_s=0.5)
    W2 = F.half_width
    env.reset(seed=1, options={"ball": {"pos": (1.0, W2 - 0.12), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (1.0, W2 - 0.22, math.pi / 2), "yellow_0": (-3.0, 0.0, 0.0)}})
    for _ in range(120):
        env.step({a: make_action() for a in env.agents})
        if env.task.referee_state.command == FREE_KICK:
            break
    st = env.task.referee_state
    assert st.command == FREE_KICK and st.team == "yellow"
    return env, np.array(st.position)


def _take(env, spot, action, steps=120):
    """Yellow's robot placed just behind the free kick's ball (facing -x, the ball in
    front of its face), then driven with ``action``; returns the fouls called."""
    w = env.world_state()
    gap = RP.front_distance + BP.radius + 0.005
    env.unwrapped.place_robots(np.array([[*w.blue.pos[0], 0.0], [spot[0] + gap, spot[1], math.pi]]))
    fouls = []
    for _ in range(steps):
        _, _, _, _, infos = env.step({"blue_0": make_action(), "yellow_0": action})
        fouls += [e for e in infos["yellow_0"]["events"] if e["type"] == "foul"]
        if fouls or env.task.referee_state.command == RUNNING:
            break
    return fouls


def test_a_free_kick_carried_off_on_the_dribbler_is_a_double_touch():
    env, spot = _yellow_free_kick()
    fouls = _take(env, spot, make_action(vx=0.3, dribble=True))
    assert [(e["foul"], e["team"]) for e in fouls] == [("double_touch", "yellow")]


def test_a_free_kick_kicked_away_is_not():
    env, spot = _yellow_free_kick()
    fouls = _take(env, spot, make_action(vx=0.3, kick=0.6))
    assert fouls == [] and env.task.referee_state.command == RUNNING


def test_standard_teams_kick_their_set_pieces_and_their_kickers_keep_off_the_ball():
    """The baseline team on both sides, 60 s under SSL game control: every kickoff and free
    kick that is taken (the ball 0.05 m from its spot) is kicked by the team whose set
    piece it is, and no double touch is called."""
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=3, n_yellow=3, max_time_s=60.0, ssl_restarts=True, fouls=True)
    ctrls = [make_controller("baseline", t, 3, env.field) for t in ("blue", "yellow")]
    env.reset(seed=5)
    taken, kicked_by, fouls, pending = 0, set(), [], None
    while env.agents:
        actions = {}
        for c in ctrls:
            actions.update(c.act(env))
        _, _, _, _, infos = env.step(actions)
        ev = infos[env.possible_agents[0]]["events"]
        kicked_by |= {e["agent"].split("_")[0] for e in ev if e["type"] == "kick"}
        fouls += [e["foul"] for e in ev if e["type"] == "foul"]
        for e in ev:
            if e["type"] != "referee":
                continue
            if e["command"] in (KICKOFF, FREE_KICK):
                pending, kicked_by = (e["team"], e["since"]), set()
            elif e["command"] == RUNNING and pending is not None:
                team, since = pending
                if e["t"] - since < 9.9:  # taken, not timed out
                    taken += 1
                    assert team in kicked_by, f"{team}'s set piece at t={since:.2f} s was not kicked"
                pending = None
    assert taken >= 3
    assert "double_touch" not in fouls


def test_the_kicker_takes_no_ball_role_until_another_robot_touches_the_ball():
    """Yellow (the baseline team, three robots) takes its free kick: the robot that kicked is
    the team's ``set_piece_guard`` from the next tick and holds no ``attacker`` role while it
    is; another robot's touch ends the guard."""
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=1, n_yellow=3, max_time_s=30.0, ssl_restarts=True, fouls=True, stop_s=0.5)
    W2 = F.half_width
    env.reset(seed=1, options={"ball": {"pos": (1.0, W2 - 0.12), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (1.0, W2 - 0.22, math.pi / 2), "yellow_0": (3.5, 0.0, math.pi),
                                          "yellow_1": (-1.0, 0.5, 0.0), "yellow_2": (2.5, -1.0, math.pi)}})
    yellow = make_controller("baseline", "yellow", 3, F)
    kicker, guarded_ticks, fouls = None, 0, []
    while env.agents and env.world_state().t < 20.0:
        actions = {"blue_0": make_action(), **yellow.act(env)}
        if yellow.set_piece_guard is not None:
            assert yellow.set_piece_guard == kicker
            assert yellow.roles.get(kicker) != "attacker"
            guarded_ticks += 1
        st = env.task.referee_state
        _, _, _, _, infos = env.step(actions)
        ev = infos["blue_0"]["events"]
        fouls += [e["foul"] for e in ev if e["type"] == "foul"]
        if st.command == FREE_KICK and st.team == "yellow" and kicker is None:
            kicks = [e["agent"] for e in ev if e["type"] == "kick"]
            kicker = int(kicks[0].split("_")[1]) if kicks else None
        if kicker is not None and guarded_ticks and yellow.set_piece_guard is None:
            break
    assert kicker is not None and guarded_ticks > 0 and yellow.set_piece_guard is None
    assert "double_touch" not in fouls


def test_a_wall_stands_between_the_opponents_free_kick_and_our_goal():
    """Blue (the baseline team, three robots) defends yellow's free kick: within 3 s of the
    command a blue robot stands within 0.1 m of the wall spot (0.65 m from the ball towards
    blue's goal), and seen from the ball no part of blue's goal mouth is left open."""
    from ssl_marl.plays.pass_decision import open_goal_interval
    from ssl_marl.plays.set_piece_kick import SHOT_OPEN_MIN_RAD
    from ssl_marl.plays.wall import wall_spot
    from ssl_marl.runners.controllers import make_controller

    env = parallel_env(n_blue=3, n_yellow=1, max_time_s=30.0, ssl_restarts=True, fouls=True, stop_s=0.5)
    W2 = F.half_width
    env.reset(seed=1, options={"ball": {"pos": (1.0, W2 - 0.12), "vel": (0.0, 2.0)},
                               "robots": {"blue_0": (-4.0, 0.0, 0.0), "blue_1": (1.0, W2 - 0.22, math.pi / 2),
                                          "blue_2": (-1.0, -1.0, 0.0), "yellow_0": (3.0, 0.0, math.pi)}})
    blue = make_controller("baseline", "blue", 3, F)
    since = None  # blue idles until the ball has gone out off it and yellow has the free kick
    while env.agents and env.world_state().t < 10.0:
        st = env.task.referee_state
        if st.command == FREE_KICK and st.team == "yellow":
            since = st.since if since is None else since
            if env.world_state().t - since >= 3.0:
                break
        idle = {a: make_action() for a in env.agents}
        env.step({**idle, **(blue.act(env) if since is not None else {})})
    assert since is not None and env.task.referee_state.command == FREE_KICK
    w = to_team_frame(env.world_state(), "blue")
    spot = wall_spot(w.ball_pos, F)
    assert float(np.min(np.hypot(*(w.blue.pos - spot).T))) < 0.1
    assert "wall_0" in blue.roles.values()
    mirrored = np.array([-1.0, -1.0])  # open_goal_interval looks at the +x goal: turn the field round
    open_angle, _ = open_goal_interval(w.ball_pos * mirrored, w.blue.pos * mirrored, F, RP, BP)
    assert open_angle < SHOT_OPEN_MIN_RAD


def test_the_attacking_plays_shoot_a_set_piece_at_an_open_goal_and_pass_when_it_is_closed():
    """``PassingParams.set_piece_shot``: with the goal open from the ball no pass plan opens
    (the attacker's set-piece kick shoots); with it closed the decider's pass opens; the
    judgement stands once the kicker is within KEEP_CHOICE_M of the ball."""
    from dataclasses import replace

    from ssl_marl.plays.pass_coordinator import PassCoordinator, PassingParams
    from ssl_marl.plays.pass_decision import Choice, Decision, PassOption
    from ssl_marl.plays.play import make_context
    from ssl_marl.plays.scene import make_world
    from ssl_marl.plays.set_piece_kick import KEEP_CHOICE_M, SHOT_OPEN_MIN_RAD, set_piece_shot_interval

    option = PassOption(2, np.array([2.0, 2.0]), 3.0, 0.9, 0.9, 0.0, 0.5)

    class PassDecider:  # always the pass
        def decide(self, request):
            return Decision(Choice.PASS, 0.1, 0.0, (option,), option)

    def ctx(kicker_x, opponents, t):
        w = make_world(blue=[(-4.2, 0.0, 0.0), (kicker_x, 0.0, 0.0), (2.0, 2.0, 0.0)], yellow=opponents,
                       ball=(2.5, 0.0), t=t, frame="blue")
        return replace(make_context(w, "blue", F, RP), role_holders={"attacker": 1}, set_piece=True)

    open_goal = [(4.4, 0.9, math.pi)]
    closed = [(3.3, -0.2, math.pi), (3.3, 0.0, math.pi), (3.3, 0.2, math.pi)]
    ours = np.array([(-4.2, 0.0), (1.8, 0.0), (2.0, 2.0)])
    assert set_piece_shot_interval(np.array([2.5, 0.0]), 1, ours, np.array(open_goal)[:, :2], F, RP, BP)[0] \
        >= SHOT_OPEN_MIN_RAD
    assert set_piece_shot_interval(np.array([2.5, 0.0]), 1, ours, np.array(closed)[:, :2], F, RP, BP)[0] \
        < SHOT_OPEN_MIN_RAD
    for shot, opponents, planned in ((True, open_goal, False), (True, closed, True), (False, open_goal, True)):
        c = PassCoordinator(PassingParams(decide_at_restart=True, set_piece_shot=shot), decider=PassDecider())
        for k in range(6):
            c.prepare(ctx(1.8, opponents, 1.0 + k / 60), restart=True)
        assert (c.plan is not None) is planned, (shot, opponents)
    # judged open while the kicker walked up, the shot stands once it is near the ball
    c = PassCoordinator(PassingParams(decide_at_restart=True, set_piece_shot=True), decider=PassDecider())
    c.prepare(ctx(1.8, open_goal, 1.0), restart=True)
    near = 2.5 - (KEEP_CHOICE_M - 0.05)
    for k in range(1, 7):
        c.prepare(ctx(near, closed, 1.0 + k / 60), restart=True)
    assert c.plan is None
    c.prepare(ctx(1.8, closed, 1.2), restart=True)  # the kicker backs off: judged again
    for k in range(1, 4):
        c.prepare(ctx(1.8, closed, 1.2 + k / 60), restart=True)
    assert c.plan is not None
