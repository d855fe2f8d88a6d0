"""Where the attacking team's shots end: every shot of a few matches, followed to its end.

6v6 Division B by default (``--robots``, ``--field``), plain format (``--format ssl``: SSL's). A **shot** is a kick of the ``--blue`` team that the match
statistics count as one (:meth:`ssl_marl.plays.stats.MatchStatsTracker.classify_kick`:
its straight path crosses the opponent goal line, +x in the field frame, within 0.25 m of
the posts, and no teammate stands in its lane). From the world one step after the kick
(field frame, m) it records the ball's distance to the goal centre and the open goal angle
(rad; both :meth:`~ssl_marl.plays.stats.MatchStatsTracker.shot_geometry`, every robot but
the kicker an obstacle), its speed (m/s), whether the path is between the posts, the blue
carrier's last attack decision if it came at most 1.5 s before (choice, shot and keep
values; a learned decision's open-play choice with ``policy`` true and no values; none: a
kick no carrier decision chose, e.g. a defender's clearance), and how the
shot ended, whichever comes first: ``goal``; ``keeper`` (first touched by an opponent
inside its defense area), ``defender`` (by another opponent), ``teammate``; ``out`` (the
ball left the field, or a no-progress restart); ``stopped`` (slower than 0.3 m/s
untouched); a touch is the referee's (:class:`ssl_marl.envs.game_control.TouchWatch`).
Blue goals that follow no such shot (a deflection, a ball pushed in) are listed apart with
blue's last kick before them.

    python benchmarks/shot_outcome_probe.py --blue attack-learned --yellow baseline --seconds 600 \\
        --seeds 61600-61603 --out results/tuning/shot_outcome_probe.json
    python benchmarks/shot_outcome_probe.py --format ssl --yellow passing-learned --seeds 61760-61761 \\
        --out results/tuning/shot_outcome_probe_ssl_passing.json
    python benchmarks/shot_outcome_probe.py --format ssl --robots 11 --field div_a --blue attack-learned-decision \\
        --seeds 62100-62101 --out results/tuning/shot_outcome_probe_ssl_div_a.json
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from ball_out_probe import probe_args, write_probe  # noqa: E402  (the probes' shared command line)


def probe_match(blue: str, yellow: str, seconds: float, seed: int, fmt: str = "plain", robots: int = 6,
                field_name: str = "div_b") -> tuple[list[dict], list[dict]]:
    """The blue shots of one match, and its blue goals that followed no shot (module docstring)."""
    from ssl_marl.envs.game_control import TouchWatch
    from ssl_marl.physics.field import FieldGeometry
    from ssl_marl.physics.params import BallParams, RobotParams
    from ssl_marl.decisions import match_decider
    from ssl_marl.plays import attack_play
    from ssl_marl.plays.attack_decision import AttackChoice
    from ssl_marl.plays.pass_decision import Choice
    from ssl_marl.plays.stats import MatchStatsTracker
    from ssl_marl.runners import match as match_runner

    field, rp, bp = FieldGeometry.from_name(field_name), RobotParams(), BallParams()
    rules = MatchStatsTracker(field, bp)  # the match statistics' shot rule (classify_kick)
    touch = TouchWatch(robots, robots, rp.radius, bp.radius)  # the referee's touch rule
    shots: list[dict] = []
    goals_other: list[dict] = []  #: blue goals that no shot above led to (deflections, pushes)
    state: dict = {"open": None, "pending": None, "decision": None, "last_kick": None, "t": 0.0}
    original_decide, original_record = attack_play.AttackDecider.decide, match_runner.MatchStats.record
    original_policy_decide = match_decider.PolicyAttackDecider.decide

    def decide(self, request):
        out = original_decide(self, request)
        d = self.last
        state["decision"] = {"t": state["t"], "choice": d.choice.value, "shot_value": round(float(d.shot), 3),
                             "keep_value": round(float(d.keep), 3)}
        return out

    def policy_decide(self, request):
        """A learned decision's own choice (requests it hands to the cost decision reach ``decide`` above):
        the option's kind as the decider counts it, no shot or keep values."""
        asked = self.decisions
        out = original_policy_decide(self, request)
        if self.decisions > asked:
            kind = (AttackChoice.SHOOT if out.choice is Choice.SHOOT else AttackChoice.DRIBBLE
                    if out.choice is Choice.KEEP else self.option.kind)
            state["decision"] = {"t": state["t"], "choice": kind.value, "policy": True}
        return out

    def close(outcome: str) -> None:
        shots.append({**state["open"], "outcome": outcome})
        state["open"] = None

    def open_shot(truth, kicker: int) -> None:
        ball, vel = np.asarray(truth.ball_pos, float), np.asarray(truth.ball_vel, float)
        if state["open"] is not None:
            close("kicked_again")
        geo = rules.shot_geometry(truth, "blue", kicker)
        y_at = ball[1] + vel[1] * (field.half_length - ball[0]) / vel[0]
        dec = state["decision"]
        state["open"] = {"t": float(truth.t), "kicker": f"blue_{kicker}",
                         "decision": dec if dec is not None and truth.t - dec["t"] <= 1.5 else None,
                         "ball": ball.round(3).tolist(), "dist_m": geo["dist_m"],
                         "speed": float(np.hypot(*vel)), "open_rad": geo["open_rad"],
                         "on_target": bool(abs(y_at) <= field.goal_width / 2)}

    def record(self, events, truth):
        state["t"] = float(truth.t)
        if state["pending"] is not None:  # the kick of the previous step: the ball is now moving
            if rules.classify_kick(truth, "blue", state["pending"]) == "shot":
                open_shot(truth, state["pending"])
            state["pending"] = None
        for e in events:
            if e.get("type") == "kick" and e["agent"].startswith("blue"):
                state["pending"] = int(e["agent"].split("_")[1])
                state["last_kick"] = {"t": float(truth.t), "kicker": e["agent"],
                                      "ball": np.asarray(truth.ball_pos).round(3).tolist()}
            if e.get("type") == "goal" and e.get("team") == "blue" and state["open"] is None:
                goals_other.append({"t": float(truth.t), "last_blue_kick": state["last_kick"]})
        if state["open"] is not None:
            types = {e.get("type") for e in events}
            rows = np.flatnonzero(touch.touching(truth, []))
            blue, yellow = rows[rows < robots], rows[rows >= robots] - robots
            if "goal" in types:
                close("goal")
            elif "ball_out" in types or "no_progress" in types:
                close("out")
            elif truth.t - state["open"]["t"] > 0.05 and blue.size:
                close("teammate")
            elif yellow.size:
                close("keeper" if field.in_defense_area(truth.yellow.pos[yellow[0]], +1) else "defender")
            elif np.hypot(*truth.ball_vel) < 0.3:
                close("stopped")
        return original_record(self, events, truth)

    match_runner.MatchStats.record = record
    attack_play.AttackDecider.decide = decide
    match_decider.PolicyAttackDecider.decide = policy_decide
    try:
        res = match_runner.play_match(blue=blue, yellow=yellow, robots=robots, field=field_name, seconds=seconds, seed=seed,
                                      progress=False, render=None,
                                      env_kwargs=match_runner.format_options(fmt, seconds))
    finally:
        match_runner.MatchStats.record = original_record
        attack_play.AttackDecider.decide = original_decide
        match_decider.PolicyAttackDecider.decide = original_policy_decide
    return ([{**s, "seed": seed, "score": res.score} for s in shots],
            [{**g, "seed": seed} for g in goals_other])


