"""Role assignment: tiers, unfilled cost, constraints, stickiness, errors (fake costs)."""

import itertools
import math

import numpy as np
import pytest

from ssl_marl.plays.assignment import RoleSlot, assign


def table(d):
    """cost function from {(role, robot): cost}."""
    return lambda role, robot: d[(role, robot)]


def test_higher_tier_is_filled_first_even_if_costlier():
    # one robot, two roles: the important role wins although the other is much cheaper
    a = assign([7], [RoleSlot("attacker", 2), RoleSlot("support", 1)],
               table({("attacker", 7): 10.0, ("support", 7): 0.1}))
    assert a.roles == {"attacker": 7, "support": None}
    assert a.robots == {7: "attacker"}
    # two robots: the tier-2 role takes its cheapest robot although the global optimum differs
    cost = {("a", 0): 1.0, ("a", 1): 1.5, ("b", 0): 1.0, ("b", 1): 100.0}
    a = assign([0, 1], [RoleSlot("a", 2), RoleSlot("b", 1)], table(cost))
    assert a.roles == {"a": 0, "b": 1}
    assert a.total_cost == pytest.approx(101.0)


def test_within_a_tier_the_assignment_is_optimal():
    rng = np.random.default_rng(0)
    for _ in range(20):
        C = rng.uniform(0, 10, (4, 5))
        a = assign(range(5), [RoleSlot(f"r{i}", 0) for i in range(4)], C)
        best = min(sum(C[i, p[i]] for i in range(4)) for p in itertools.permutations(range(5), 4))
        assert a.total_cost == pytest.approx(best)
        assert len(a.unassigned) == 1


def test_unfilled_cost_leaves_a_role_empty_and_frees_the_robot():
    roles = [RoleSlot("far_role", 2, unfilled_cost=5.0), RoleSlot("near_role", 1)]
    cost = {("far_role", 0): 6.0, ("near_role", 0): 1.0}
    a = assign([0], roles, table(cost))
    assert a.roles == {"far_role": None, "near_role": 0}
    assert a.unfilled == ("far_role",)
    assert a.total_cost == pytest.approx(5.0 + 1.0)
    # cheaper than leaving it: filled
    a = assign([0], [RoleSlot("far_role", 2, unfilled_cost=7.0), RoleSlot("near_role", 1)], table(cost))
    assert a.roles == {"far_role": 0, "near_role": None}


def test_more_roles_than_robots_drops_cheapest_to_leave_and_lower_tiers():
    roles = [RoleSlot("a", 1, unfilled_cost=50.0), RoleSlot("b", 1, unfilled_cost=10.0),
             RoleSlot("c", 1, unfilled_cost=30.0), RoleSlot("low", 0)]
    a = assign([0, 1], roles, np.ones((4, 2)))
    assert a.roles["b"] is None and a.roles["low"] is None
    assert {a.roles["a"], a.roles["c"]} == {0, 1}
    assert a.unassigned == ()


def test_more_robots_than_roles_lists_unassigned():
    C = np.array([[3.0, 1.0, 2.0, 9.0]])
    a = assign([10, 11, 12, 13], ["only"], C)
    assert a.roles == {"only": 11}
    assert a.unassigned == (10, 12, 13)


def test_fixed_robot_is_a_hard_constraint():
    C = np.array([[9.0, 0.0, 0.0],   # goalie: robot 0 is the most expensive
                  [0.0, 1.0, 2.0]])  # attacker: robot 0 would be best
    a = assign([0, 1, 2], [RoleSlot("goalie", 100), RoleSlot("attacker", 90)], C, fixed={"goalie": 0})
    assert a.roles == {"goalie": 0, "attacker": 1}
    # the fixed robot is absent: the role is assigned like any other
    a = assign([1, 2], [RoleSlot("goalie", 100), RoleSlot("attacker", 90)], C[:, 1:], fixed={"goalie": 0})
    assert a.roles["goalie"] in (1, 2) and a.roles["attacker"] in (1, 2)
    with pytest.raises(ValueError, match="unknown role"):
        assign([0], ["a"], [[1.0]], fixed={"nope": 0})


def test_forbidden_pairs_are_constraints_not_costs():
    calls = []

    def cost(role, robot):
        calls.append((role, robot))
        if (role, robot) == ("a", 0):
            return math.inf  # never evaluated: the pair is forbidden
        return 1.0 if robot == 0 else 5.0

    a = assign([0, 1], ["a", "b"], cost, forbidden=[("a", 0)])
    assert a.roles == {"a": 1, "b": 0}
    assert ("a", 0) not in calls
    # all robots forbidden for a role: it stays empty
    a = assign([0, 1], ["a", "b"], np.ones((2, 2)), forbidden=[("a", 0), ("a", 1)])
    assert a.roles["a"] is None and a.roles["b"] in (0, 1)
    # a forbidden cell may hold inf in a matrix
    a = assign([0, 1], ["a"], np.array([[np.inf, 2.0]]), forbidden=[("a", 0)])
    assert a.roles == {"a": 1}
    # a fixed robot that is forbidden for the role is not forced
    a = assign([0, 1], ["g"], np.array([[1.0, 2.0]]), fixed={"g": 0}, forbidden=[("g", 0)])
    assert a.roles == {"g": 1}


def test_stickiness_keeps_the_previous_holder_on_near_ties():
    C = np.array([[1.00, 1.05]])  # robot 0 slightly better
    assert assign([0, 1], ["attacker"], C).roles["attacker"] == 0
    sticky = assign([0, 1], ["attacker"], C, previous={"attacker": 1}, stickiness=0.3)
    assert sticky.roles["attacker"] == 1
    assert sticky.total_cost == pytest.approx(1.05)  # reported without the bonus
    # a clear advantage still wins
    C = np.array([[1.0, 2.0]])
    assert assign([0, 1], ["attacker"], C, previous={"attacker": 1}, stickiness=0.3).roles["attacker"] == 0
    # unknown previous roles / robots are ignored
    assign([0, 1], ["attacker"], C, previous={"gone": 5, "attacker": 9}, stickiness=0.3)
    with pytest.raises(ValueError, match="stickiness"):
        assign([0], ["a"], [[1.0]], stickiness=-1.0)


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
def test_non_finite_cost_raises_naming_role_and_robot(bad):
    C = np.ones((2, 3))
    C[1, 2] = bad
    with pytest.raises(ValueError, match=r"role 'support'.*robot 12"):
        assign([10, 11, 12], ["attacker", "support"], C)
    with pytest.raises(ValueError, match=r"role 'b'.*robot 4"):
        assign([3, 4], ["a", "b"], lambda role, robot: bad if (role, robot) == ("b", 4) else 1.0)


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="duplicate role"):
        assign([0], ["a", "a"], np.ones((2, 1)))
    with pytest.raises(ValueError, match="duplicate robot"):
        assign([0, 0], ["a"], np.ones((1, 2)))
    with pytest.raises(ValueError, match="shape"):
        assign([0, 1], ["a"], np.ones((2, 2)))
    with pytest.raises(ValueError, match="unfilled_cost"):
        assign([0], [RoleSlot("a", unfilled_cost=math.inf)], [[1.0]])


def test_empty_cases():
    assert assign([], ["a", "b"], np.zeros((2, 0))).roles == {"a": None, "b": None}
    a = assign([0, 1], [], np.zeros((0, 2)))
    assert a.roles == {} and a.unassigned == (0, 1)
