"""Attack 3v2: the task's judge on constructed scenes, decision points, the hand-coded
policy, determinism, the shared features, the passing play's decider hook and the CLI's
--blue-decision errors."""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from ssl_marl.decisions.attack import Attack3v2Env, HandcodedAttackPolicy
from ssl_marl.decisions.attack_features import (ATTACK_OBS_DIM, ATTACK_OPTIONS, DRIBBLE_LEFT, N_ATTACK_OPTIONS, PASS_1,
                                                PASS_2, SHOOT, attack_action_mask, attack_observation, dribble_point,
                                                opponent_slots, option_decision, teammate_slots)
from ssl_marl.decisions.policies import RandomPolicy, run_episode
from ssl_marl.envs.tasks.attack import AttackRules
from ssl_marl.physics import FieldGeometry
from ssl_marl.physics.params import BallParams, RobotParams
from ssl_marl.plays.pass_decision import Choice, DecisionParams, decide
from ssl_marl.plays.pass_coordinator import CarrierRequest, CostDecider, PassCoordinator, PassingParams
from ssl_marl.plays.play import make_context
from ssl_marl.plays.scene import ball_in_front, make_world
from ssl_marl.plays.shoot import ShootState
from ssl_marl.plays.tactic_base import TacticStatus

F = FieldGeometry.div_b()
RP = RobotParams()
PARKED = (-4.2, 0.0, 0.0)


def _env(max_time_s: float = 15.0, **kw) -> Attack3v2Env:
    return Attack3v2Env(skills="baseline", rules=AttackRules(max_time_s=max_time_s), **kw)


def _scene(ball, ball_vel=(0.0, 0.0), blue=None, yellow=None) -> dict:
    """Reset options: all six robots named (field frame)."""
    blue = blue or [PARKED, (1.0, -2.0, 0.0), (1.0, 0.0, 0.0), (1.0, 2.0, 0.0)]
    yellow = yellow or [(4.2, 0.0, math.pi), (3.0, 1.5, math.pi)]
    robots = {f"blue_{i}": p for i, p in enumerate(blue)}
    robots.update({f"yellow_{i}": p for i, p in enumerate(yellow)})
    return {"robots": robots, "ball": {"pos": ball, "vel": ball_vel}}


def _play_out(env, options, max_steps=50):
    obs, infos = env.reset(seed=1, options=options)
    for _ in range(max_steps):
        acts = {a: (SHOOT if infos[a]["decision"] else 0) for a in env.possible_agents}
        obs, rew, term, trunc, infos = env.step(acts)
        if not env.agents:
            return rew, term, trunc, infos
    raise AssertionError("episode did not end")


# ------------------------------------------------------------------- the judge
def test_goal_ends_the_episode_with_the_team_reward():
    rew, term, trunc, infos = _play_out(_env(), _scene((4.3, 0.1), (3.0, 0.0)))
    assert all(term.values()) and not any(trunc.values())
    assert all(r == 1.0 for r in rew.values())
    assert all(i["goal"] == 1 and i["outcome"] == "goal" for i in infos.values())


def test_defender_control_ends_the_episode_without_reward():
    x, y, h = 2.5, 0.0, math.pi  # the defender faces -x with the ball on its dribbler
    rew, term, _, infos = _play_out(_env(), _scene(ball_in_front(x, y, h), yellow=[(4.2, 0.0, math.pi), (x, y, h)]))
    assert all(term.values()) and all(r == 0.0 for r in rew.values())
    assert infos["attacker_0"]["outcome"] == "lost_defender" and infos["attacker_0"]["goal"] == 0


@pytest.mark.parametrize("ball,vel", [((1.0, 2.9), (0.0, 3.0)),  # over the touch line
                                      ((0.3, -1.0), (-3.0, 0.0))])  # back over the halfway line
def test_ball_out_of_the_half_field_ends_the_episode(ball, vel):
    _, term, _, infos = _play_out(_env(), _scene(ball, vel))
    assert all(term.values()) and infos["attacker_1"]["outcome"] == "out"


def test_time_limit_truncates():
    assert AttackRules().max_time_s == 15.0
    # a resting ball far from everyone: nobody scores within 0.5 s
    _, term, trunc, infos = _play_out(_env(max_time_s=0.5), _scene((0.5, 2.5)))
    assert all(trunc.values()) and not any(term.values())
    assert infos["attacker_2"]["outcome"] == "timeout" and infos["attacker_2"]["goal"] == 0


