"""Skills take a field-frame snapshot plus the robot's team (``act(world, robot, team=)``),
or a team-frame snapshot; a field-frame snapshot without a team is a clear error."""

from __future__ import annotations

import numpy as np
import pytest

from ssl_marl.envs import parallel_env
from ssl_marl.physics.state import to_team_frame
from ssl_marl.skills import make_skill, skill_names


@pytest.fixture(scope="module")
def env():
    e = parallel_env(n_blue=3, n_yellow=3, field="div_b", realism="none")
    e.reset(seed=3)
    for _ in range(20):
        e.step({a: e.action_space(a).sample() for a in e.agents})
    return e


@pytest.mark.parametrize("kind", ["baseline", "learned"])
@pytest.mark.parametrize("name", skill_names())
@pytest.mark.parametrize("team", ["blue", "yellow"])
def test_team_argument_equals_team_frame_snapshot(env, kind, name, team):
    from ssl_marl.skills.registry import get_skill

    spec = get_skill(name)
    if kind == "learned" and spec.has_learned and spec.actor is None:
        pytest.skip(f"{name} ships no learned actor")
    ws = env.world_state()

    def build():
        skill = make_skill(name, kind, env.field)
        if hasattr(skill, "set_target"):  # the pass needs its receiver point (team frame)
            skill.set_target(np.array([1.0, 0.5]))
        return skill

    a = build().act(ws, 1, team=team)
    b = build().act(to_team_frame(ws, team), 1)
    np.testing.assert_array_equal(a, b)


def test_field_frame_without_team_says_what_to_do(env):
    with pytest.raises(ValueError, match=r"pass the robot's team, e.g. skill.act\(env.world_state\(\), robot, "
                                         r"team='blue'\)"):
        make_skill("go_to_ball", "learned", env.field).act(env.world_state(), 0)


def test_mismatched_team_is_refused(env):
    with pytest.raises(ValueError, match="'yellow''s frame"):
        make_skill("go_to_ball", "baseline", env.field).act(env.vision_state("yellow"), 0, team="blue")
    with pytest.raises(ValueError, match="unknown team 'red'"):
        make_skill("go_to_ball", "baseline", env.field).act(env.world_state(), 0, team="red")
