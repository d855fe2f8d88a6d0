"""Markdown tables of docs/RESULTS.md, each built from result records under ``results/``.

Every function takes the results folder and returns the table's lines. Records are read
with :func:`ssl_marl.runners.result.load_result` (summary ``results.json`` with its
per-episode rows), training logs with :mod:`train.compare`.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any, Iterable

from ssl_marl.runners.statistics import wilson_interval
from ssl_marl.runners.result import load_result
from train.tools.compare import markdown, summarize

Lines = list[str]


def _head(*columns: str) -> Lines:
    return ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]


def commit_label(git: dict) -> str:
    """A manifest's ``git`` record as a table cell: the short commit, "+" when the tree had
    uncommitted changes."""
    return git["commit"][:7] + ("+" if git.get("dirty") else "")


def _summary(results: Path, name: str) -> dict[str, Any]:
    """``results/<name>/results.json`` without its rows (fast)."""
    return json.loads((results / name / "results.json").read_text())


def _rate(rate: float, ci: list[float]) -> str:
    return f"{rate:.3f} [{ci[0]:.3f}, {ci[1]:.3f}]"


def _time(t: dict | None) -> str:
    return "-" if not t or t.get("mean") is None else f"{t['mean']:.2f} +/- {t['std']:.2f}"


def _counts(d: dict | None) -> str:
    items = [(k, v) for k, v in (d or {}).items() if v]
    return ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in items) or "-"


def _tracker(cfg: dict) -> str:
    return "on" if cfg.get("tracker") else "off"


# ------------------------------------------------------------------ skills and tactics
def skills(results: Path, names: Iterable[str]) -> Lines:
    """One row per ``ssl-marl eval-skill`` record."""
    rows = _head("run", "skill", "policy", "field", "realism", "tracker", "episodes", "success [95% CI]",
                 "time to success (s)", "failures", "paper")
    for n in names:
        r = _summary(results, n)
        c = r["config"]
        paper = "-" if r.get("paper_success_rate") is None else f"{r['paper_success_rate']:g}"
        rows.append(f"| `{n}` | {r['skill']} | {r['policy']} | {c.get('field', 'div_b')} | {c.get('realism', 'none')} | "
                    f"{_tracker(c)} | {r['episodes']} | {_rate(r['success_rate'], r['success_ci95'])} | "
                    f"{_time(r['time_to_success_s'])} | {_counts(r['failure_reasons'])} | {paper} |")
    return rows


def tactics(results: Path, names: Iterable[str]) -> Lines:
    """One row per ``ssl-marl eval-tactic`` record (either tactic)."""
    rows = _head("run", "tactic", "skills", "field", "realism", "tracker", "episodes", "success [95% CI]",
                 "time to goal (s)", "failures", "kicks per episode", "go-to-ball stalls (episodes)")
    for n in names:
        r = _summary(results, n)
        c = r["config"]
        stalls = f"{r['go_to_ball_stalls']} ({r['episodes_with_stall']})" if "go_to_ball_stalls" in r else "-"
        rows.append(f"| `{n}` | {r.get('tactic', 'go-to-ball-and-shoot')} | {r['skills']} | {c['field']} | "
                    f"{c['realism']} | {_tracker(c)} | {r['episodes']} | {_rate(r['success_rate'], r['success_ci95'])} | "
                    f"{_time(r['time_s'])} | {_counts(r['failures'])} | {r['kicks_mean']:.2f} | {stalls} |")
    return rows


def tracker_pairs(results: Path, pairs: Iterable[tuple[str, str, str]]) -> Lines:
    """Tracker on / off on the same episodes, and the same first episodes of the no-noise
    record: (label, folder stem under ``tracker_eval/``, no-noise record)."""
    rows = _head("run", "episodes", "tracker on: success [95% CI]", "time (s)", "failures",
                 "tracker off: success [95% CI]", "time (s)", "failures", "no noise, same episodes")
    for label, stem, plain in pairs:
        on, off = (_summary(results, f"tracker_eval/{stem}_{s}") for s in ("on", "off"))
        key = "time_to_success_s" if "skill" in on else "time_s"
        fail = "failure_reasons" if "skill" in on else "failures"
        n = on["episodes"]
        first = load_result(results / plain)["episodes_detail"][:n]
        k = sum(bool(e["success"]) for e in first)
        rows.append(f"| {label} | {n} | {_rate(on['success_rate'], on['success_ci95'])} | {_time(on[key])} | "
                    f"{_counts(on[fail])} | {_rate(off['success_rate'], off['success_ci95'])} | {_time(off[key])} | "
                    f"{_counts(off[fail])} | {_rate(k / n, list(wilson_interval(k, n)))} |")
    return rows


def tracker_errors(results: Path) -> Lines:
    """RMS errors of raw vision and the tracker against the truth (``tracker_errors.json``)."""
    d = json.loads((results / "tracker_errors.json").read_text())
    kinds = ("raw_target", "tracker_target", "raw_capture", "tracker_capture")
    rows = _head("scenario", "object", "samples", "raw at contact", "tracker at contact", "raw at capture",
                 "tracker at capture")
    for scen, s in d["scenarios"].items():
        for obj, e in s["errors"].items():
            def cell(kind: str) -> str:
                v = e[kind]
                parts = [f"{v['pos_m_rms']:.4f}", f"{v['vel_mps_rms']:.3f}"]
                if "heading_rad_rms" in v:
                    parts.append(f"{v['heading_rad_rms']:.4f}")
                return " / ".join(parts)
            rows.append(f"| {scen} | {obj.replace('_', ' ')} | {e['raw_target']['samples']} | "
                        + " | ".join(cell(k) for k in kinds) + " |")
    for scen, s in d["scenarios"].items():
        a = s["dribbler_flag_agreement"]
        rows.append(f"| {scen} | ball-on-dribbler flag agreement | - | {100 * a['raw_target']:.1f} % | "
                    f"{100 * a['tracker_target']:.1f} % | - | - |")
    return rows


# ------------------------------------------------------------------ passing
def drills(results: Path, names: Iterable[str]) -> Lines:
    rows = _head("run", "pass", "receive", "realism", "runs x s", "passes completed / attempted",
                 "completion [95% CI]", "passes per minute", "losses")
    for n in names:
        r = _summary(results, n)
        rows.append(f"| `{n}` | {r['policy']} | {r.get('receive_policy', r['policy'])} | {r['realism']} | {r['runs']} x {r['duration_s']:g} | "
                    f"{r['completed']} / {r['attempts']} | {_rate(r['completion_rate'], r['completion_ci95'])} | "
                    f"{r['passes_per_minute']:.1f} | {_counts(r['losses'])} |")
    return rows


# ------------------------------------------------------------------ decision tasks
def keepaway(results: Path, entries: Iterable[tuple[str, str]]) -> Lines:
    rows = _head("keepers", "run", "episodes", "mean duration (s) [95 % t-interval]", "median", "p95", "max",
                 "outcomes", "passes completed / kicked", "decisions (hold / pass_to_1 / pass_to_2)")
    for label, n in entries:
        r = _summary(results, n)
        lo, hi = r["mean_duration_ci95"]
        t, o = r["duration_s"], r["options"]
        kicked = r.get("passes_kicked", 0)
        passes = f"{r.get('passes_completed', 0)} / {kicked}" + (
            f" ({100 * r['passes_completed'] / kicked:.0f} %)" if kicked else "")
        rows.append(f"| {label} | `{n}` | {r['episodes']} | {r['mean_duration_s']:.2f} [{lo:.2f}, {hi:.2f}] | "
                    f"{t['median']:.2f} | {t['p95']:.2f} | {t['max']:.1f} | {_counts(r['outcomes'])} | {passes} | "
                    f"{o.get('hold', 0)} / {o.get('pass_to_1', 0)} / {o.get('pass_to_2', 0)} |")
    return rows


def attack(results: Path, entries: Iterable[tuple[str, str]]) -> Lines:
    """Attack 3v2 records; rows after the first are paired with it episode by episode."""
    rows = _head("policy", "run", "episodes", "goal rate [95 % Wilson]", "paired vs the first row (points, 95 %)",
                 "outcomes", "options chosen")
    first: list[dict] | None = None
    for label, n in entries:
        r = load_result(results / n)
        goals = [float(bool(e["goal"])) for e in r["episodes_detail"]]
        if first is None:
            first, paired = goals, "-"
        else:
            m, h = paired_difference(goals, first[:len(goals)])
            paired = f"{100 * m:+.1f} +- {100 * h:.1f}"
        o = r["options"]
        total = max(sum(o.values()), 1)
        opts = ", ".join(f"{k} {100 * v / total:.0f} %" for k, v in sorted(o.items(), key=lambda kv: -kv[1]) if v)
        rows.append(f"| {label} | `{n}` | {r['episodes']} | {_rate(r['goal_rate'], r['goal_rate_ci95'])} | {paired} | "
                    f"{_counts(r['outcomes'])} | {opts} |")
    return rows


def probe_rows(path: Path, key: str) -> Lines:
    """A probe's rows (``{"rows": [{key, episodes, goal_rate, outcomes}, ...]}``): goal rate
    with its 95 % Wilson interval and the outcomes, one line per row."""
    d = json.loads(path.read_text())
    rows = _head(key, "episodes", "goal rate [95 % Wilson]", "outcomes")
    for r in d["rows"]:
        n = r["episodes"]
        lo, hi = wilson_interval(round(r["goal_rate"] * n), n)
        rows.append(f"| `{r[key]}` | {n} | {_rate(r['goal_rate'], [lo, hi])} | {_counts(r['outcomes'])} |")
    return rows


def drill_ends(entries: Iterable[tuple[str, Path]]) -> Lines:
    """``benchmarks/drill_end_probe.py`` records: outcomes, who won the lost balls, the carrier's
    last option before a ball lost to a defender, median times (s)."""
    rows = _head("policy", "episodes", "outcomes", "ball lost to a defender: the defence's role",
                 "the carrier's last option before it (none: no decision yet)", "median end (s): lost / out / goal")
    for label, path in entries:
        s = json.loads(path.read_text())["summary"]
        last = {("none" if k == "null" else k): v for k, v in s["last_option_before"]["lost_defender"].items()}
        roles = {"+".join("presser" if x == "attacker" else x for x in k.split("+")): v
                 for k, v in s["lost_defender_by_role"].items()}
        med = " / ".join(f"{s['median_t_s'][o]:.2f}" if o in s["median_t_s"] else "-" for o in ("lost_defender", "out", "goal"))
        rows.append(f"| {label} | {s['episodes']} | {_counts(s['outcomes'])} | {_counts(roles)} | {_counts(last)} | {med} |")
    return rows


def departure_scores(path: Path, names: dict[str, str] | None = None) -> Lines:
    """``python -m train.mappo_rollout_pi score`` rows: the departure rule's goal rate, the
    benchmark's and the best option's on the same labelled episodes, the paired difference
    (points, 95 %) and how often it departs. ``names``: display names of the value actor files."""
    d = json.loads(path.read_text())
    rows = _head("value actor(s)", "margin", "episodes", "goal rate", "benchmark", "paired (points, 95 %)",
                 "departures", "best option (oracle)")
    for r in d["rows"]:
        who = " + ".join((names or {}).get(Path(a).name, Path(a).name) for a in r["actors"])
        lo, hi = r["paired_diff_ci95"]
        rows.append(f"| {who} | {r['margin']:g} ({r['units']}) | {r['episodes']} | {r['goal_rate']:.3f} | "
                    f"{r['benchmark_goal_rate']:.3f} | {100 * r['paired_diff']:+.1f} [{100 * lo:+.1f}, {100 * hi:+.1f}] | "
                    f"{r['deviations']} | {r['oracle_goal_rate']:.3f} |")
    return rows


def decision_tasks(results: Path, pattern: str) -> Lines:
    """Every ``ssl-marl eval-task`` record whose folder matches ``pattern`` (a glob under
    ``results``); one line saying so when there is none."""
    found = sorted(p.parent.name for p in results.glob(f"{pattern}/results.json")
                   if "task" in json.loads(p.read_text()))
    if not found:
        return [f"No records match `results/{pattern}/` yet."]
    rows = _head("run", "task", "policy", "realism", "field", "episodes", "score [95% CI]", "outcomes")
    for n in found:
        r = _summary(results, n)
        if "goal_rate" in r:
            score = _rate(r["goal_rate"], r["goal_rate_ci95"])
        else:
            lo, hi = r["mean_duration_ci95"]
            score = f"{r['mean_duration_s']:.2f} s [{lo:.2f}, {hi:.2f}]"
        c = r["config"]
        rows.append(f"| `{n}` | {r['task']} | {r['policy']} | {c.get('realism', 'none')} | {c.get('field', 'div_b')} | "
                    f"{r['episodes']} | {score} | {_counts(r['outcomes'])} |")
    return rows


def paired_difference(a: list[float], b: list[float]) -> tuple[float, float]:
    """Mean of a - b over paired episodes and its 95 % half-width (normal approximation)."""
    d = [x - y for x, y in zip(a, b)]
    m = sum(d) / len(d)
    sd = math.sqrt(sum((x - m) ** 2 for x in d) / (len(d) - 1))
    return m, 1.959964 * sd / math.sqrt(len(d))


def _csv(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def mappo_runs(results: Path, entries: Iterable[tuple[str, str]], baseline: str | None,
               score: str) -> Lines:
    """MAPPO training runs (``results/training/<run>``: progress.csv, val.csv) with the
    evaluation record of each run's exported actor ("" for none), paired against
    ``baseline`` (a record of the same task and seeds) when given."""
    base = load_result(results / baseline)["episodes_detail"] if baseline else None
    rows = _head("run", "decisions", "agent-steps", "episodes", "loop wall time (min)", "decisions / s",
                 "best validation (decisions)", "evaluation [95 % CI] (episodes)", "paired vs hand-coded")
    for run, evaluation in entries:
        prog, val = _csv(results / "training" / run / "progress.csv"), _csv(results / "training" / run / "val.csv")
        last = prog[-1]
        best = max(val, key=lambda v: float(v["val_score"]))
        ev, paired = "-", "-"
        if evaluation:
            r = load_result(results / evaluation)
            if score == "duration":
                lo, hi = r["mean_duration_ci95"]
                ev = f"{r['mean_duration_s']:.2f} s [{lo:.2f}, {hi:.2f}] ({r['episodes']})"
                key = "duration_s"
            else:
                ev = f"{_rate(r['goal_rate'], r['goal_rate_ci95'])} ({r['episodes']})"
                key = "goal"
            if base is not None:
                n = r["episodes"]
                m, h = paired_difference([float(e[key]) for e in r["episodes_detail"]],
                                         [float(e[key]) for e in base[:n]])
                paired = f"{m:+.2f} +- {h:.2f}" if score == "duration" else f"{100 * m:+.1f} +- {100 * h:.1f} points"
        rows.append(f"| `{run}` | {int(last['decisions']):,} | {int(last['agent_steps']):,} | {int(last['episodes']):,} | "
                    f"{float(last['wall_time']) / 60:.1f} | {int(last['decisions']) / float(last['wall_time']):.1f} | "
                    f"{float(best['val_score']):.2f} ({int(best['decisions']):,}) | {ev} | {paired} |")
    return rows


def pass_and_score(results: Path) -> Lines:
    rows = _head("policy", "episodes", "success (goal after a pass) [95% CI]", "pass completed", "outcomes")
    folder = results / "training" / "mappo_pass_and_score_s0"
    for f in sorted(folder.glob("eval_*.json")):
        d = json.loads(f.read_text())
        rows.append(f"| {d['policy']} | {d['episodes']} | {_rate(d['mean_score'], d['ci95'])} | "
                    f"{100 * d['pass_rate']:.0f} % | {_counts(d['outcomes'])} |")
    return rows


# ------------------------------------------------------------------ training
def selection(results: Path, runs: Iterable[str]) -> Lines:
    rows = _head("run", "validation seed x episodes", "success per checkpoint (samples: rate)", "chosen")
    for run in runs:
        s = json.loads((results / "training" / run / "selection.json").read_text())
        cands = ", ".join(f"{c['samples'] // 1000}k: {c['success_rate']:.3f}"
                          for c in sorted(s["candidates"], key=lambda c: c["samples"]))
        rows.append(f"| `{run}` | {s['validation_seed']} x {s['episodes']} | {cands} | {s['best']['samples'] // 1000}k |")
    return rows


def selection_by_field(results: Path, run: str) -> Lines:
    """Per-checkpoint validation on each field of a run selected on several fields."""
    s = json.loads((results / "training" / run / "selection.json").read_text())
    cands = sorted(s["candidates"], key=lambda c: c["samples"])
    fields = sorted(cands[0]["by_field"])
    rows = _head("checkpoint", *(f"{c['samples'] // 1000}k" for c in cands))
    for f in fields:
        rows.append(f"| {f} ({s['validation_seed']} x {s['episodes']}) | "
                    + " | ".join(f"{c['by_field'][f]['success_rate']:.3f}" for c in cands) + " |")
    rows.append("| chosen | " + " | ".join("**yes**" if c["samples"] == s["best"]["samples"] else ""
                                            for c in cands) + " |")
    return rows


def training_compare(results: Path, runs: Iterable[str], window: int, upto: int | None,
                     target: float = 0.99) -> Lines:
    """:mod:`train.compare`'s tables for runs under ``results/training``."""
    return markdown([summarize(results / "training" / r, window, upto, target) for r in runs], target).splitlines()


