"""Results tables from evaluation JSON files (never hand-typed numbers).

    python -m train.report [--results results] [--out docs/results_tables.md]

Reads every ``results/*/results.json`` written by ``ssl-marl eval-skill`` and
``ssl-marl eval-tactic`` (and ``results/match_*.json`` series from ``ssl-marl match --json``,
``results/training/*/selection.json`` from ``python -m train.select``)
and writes markdown tables, printing them too.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from ssl_marl.io import atomic_write_bytes


def _fmt_time(t: dict) -> str:
    if not t or t.get("mean") is None:
        return "n/a"
    return f"{t['mean']:.2f} +/- {t['std']:.2f}"


def skill_rows(results: Path) -> list[str]:
    rows = ["| run | skill | policy | realism | episodes | success [95% CI] | time to success (s) | failures | paper |",
            "|---|---|---|---|---|---|---|---|---|"]
    for f in sorted(results.glob("*/results.json")):
        r = json.loads(f.read_text())
        if "skill" not in r:
            continue
        lo, hi = r["success_ci95"]
        rows.append(f"| `{f.parent.name}` | {r['skill']} | {r['policy']} | {r['config'].get('realism', 'none')} | "
                    f"{r['episodes']} | {r['success_rate']:.3f} [{lo:.3f}, {hi:.3f}] | {_fmt_time(r['time_to_success_s'])} | "
                    f"{r['failure_reasons'] or '-'} | {r.get('paper_success_rate', '')} |")
    return rows


def tactic_rows(results: Path) -> list[str]:
    rows = ["| run | skills | realism | episodes | success [95% CI] | time to goal (s) | failures | paper |",
            "|---|---|---|---|---|---|---|---|"]
    for f in sorted(results.glob("*/results.json")):
        r = json.loads(f.read_text())
        if "protocol" not in r or "skills" not in r or r.get("tactic", "go-to-ball-and-shoot") != "go-to-ball-and-shoot":
            continue  # other tactics have their own table
        lo, hi = r["success_ci95"]
        rows.append(f"| `{f.parent.name}` | {r['skills']} | {r['config'].get('realism', 'none')} | {r['episodes']} | "
                    f"{r['success_rate']:.3f} [{lo:.3f}, {hi:.3f}] | {_fmt_time(r['time_s'])} | "
                    f"{r['failures']} | 0.755, 7.49 +/- 3.87 |")
    return rows


def dribble_rows(results: Path) -> list[str]:
    """Rows for the dribble-and-shoot runs (``results/tactic_dribble_*/results.json``)."""
    rows = ["| run | skills | realism | tracker | field | episodes | success [95% CI] | time to goal (s) | failures | "
            "go-to-ball stalls (episodes) | missed deadlines |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for f in sorted(results.glob("tactic_dribble_*/results.json")):
        r = json.loads(f.read_text())
        c = r["config"]
        lo, hi = r["success_ci95"]
        missed = r["missed_deadlines"] if c.get("realtime") else "-"
        rows.append(f"| `{f.parent.name}` | {r['skills']} | {c.get('realism', 'none')} | "
                    f"{'on' if c.get('tracker') else 'off'} | {c.get('field')} | {r['episodes']} | "
                    f"{r['success_rate']:.3f} [{lo:.3f}, {hi:.3f}] | {_fmt_time(r['time_s'])} | {r['failures']} | "
                    f"{r.get('go_to_ball_stalls', '-')} ({r.get('episodes_with_stall', '-')}) | {missed} |")
    return rows


def match_rows(results: Path) -> list[str]:
    rows = ["| series | blue | yellow | matches | W-D-L (blue) | goals for-against | shots/match (blue, yellow) | "
            "possession (blue, yellow) |", "|---|---|---|---|---|---|---|---|"]
    for f in sorted(results.glob("match_*.json")):
        s = json.loads(f.read_text())["summary"]
        rows.append(f"| `{f.stem}` | {s['blue']} | {s['yellow']} | {s['matches']} | {s['wins']}-{s['draws']}-{s['losses']} | "
                    f"{s['goals_for']}-{s['goals_against']} | {s['shots_blue_mean']:.1f}, {s['shots_yellow_mean']:.1f} | "
                    f"{100 * s['possession_blue_mean']:.0f}%, {100 * s['possession_yellow_mean']:.0f}% |")
    return rows


def selection_rows(results: Path) -> list[str]:
    """One row per ``results/training/<run>/selection.json`` written by ``python -m train.select``."""
    rows = ["| run | validation seed x episodes | success per checkpoint (samples: rate) | chosen |",
            "|---|---|---|---|"]
    for f in sorted(results.glob("training/*/selection.json")):
        s = json.loads(f.read_text())
        cands = ", ".join(f"{c['samples'] // 1000}k: {c['success_rate']:.3f}" for c in s["candidates"])
        rows.append(f"| `{f.parent.name}` | {s['validation_seed']} x {s['episodes']} | {cands} | "
                    f"{s['best']['samples'] // 1000}k |")
    return rows


def main(argv: list[str] | None = None) -> str:
    p = argparse.ArgumentParser(prog="python -m train.report", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--results", default="results", help="folder of evaluation outputs (default results)")
    p.add_argument("--out", default=None, help="also write the markdown to this file")
    a = p.parse_args(argv)
    res = Path(a.results)
    text = "\n".join(["### Skills (ssl-marl eval-skill)", "", *skill_rows(res), "",
                      "### Tactic (ssl-marl eval-tactic)", "", *tactic_rows(res), "",
                      "### Dribble-and-shoot (ssl-marl eval-tactic --tactic dribble-and-shoot)", "",
                      *dribble_rows(res), "",
                      "### Match series (ssl-marl match --matches K --json results/match_NAME.json)", "",
                      *match_rows(res), "",
                      "### Checkpoint selection (python -m train.select RUN)", "", *selection_rows(res), ""])
    print(text)
    if a.out:
        atomic_write_bytes(a.out, text.encode())
    return text
