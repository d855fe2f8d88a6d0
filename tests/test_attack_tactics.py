"""Chip pass and one-touch redirect tactics in a chip env, and the attacking team kinds."""

import math

import numpy as np
import pytest

from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams
from ssl_marl.plays.chip_pass_tactic import ChipPass
from ssl_marl.plays.pass_tactic import PassState
from ssl_marl.plays.receive_tactic import ReceiveState
from ssl_marl.plays.redirect_tactic import Redirect
from ssl_marl.plays.scene import ball_in_front
from ssl_marl.plays.spot_support_tactic import SpotSupport

F = FieldGeometry.div_b()
BP = BallParams()


def _chip_env(n_blue, n_yellow=0):
    from ssl_marl.envs import parallel_env

    env = parallel_env(n_blue=n_blue, n_yellow=n_yellow, field="div_b", max_time_s=30.0, chip_kicks=True)
    return env, env.config.robot


def _chip_pass_over_a_blocker(skills, chip=True, blocker_x=0.5):
    """A ChipPass passer at (-1, 0) with the ball, a receiver (ordinary Redirect) at
    (2.5, 0), a yellow robot standing in the lane at (blocker_x, 0). Returns (passer,
    receiver, chip entry of the kick (None: no kick), the ball's greatest height near
    the blocker (m), x of the first touchdown (m, None: never in the air), whether a
    yellow robot touched the ball, robot parameters)."""
    env, rp = _chip_env(2, 1)
    ball = ball_in_front(-1.0, 0.0, 0.0)
    target = (2.5, 0.0)
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": {"blue_0": (-1.0, 0.0, 0.0),
                                                                   "blue_1": (target[0], 0.0, math.pi),
                                                                   "yellow_0": (blocker_x, 0.0, math.pi)}})
    passer = ChipPass(F, rp, BP, skills=skills, target_robot=1, target_point=target, receiver_ready=True, chip=chip)
    receiver = Redirect(F, rp, BP, skills=skills, receive_point=target, ball_from=tuple(ball))
    chip_entry, over, landing, touched, max_h = None, 0.0, None, False, 0.0
    for _ in range(5 * 60):
        w = env.vision_state("blue")
        a, b = passer.act(w, 0), receiver.act(w, 1)
        assert a.shape == (6,) and b.shape == (6,)
        if a[4] > 0.0:
            chip_entry = float(a[5])
        env.step({"blue_0": a, "blue_1": b, "yellow_0": np.zeros(6)})
        ws = env.world_state()
        touched |= bool(np.hypot(*(ws.ball_pos - ws.yellow.pos[0])) < rp.radius + BP.radius + 0.01) \
            and ws.ball_height < rp.height
        max_h = max(max_h, ws.ball_height)
        if abs(float(ws.ball_pos[0]) - blocker_x) < 0.1:
            over = max(over, ws.ball_height)
        if landing is None and max_h > 0.1 and ws.ball_height < 0.02:
            landing = float(ws.ball_pos[0])
        if receiver.status.state in (ReceiveState.CONTROLLED, ReceiveState.FAILED):
            break
    return passer, receiver, chip_entry, over, landing, touched, rp


@pytest.mark.parametrize("skills", ["baseline", "learned"])
def test_chip_pass_tactic_lifts_the_ball_over_a_midway_blocker_to_the_receiver(skills):
    """A chosen chip: the KICK state runs the chip-pass skill of the team's kind, which
    picks the chip over the robot in the lane; the receiver takes the ball."""
    passer, receiver, chip_entry, over, landing, touched, rp = _chip_pass_over_a_blocker(skills)
    assert passer.status.state is PassState.DONE and chip_entry is not None and chip_entry > 0.0
    assert over > rp.height  # over the blocker's 0.15 m
    assert 0.5 < landing < 2.5  # first touchdown past the blocker, short of the receiver
    assert not touched
    assert receiver.status.state is ReceiveState.CONTROLLED


