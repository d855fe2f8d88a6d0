"""Markdown tables of docs/RESULTS.md built from match series, leagues and match probes
(``results/<name>.json`` series read with :func:`ssl_marl.runners.result.load_result`,
tuning records under ``results/tuning/``). Every function takes the results folder and
returns the table's lines; the skill, decision and training tables are
:mod:`train.tools.report_tables`.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from ssl_marl.runners.result import load_manifest, load_result
from train.tools.report_tables import Lines, _head, commit_label


def series(results: Path, names: Iterable[str]) -> Lines:
    """One row per match series (``results/<name>.json``)."""
    rows = _head("series", "blue", "yellow", "seeds", "matches", "W-D-L (blue)", "goals for-against", "goals/match",
                 "goal diff/match", "blue: shots/match / passes / intercepted",
                 "yellow: shots/match / passes / intercepted")
    for n in names:
        d = load_result(results / f"{n}.json")
        s, seeds = d["summary"], [m["seed"] for m in d["matches"]]
        k = max(s["matches"], 1)

        def side(team: str) -> str:
            t = s["stats"][team]
            pc = "-" if t["pass_completion"] is None else f"{100 * t['pass_completion']:.0f} %"
            return f"{t['shots'] / k:.1f} / {t['passes_completed']}-{t['passes_attempted']} ({pc}) / {t['passes_intercepted']}"
        rows.append(f"| `{n}` | {s['blue']} | {s['yellow']} | {min(seeds)}-{max(seeds)} | {s['matches']} | "
                    f"{s['wins']}-{s['draws']}-{s['losses']} | {s['goals_for']}-{s['goals_against']} | "
                    f"{(s['goals_for'] + s['goals_against']) / k:.2f} | {s['goal_diff_mean']:+.2f} | {side('blue')} | "
                    f"{side('yellow')} |")
    return rows


def _team_label(team: Any) -> str:
    """A series' team: its kind, and the skills a team file or ``--*-skill`` option ran
    hand-coded in a learned-skill team (``attack-learned, hand-coded pass``) or from an
    actor file (``attack-learned, go-to-ball actor-000740001.pt``)."""
    if not isinstance(team, dict):
        return str(team)
    skills = team.get("skills", {})
    swapped = [k.replace("_", "-") for k, v in skills.items() if v == "baseline"]
    files = [f"{k.replace('_', '-')} `{Path(v).name}`" for k, v in skills.items()
             if isinstance(v, str) and v.endswith(".pt")]
    return team["kind"] + (f", hand-coded {' + '.join(swapped)}" if swapped else "") + \
        "".join(f", {f}" for f in files)


def series_600(results: Path, names: Iterable[str]) -> Lines:
    """One row per series of long matches (``results/<name>.json``): W-D-L, win rate and
    goal difference per 600 s with their 95 % intervals
    (:func:`~ssl_marl.runners.statistics.series_statistics`), blue's shots, goals and
    passes by kind."""
    rows = _head("series", "blue vs yellow", "field, realism", "seeds", "matches", "W-D-L (blue)",
                 "win rate [95% CI]", "goals for-against (per match)", "goal diff per 600 s [95% CI]",
                 "blue shots direct / redirect / after chip", "blue goals direct / redirect / after chip / other",
                 "blue passes completed: flat / chip")
    for n in names:
        d = load_result(results / f"{n}.json")
        s, st = d["summary"], d["summary"]["statistics"]
        seeds = [m["seed"] for m in d["matches"]]
        cfg = d["matches"][0]["config"]
        b = s["stats"]["blue"]
        k = max(s["matches"], 1)
        lo, hi = st["goal_diff_per_600s_ci95"]
        wlo, whi = st["win_rate_ci95"]

        def frac(c: int, a: int) -> str:
            return f"{c} of {a}" + (f" ({100 * c / a:.0f} %)" if a else "")
        dec = cfg.get("decision") or {}
        label = {side: _team_label(s[side]) + (f", {Path(str(dec[side])).name} decision"
                                               if dec.get(side) not in (None, "handcoded") else "")
                 for side in ("blue", "yellow")}
        rows.append(f"| `{n}` | {label['blue']} vs {label['yellow']} | {cfg['field']}, {cfg['realism']} | "
                    f"{min(seeds)}-{max(seeds)} | {s['matches']} | {s['wins']}-{s['draws']}-{s['losses']} | "
                    f"{100 * st['win_rate']:.0f} % [{100 * wlo:.0f}, {100 * whi:.0f}] | "
                    f"{s['goals_for']}-{s['goals_against']} ({s['goals_for'] / k:.2f}-{s['goals_against'] / k:.2f}) | "
                    f"{st['goal_diff_per_600s']:+.2f} [{lo:+.2f}, {hi:+.2f}] | "
                    f"{b['shots_direct']} / {b['shots_redirect']} / {b['shots_after_chip_pass']} | "
                    f"{b['goals_direct']} / {b['goals_redirect']} / {b['goals_after_chip_pass']} / {b['goals_other']} | "
                    f"{frac(b['passes_flat_completed'], b['passes_flat_attempted'])} / "
                    f"{frac(b['passes_chip_completed'], b['passes_chip_attempted'])} |")
    return rows


def goal_rate(results: Path, names: Iterable[str]) -> Lines:
    """One row per match series (``results/<name>.json``): match length, seeds, in how many
    matches at least one goal fell, goals in all and per match (the README's first command's
    check: a goal on >= 70 % of 20 seeds)."""
    rows = _head("series", "blue vs yellow", "match (s)", "seeds", "matches", "matches with a goal",
                 "goals (per match)")
    for n in names:
        d = load_result(results / f"{n}.json")
        s, ms = d["summary"], d["matches"]
        seeds = [m["seed"] for m in ms]
        scored = sum(1 for m in ms if m["goals"])
        goals = sum(len(m["goals"]) for m in ms)
        k = max(len(ms), 1)
        rows.append(f"| `{n}` | {_team_label(s['blue'])} vs {_team_label(s['yellow'])} | "
                    f"{ms[0]['config']['seconds']:.0f} | {min(seeds)}-{max(seeds)} | {len(ms)} | "
                    f"{scored} ({100 * scored / k:.0f} %) | {goals} ({goals / k:.2f}) |")
    return rows


def league(results: Path, name: str) -> Lines:
    """The ratings table of a league folder (``results/<name>/league.json``), as
    :func:`ssl_marl.runners.league.ratings_markdown` writes it."""
    from ssl_marl.runners.league import ratings_markdown

    text = ratings_markdown(json.loads((results / name / "league.json").read_text()))
    return [ln for ln in text.splitlines() if ln.startswith("|")]


def tuning(results: Path, entries: Iterable[tuple[str, str, str | None]]) -> Lines:
    """Tuning match sets (``results/tuning/*.json``): (label, file, key inside it or None)."""
    rows = _head("variant", "opponent", "seeds", "matches", "W-D-L (blue)", "goals", "shots (blue / yellow)",
                 "passes completed / attempted (blue)", "no-progress restarts")
    for label, file, key in entries:
        d = json.loads((results / "tuning" / file).read_text())
        d = d[key] if key else d
        ms = d["matches"]
        w = sum(m["score"]["blue"] > m["score"]["yellow"] for m in ms)
        lo = sum(m["score"]["blue"] < m["score"]["yellow"] for m in ms)
        tot = lambda team, f: sum(m["stats"][team][f] for m in ms)  # noqa: E731
        restarts = sum(m["no_progress"] for m in ms) if all("no_progress" in m for m in ms) else "-"
        seeds = [m["seed"] for m in ms]
        rows.append(f"| {label} | {d['opponent']} | {min(seeds)}-{max(seeds)} | {len(ms)} | {w}-{len(ms) - w - lo}-{lo} | "
                    f"{tot('blue', 'goals')}-{tot('yellow', 'goals')} | {tot('blue', 'shots')} / {tot('yellow', 'shots')} | "
                    f"{tot('blue', 'passes_completed')} / {tot('blue', 'passes_attempted')} | {restarts} |")
    return rows


def _variant_records(results: Path, files: str | tuple[str, ...]) -> tuple[list[dict], list[dict], list[str]]:
    """The ``benchmarks/match_variants.py`` records ``files`` (under ``results/tuning/match_variants/``):
    (records, their matches pooled, their commits' labels)."""
    recs = [json.loads((results / "tuning" / "match_variants" / f).read_text())
            for f in ((files,) if isinstance(files, str) else files)]
    return recs, [m for d in recs for m in d["matches"]], sorted({commit_label(d["manifest"]["git"]) for d in recs})


def match_variants(results: Path, entries: Iterable[tuple[str, str | tuple[str, ...]]], fouls: bool = False) -> Lines:
    """Tuning matches under variants of the restarts and the carrier's keep rule
    (``benchmarks/match_variants.py``; ``results/tuning/match_variants/<file>``): (label, file
    or files whose matches are pooled); ``fouls``: a column of blue's fouls per match (those in
    the opponent's defense area / all; "-" where the records do not keep them)."""
    from ssl_marl.runners.statistics import series_statistics

    rows = _head("variant", "commit", "blue vs yellow", "seeds", "matches", "W-D-L (blue)", "goals for-against",
                 "goal diff per 600 s [95% CI]", "ball-outs per match", "blue shots per match",
                 "blue passes completed (the referee's count)",
                 *(("blue fouls per match: in the defense area / all",) if fouls else ()))
    for label, files in entries:
        recs, ms, commits = _variant_records(results, files)
        rules = recs[0]["manifest"]["rules"]
        st = series_statistics([m["score"]["blue"] for m in ms], [m["score"]["yellow"] for m in ms],
                               float(rules["seconds"]))
        lo, hi = st["goal_diff_per_600s_ci95"]
        outs = (f"{sum(m['referee'].get('ball_out', 0) for m in ms) / len(ms):.0f}"
                if all(m["referee"] for m in ms) else "-")
        passes = "-"
        if all("passes_attempted" in m["blue"] for m in ms):
            done, tried = (sum(m["blue"][k] for m in ms) for k in ("passes_completed", "passes_attempted"))
            passes = f"{done} of {tried} ({100 * done / max(tried, 1):.0f} %)"
        seeds = [m["seed"] for m in ms]
        cells = [label, ", ".join(commits), f"{rules['blue']} vs {rules['yellow']}", f"{min(seeds)}-{max(seeds)}",
                 str(len(ms)), f"{st['wins']}-{st['draws']}-{st['losses']}", f"{st['goals_for']}-{st['goals_against']}",
                 f"{st['goal_diff_per_600s']:+.2f} [{lo:+.2f}, {hi:+.2f}]", outs,
                 f"{sum(m['blue']['shots'] for m in ms) / len(ms):.1f}", passes]
        if fouls:
            kept = all("fouls" in m for m in ms)
            area = sum(m.get("fouls", {}).get("blue", {}).get("attacker_in_defense_area", 0) for m in ms)
            every = sum(sum(m.get("fouls", {}).get("blue", {}).values()) for m in ms)
            cells.append(f"{area / len(ms):.1f} / {every / len(ms):.1f}" if kept else "-")
        rows.append("| " + " | ".join(cells) + " |")
    return rows


def selfplay_variants(results: Path, entries: Iterable[tuple[str, str | tuple[str, ...]]]) -> Lines:
    """Self-play tuning matches under variants (``benchmarks/match_variants.py`` records that keep
    both teams' statistics; ``results/tuning/match_variants/<file>``): (label, file or files
    pooled); goals, shots (redirects) and passes completed are both teams' together."""
    rows = _head("variant (both teams)", "commit", "seeds", "matches", "goals", "shots (redirect)",
                 "passes completed (both teams, the referee's count)")
    for label, files in entries:
        _, ms, commits = _variant_records(results, files)
        if not all("yellow" in m for m in ms):
            raise ValueError(f"selfplay_variants: {label}: a record without yellow's statistics")

        def tot(key: str) -> int:
            return sum(m[side][key] for m in ms for side in ("blue", "yellow"))

        done, tried = tot("passes_completed"), tot("passes_attempted")
        seeds = [m["seed"] for m in ms]
        rows.append(f"| {label} | {', '.join(commits)} | {min(seeds)}-{max(seeds)} | {len(ms)} | {tot('goals')} | "
                    f"{tot('shots')} ({tot('shots_redirect')}) | {done} of {tried} ({100 * done / max(tried, 1):.1f} %) |")
    return rows


def _played_commits(manifest: dict) -> list[str]:
    """The commits a series was played with: its parts' (a merged series,
    ``benchmarks/merge_match_series.py``) or its own (7 characters)."""
    parts = manifest.get("parts")
    gits = [p.get("git", {}) for p in parts.values()] if isinstance(parts, dict) else [manifest.get("git", {})]
    return [g.get("commit", "?")[:7] for g in gits]


def both_colours(label: str, blue_series: str, yellow_series: str) -> tuple[str, tuple[tuple[str, str], ...]]:
    """A :func:`pooled_sides` row spec: one team, blue in ``blue_series`` and yellow in ``yellow_series``."""
    return label, ((blue_series, "blue"), (yellow_series, "yellow"))


def both_colours_rounds(label: str, names: list[str], first_seed: int,
                        seeds_per_round: int = 20) -> list[tuple[str, tuple[tuple[str, str], ...]]]:
    """:func:`pooled_sides` row specs of one team played in rounds: ``names`` alternate the
    team's blue and yellow series, each pair a round of ``seeds_per_round`` seeds from
    ``first_seed`` on (its row labelled with the seed range), then a row of all of them."""
    if len(names) % 2:
        raise ValueError(f"both_colours_rounds: names must pair blue and yellow series, got {len(names)}")
    rows = []
    for k in range(len(names) // 2):
        lo = first_seed + k * seeds_per_round
        rows.append(both_colours(f"{label}, seeds {lo}-{lo + seeds_per_round - 1}", names[2 * k], names[2 * k + 1]))
    rows.append((f"{label}, all", tuple((name, "blue" if i % 2 == 0 else "yellow") for i, name in enumerate(names))))
    return rows


def pooled_sides(results: Path, rows_spec: Iterable[tuple[str, tuple[tuple[str, str], ...]]]) -> Lines:
    """One row per (label, ((series name, side), ...)): the matches of the named series
    pooled from the named side's point of view ("blue" or "yellow"), so a team played on
    both colours is judged without a colour's advantage: W-D-L, win rate (Wilson) and goal
    difference per 600 s (t interval), :func:`~ssl_marl.runners.statistics.series_statistics`."""
    from ssl_marl.runners.statistics import series_statistics

    rows = _head("team (side)", "series", "matches", "W-D-L", "win rate [95% CI]", "goals for-against",
                 "goal diff per 600 s [95% CI]")
    for label, parts in rows_spec:
        gf, ga, secs = [], [], set()
        for name, side in parts:
            if side not in ("blue", "yellow"):
                raise ValueError(f"pooled_sides: side must be blue or yellow, got {side!r}")
            other = "yellow" if side == "blue" else "blue"
            for m in load_result(results / f"{name}.json")["matches"]:
                gf.append(m["score"][side])
                ga.append(m["score"][other])
                secs.add(float(m["config"]["seconds"]))
        if len(secs) != 1:
            raise ValueError(f"pooled_sides: {label} pools matches of different lengths {sorted(secs)}")
        st = series_statistics(gf, ga, secs.pop())
        wlo, whi = st["win_rate_ci95"]
        lo, hi = st["goal_diff_per_600s_ci95"]
        rows.append("| " + " | ".join([label, ", ".join(f"`{n}` ({s})" for n, s in parts), str(len(gf)),
                                       f"{st['wins']}-{st['draws']}-{st['losses']}",
                                       f"{100 * st['win_rate']:.0f} % [{100 * wlo:.0f}, {100 * whi:.0f}]",
                                       f"{st['goals_for']}-{st['goals_against']}",
                                       f"{st['goal_diff_per_600s']:+.2f} [{lo:+.2f}, {hi:+.2f}]"]) + " |")
    return rows


def colour_balance(results: Path, groups: Iterable[tuple[str, tuple[str, ...]]]) -> Lines:
    """Self-play series (the same team on both sides), pooled per group (label, series
    names under ``results/``): blue's goal and kick surplus over yellow per match with its
    95 % t interval (:func:`~ssl_marl.runners.statistics.t_interval`), and blue's share of
    the shots. With no colour bias both surpluses are 0."""
    from ssl_marl.runners.statistics import t_interval

    rows = _head("series", "commit", "team", "matches", "goals blue-yellow", "goal surplus of blue per match [95% CI]",
                 "kick surplus of blue per match [95% CI]", "blue's share of the shots")
    for label, names in groups:
        ds = [load_result(results / f"{n}.json") for n in names]
        ms = [m for d in ds for m in d["matches"]]
        teams = {(m["config"]["blue"], m["config"]["yellow"]) for m in ms}
        if len(teams) != 1 or len(next(iter(teams))) != 2 or len(set(next(iter(teams)))) != 1:
            raise ValueError(f"colour_balance: {label} is not self-play of one team: {sorted(teams)}")
        commits = sorted({c for n in names for c in _played_commits(load_manifest(results / f"{n}.json") or {})})
        goals = [m["score"]["blue"] - m["score"]["yellow"] for m in ms]
        kicks = [m["stats"]["blue"]["kicks"] - m["stats"]["yellow"]["kicks"] for m in ms]
        shots = [sum(m["stats"][c]["shots"] for m in ms) for c in ("blue", "yellow")]
        cells = [label, ", ".join(commits), next(iter(teams))[0], str(len(ms)),
                 f"{sum(m['score']['blue'] for m in ms)}-{sum(m['score']['yellow'] for m in ms)}"]
        for v in (goals, kicks):
            lo, hi = t_interval(v)
            cells.append(f"{sum(v) / len(v):+.2f} [{lo:+.2f}, {hi:+.2f}]")
        cells.append(f"{100 * shots[0] / max(sum(shots), 1):.0f} %")
        rows.append("| " + " | ".join(cells) + " |")
    return rows


def shot_outcomes(paths: Path | Iterable[Path]) -> Lines:
    """``benchmarks/shot_outcome_probe.py``'s summaries (one row per record): where the blue shots came from
    and how they ended."""
    rows = _head("match (blue vs yellow)", "seeds", "shots", "on target", "open < 0.05 rad", "from own half",
                 "from the scoring zone", "after the carrier's decision: shoot / dribble / pass / none",
                 "ended: goal / keeper / defender / teammate / out / stopped", "blue goals from no shot")
    for path in [paths] if isinstance(paths, Path) else paths:
        d = json.loads(path.read_text())
        s, seeds, rules = d["summary"], d["manifest"]["seeds"]["seeds"], d["manifest"]["rules"]
        o, dec = s["outcomes"], s["after_decision"]
        n = rules.get("robots", 6)  # records without robots / field / format: 6v6 Division B, plain format
        match = (f"{n}v{n} {rules.get('field', 'div_b')}, {rules.get('format', 'plain')} "
                 f"({rules['blue']} vs {rules['yellow']})")
        rows.append(f"| {match} | {min(seeds)}-{max(seeds)} | {s['shots']} | {s['on_target']} | {s['open_below_0_05rad']} | "
                    f"{s['from_own_half']} | {s['from_scoring_zone']} | "
                    f"{' / '.join(str(dec.get(k, 0)) for k in ('shoot', 'dribble', 'pass', 'none'))} | "
                    f"{' / '.join(str(o.get(k, 0)) for k in ('goal', 'keeper', 'defender', 'teammate', 'out', 'stopped'))} | "
                    f"{s['blue_goals_without_a_shot']} |")
    return rows


def foul_probe(results: Path, entries: Iterable[tuple[str, str]]) -> Lines:
    """``benchmarks/foul_probe.py``: (label, file under ``results/tuning/foul_probe/``): each team's
    fouls by kind, and who touched the ball in the opponent's defense area (role (its tactic's state):
    count)."""
    rows = _head("blue", "seeds", "team", "fouls per match", "in the defense area / dribbling / double touch / "
                 "too close", "in the defense area, by role (state)")
    kinds = ("attacker_in_defense_area", "excessive_dribbling", "double_touch", "defender_too_close")
    for label, name in entries:
        d = json.loads((results / "tuning" / "foul_probe" / name).read_text())
        s, seeds = d["summary"], d["manifest"]["seeds"]["seeds"]
        for team in ("blue", "yellow"):
            t = s[team]
            who = t["by_foul_and_role"].get("attacker_in_defense_area", {})
            rows.append(f"| {label} | {min(seeds)}-{max(seeds)} | {team} ({d['manifest']['rules'][team]}) | "
                        f"{t['fouls'] / s['matches']:.1f} | "
                        f"{' / '.join(str(t['by_foul'].get(k, 0)) for k in kinds)} | "
                        f"{', '.join(f'{k}: {v}' for k, v in sorted(who.items(), key=lambda kv: -kv[1]))} |")
    return rows


def wall_probe(path: Path) -> Lines:
    """``benchmarks/wall_probe.py``: what a goalie and 0-3 defenders on the ball-goal line leave
    open of the goal, over the scoring zone's ball positions."""
    d = json.loads(path.read_text())
    rows = _head("field", "defence", "ball positions", "best shot line's margin, median (s)",
                 "best line >= 0 s / >= 0.05 s / >= 0.1 s", "open goal angle, median (rad)", "open >= 0.05 rad")
    for r in d["rows"]:
        z = r["scoring_zone"]
        shares = " / ".join(f"{100 * z[f'share_margin_ge_{t}s']:.0f} %" for t in ("0", "0.05", "0.1"))
        rows.append(f"| {r['field']} | goalie + {r['defenders']} | {z['positions']} | {z['median_best_margin_s']:+.3f} | "
                    f"{shares} | {z['median_open_angle_rad']:.3f} | {100 * z['share_open_ge_0.05rad']:.0f} % |")
    return rows


def pass_losses(paths: Iterable[Path]) -> Lines:
    """``benchmarks/pass_loss_probe.py`` records: the passes the referee's statistics counted
    (under the record's ``pass_max_arrive_speed``), by the tactic the kicker ran and by how
    they ended, and the lost passes by cause."""
    rows = _head("seeds", "commit", "teams", "a flat pass reaches the teammate at most (m/s)", "kicker's tactic",
                 "passes counted", "completed / intercepted / lost", "lost: ball out / other",
                 "lost by cause: receiver touched / opponent touched / short / missed", "median kick speed (m/s)")
    for path in paths:
        rows += _pass_loss_rows(json.loads(path.read_text()))
    return rows


def _pass_loss_rows(d: dict) -> Lines:
    s, seeds = d["summary"], d["manifest"]["seeds"]["seeds"]
    teams = f"{d['manifest']['rules']['blue']} vs {d['manifest']['rules']['yellow']}"
    commit = commit_label(d["manifest"]["git"])
    rows = []
    by_tac: dict[str, list[dict]] = {}
    for p in d["passes"]:
        by_tac.setdefault(str(p.get("tactic")).split(":")[0], []).append(p)
    for tac, ps in sorted(by_tac.items(), key=lambda kv: -len(kv[1])):
        outcomes, _, lost_cells = _pass_outcome_cells(ps)
        rows.append(f"| {min(seeds)}-{max(seeds)} | {commit} | {teams} | {s['pass_max_arrive_speed']} | {tac} | {len(ps)} | "
                    f"{outcomes} | {lost_cells} | {float(np.median([p['speed'] for p in ps])):.2f} |")
    return rows


def _pass_outcome_cells(ps: list[dict]) -> tuple[str, str, str]:
    """Cells of a group of probed passes: "completed / intercepted / lost", the completion
    ("NN %"), and "ball out / other | receiver touched / opponent touched / short / missed" of the
    lost ones."""
    n = {o: sum(p["outcome"] == o for p in ps) for o in ("completed", "intercepted", "lost")}
    lost = [p for p in ps if p["outcome"] == "lost"]
    out = sum(p["why"] == "ball_out" for p in lost)
    causes = " / ".join(str(sum(p["cause"] == c for p in lost))
                        for c in ("receiver_touched", "opponent_touched", "short", "missed"))
    return (f"{n['completed']} / {n['intercepted']} / {n['lost']}", f"{100 * n['completed'] / max(len(ps), 1):.0f} %",
            f"{out} / {len(lost) - out} | {causes}")


def pass_losses_by_play(paths: Iterable[Path]) -> Lines:
    """``benchmarks/pass_loss_probe.py --format ssl`` records: each team's passes (the referee's
    statistics' count) in set pieces (the first kick of an awarded kickoff or free kick) and in
    open play, by how they ended, and the lost ones by cause."""
    rows = _head("seeds", "commit", "team", "passes", "passes counted", "completed / intercepted / lost",
                 "completion", "lost: ball out / other", "lost by cause: receiver touched / opponent touched / short / missed")
    for path in paths:
        d = json.loads(path.read_text())
        seeds, rules = d["manifest"]["seeds"]["seeds"], d["manifest"]["rules"]
        commit = commit_label(d["manifest"]["git"])
        margin = d["summary"].get("restart_receive_margin_m")  # the probe's --restart-receive-margin
        margin = f", set-piece passes {margin:g} m inside the lines" if margin is not None else ""
        for team in ("blue", "yellow"):
            for label, sp in (("set pieces", True), ("open play", False)):
                ps = [q for q in d["passes"] if q["team"] == team and bool(q.get("set_piece")) == sp]
                if not ps:
                    continue
                outcomes, completion, lost_cells = _pass_outcome_cells(ps)
                rows.append(f"| {min(seeds)}-{max(seeds)} | {commit} | {team} ({rules[team]}{margin}) | {label} | {len(ps)} | "
                            f"{outcomes} | {completion} | {lost_cells} |")
    return rows


def pass_options(results: Path, files: Iterable[str]) -> Lines:
    """``benchmarks/pass_option_probe.py`` records (``results/tuning/<file>``): the pass options
    the attacking carrier's decision rated and its choices."""
    rows = _head("receiver guard (m)", "seeds", "decisions", "flat passes rated: eligible (success >= 0.35)",
                 "passes into a redirect rated: eligible", "choices: shoot / dribble / pass / chip / redirect")
    for file in files:
        d = json.loads((results / "tuning" / file).read_text())
        s, seeds = d["summary"], d["manifest"]["seeds"]["seeds"]
        pct = lambda a, b: f"{s[a]} of {s[b]} ({100 * s[a] / max(s[b], 1):.1f} %)"  # noqa: E731
        rows.append(f"| {s['receiver_guard_m']:g} | {min(seeds)}-{max(seeds)} | {s['decisions']} | "
                    f"{pct('flat_options_eligible', 'flat_options')} | {pct('redirect_options_eligible', 'redirect_options')} | "
                    f"{' / '.join(str(s.get('choice_' + k, 0)) for k in ('shoot', 'dribble', 'pass', 'chip', 'redirect'))} |")
    return rows


def set_piece_series(results: Path, names: Iterable[str]) -> Lines:
    """One row per series of long matches under SSL game control (``results/<name>.json``):
    the code's commit (from the manifest), W-D-L, goals and goal difference per 600 s with
    its 95 % interval, and blue's set pieces (awarded; passes, chips among them, and shots
    as their first kick; goals of set-piece possessions; "-" where the code did not count
    them), shots and pass completion."""
    rows = _head("series", "code", "blue vs yellow", "seeds", "matches", "W-D-L (blue)", "goals for-against",
                 "goal diff per 600 s [95% CI]", "blue set pieces: awarded / passes (chips) / shots",
                 "blue goals from set pieces", "blue shots", "blue passes completed")
    for n in names:
        d, manifest, cells = _series_cells(results, n)
        commit = manifest["git"]["commit"][:7]
        b = d["summary"]["stats"]["blue"]
        counted = any("set_pieces" in m["stats"]["blue"] for m in d["matches"])
        sp = (f"{b['set_pieces']} / {b['set_piece_passes']} ({b['set_piece_chips']}) / {b['set_piece_shots']}"
              if counted else "-")
        rows.append(f"| `{n}` | {commit} | {cells} | {sp} | {b['goals_set_piece'] if counted else '-'} | {b['shots']} | "
                    f"{b['passes_completed']} of {b['passes_attempted']} |")
    return rows


def _series_cells(results: Path, n: str) -> tuple[dict, dict, str]:
    """A series record (``results/<n>.json``), its manifest and its row cells
    "blue vs yellow | seeds | matches | W-D-L | goals | goal diff per 600 s [95% CI]"."""
    d = load_result(results / f"{n}.json")
    s, st = d["summary"], d["summary"]["statistics"]
    manifest = load_manifest(results / f"{n}.json") or {}
    seeds = [m["seed"] for m in d["matches"]]
    lo, hi = st["goal_diff_per_600s_ci95"]
    cells = (f"{s['blue']} vs {s['yellow']} | {min(seeds)}-{max(seeds)} | {s['matches']} | "
             f"{s['wins']}-{s['draws']}-{s['losses']} | {s['goals_for']}-{s['goals_against']} | "
             f"{st['goal_diff_per_600s']:+.2f} [{lo:+.2f}, {hi:+.2f}]")
    return d, manifest, cells


def ssl_fouls_series(results: Path, rows_spec: Iterable[tuple[str, str]]) -> Lines:
    """One row per SSL-format series (label, name of ``results/<name>.json``): the code's
    commit, W-D-L, goals, goal difference per 600 s with its 95 % interval, blue's set pieces
    (awarded; shots and passes as their first kick) and the fouls the referee called on each
    side (the matches' ``stats.fouls``), per match."""
    names = ("defender_too_close", "double_touch", "excessive_dribbling", "attacker_in_defense_area")
    rows = _head("code (commit)", "series", "blue vs yellow", "seeds", "matches", "W-D-L (blue)", "goals for-against",
                 "goal diff per 600 s [95% CI]", "blue set pieces: awarded / passes / shots",
                 "fouls on blue per match: too close / double touch / dribbling / defense area",
                 "fouls on yellow per match: the same")
    for label, n in rows_spec:
        d, manifest, cells = _series_cells(results, n)
        commit = ", ".join(sorted(set(_played_commits(manifest))))
        b, k = d["summary"]["stats"]["blue"], len(d["matches"])
        fouls = {side: " / ".join(f"{sum(m['stats']['fouls'][side].get(f, 0) for m in d['matches']) / k:.1f}"
                                  for f in names) for side in ("blue", "yellow")}
        rows.append(f"| {label} ({commit}) | `{n}` | {cells} | "
                    f"{b['set_pieces']} / {b['set_piece_passes']} / {b['set_piece_shots']} | "
                    f"{fouls['blue']} | {fouls['yellow']} |")
    return rows


def set_piece_probe(results: Path, files: Iterable[str]) -> Lines:
    """``benchmarks/set_piece_probe.py`` records (``results/tuning/<file>``): per team, how
    its set pieces (free kicks and kickoffs; records of code that announced no kickoff count
    none) were taken (kicked; released by a bump; carried off in contact, a double touch by
    the rules; timed out)."""
    rows = _head("teams", "seeds", "commit", "team", "set pieces (kickoffs)", "kicked", "released",
                 "carried (double touch by the rules)", "timed out")
    for file in files:
        d = json.loads((results / "tuning" / file).read_text())
        s, man = d["summary"], d["manifest"]
        seeds = man["seeds"]["seeds"]
        rules = man["rules"]
        for team in ("blue", "yellow"):
            hows = ("kick", "released", "carried", "timeout")
            c = {how: s.get(f"{team}_free_kick_{how}", 0) + s.get(f"{team}_kickoff_{how}", 0) for how in hows}
            kickoffs = sum(s.get(f"{team}_kickoff_{how}", 0) for how in hows)
            n = sum(c.values())
            pct = lambda k: f"{c[k]} ({100 * c[k] / max(n, 1):.0f} %)"  # noqa: E731
            rows.append(f"| {rules['blue']} vs {rules['yellow']} | {min(seeds)}-{max(seeds)} | "
                        f"{man['git']['commit'][:7]} | {rules[team]} ({team}) | {n} ({kickoffs}) | {pct('kick')} | "
                        f"{pct('released')} | {pct('carried')} | {pct('timeout')} |")
    return rows


def _side_matches(results: Path, label: str, parts: Iterable[tuple[str, str]]) -> tuple[list[dict], list[str], float]:
    """The matches of ``parts`` ((series name, side), ...) with each side's stats and score
    turned to the named side's point of view ("own" / "opp"), their series' commits and
    the one match length (s) they share."""
    ms, commits, secs = [], set(), set()
    for name, side in parts:
        if side not in ("blue", "yellow"):
            raise ValueError(f"{label}: side must be blue or yellow, got {side!r}")
        other = "yellow" if side == "blue" else "blue"
        commits.update(_played_commits(load_manifest(results / f"{name}.json") or {}))
        for m in load_result(results / f"{name}.json")["matches"]:
            ms.append({"own": m["stats"][side], "opp": m["stats"][other], "gf": m["score"][side],
                       "ga": m["score"][other]})
            secs.add(float(m["config"]["seconds"]))
    if len(secs) != 1:
        raise ValueError(f"{label} pools matches of different lengths {sorted(secs)}")
    return ms, sorted(commits), secs.pop()


def pooled_attack(results: Path, rows_spec: Iterable[tuple[str, tuple[tuple[str, str], ...]]]) -> Lines:
    """The attacking-game targets from one team's side, pooled over series where it played
    blue and yellow (label, ((series name, side), ...)): W-D-L, win rate (Wilson), goals
    scored and conceded per match, goal difference per 600 s (t interval), the side's
    goals by kind and its passes completed by kind (the statistics module's counts)."""
    from ssl_marl.runners.statistics import series_statistics

    rows = _head("team (vs)", "series (side)", "commit", "matches", "W-D-L", "win rate [95% CI]",
                 "goals scored-conceded per match", "goal diff per 600 s [95% CI]",
                 "goals direct / redirect / after chip / other", "passes completed: flat / chip / all")
    for label, parts in rows_spec:
        parts = tuple(parts)
        ms, commits, secs = _side_matches(results, label, parts)
        st = series_statistics([m["gf"] for m in ms], [m["ga"] for m in ms], secs)
        wlo, whi = st["win_rate_ci95"]
        lo, hi = st["goal_diff_per_600s_ci95"]
        tot = lambda key: sum(m["own"][key] for m in ms)  # noqa: E731

        def frac(kind: str) -> str:
            c, a = tot(f"passes{kind}_completed"), tot(f"passes{kind}_attempted")
            return f"{c} of {a}" + (f" ({100 * c / a:.0f} %)" if a else "")
        k = len(ms)
        rows.append("| " + " | ".join([
            label, ", ".join(f"`{n}` ({s})" for n, s in parts), ", ".join(commits), str(k),
            f"{st['wins']}-{st['draws']}-{st['losses']}", f"{100 * st['win_rate']:.0f} % [{100 * wlo:.0f}, {100 * whi:.0f}]",
            f"{st['goals_for'] / k:.2f}-{st['goals_against'] / k:.2f} ({st['goals_for']}-{st['goals_against']})",
            f"{st['goal_diff_per_600s']:+.2f} [{lo:+.2f}, {hi:+.2f}]",
            " / ".join(str(tot(f"goals_{g}")) for g in ("direct", "redirect", "after_chip_pass", "other")),
            f"{frac('_flat')} / {frac('_chip')} / {frac('')}"]) + " |")
    return rows


def colour_mirror(results: Path, files: Iterable[str]) -> Lines:
    """``benchmarks/colour_mirror_check.py`` records (``results/tuning/<file>``): per team, the
    control step at which a scene and its colour-swapped mirror first part (a command or the
    world differs beyond the check's tolerances), and how far apart the worlds were then."""
    import statistics

    rows = _head("team (both sides)", "commit", "scenes", "first parting step: median (min-max)",
                 "world difference then (m): median (max)", "scenes that never parted (steps)")
    for file in files:
        d = json.loads((results / "tuning" / file).read_text())
        parted = [s for s in d["scenes"] if s["step"] is not None]
        steps = [s["step"] for s in parted]
        worlds = [s["world_diff_m"] for s in parted]
        n_steps = d["manifest"]["rules"]["steps"]
        rows.append("| " + " | ".join([
            d["team"] if d["opponent"] == d["team"] else f"{d['team']} vs {d['opponent']}",
            commit_label(d["manifest"]["git"]), str(len(d["scenes"])),
            f"{statistics.median(steps):.0f} ({min(steps)}-{max(steps)})" if steps else "-",
            f"{statistics.median(worlds):.1e} ({max(worlds):.1e})" if worlds else "-",
            f"{len(d['scenes']) - len(parted)} ({n_steps})"]) + " |")
    return rows


def paired_series(results: Path, rows_spec: Iterable[tuple[str, str, str]]) -> Lines:
    """Two match series on the same seeds, paired match by match: (label, series A, series B) with
    blue the team compared; the mean difference A - B per match of blue's goals and of the goal
    difference, with its 95 % interval (:func:`ssl_marl.runners.statistics.t_interval`, as every series)."""
    from ssl_marl.runners.statistics import series_statistics, t_interval

    rows = _head("comparison (A vs B)", "seeds", "matches", "A: W-D-L, goals", "B: W-D-L, goals",
                 "blue goals per match A - B [95% CI]", "goal diff per match A - B [95% CI]")

    def goals(ms: list[dict]) -> tuple[list[int], list[int]]:
        return [m["score"]["blue"] for m in ms], [m["score"]["yellow"] for m in ms]

    def wdl(ms: list[dict]) -> str:
        s = series_statistics(*goals(ms))
        return f"{s['wins']}-{s['draws']}-{s['losses']}, {s['goals_for']}-{s['goals_against']}"

    def diff(values: list[float]) -> str:
        lo, hi = t_interval(values)
        return f"{sum(values) / len(values):+.2f} [{lo:+.2f}, {hi:+.2f}]"

    for label, a_name, b_name in rows_spec:
        a = {m["seed"]: m for m in load_result(results / f"{a_name}.json")["matches"]}
        b = {m["seed"]: m for m in load_result(results / f"{b_name}.json")["matches"]}
        seeds = sorted(set(a) & set(b))
        if not seeds or len(seeds) != len(a) or len(seeds) != len(b):
            raise ValueError(f"paired_series: {a_name} and {b_name} are not played on the same seeds")
        (fa, aa), (fb, ab) = goals([a[s] for s in seeds]), goals([b[s] for s in seeds])
        rows.append(f"| {label} | {seeds[0]}-{seeds[-1]} | {len(seeds)} | {wdl([a[s] for s in seeds])} | "
                    f"{wdl([b[s] for s in seeds])} | {diff([x - y for x, y in zip(fa, fb)])} | "
                    f"{diff([(x - u) - (y - v) for x, u, y, v in zip(fa, aa, fb, ab)])} |")
    return rows