# ------------------------------------------------------------------ go-to-ball, rolling ball
#: the probe's named policies as the rolling-ball tables print them (the records ran before the
#: ball-velocity actor was shipped, so their "learned" is the paper-state actor)
ROLLING_LABELS = {"baseline": "hand-coded", "learned": "paper state (`go_to_ball/v1`)"}


def _rolling_rows(path: Path) -> dict[str, dict[str, Any]]:
    return {r["policy"]: r for r in json.loads(path.read_text())["rows"]}


def _penalised_time(row: dict[str, Any], limit_s: float) -> float:
    """Mean time to the ball with failures counted at the episode limit (s)."""
    rate = row["success_rate"]
    return rate * (row["mean_time_s"] or 0.0) + (1.0 - rate) * limit_s


def rolling_probe(results: Path, names: Iterable[str], actor_labels: dict[str, str]) -> Lines:
    """One row per (record, policy) of ``benchmarks/go_to_ball_rolling_probe.py`` (records
    under ``results/``); the named policies as :data:`ROLLING_LABELS` print them, actor
    files as ``actor_labels`` does."""
    labels = {**ROLLING_LABELS, **actor_labels}
    rows = _head("record", "field", "realism", "policy", "episodes", "success [95% CI]", "mean time to the ball (s)")
    for name in names:
        d = json.loads((results / name).read_text())
        for r in d["rows"]:
            lo, hi = wilson_interval(r["success"], r["episodes"])
            rows.append(f"| `{name}` | {d['field']} | {d['realism']} | {labels[r['policy']]} | {r['episodes']} | "
                        f"{_rate(r['success_rate'], [lo, hi])} | {r['mean_time_s']:.2f} |")
    return rows