def test_chip_pass_tactic_without_a_chip_passes_flat_into_the_blocker():
    """No chip chosen: the pass skill kicks flat (chip entry 0) and the blocker meets the ball."""
    passer, _, chip_entry, over, landing, touched, _ = _chip_pass_over_a_blocker("baseline", chip=False)
    assert passer.status.state is PassState.DONE and chip_entry == 0.0
    assert over == 0.0 and landing is None and touched


@pytest.mark.parametrize("blocker_x", [0.0, 0.5, 1.0])
def test_the_decisions_chip_is_the_one_the_chip_pass_tactic_kicks(blocker_x):
    """On the scene of the chip tests, the attack decision offers a chip to the receiver;
    the ChipPass tactic (hand-coded chip-pass skill) told that pass kicks a chip of the
    option's speed and elevation (up to one step of the skill's grid: the dribbled ball
    moves a little before the kick)."""
    from ssl_marl.plays.attack_decision import AttackChoice, decide_attack

    env, rp = _chip_env(2, 1)
    ball = ball_in_front(-1.0, 0.0, 0.0)
    env.reset(seed=0, options={"ball": {"pos": ball}, "robots": {"blue_0": (-1.0, 0.0, 0.0),
                                                                   "blue_1": (2.5, 0.0, math.pi),
                                                                   "yellow_0": (blocker_x, 0.0, math.pi)}})
    w = env.vision_state("blue")
    d = decide_attack(w.ball_pos, 0, w.blue.pos, w.yellow.pos, F, rp, BP, candidates=(1,), heading=0.0)
    chip = next(o for o in d.options if o.kind is AttackChoice.CHIP)
    target = (float(chip.point[0]), float(chip.point[1]))
    passer = ChipPass(F, rp, BP, skills="baseline", target_robot=1, target_point=target, receiver_ready=True,
                      chip=True)
    for _ in range(3 * 60):
        a = passer.act(env.vision_state("blue"), 0)
        if a[4] > 0.0:
            break
        env.step({"blue_0": a, "blue_1": np.zeros(6), "yellow_0": np.zeros(6)})
    assert a[4] > 0.0 and a[5] > 0.0
    speed_step, angle_step = (rp.kick_speed_max - 1.0) / 55, (rp.chip_angle_max - math.radians(15.0)) / 45
    assert float(a[4]) * rp.kick_speed_max == pytest.approx(chip.kick_speed, abs=speed_step + 1e-6)
    assert float(a[5]) * rp.chip_angle_max == pytest.approx(chip.chip_angle, abs=angle_step + 1e-6)


@pytest.mark.parametrize("skills, keeper", [("baseline", None), ("baseline", (4.4, -0.2, math.pi)),
                                             ("learned", None), ("learned", (4.4, 0.0, math.pi))])
def test_redirect_tactic_sends_an_incoming_pass_into_the_goal(skills, keeper):
    """A pass into a redirect: RECEIVING runs the redirect skill, which chooses its own
    aim in the open goal (the play's aim (4.5, -0.2) lies behind a keeper at y = -0.2)
    and meets the ball; it scores in one touch."""
    env, rp = _chip_env(1, 1 if keeper else 0)
    robots = {"blue_0": (2.5, 0.65, -0.4), **({"yellow_0": keeper} if keeper else {})}
    env.reset(seed=0, options={"ball": {"pos": (3.6, -2.0), "vel": (-1.26, 3.27)}, "robots": robots})
    r = Redirect(F, rp, BP, skills=skills, receive_point=(2.6, 0.6), ball_from=(3.6, -2.0),
                 redirect_target=(F.half_length, -0.2))
    scored, states, kicks = False, set(), 0
    for _ in range(3 * 60):
        a = r.act(env.vision_state("blue"), 0)
        assert a.shape == (6,) and a[5] == 0.0
        states.add(r.status.state)
        _, _, _, _, infos = env.step({"blue_0": a, **({"yellow_0": np.zeros(6)} if keeper else {})})
        events = infos["blue_0"]["events"]
        scored |= any(e.get("type") == "goal" for e in events)
        kicks += sum(e.get("type") == "kick" and e.get("agent") == "blue_0" for e in events)
        if scored or not env.agents:
            break
    assert scored and kicks == 1  # one touch: the kicker fired on contact and the ball went in
    assert {ReceiveState.RECEIVING, ReceiveState.CONTROLLED} <= states and ReceiveState.FETCH not in states


