"""Where passes go wrong: every pass of a few matches, followed from its kick to its end.

For each pass the match statistics count (:class:`ssl_marl.plays.stats.MatchStatsTracker`,
the same runner :func:`ssl_marl.runners.match.play_match`) this records, field frame:
the kick speed (m/s, the step after the kick), the pass kind (flat / chip), the intended
receiver (the teammate nearest the kick's straight path within the statistics' lane) with
its distance along the path and lateral offset (m), the kicker's role and tactic state on
the team controller's last tick (``ChipPass:kick``: a pass the team planned;
``Attacker:aim_to_shoot``: a shot; ``Defender:clear_kick``: a clearance), the closest approach of that receiver
and of the nearest opponent to the ball while the pass is open (m), the ball's speed at the
receiver's closest approach (m/s), whether the receiver touched the ball (centre distance
below robot radius + ball radius + 5 mm), and how the pass ended (completed, intercepted,
lost with the statistics' ``why``). The summary counts lost passes by cause:
``receiver_touched`` (the receiver reached the ball but did not control it),
``opponent_touched``, ``short`` (nobody touched it, the ball stopped or ran out before the
receiver: at its closest approach the receiver was still ahead of the ball),
``missed`` (nobody touched it and it passed the receiver's spot more than a robot radius
away). ``by_kicker_tactic`` counts the outcomes per kicker tactic: how many of the passes the
statistics count were passes the team meant; ``by_play`` the outcomes of set-piece passes (the first kick
of a kickoff or free kick the referee awarded) and of passes in open play (``--format ssl``: SSL's game
control, whose free kicks make most of the passes).

    python benchmarks/pass_loss_probe.py --blue attack-learned --yellow attack-learned \\
        --seconds 600 --seeds 61600-61601 --out results/tuning/pass_loss_probe.json
    python benchmarks/pass_loss_probe.py --format ssl --yellow attack-learned --seeds 61810-61811 \\
        --out results/tuning/pass_loss_probe_ssl_selfplay.json
    # the same with every flat kick past a teammate counted as a pass:
    python benchmarks/pass_loss_probe.py ... --pass-max-arrive-speed inf --out results/tuning/pass_loss_probe_any_speed.json
    # the attacking plays' set-piece passes to receive points at least M m inside the field lines
    # (ATTACK_RESTART_DECISION.receive_margin_m; the attacking teams of this process only):
    python benchmarks/pass_loss_probe.py --format ssl --blue attack-learned-decision --yellow attack-learned-decision \
        --restart-receive-margin 0.15 --seeds 60900-60902 --out results/tuning/set_piece_margin_0.15.json
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.ball_out_probe import probe_args, write_probe  # noqa: E402

def _touch_m() -> float:
    """Robot radius + ball radius + 5 mm (m): a centre distance at which the robot touches the ball."""
    from ssl_marl.physics.params import BallParams, RobotParams

    return RobotParams().radius + BallParams().radius + 0.005


TOUCH_M = _touch_m()


def _receiver(world, team: str, kicker: int, params) -> tuple[int | None, float, float]:
    """The teammate nearest the kick's straight path within the statistics' lane and at
    least ``min_pass_m`` ahead (index, along m, lateral m), or (None, 0, inf)."""
    from ssl_marl.plays.stats import kick_path_offsets

    lane = [o for o in kick_path_offsets(world, team, kicker) if o[1] >= params.min_pass_m and o[2] <= params.pass_lane_m]
    return min(lane, key=lambda o: o[2]) if lane else (None, 0.0, np.inf)


def probe_match(blue: str, yellow: str, seconds: float, seed: int,
                max_arrive: float | None = None, fmt: str = "plain") -> list[dict]:
    """Every pass of one match (see the module docstring); ``max_arrive`` (m/s) replaces the
    statistics' ``pass_max_arrive_speed`` (inf: any flat kick past a teammate is a pass);
    ``fmt``: the match format (:func:`ssl_marl.runners.match.format_options`)."""
    from ssl_marl.plays import stats as stats_mod
    from ssl_marl.runners import match as match_runner

    passes: list[dict] = []
    cur: dict = {}
    original = stats_mod.MatchStatsTracker.observe
    make = match_runner.make_controller
    ctrls: dict = {}

    def capture(kind, team, *a, **kw):
        ctrls[team] = make(kind, team, *a, **kw)
        return ctrls[team]

    def intent(team: str, idx: int) -> tuple[str | None, str | None]:
        """(role, tactic class) the kicker ran on its last tick (None, None for a non-STP team)."""
        c = ctrls.get(team)
        if c is None or not hasattr(c, "tactic"):
            return None, None
        t = c.tactic(idx)
        return c.roles.get(idx), (type(t).__name__ + ":" + str(getattr(getattr(t, "state", None), "value", ""))
                                  if t is not None else None)

    def observe(self, world, events=()):
        if max_arrive is not None and self.params.pass_max_arrive_speed != max_arrive:
            self.params = dataclasses.replace(self.params, pass_max_arrive_speed=max_arrive)
        n_log, set_piece_for = len(self.log), self._set_piece_for
        original(self, world, events)
        for entry in self.log[n_log:]:
            if entry["type"] == "pass":
                team = entry["team"]
                other = "yellow" if team == "blue" else "blue"
                r, along, lat = _receiver(world, team, entry["kicker"], self.params)
                cur.clear()
                role, tactic = intent(team, entry["kicker"])
                cur.update(team=team, other=other, kicker=entry["kicker"], kind=entry["kind"], t=entry["t"],
                           role=role, tactic=tactic, set_piece=set_piece_for == team,
                           speed=float(np.hypot(*world.ball_vel)), receiver=r, along_m=along, lateral_m=lat,
                           from_xy=np.round(world.ball_pos, 3).tolist(), rec_min_m=np.inf, opp_min_m=np.inf,
                           speed_at_rec=None, rec_behind=None, steps=0)
            elif entry["type"].startswith("pass_") and cur:
                cur.update(outcome=entry["type"][5:], why=entry.get("why"), end_xy=np.round(world.ball_pos, 3).tolist(),
                           duration_s=entry["t"] - cur["t"], seed=seed)
                passes.append({k: (None if isinstance(v, float) and not np.isfinite(v) else v) for k, v in cur.items()})
                cur.clear()
        if cur and not any(e["type"].startswith("pass") for e in self.log[n_log:]):
            b = np.asarray(world.ball_pos, float)
            cur["steps"] += 1
            if cur["receiver"] is not None:
                rp = world.team(cur["team"]).pos[cur["receiver"]]
                d = float(np.hypot(*(rp - b)))
                if d < cur["rec_min_m"]:
                    v = np.asarray(world.ball_vel, float)
                    cur.update(rec_min_m=d, speed_at_rec=float(np.hypot(*v)),
                               rec_behind=bool((rp - b) @ v < 0))  # the ball has passed the receiver
            opp = world.team(cur["other"]).pos
            if len(opp):
                cur["opp_min_m"] = min(cur["opp_min_m"], float(np.min(np.hypot(*(opp - b).T))))

    stats_mod.MatchStatsTracker.observe = observe
    match_runner.make_controller = capture
    try:
        res = match_runner.play_match(blue=blue, yellow=yellow, seconds=seconds, seed=seed, progress=False,
                                      env_kwargs=match_runner.format_options(fmt, seconds))
    finally:
        stats_mod.MatchStatsTracker.observe = original
        match_runner.make_controller = make
    return [{**p, "score": res.score} for p in passes]


def cause(p: dict) -> str:
    """Why a pass that was not completed failed (see the module docstring)."""
    if p["rec_min_m"] is not None and p["rec_min_m"] <= TOUCH_M:
        return "receiver_touched"
    if p["opp_min_m"] is not None and p["opp_min_m"] <= TOUCH_M:
        return "opponent_touched"
    if p["rec_behind"] is False or p["rec_behind"] is None:
        return "short"
    return "missed"


def summarize(passes: list[dict]) -> dict:
    lost = [p for p in passes if p["outcome"] == "lost"]
    out: dict = {"passes": len(passes), "by_outcome": {}, "lost_by_why": {}, "lost_by_cause": {},
                 "ball_out_by_cause": {}}
    out["by_kicker_tactic"], out["by_play"] = {}, {}
    for p in passes:
        play = out["by_play"].setdefault("set_piece" if p.get("set_piece") else "open_play", {})
        play[p["outcome"]] = play.get(p["outcome"], 0) + 1
        out["by_outcome"][p["outcome"]] = out["by_outcome"].get(p["outcome"], 0) + 1
        tac = str(p.get("tactic")).split(":")[0]
        row = out["by_kicker_tactic"].setdefault(tac, {})
        row[p["outcome"]] = row.get(p["outcome"], 0) + 1
    for p in lost:
        c = cause(p)
        out["lost_by_why"][p["why"]] = out["lost_by_why"].get(p["why"], 0) + 1
        out["lost_by_cause"][c] = out["lost_by_cause"].get(c, 0) + 1
        if p["why"] == "ball_out":
            out["ball_out_by_cause"][c] = out["ball_out_by_cause"].get(c, 0) + 1
    for name, sel in (("completed", [p for p in passes if p["outcome"] == "completed"]), ("lost", lost)):
        if sel:
            out[f"{name}_median"] = {k: float(np.median([p[k] for p in sel if p[k] is not None] or [np.nan]))
                                     for k in ("speed", "along_m", "lateral_m", "rec_min_m", "speed_at_rec")}
    return out


def main(argv: list[str] | None = None) -> int:
    def extra(ap):
        ap.add_argument("--pass-max-arrive-speed", type=float, default=None,
                        help="replace the statistics' pass_max_arrive_speed (m/s; inf: every flat kick past "
                             "a teammate in its lane counts as a pass; default: the statistics' own)")
        ap.add_argument("--format", choices=("plain", "ssl"), default="plain",
                        help="match format (ssl_marl.runners.match.format_options; default plain)")
        ap.add_argument("--restart-receive-margin", type=float, default=None, metavar="M",
                        help="the attacking plays' set-piece passes go to receive points at least M m inside "
                             "the field lines (ATTACK_RESTART_DECISION.receive_margin_m; default: the plays' own)")

    args = probe_args(__doc__.splitlines()[0], "61600-61601", "JSON output (summary and every pass)", argv, extra)
    from ssl_marl.plays import attack_play

    if args.restart_receive_margin is not None:  # read when the attacking plays are built
        attack_play.ATTACK_PASSING = dataclasses.replace(attack_play.ATTACK_PASSING, restart_decision=dataclasses.replace(
            attack_play.ATTACK_PASSING.restart_decision, receive_margin_m=args.restart_receive_margin))
    passes = [p for s in args.seeds
              for p in probe_match(args.blue, args.yellow, args.seconds, s, args.pass_max_arrive_speed, args.format)]
    for p in passes:
        p["cause"] = None if p["outcome"] == "completed" else cause(p)
    from ssl_marl.plays.stats import StatsParams

    rule = StatsParams().pass_max_arrive_speed if args.pass_max_arrive_speed is None else args.pass_max_arrive_speed
    margin = attack_play.ATTACK_PASSING.restart_decision.receive_margin_m
    write_probe(args, {"summary": {**summarize(passes), "pass_max_arrive_speed": str(rule),
                                   "restart_receive_margin_m": margin}, "passes": passes})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
