"""Merge match-series JSON parts (``ssl-marl match --matches K --json PART``) into one series file.

A series can be played in parts (seeds S..S+k-1, S+k..., e.g. to extend a finished series or
to split it over machines); this writes the same record one
``ssl-marl match --matches N --json OUT`` would (``ssl_marl.runners.result.write_series_file``:
OUT with the summary, ``<stem>.matches.csv.gz`` with the matches in seed order,
``<stem>.manifest.json``), the summary recomputed by ``ssl_marl.runners.result.summarize``
and the manifest listing the parts' own manifests under ``"parts"``.

    python benchmarks/merge_match_series.py runs/parts/pl_vs_b_*.json --out results/series.json

Parts must share the match settings (teams, robots, field, seconds, realism); a duplicate
seed or a mismatch is an error.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import fields

SETTINGS = ("blue", "yellow", "robots", "field", "seconds", "realism", "realtime", "start_jitter_m")


def load_matches(paths: list[str]) -> list[dict]:
    matches: dict[int, dict] = {}
    ref = None
    from ssl_marl.runners.result import load_result

    for path in paths:
        data = load_result(path)
        for m in data["matches"] if "matches" in data else [data]:
            settings = {k: m["config"].get(k) for k in SETTINGS}
            if ref is None:
                ref = settings
            elif settings != ref:
                raise ValueError(f"{path}: match seed {m['seed']} has settings {settings}, expected {ref}")
            if m["seed"] in matches:
                raise ValueError(f"{path}: seed {m['seed']} appears twice")
            matches[m["seed"]] = m
    return [matches[s] for s in sorted(matches)]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("parts", nargs="+", help="series or single-match JSON files")
    ap.add_argument("--out", required=True, help="merged series JSON")
    args = ap.parse_args(argv)
    from ssl_marl.runners.provenance import build_manifest
    from ssl_marl.runners.result import MatchResult, load_manifest, summarize, write_series_file

    dicts = load_matches(args.parts)
    names = {f.name for f in fields(MatchResult)}
    results = [MatchResult(**{k: v for k, v in d.items() if k in names}) for d in dicts]
    summary = summarize(results)
    manifest = build_manifest(rules={"runner": "merge_match_series", **{k: dicts[0]["config"].get(k) for k in SETTINGS}},
                              seeds={"seeds": [d["seed"] for d in dicts]})
    manifest["parts"] = {p: load_manifest(p) for p in args.parts}
    write_series_file(args.out, summary, [r.to_dict() for r in results], manifest)
    print(f"{len(results)} matches (seeds {dicts[0]['seed']}-{dicts[-1]['seed']}) -> {args.out}: "
          f"W {summary['wins']} D {summary['draws']} L {summary['losses']}, "
          f"goals {summary['goals_for']}-{summary['goals_against']}")
    print(table_row(args.out, summary))
    return 0


def table_row(name: str, s: dict) -> str:
    """A markdown row of a series summary (docs/RESULTS.md's series tables come from
    ``python -m train.report``)."""
    n = max(s["matches"], 1)
    st = s["stats"]

    def side(team: str) -> str:
        t = st[team]
        pc = "-" if t["pass_completion"] is None else f"{100 * t['pass_completion']:.0f} %"
        return (f"{t['shots'] / n:.1f} / {t['passes_completed']}-{t['passes_attempted']} ({pc}) / "
                f"{t['passes_intercepted']}")

    return (f"| `{name}` | {s['blue']} | {s['yellow']} | {s['matches']} | {s['wins']}-{s['draws']}-{s['losses']} | "
            f"{s['goals_for']}-{s['goals_against']} | {(s['goals_for'] + s['goals_against']) / n:.2f} | "
            f"{s['goal_diff_mean']:+.2f} | {side('blue')} | {side('yellow')} |")


if __name__ == "__main__":
    sys.exit(main())