def test_attack_tactics_build_the_skills_of_the_team_kind():
    """ChipPass / Redirect get their chip-pass and redirect skills from the team's skill
    set: the attack-learned team's are the learned ones, the attack-baseline team's
    the hand-coded ones; one source can be swapped (``--blue-skill chip-pass=baseline``)."""
    from ssl_marl.plays.attack_play import attack_plays
    from ssl_marl.plays.skillset import ATTACK_SKILLS, TEAM_SKILLS
    from ssl_marl.plays.team import required_skills
    from ssl_marl.runners.controllers import kind_skills, parse_skill_source, resolve_team_option
    from ssl_marl.skills.chip_pass import ChipPassBaseline, LearnedChipPass
    from ssl_marl.skills.redirect import LearnedRedirect, RedirectBaseline

    assert set(required_skills(attack_plays())) == set(ATTACK_SKILLS)
    assert set(kind_skills("passing-learned")) == set(TEAM_SKILLS)
    learned, baseline = kind_skills("attack-learned"), kind_skills("attack-baseline")
    assert learned["chip_pass"] == learned["redirect"] == "learned" and baseline["chip_pass"] == "baseline"
    for skills, chip_cls, redirect_cls in ((learned, LearnedChipPass, LearnedRedirect),
                                           (baseline, ChipPassBaseline, RedirectBaseline)):
        passer, receiver = ChipPass(F, skills=skills), Redirect(F, skills=skills)
        assert type(passer.chip_skill) is chip_cls and type(receiver.redirect_skill) is redirect_cls
        assert passer.kick_skill() is passer.pass_skill  # a flat pass runs the pass skill
        passer.set_params(chip=True)
        assert passer.kick_skill() is passer.chip_skill
    _, mixed, _ = resolve_team_option("attack-learned", [parse_skill_source("chip-pass=baseline")])
    assert type(ChipPass(F, skills=mixed).chip_skill) is ChipPassBaseline
    assert type(Redirect(F, skills=mixed).redirect_skill) is LearnedRedirect


def test_redirect_without_a_target_is_an_ordinary_receive_and_supports_emit_six_entries():
    env, rp = _chip_env(1)
    env.reset(seed=0, options={"ball": {"pos": (0.0, 0.0)}, "robots": {"blue_0": (1.0, 1.0, 0.0)}})
    r = Redirect(F, rp, BP, receive_point=(1.0, 1.0))
    assert r.act(env.vision_state("blue"), 0).shape == (6,)
    s = SpotSupport(F, rp, BP, spot=(2.0, 1.0))
    assert s.act(env.vision_state("blue"), 0).shape == (6,)
    with pytest.raises(ValueError):
        s.set_params(spot=(9.0, 0.0))


def test_attack_team_plays_a_short_match_in_a_chip_env():
    from ssl_marl.runners.controllers import CHIP_KINDS, team_spec
    from ssl_marl.envs.actions import fit_action
    from ssl_marl.runners.match import play_match

    assert "attack-learned" in CHIP_KINDS and team_spec("attack-baseline").plays.__name__ == "attack_plays"
    assert fit_action(np.zeros(5, np.float32), 6).shape == (6,)
    assert fit_action(np.zeros(5, np.float32), 5).shape == (5,)
    res = play_match("attack-baseline", "baseline", robots=3, seconds=6.0, seed=3, progress=False)
    assert set(res.score) == {"blue", "yellow"}