def rolling_selection(results: Path, by_field: dict[str, list[str]]) -> Lines:
    """Checkpoint validation on the rolling-ball probe, per field (records under
    ``results/``): success and mean time per field, and the mean over the fields of the
    time with failures counted at the limit (the lowest is chosen)."""
    fields = sorted(by_field)
    merged: dict[str, dict[str, dict[str, Any]]] = {}
    limit = 0.0
    for f in fields:
        for name in by_field[f]:
            d = json.loads((results / name).read_text())
            limit = d["max_time_s"]
            for policy, r in _rolling_rows(results / name).items():
                merged.setdefault(policy, {})[f] = r
    score = {p: sum(_penalised_time(v[f], limit) for f in fields) / len(fields)
             for p, v in merged.items() if len(v) == len(fields)}
    best = min((p for p in score if p.endswith(".pt")), key=score.get)
    rows = _head("policy", *(f"{f}: success, time (s)" for f in fields), "time, failures at the limit (s)", "chosen")
    for p, s in score.items():
        label = ROLLING_LABELS.get(p) or f"{int(Path(p).stem.split('-')[-1]) // 1000}k"
        cells = " | ".join(f"{merged[p][f]['success_rate']:.3f}, {merged[p][f]['mean_time_s']:.2f}" for f in fields)
        rows.append(f"| {label} | {cells} | {s:.3f} | {'**yes**' if p == best else ''} |")
    return rows