# --------------------------------------------------------- decisions and API
def test_decision_points_are_explicit_and_only_the_carrier_decides():
    env = _env()
    obs, infos = env.reset(seed=41000)
    assert not any(i["decision"] for i in infos.values())
    for _ in range(10):
        obs, _, _, _, infos = env.step({a: 0 for a in env.possible_agents})
        deciding = [a for a in env.possible_agents if infos[a]["decision"]]
        if deciding:
            break
    assert len(deciding) == 1
    a = deciding[0]
    req = env.pending_request
    assert env.agent_of(req.carrier) == a and bool(env.engine.world_state().blue.ball_on_dribbler[req.carrier])
    m = infos[a]["action_mask"]
    assert m.dtype == np.int8 and m.shape == (N_ATTACK_OPTIONS,) and m[SHOOT] == 1 and m[3:].all()
    for b in env.possible_agents:
        assert obs[b].shape == (ATTACK_OBS_DIM,) and env.observation_space(b).contains(obs[b])
        if b != a:
            assert infos[b]["action_mask"].all()
    assert env.state().shape == env.state_space.shape and env.state_space.contains(env.state())
    assert env.option_names == ATTACK_OPTIONS


def test_illegal_pass_raises_or_becomes_a_shot():
    env = _env()
    _, infos = env.reset(seed=41000)
    while not any(i["decision"] for i in infos.values()):
        _, _, _, _, infos = env.step({a: 0 for a in env.possible_agents})
    a = next(a for a in env.possible_agents if infos[a]["decision"])
    mask = infos[a]["action_mask"].copy()
    env._masks[a] = mask * 0 + np.array([1, 0, 0, 1, 1, 1], np.int8)  # make the passes illegal
    with pytest.raises(ValueError, match="illegal"):
        env.step({b: (PASS_1 if b == a else 0) for b in env.possible_agents})


def test_parallel_api():
    from pettingzoo.test import parallel_api_test

    parallel_api_test(_env(max_time_s=2.0, illegal_option="default"), num_cycles=20)


def test_deterministic_under_the_seed():
    a = run_episode(_env(max_time_s=3.0), RandomPolicy(3), seed=41005, record=True)
    b = run_episode(_env(max_time_s=3.0), RandomPolicy(3), seed=41005, record=True)
    assert a["trace"] == b["trace"] and a["outcome"] == b["outcome"] and a["t_s"] == b["t_s"]
    assert a["decisions"] >= 1


def test_spawn_follows_the_documented_ranges():
    env = _env()
    for s in range(5):
        env.reset(seed=s)
        w = env.engine.world_state()
        carrier = env.task.carrier_robot
        k = int(carrier.split("_")[1])
        c = w.blue.pos[k]
        assert 0.5 <= c[0] <= 2.5 and abs(c[1]) <= 2.0
        assert 0.1 <= float(np.hypot(*(w.ball_pos - c))) <= 0.31
        assert np.hypot(*(w.yellow.pos[1] - w.ball_pos)) >= 0.79 and w.yellow.pos[1, 0] <= F.half_length - 1.0
        assert w.yellow.pos[0, 0] == pytest.approx(F.half_length - 0.25)


def test_spawn_is_measured_from_the_goal_line_on_both_fields():
    """On Division A the attack starts as far from the goal as on Division B (x shifted by
    the 1.5 m longer half length); the ball and the attackers are the same draw."""
    b, a = _env(), _env(field="div_a")
    shift = a.field.half_length - b.field.half_length
    assert shift == pytest.approx(1.5)
    for s in range(4):
        b.reset(seed=s)
        a.reset(seed=s)
        wb, wa = b.engine.world_state(), a.engine.world_state()
        assert a.task.carrier_robot == b.task.carrier_robot
        np.testing.assert_allclose(wa.ball_pos, wb.ball_pos + [shift, 0.0], atol=1e-9)
        np.testing.assert_allclose(wa.blue.pos[1:], wb.blue.pos[1:] + [shift, 0.0], atol=1e-9)
        np.testing.assert_allclose(wa.yellow.pos[0], wb.yellow.pos[0] + [shift, 0.0], atol=1e-9)
        assert wa.yellow.pos[1, 0] <= a.field.half_length - a.field.defense_depth


# ------------------------------------------------------- hand-coded policy
def _request(blue, yellow, ball, carrier, t=1.0, candidates=None):
    w = make_world(blue=blue, yellow=yellow, ball=ball, t=t, frame="blue",
                   blue_on_dribbler=[i == carrier for i in range(len(blue))])
    ctx = make_context(w, "blue", F, RP)
    cands = candidates if candidates is not None else tuple(k for k in range(1, len(blue)) if k != carrier)
    return CarrierRequest(ctx, carrier, cands, DecisionParams(), False, BallParams(), t)