def test_behind_ball_waypoint_walks_round_the_ball_to_the_pass_line():
    from ssl_marl.plays.pass_tactic import PassParams
    from ssl_marl.plays.set_piece_kick import BESIDE_M, behind_ball_waypoint

    rp, p = _chip_env(1)[1], PassParams()
    ball, target = np.array([0.0, 0.0]), np.array([3.0, 0.0])
    back = rp.front_distance + BP.radius + p.behind_gap_m
    # in front of the ball: first sideways (BESIDE_M off the line, on the robot's side), then back
    np.testing.assert_allclose(behind_ball_waypoint((0.5, 0.1), math.pi, ball, target, rp, BP, p), (0.5, BESIDE_M))
    np.testing.assert_allclose(behind_ball_waypoint((0.5, 0.32), math.pi, ball, target, rp, BP, p),
                               (-back, BESIDE_M))
    np.testing.assert_allclose(behind_ball_waypoint((-0.05, -0.1), 0.0, ball, target, rp, BP, p),
                               (-0.05, -BESIDE_M))
    # beside and behind: the staging point on the line
    np.testing.assert_allclose(behind_ball_waypoint((-0.5, -0.6), 0.0, ball, target, rp, BP, p), (-back, 0.0))
    # behind on the line but facing away: still the staging point (turn there)
    np.testing.assert_allclose(behind_ball_waypoint((-back, 0.0), math.pi / 2, ball, target, rp, BP, p), (-back, 0.0))
    # behind, on the line, facing the target: the go-to-ball skill takes over
    assert behind_ball_waypoint((-back, 0.01), 0.05, ball, target, rp, BP, p) is None
    # ... unless it waits for the receiver: it stays on the staging point, off the ball
    np.testing.assert_allclose(behind_ball_waypoint((-back, 0.01), 0.05, ball, target, rp, BP, p, wait=True),
                               (-back, 0.0))


def _free_kick_scene(blocker: tuple[float, float] | None = None):
    """A free kick for blue (ball out over the side line at x = -1 m in blue's half, nobody
    touched it; SSL game control, 0.5 s STOP): four attacking-team robots against an idle
    goalie and defender, and an idle ``blocker`` where given. Returns env, blue, yellow and
    blue's pass coordinator."""
    from ssl_marl.envs import parallel_env
    from ssl_marl.runners.controllers import make_controller

    n_yellow = 2 if blocker is None else 3
    env = parallel_env(n_blue=4, n_yellow=n_yellow, field="div_b", max_time_s=12.0, chip_kicks=True,
                       ssl_restarts=True, fouls=True, stop_s=0.5)
    cfg = env.config
    blue = make_controller("attack-baseline", "blue", 4, F, robot=cfg.robot, ball=cfg.ball, dt=cfg.dt)
    yellow = make_controller("idle", "yellow", n_yellow, F)
    robots = {"blue_0": (-4.0, 0.0, 0.0), "blue_1": (-2.0, 1.5, 0.0), "blue_2": (0.5, 1.0, math.pi),
              "blue_3": (-0.5, -1.5, 0.0), "yellow_0": (4.0, 0.0, math.pi), "yellow_1": (2.0, -2.0, math.pi)}
    if blocker is not None:
        robots["yellow_2"] = (*blocker, 0.0)
    env.reset(seed=0, options={"ball": {"pos": (-1.0, 2.9), "vel": (0.0, 2.0)}, "robots": robots})
    coord = next(p.prepare.coordinator for p in blue.selector.plays if p.prepare is not None)
    return env, blue, yellow, coord


def test_attack_team_takes_its_free_kick_as_a_set_piece():
    """The free kick of :func:`_free_kick_scene`: the attacking plays plan the pass before
    anyone reaches the ball (a set-piece plan), the kicker walks round behind the ball and
    passes within the free kick."""
    from ssl_marl.envs.game_control import FREE_KICK
    from ssl_marl.plays.attack_play import attack_decider_of
    from ssl_marl.runners.match import fit_action

    env, blue, yellow, coord = _free_kick_scene()
    restart_plans, fk_seen, fouls, kicked_in_fk = 0, False, [], False
    while env.agents and env.world_state().t < 10.0:
        st = env.task.referee_state
        in_fk = st.command == FREE_KICK and st.team == "blue"
        fk_seen |= in_fk
        actions = {k: fit_action(v, 6) for k, v in {**blue.act(env), **yellow.act(env)}.items()}
        if coord.plan is not None and coord.plan.restart and coord.plan.phase.value == "setup":
            restart_plans += 1
        _, _, _, _, infos = env.step(actions)
        ev = infos["blue_0"]["events"]
        fouls += [e for e in ev if e["type"] == "foul"]
        kicked_in_fk |= in_fk and any(e["type"] == "kick" and e["agent"].startswith("blue") for e in ev)
        if coord.counters.kicked:
            break
    assert fk_seen and restart_plans > 0  # planned while the ball still rested at the spot
    assert coord.counters.kicked == 1 and attack_decider_of(blue.selector.plays).counters.shoot == 0
    assert not fouls


