"""Behaviour-unchanged check for refactors: run the first episodes of every skill and
tactic evaluation and one match series with the code on ``PYTHONPATH``, and compare
them with the same runs of another checkout, episode by episode.

Usage::

    # 1. record with the old code (a clean export of the old commit):
    git archive OLD | tar -x -C /tmp/old
    PYTHONPATH=/tmp/old python benchmarks/compare_episodes.py record /tmp/before
    # 2. record with the new code and compare:
    PYTHONPATH=$PWD python benchmarks/compare_episodes.py record /tmp/after
    python benchmarks/compare_episodes.py compare /tmp/before /tmp/after

Recorded: the skill evaluations (go-to-ball, aim-to-shoot, pass, receive; hand-coded and
learned; without realism and realistic with the tracker off), the paper's tactic and
dribble-and-shoot, the decision tasks (keepaway, attack 3v2; hand-coded and learned, no
realism), the pass-endurance drill, and match series of STP, passing and learned-decision
teams. Compared: every field of every episode / run / match except wall-clock times. Exact equality (floats included).
Exit status 0 when all are identical.
"""

from __future__ import annotations

import csv
import gzip
import io
import json
import subprocess
import sys
from pathlib import Path

EPISODES = 50
RUNS = {  # name -> ssl-marl arguments (output path appended)
    **{f"{skill}-{policy}{'-realistic' if real else ''}":
       ["eval-skill", skill, "--policy", policy, "--episodes", str(EPISODES), "--seed", "10000", "--workers", "1"]
       + (["--realism", "realistic"] if real else []) + ["--quiet", "--out"]
       for skill in ("go-to-ball", "aim-to-shoot") for policy in ("baseline", "learned") for real in (False, True)},
    **{f"tactic-{skills}": ["eval-tactic", "--skills", skills, "--episodes", str(EPISODES), "--seed", "20000",
                            "--workers", "1", "--quiet", "--out"] for skills in ("baseline", "learned")},
    "tactic-learned-realistic": ["eval-tactic", "--skills", "learned", "--episodes", str(EPISODES), "--seed", "20000",
                                 "--workers", "1", "--realism", "realistic", "--quiet", "--out"],
    **{f"{skill}-{policy}{'-realistic' if real else ''}":
       ["eval-skill", skill, "--policy", policy, "--episodes", "30", "--seed", "10000", "--workers", "1"]
       + (["--realism", "realistic"] if real else []) + ["--quiet", "--out"]
       for skill in ("pass", "receive") for policy in ("baseline", "learned") for real in (False, True)},
    **{f"dribble-{skills}": ["eval-tactic", "--tactic", "dribble-and-shoot", "--skills", skills, "--episodes", "20",
                             "--seed", "20000", "--workers", "1", "--quiet", "--out"] for skills in ("baseline", "learned")},
    **{f"task-{task}-{policy}": ["eval-task", task, "--policy", policy, "--episodes", "30", "--workers", "1",
                                 "--quiet", "--out"]
       for task in ("keepaway", "attack-3v2") for policy in ("handcoded", "learned")},
    "drill-pass-endurance": ["eval-drill", "pass-endurance", "--policy", "learned", "--receive-policy", "learned",
                             "--runs", "2", "--duration", "30", "--seed", "10000", "--quiet", "--out"],
    "series-passing.json": ["match", "--blue", "passing-learned", "--yellow", "baseline", "--robots", "6",
                            "--seconds", "60", "--matches", "2", "--seed", "30000", "--workers", "1", "--quiet", "--json"],
    "series-decision.json": ["match", "--blue", "passing-learned-decision", "--yellow", "passing-baseline",
                             "--robots", "6", "--seconds", "60", "--matches", "2", "--seed", "30100", "--workers", "1",
                             "--quiet", "--json"],
    "series.json": ["match", "--matches", "2", "--seed", "30000", "--workers", "1", "--quiet", "--json"],
    "series90.json": ["match", "--blue", "learned", "--yellow", "baseline", "--robots", "6", "--seconds", "90",
                      "--matches", "2", "--seed", "30000", "--workers", "1", "--quiet", "--json"],
}
WALL = ("wall_time_s", "act_time_ms", "wall_time_s_total")


def _has_tracker_option() -> bool:
    """True when this checkout's CLI has ``--tracker``: realistic runs are then
    recorded with ``--tracker off``, the behaviour of checkouts without a tracker."""
    helptext = subprocess.run([sys.executable, "-m", "ssl_marl.cli", "eval-skill", "--help"], check=True,
                              capture_output=True, text=True).stdout
    return "--tracker" in helptext


def record(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    tracker_off = ["--tracker", "off"] if _has_tracker_option() else []
    for name, args in RUNS.items():
        if "realistic" in args:
            args = args[:-2] + tracker_off + args[-2:]  # before "--quiet", "--out"/"--json"
        cmd = [sys.executable, "-m", "ssl_marl.cli", *args, str(out / name)]
        print("+", " ".join(cmd[2:]), flush=True)
        subprocess.run(cmd, check=True)


def _strip(rows: list) -> list:
    return [{k: v for k, v in r.items() if k not in WALL} if isinstance(r, dict) else r for r in rows]


def _load(path: Path) -> list:
    """The per-episode (per-match, per-run) rows of one recorded run, wall-clock fields left out.

    Reads both record layouts: rows inside ``results.json`` (or the series file) under
    ``episodes_detail`` / ``runs_detail`` / ``matches``, or in the gzip CSV that its
    ``rows_file`` names (``ssl_marl.runners.result.write_result_folder``: every cell one JSON
    value, an empty cell a missing field). Read here without importing ``ssl_marl``, so that
    records of any two checkouts compare.
    """
    file = path / "results.json" if path.is_dir() else path
    data = json.loads(file.read_text())
    if "rows_file" in data:
        text = gzip.decompress((file.parent / data["rows_file"]).read_bytes()).decode()
        reader = csv.reader(io.StringIO(text))
        header = next(reader, [])
        return _strip([{c: json.loads(v) for c, v in zip(header, line) if v != ""} for line in reader])
    for key in ("episodes_detail", "runs_detail", "matches"):
        if key in data:
            return _strip(data[key])
    raise KeyError(f"{file}: no episodes_detail, runs_detail, matches or rows_file")


def compare(before: Path, after: Path) -> int:
    bad = 0
    for name in RUNS:
        if not (before / name).exists() or not (after / name).exists():
            bad += 1
            print(f"{name:36s} MISSING in {before if not (before / name).exists() else after}")
            continue
        a, b = _load(before / name), _load(after / name)
        same = a == b
        bad += not same
        diff = "" if same else next(f" (first difference: episode {i})" for i, (x, y) in
                                    enumerate(zip(a, b)) if x != y) if len(a) == len(b) else " (lengths differ)"
        print(f"{name:36s} {len(a):3d} episodes/matches  {'identical' if same else 'DIFFERENT' + diff}", flush=True)
    print("all identical" if not bad else f"{bad} run(s) differ")
    return 1 if bad else 0


def main(argv: list[str]) -> int:
    if len(argv) == 2 and argv[0] == "record":
        record(Path(argv[1]))
        return 0
    if len(argv) == 3 and argv[0] == "compare":
        return compare(Path(argv[1]), Path(argv[2]))
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