def rollout_values(paths: Iterable[Path], by: str) -> Lines:
    """``python -m train.mappo_rollout_pi summarize`` records: every option's mean rollout value
    (the episode's return after it, the benchmark everywhere else) and how many decisions offered
    it, by decision index (``by="decision"``) or by the option the benchmark chose (``"choice"``)."""
    key, first = ("by_decision", "decision") if by == "decision" else ("by_benchmark_option", "benchmark chose")
    rows = _head(first, "seeds", "collected at", "decisions",
                 "benchmark's value" if by == "decision" else "its value", "every legal option: mean value (decisions)")
    for path in paths:
        rows += _rollout_value_rows(json.loads(Path(path).read_text()), key, by)
    return rows


def _rollout_value_rows(d: dict, key: str, by: str) -> Lines:
    commits = sorted({c["commit"][:7] for c in d["chunks"]})
    rows = []
    for r in d[key]:
        opts = ", ".join(f"{n} {v:.2f} ({c})" for n, (c, v) in r["options"].items())
        label = r["decision"] if by == "decision" else r["option"]
        value = r["benchmark"] if by == "decision" else r["value"]
        rows.append(f"| {label} | {d['seeds'][0]}-{d['seeds'][1]} | {', '.join(commits)} | {r['decisions']} | "
                    f"{value:.3f} | {opts} |")
    return rows
