"""Result records on disk (ssl_marl/runners/result.py, provenance.py): rows round-trip
exactly through the gzip CSV, manifests carry the provenance, and
benchmarks/compare_episodes.py finds a record identical in either layout."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

from ssl_marl.io import atomic_write_json
from ssl_marl.runners.provenance import UNRECORDED, build_manifest, git_state, sha256_file
from ssl_marl.runners.result import (decode_rows, encode_rows, load_manifest, load_result, write_result_folder,
                                     write_series_file)

ROOT = Path(__file__).resolve().parents[1]
ROWS = [
    {"episode": 0, "success": True, "time_s": 2.7333333333333285, "failure_reason": None, "return": -116.80335389958161},
    {"episode": 1, "success": False, "time_s": 0.1 + 0.2, "failure_reason": "timeout", "return": -0.0,
     "tiny": 5e-324, "text": 'a "quoted", comma\nand newline', "options": {"hold": 3, "pass": [1, 2.5]}},
    {"episode": 2, "success": False, "time_s": 1e300, "failure_reason": "1", "return": 7.0},
]


def _compare_module():
    spec = importlib.util.spec_from_file_location("compare_episodes", ROOT / "benchmarks" / "compare_episodes.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_rows_round_trip_exactly():
    back = decode_rows(encode_rows(ROWS))
    assert back == ROWS
    assert [type(v) for r in back for v in r.values()] == [type(v) for r in ROWS for v in r.values()]
    assert "tiny" not in back[0] and back[1]["failure_reason"] == "timeout" and back[2]["failure_reason"] == "1"
    assert encode_rows(ROWS) == encode_rows(ROWS)  # no date inside the gzip stream


def test_result_folder_splits_rows_and_loads_back(tmp_path):
    summary = {"skill": "go-to-ball", "episodes": 3, "success_rate": 1 / 3, "episodes_detail": ROWS}
    manifest = build_manifest(rules={"realism": "none"}, seeds={"seed": 10000, "episodes": 3}, argv=["x"])
    write_result_folder(tmp_path, summary, manifest)
    head = json.loads((tmp_path / "results.json").read_text())
    assert "episodes_detail" not in head and head["rows_file"] == "episodes.csv.gz"
    assert load_result(tmp_path) == summary
    assert load_manifest(tmp_path) == manifest


def test_series_file_loads_back(tmp_path):
    summary = {"matches": 2, "wins": 1}
    matches = [{"seed": 1, "score": {"blue": 1, "yellow": 0}, "stats": {"events": [{"t": 1.5, "kind": "shot"}]}},
               {"seed": 2, "score": {"blue": 0, "yellow": 0}, "stats": {}}]
    manifest = build_manifest(rules={"blue": "baseline"}, seeds={"seed": 1, "matches": 2}, argv=["x"])
    path = write_series_file(tmp_path / "s.json", summary, matches, manifest)
    assert (tmp_path / "s.matches.csv.gz").is_file() and (tmp_path / "s.manifest.json").is_file()
    assert load_result(path) == {"summary": summary, "matches": matches}
    assert load_manifest(path) == manifest


def test_manifest_records_provenance(tmp_path):
    actor = tmp_path / "actor.pt"
    actor.write_bytes(b"weights")
    m = build_manifest(rules={"realism": "realistic", "skills": {"pass": str(actor)}}, seeds={"seed": 5},
                       argv=["ssl-marl", "eval-skill"])
    assert m["command"] == ["ssl-marl", "eval-skill"] and m["seeds"] == {"seed": 5}
    assert m["actors"][str(actor)] == sha256_file(actor)
    assert any(k.startswith("ssl_marl/skills/pretrained/") for k in m["actors"])
    assert {"no_progress_s", "passing_snap_shot", "realism"} <= set(m["rules"])
    assert {"cpu", "cores", "os", "python", "torch", "numpy"} <= set(m["machine"])
    assert m["date"].endswith("+00:00")
    assert git_state(tmp_path) == {"commit": UNRECORDED, "dirty": UNRECORDED}


def test_git_state_of_a_copied_tree_takes_the_named_commit(tmp_path, monkeypatch):
    """A copied tree records the commit its sender names, marked as named, beside its own answer."""
    from ssl_marl.runners.provenance import COMMIT_ENV

    monkeypatch.delenv(COMMIT_ENV, raising=False)
    assert git_state(tmp_path) == {"commit": UNRECORDED, "dirty": UNRECORDED}
    monkeypatch.setenv(COMMIT_ENV, "ab" * 20)
    own = {"commit": UNRECORDED, "dirty": UNRECORDED}
    assert git_state(tmp_path) == {"commit": "ab" * 20, "dirty": UNRECORDED, "source": COMMIT_ENV, "checkout": own}
    here = git_state()  # this checkout (or no git): a name equal to its own commit changes nothing
    monkeypatch.setenv(COMMIT_ENV, str(here["commit"]))
    assert git_state() == here


def test_compare_episodes_reads_both_layouts(tmp_path):
    cmp = _compare_module()
    rows = [dict(r, wall_time_s=float(i)) for i, r in enumerate(ROWS)]
    summary = {"episodes": 3, "episodes_detail": rows}
    atomic_write_json(tmp_path / "old" / "results.json", summary)
    write_result_folder(tmp_path / "new", summary, {"format": 1})
    assert cmp._load(tmp_path / "old") == cmp._load(tmp_path / "new")
    assert all("wall_time_s" not in r for r in cmp._load(tmp_path / "new"))
    changed = [dict(r) for r in rows]
    changed[1]["time_s"] = 0.3  # 0.1 + 0.2 != 0.3: one ulp apart must differ
    write_result_folder(tmp_path / "changed", dict(summary, episodes_detail=changed), {"format": 1})
    assert cmp._load(tmp_path / "old") != cmp._load(tmp_path / "changed")
    matches = [{"seed": 3, "score": {"blue": 0, "yellow": 1}, "wall_time_s": 4.0}]
    atomic_write_json(tmp_path / "old.json", {"summary": {}, "matches": matches})
    write_series_file(tmp_path / "new.json", {}, matches, {"format": 1})
    assert cmp._load(tmp_path / "old.json") == cmp._load(tmp_path / "new.json") == [{"seed": 3, "score": {"blue": 0, "yellow": 1}}]


@pytest.mark.parametrize("name", ["go_to_ball_learned", "keepaway_handcoded", "pass_endurance_baseline"])
def test_committed_records_load(name):
    folder = ROOT / "results" / name
    data = load_result(folder)
    rows = data.get("episodes_detail", data.get("runs_detail"))
    assert rows and len(rows) == data.get("episodes", data.get("runs"))
    assert load_manifest(folder)["git"]["commit"] != UNRECORDED


def test_every_committed_series_file_finds_its_rows_and_manifest():
    files = sorted((ROOT / "results").glob("*.json"))
    series = [f for f in files if "rows_file" in json.loads(f.read_text())]
    assert series
    for f in series:
        data = load_result(f)
        assert len(data["matches"]) == data["summary"]["matches"], f.name
        assert load_manifest(f) is not None, f.name


def test_code_hash_changes_with_any_source_byte(tmp_path):
    """The package-source hash a league records per match: stable, and changed by one byte of
    any module or by a new module."""
    from ssl_marl.runners.provenance import code_hash

    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "sub" / "b.py").write_text("y = 2\n")
    first = code_hash.__wrapped__(pkg)
    assert code_hash.__wrapped__(pkg) == first and len(first) == 64
    (pkg / "sub" / "b.py").write_text("y = 3\n")
    second = code_hash.__wrapped__(pkg)
    (pkg / "c.py").write_text("")
    assert len({first, second, code_hash.__wrapped__(pkg)}) == 3