def summarize(shots: list[dict], half_length: float = 4.5) -> dict:
    """Counts over ``shots``; the scoring zone is 1 m from the half-way line to 0.7 m before the goal line
    (``half_length``, m), within 1.5 m of the long axis."""
    out = Counter(s["outcome"] for s in shots)
    dist = np.array([s["dist_m"] for s in shots]) if shots else np.zeros(0)
    op = np.array([s["open_rad"] for s in shots]) if shots else np.zeros(0)
    return {"shots": len(shots), "outcomes": dict(out),
            "on_target": int(sum(s["on_target"] for s in shots)),
            "median_dist_m": float(np.median(dist)) if dist.size else None,
            "open_below_0_05rad": int((op < 0.05).sum()),
            "from_own_half": int(sum(s["ball"][0] < 0 for s in shots)),
            "from_scoring_zone": int(sum(1.0 <= s["ball"][0] <= half_length - 0.7 and abs(s["ball"][1]) <= 1.5
                                         for s in shots)),
            "after_decision": dict(Counter((s["decision"] or {}).get("choice", "none") for s in shots)),
            "by_open": {k: dict(Counter(s["outcome"] for s in shots if (s["open_rad"] >= 0.05) == (k == "open")))
                        for k in ("open", "closed")}}


def main(argv: list[str] | None = None) -> int:
    def fmt(ap):
        ap.add_argument("--format", choices=("plain", "ssl"), default="plain",
                        help="match format (ssl_marl.runners.match.format_options; default plain)")
        ap.add_argument("--robots", type=int, default=6, help="robots per team (default 6)")
        ap.add_argument("--field", choices=("div_a", "div_b"), default="div_b", help="field (default div_b)")
    args = probe_args(__doc__.splitlines()[0], "61600-61601", "JSON output (summary and every shot)", argv, extra=fmt)
    shots, goals_other = [], []
    for seed in args.seeds:
        s, g = probe_match(args.blue, args.yellow, args.seconds, seed, args.format, args.robots, args.field)
        shots += s
        goals_other += g
    from ssl_marl.physics.field import FieldGeometry
    summary = {**summarize(shots, FieldGeometry.from_name(args.field).half_length),
               "blue_goals_without_a_shot": len(goals_other)}
    write_probe(args, {"summary": summary, "shots": shots, "goals_without_a_shot": goals_other})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