def test_attack_team_chips_its_free_kick_over_a_robot_in_the_lane():
    """The free kick of :func:`_free_kick_scene` with a robot standing midway in the lane to
    the teammate the flat set piece goes to (blue_2): the set piece is planned as a chip
    (decided at the restart) and the kick that follows lifts the ball over 0.15 m, with no
    foul called."""
    from ssl_marl.plays.attack_decision import AttackChoice
    from ssl_marl.plays.attack_play import attack_decider_of
    from ssl_marl.runners.match import fit_action

    env, blue, yellow, coord = _free_kick_scene(blocker=(-0.05, 2.05))
    dec = attack_decider_of(blue.selector.plays)
    set_piece_chip, kick_t, top, fouls = False, None, 0.0, []
    while env.agents and env.world_state().t < 10.0:
        actions = {k: fit_action(v, 6) for k, v in {**blue.act(env), **yellow.act(env)}.items()}
        if coord.plan is not None and coord.plan.restart and dec.option is not None:
            set_piece_chip |= dec.option.kind is AttackChoice.CHIP
        _, _, _, _, infos = env.step(actions)
        ev = infos["blue_0"]["events"]
        fouls += [e for e in ev if e["type"] == "foul"]
        if kick_t is None and any(e["type"] == "kick" and e["agent"].startswith("blue") for e in ev):
            kick_t = env.world_state().t
        if kick_t is not None:
            top = max(top, env.world_state().ball_height)
            if env.world_state().t > kick_t + 0.6:
                break
    assert set_piece_chip and dec.counters.chip >= 1 and dec.counters.pass_ == 0
    assert kick_t is not None and top > 0.15  # over the robots
    assert not fouls


def test_learned_redirect_copies_do_not_share_their_contact_planner():
    """Tactics get copies of one learned redirect prototype; each copy plans its own contact."""
    from ssl_marl.plays.skillset import make_tactic_skill

    a, b = (make_tactic_skill("redirect", "learned", F) for _ in range(2))
    assert a.policy is b.policy and a._base is not b._base
    a._base._contact = np.array([1.0, 0.0])
    b.reset()
    assert a._base._contact is not None


def test_threat_defender_plays_only_against_opponents_in_our_half():
    import math

    from ssl_marl.physics.field import FieldGeometry
    from ssl_marl.physics.params import RobotParams
    from ssl_marl.plays.attack_play import threat_defender_role
    from ssl_marl.plays.play import OPTIONAL_ROLE_UNFILLED_COST, defender_role, make_context
    from ssl_marl.plays.scene import make_world

    f, rp = FieldGeometry.div_b(), RobotParams()
    blue = [(-4.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 1.0, 0.0)]

    def ctx(yellow, ball):
        return make_context(make_world(blue=blue, yellow=[(x, y, math.pi) for x, y in yellow], ball=ball, frame="blue"),
                            "blue", f, rp)

    role = threat_defender_role(1, 70, 2)
    assert role.name == "defender_1" and role.unfilled_cost == OPTIONAL_ROLE_UNFILLED_COST
    far = ctx([(4.0, 0.0), (2.5, 0.5), (-1.0, 1.0)], (1.5, 0.0))  # one opponent in our half, the ball in theirs
    assert role.target(far) is None
    near = ctx([(4.0, 0.0), (-0.5, 0.5), (-1.0, 1.0)], (1.5, 0.0))  # two in our half
    ball_ours = ctx([(4.0, 0.0), (2.5, 0.5), (3.0, 1.0)], (-0.5, 0.0))  # the ball in our half
    for c in (near, ball_ours):
        assert np.allclose(role.target(c), defender_role(1, 70).target(c))
    for always in (None, 0):
        assert threat_defender_role(1, 70, always).target(far) is not None
