"""Where the attacking team's shots end: every shot of a few matches, followed to its end.

A **shot** is a kick of the ``--blue`` team whose straight path crosses the opponent
goal line (+x in the field frame, one period) between the posts widened by 0.1 m, as
the match statistics count it. From the world at the kick (field frame, m) it records
the kicker's distance to the goal centre, the ball speed just after the kick (m/s), the
open goal angle (rad, :func:`~ssl_marl.plays.pass_decision.open_goal_interval` with
every other robot as an obstacle), whether the path is between the posts, the blue
carrier's last attack decision if it came at most 1.5 s before (choice, shot and keep
values; none: a kick no carrier decision chose, e.g. a defender's clearance), and how the
shot ended, whichever comes first: ``goal``; ``keeper`` (first touched by an opponent
inside its defense area), ``defender`` (by another opponent), ``teammate``; ``out``
(the ball left the field); ``stopped`` (slower than 0.3 m/s untouched); a touch is a
robot centre within robot radius + ball radius + 0.02 m of the ball. Blue goals that
follow no such shot (a deflection, a ball pushed in) are listed apart with blue's last
kick before them.

    python benchmarks/shot_outcome_probe.py --blue attack-learned --yellow baseline --seconds 600 \\
        --seeds 61600-61603 --out results/tuning/shot_outcome_probe.json
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from ball_out_probe import probe_args, write_probe  # noqa: E402  (the probes' shared command line)


def probe_match(blue: str, yellow: str, seconds: float, seed: int) -> list[dict]:
    """The blue shots of one match (module docstring)."""
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.plays.pass_decision import open_goal_interval
    from ssl_marl.runners import match as match_runner

    from ssl_marl.plays import attack_play

    shots: list[dict] = []
    goals_other: list[dict] = []  #: blue goals that no shot above led to (deflections, pushes)
    state: dict = {"open": None, "pending": None, "decision": None, "t": 0.0}
    original_decide = attack_play.AttackDecider.decide

    def decide(self, request):
        out = original_decide(self, request)
        d = self.last
        state["decision"] = {"t": state["t"], "choice": d.choice.value, "shot_value": round(float(d.shot), 3),
                             "keep_value": round(float(d.keep), 3)}
        return out
    original = match_runner.MatchStats.record
    rp, bp = RobotParams(), BallParams()
    reach = rp.radius + bp.radius + 0.02

    def close(outcome: str) -> None:
        shot = state["open"]
        shot["outcome"] = outcome
        shots.append(shot)
        state["open"] = None

    def record(self, events, truth):
        field = self._probe_field
        state["t"] = float(truth.t)
        ball = np.asarray(truth.ball_pos, float)
        vel = np.asarray(truth.ball_vel, float)
        if state["pending"] is not None:  # the kick of the previous step: the ball is now moving
            agent, pos = state["pending"]
            state["pending"] = None
            L2 = field.half_length
            if vel[0] > 0.1:
                y_at = ball[1] + vel[1] * (L2 - ball[0]) / vel[0]
                if abs(y_at) <= field.goal_width / 2 + 0.1:
                    if state["open"] is not None:
                        close("kicked_again")
                    others = np.concatenate([truth.blue.pos, truth.yellow.pos])
                    others = others[np.hypot(*(others - pos).T) > 0.05]
                    open_angle, _ = open_goal_interval(ball, others, field, rp, bp)
                    dec = state["decision"]
                    recent = dec is not None and truth.t - dec["t"] <= 1.5
                    state["open"] = {"t": float(truth.t), "kicker": agent,
                                     "decision": dec if recent else None, "ball": ball.round(3).tolist(),
                                     "dist_m": float(np.hypot(L2 - ball[0], ball[1])),
                                     "speed": float(np.hypot(*vel)), "open_rad": float(open_angle),
                                     "on_target": bool(abs(y_at) <= field.goal_width / 2)}
        for e in events:
            if e.get("type") == "kick" and e["agent"].startswith("blue"):
                i = int(e["agent"].split("_")[1])
                state["pending"] = (e["agent"], np.asarray(truth.blue.pos[i], float))
                state["last_kick"] = {"t": float(truth.t), "kicker": e["agent"], "ball": ball.round(3).tolist()}
            if e.get("type") == "goal" and e.get("team") == "blue" and state["open"] is None:
                goals_other.append({"t": float(truth.t), "last_blue_kick": state.get("last_kick")})
        if state["open"] is not None:
            types = {e.get("type") for e in events}
            if "goal" in types:
                close("goal")
            elif "ball_out" in types or "no_progress" in types:
                close("out")
            else:
                d_y = np.hypot(*(truth.yellow.pos - ball).T)
                d_b = np.hypot(*(truth.blue.pos - ball).T)
                if (truth.t - state["open"]["t"]) > 0.05 and d_b.min() <= reach:
                    close("teammate")
                elif d_y.min() <= reach:
                    j = int(np.argmin(d_y))
                    close("keeper" if field.in_defense_area(truth.yellow.pos[j], +1) else "defender")
                elif np.hypot(*vel) < 0.3:
                    close("stopped")
        return original(self, events, truth)

    match_runner.MatchStats.record = record
    attack_play.AttackDecider.decide = decide
    original_init = match_runner.MatchStats.__init__

    def init(self):
        original_init(self)
        from ssl_marl.physics.field import FieldGeometry
        self._probe_field = FieldGeometry.div_b()
    match_runner.MatchStats.__init__ = init
    try:
        res = match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False,
                                      render=None)
    finally:
        match_runner.MatchStats.record = original
        match_runner.MatchStats.__init__ = original_init
        attack_play.AttackDecider.decide = original_decide
    return ([{**s, "seed": seed, "score": res.score} for s in shots],
            [{**g, "seed": seed} for g in goals_other])


def summarize(shots: list[dict]) -> dict:
    out = Counter(s["outcome"] for s in shots)
    dist = np.array([s["dist_m"] for s in shots]) if shots else np.zeros(0)
    op = np.array([s["open_rad"] for s in shots]) if shots else np.zeros(0)
    return {"shots": len(shots), "outcomes": dict(out),
            "on_target": int(sum(s["on_target"] for s in shots)),
            "median_dist_m": float(np.median(dist)) if dist.size else None,
            "open_below_0_05rad": int((op < 0.05).sum()),
            "from_own_half": int(sum(s["ball"][0] < 0 for s in shots)),
            "from_scoring_zone": int(sum(1.0 <= s["ball"][0] <= 3.8 and abs(s["ball"][1]) <= 1.5 for s in shots)),
            "after_decision": dict(Counter((s["decision"] or {}).get("choice", "none") for s in shots)),
            "by_open": {k: dict(Counter(s["outcome"] for s in shots if (s["open_rad"] >= 0.05) == (k == "open")))
                        for k in ("open", "closed")}}


def main(argv: list[str] | None = None) -> int:
    args = probe_args(__doc__.splitlines()[0], "61600-61601", "JSON output (summary and every shot)", argv)
    shots, goals_other = [], []
    for seed in args.seeds:
        s, g = probe_match(args.blue, args.yellow, args.seconds, seed)
        shots += s
        goals_other += g
    summary = {**summarize(shots), "blue_goals_without_a_shot": len(goals_other)}
    write_probe(args, {"summary": summary, "shots": shots, "goals_without_a_shot": goals_other})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