def _policy_choice(req):
    env = SimpleNamespace(pending_request=req, passing=PassingParams())
    mask = attack_action_mask(req.ctx.world, "blue", req.carrier, F, candidates=req.candidates)
    return HandcodedAttackPolicy().act(env, "attacker_0", None, {"decision": True, "action_mask": mask})


def test_handcoded_shoots_at_an_open_goal():
    blue = [PARKED, (3.0, 0.0, 0.0), (1.0, 2.0, 0.0), (1.0, -2.0, 0.0)]
    req = _request(blue, [(4.3, 0.35, math.pi), (1.0, -2.5, 0.0)], ball_in_front(3.0, 0.0, 0.0), 1)
    assert _policy_choice(req) == SHOOT


def test_handcoded_passes_to_the_free_teammate_when_the_shot_is_blocked():
    blue = [PARKED, (1.5, 0.0, 0.0), (3.0, 1.8, -1.8), (0.5, -2.5, 0.0)]
    yellow = [(4.3, 0.0, math.pi), (1.95, 0.0, math.pi)]  # the defender right in front of the ball
    req = _request(blue, yellow, ball_in_front(1.5, 0.0, 0.0), 1)
    d = CostDecider().decide(req)
    assert d.choice is Choice.PASS and d.target == 2
    slots = teammate_slots(req.ctx.world, "blue", 1)
    assert slots == (2, 3)  # larger y first
    assert _policy_choice(req) == PASS_1


# ------------------------------------------------------------ shared features
def test_features_slots_mask_and_options_on_a_constructed_scene():
    blue = [PARKED, (1.5, 0.0, 0.0), (3.0, 1.8, -1.8), (0.5, -2.5, 0.0)]
    yellow = [(4.3, 0.0, math.pi), (1.95, 0.0, math.pi)]
    w = make_world(blue=blue, yellow=yellow, ball=ball_in_front(1.5, 0.0, 0.0), frame="blue",
                   blue_on_dribbler=[False, True, False, False])
    assert opponent_slots(w, "blue", F) == (0, 1)
    o = attack_observation(w, "blue", 1, F)
    assert o.shape == (ATTACK_OBS_DIM,) and o.dtype == np.float32 and np.isfinite(o).all()
    assert o[10] == 1.0 and o[16] == 1.0 and o[23] == 1.0  # ball on my dribbler; both teammate slots present
    assert o[14] < 0.1 and o[21] > 0.3  # blocked shot; a safe pass to slot 1
    mask = attack_action_mask(w, "blue", 1, F)
    assert mask.tolist() == [1, 1, 1, 1, 1, 1]
    assert attack_action_mask(w, "blue", 1, F, candidates=()).tolist() == [1, 0, 0, 1, 1, 1]  # cooldown: no pass
    d = option_decision(PASS_1, w, "blue", 1, F)
    assert d.choice is Choice.PASS and d.target == 2
    d = option_decision(DRIBBLE_LEFT, w, "blue", 1, F)
    assert d.choice is Choice.KEEP and d.dribble_to[1] > w.ball_pos[1] and d.commit_s > 0
    with pytest.raises(ValueError, match="option"):
        option_decision(6, w, "blue", 1, F)
    with pytest.raises(ValueError, match="not legal"):
        option_decision(PASS_2, w, "blue", 1, F, candidates=(2,))
    # a match: six robots a side, the two most advanced field players are the slots
    w6 = make_world(blue=[PARKED, (0.0, 0.0, 0.0), (1.0, 1.0, 0.0), (2.0, -1.0, 0.0), (-2.0, 0.0, 0.0),
                          (1.5, 2.0, 0.0)], yellow=[(4.2, 0.0, math.pi)] + [(x, 0.5, math.pi) for x in range(-2, 3)],
                    ball=ball_in_front(0.0, 0.0, 0.0), frame="blue")
    assert teammate_slots(w6, "blue", 1) == (5, 3)
    assert attack_observation(w6, "blue", 1, F).shape == (ATTACK_OBS_DIM,)
    assert dribble_point(DRIBBLE_LEFT, np.array([4.0, 2.9]), F).tolist() == [F.half_length - 0.3, F.half_width - 0.3]


# ----------------------------------------------------------- the decider hook
BLOCKED = dict(blue=[(-4.2, 0.0, 0.0), (1.5, 0.0, 0.0), (2.0, 2.2, -1.8)],
               yellow=[(3.3, -0.2, math.pi), (3.3, 0.0, math.pi), (3.3, 0.2, math.pi)],
               ball=ball_in_front(1.5, 0.0, 0.0), blue_on_dribbler=[False, True, False])


def _settled(coord, t):
    w = make_world(**BLOCKED, t=t, frame="blue")
    ctx = replace(make_context(w, "blue", F, RP), role_status={"attacker": TacticStatus(ShootState.KEEP)},
                  role_holders={"attacker": 1})
    coord.prepare(ctx)
    return w


class _Fixed:
    def __init__(self, option):
        self.option, self.calls, self.reset_env = option, 0, None

    def reset(self, env):
        self.reset_env = env

    def act(self, env, agent, obs, info):
        assert obs.shape == (ATTACK_OBS_DIM,) and info["decision"]
        self.calls += 1
        return self.option


def test_default_decider_is_the_cost_decision_unchanged():
    c = PassCoordinator()
    assert isinstance(c.decider, CostDecider)
    for k in range(3):
        w = _settled(c, 1.0 + k / 60)
    ours = w.team("blue")
    d = decide(w.ball_pos, 1, ours.pos, w.opponents("blue").pos, F, RP, c.bp, c.params.decision, candidates=(2,),
               heading=float(ours.heading[1]))
    assert c.decision.choice is d.choice is Choice.PASS and c.plan.receiver == d.target == 2
    assert c.keep_target() is None and c.decision.commit_s == 0.0


def test_a_policy_decider_changes_the_decision_and_commits():
    from ssl_marl.decisions.match_decider import PolicyCarrierDecider

    pol = _Fixed(DRIBBLE_LEFT)
    c = PassCoordinator(decider=PolicyCarrierDecider(pol))
    assert pol.reset_env.observation_space("attacker_0").shape == (ATTACK_OBS_DIM,)
    for k in range(12):  # 0.2 s: inside the dribble's commitment, the policy is asked once
        w = _settled(c, 1.0 + k / 60)
    assert pol.calls == 1 and c.plan is None and c.decision.choice is Choice.KEEP
    assert c.keep_target() == pytest.approx(tuple(dribble_point(DRIBBLE_LEFT, w.ball_pos, F)))
    assert c.keep_speed() == pytest.approx(0.5) and c.hold_fire()
    pol2 = _Fixed(PASS_1)
    c2 = PassCoordinator(decider=PolicyCarrierDecider(pol2))
    _settled(c2, 1.0)
    assert c2.plan is not None and c2.plan.receiver == 2
    c3 = PassCoordinator(decider=PolicyCarrierDecider(_Fixed(PASS_2)))  # slot 2 is empty: illegal
    with pytest.raises(ValueError, match="not legal"):
        _settled(c3, 1.0)
    c4 = PassCoordinator(decider=PolicyCarrierDecider(_Fixed(SHOOT)))
    _settled(c4, 1.0)
    assert c4.decision.choice is Choice.SHOOT and not c4.hold_fire()


def test_match_with_a_policy_decider_uses_it(tmp_path):
    from ssl_marl.runners.match import play_match

    pol = _Fixed(SHOOT)
    r = play_match(blue="passing-baseline", yellow="baseline", blue_decision=pol, robots=3, seconds=4.0, seed=2,
                   progress=False, start_jitter_m=0.0)
    assert r.config["decision"]["blue"] == "_Fixed" and r.config["decision"]["yellow"] is None
    with pytest.raises(ValueError, match="needs a passing or attacking team"):
        play_match(blue="baseline", blue_decision=pol, seconds=1.0, progress=False)


# --------------------------------------------------------------------- CLI
def _cli(args, capsys):
    from ssl_marl.cli import main

    rc = main(["match", "--seconds", "0.5", "--render", "none", "--quiet", "--robots", "2"] + args)
    return rc, capsys.readouterr().err


def test_cli_decision_errors(tmp_path, capsys):
    import torch

    rc, err = _cli(["--blue", "learned", "--blue-decision", "handcoded"], capsys)
    assert rc == 2 and "needs a passing or attacking team" in err
    rc, err = _cli(["--blue", "passing-baseline", "--blue-decision", str(tmp_path / "missing.pt")], capsys)
    assert rc == 2 and "does not exist" in err
    bad = tmp_path / "keepaway_actor.pt"
    torch.save({"format": "ssl_marl.decision_actor/1", "task": "keepaway", "obs_dim": 12, "n_options": 3,
                "hidden": [8], "state_dict": {}}, bad)
    rc, err = _cli(["--yellow", "passing-baseline", "--yellow-decision", str(bad)], capsys)
    assert rc == 2 and "obs_dim=12" in err


def test_plays_do_not_import_the_decisions_package():
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "ssl_marl" / "plays"
    for path in sorted(root.glob("*.py")):
        text = path.read_text()
        assert "decisions" not in "".join(l for l in text.splitlines(True) if l.lstrip().startswith(("import", "from"))), \
            f"{path.name} imports the decisions package (plays reach it only through the CarrierDecider hook)"
