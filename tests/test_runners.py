"""The runners layer: layering, the one pool (local and Ray), the video sink, the
control deadline, and per-skill sources (trained actors) for STP teams."""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import numpy as np
import pytest

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

from ssl_marl.envs.deadline import ControlDeadline  # noqa: E402
from ssl_marl.runners.controllers import load_team_file, parse_skill_source, team_skills  # noqa: E402
from ssl_marl.runners.pool import chunk_indices, run_pool  # noqa: E402
from ssl_marl.envs.animation import VideoSink  # noqa: E402
from ssl_marl.skills.registry import get_skill  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ layering
def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            out.add("." * node.level + (node.module or ""))
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
    return out


@pytest.mark.parametrize("package", ["physics", "envs", "skills", "plays"])
def test_lower_layers_import_nothing_from_runners(package):
    for path in sorted((ROOT / "ssl_marl" / package).glob("*.py")):
        bad = [m for m in _imports(path) if "runners" in m]
        assert not bad, f"{path.relative_to(ROOT)} imports {bad} (data flows physics -> ... -> plays -> runners)"


# ---------------------------------------------------------------------- pool
def _square(x: int) -> int:
    return x * x


def test_pool_returns_results_in_job_order_for_any_worker_count():
    jobs = list(range(7))
    assert run_pool(_square, jobs, 1, progress=False) == [j * j for j in jobs]
    assert run_pool(_square, jobs, 2, progress=False) == [j * j for j in jobs]


def test_pool_rejects_bad_backend_and_workers():
    with pytest.raises(ValueError, match="backend"):
        run_pool(_square, [1], 1, backend="dask", progress=False)
    with pytest.raises(ValueError, match="workers"):
        run_pool(_square, [1], 0, progress=False)
    with pytest.raises(ValueError, match="address"):
        run_pool(_square, [1], 1, address="127.0.0.1:6379", progress=False)


def test_chunks_cover_every_index_once():
    for n, w in ((1, 1), (7, 2), (1000, 2), (30, None)):
        chunks = chunk_indices(n, w)
        assert [i for c in chunks for i in c] == list(range(n))
        assert max(map(len, chunks)) <= 25


# ------------------------------------------------------------------ deadline
class FakeClock:
    def __init__(self) -> None:
        self.t = 100.0

    def __call__(self) -> float:
        return self.t

    def sleep(self, s: float) -> None:
        assert s >= 0
        self.t += s


def test_deadline_drops_late_commands_and_counts_them():
    clock = FakeClock()
    d = ControlDeadline(1 / 60, clock=clock, sleep=clock.sleep)

    def slow():
        clock.t += 0.02  # 20 ms > 16.7 ms
        return "new"

    def fast():
        clock.t += 0.005
        return "new"

    assert d.command(fast, "old")[0] == "new" and d.missed == 0
    cmd, elapsed = d.command(slow, "old")
    assert cmd == "old" and d.missed == 1 and elapsed == pytest.approx(0.02)


def test_deadline_tick_pacing_counts_missed_ticks():
    clock = FakeClock()
    d = ControlDeadline(0.01, clock=clock, sleep=clock.sleep)
    d.start()
    assert d.wait_for_tick() == 1 and clock.t == pytest.approx(100.01)  # slept to the tick
    clock.t += 0.025  # 2.5 periods late
    assert d.wait_for_tick() == 3 and d.missed == 2
    with pytest.raises(ValueError, match="period_s"):
        ControlDeadline(0.0)


# --------------------------------------------------------------------- video
def _frames(n: int, h: int = 24, w: int = 32) -> list[np.ndarray]:
    colours = np.array([[0, 120, 0], [255, 255, 255], [250, 120, 0], [0, 0, 255]], np.uint8)
    out = []
    for k in range(n):
        f = np.empty((h, w, 3), np.uint8)
        f[:] = colours[0]
        f[4:8, (2 * k) % (w - 4):(2 * k) % (w - 4) + 4] = colours[1 + k % 3]
        out.append(f)
    return out


def test_gif_sink_streams_frames_that_read_back_exactly(tmp_path):
    import imageio.v3 as iio

    frames = _frames(6)
    frames.insert(3, frames[2].copy())  # a repeated frame: stored once, shown twice as long
    path = tmp_path / "clip.gif"
    with VideoSink(path, fps=10) as sink:
        for f in frames:
            sink.add(f)
    back = iio.imread(path, index=None)
    expected = [f for i, f in enumerate(frames) if i != 3]
    assert back.shape[0] == len(expected)
    for got, want in zip(back, expected):
        np.testing.assert_array_equal(got[..., :3], want)
    meta = iio.immeta(path, index=2)
    assert meta["duration"] == pytest.approx(200, abs=10)  # frame 2 shown for two frame periods


def test_gif_sink_maps_later_frames_to_frame_0s_palette_or_their_own(tmp_path):
    import imageio.v3 as iio

    from ssl_marl.envs.animation import PALETTE_TOLERANCE

    rng = np.random.default_rng(0)
    first = rng.integers(0, 256, (40, 60, 3), dtype=np.uint8)  # ~2,400 colours: frame 0's palette is lossy
    second = first.copy()
    second[5:15, 5:25] = first[20:30, 30:50]  # only colours of frame 0
    third = second.copy()
    third[30:38, 40:58] = (255, 0, 255)  # a colour frame 0 hardly has
    path = tmp_path / "p.gif"
    with VideoSink(path, fps=10) as sink:
        for f in (first, second, third):
            sink.add(f)
    back = iio.imread(path, index=None)[..., :3].astype(int)
    assert back.shape[0] == 3
    for got, want in zip(back, (first, second, third)):
        assert np.abs(got - want).max() <= 2 * PALETTE_TOLERANCE
    np.testing.assert_array_equal(back[2][30:38, 40:58], np.broadcast_to([255, 0, 255], (8, 18, 3)))


def test_sink_publishes_atomically_and_rejects_bad_input(tmp_path):
    path = tmp_path / "v.gif"
    path.write_bytes(b"old")
    sink = VideoSink(path, fps=10)
    sink.add(_frames(1)[0])
    assert path.read_bytes() == b"old"  # nothing published before close
    sink.close(ok=False)
    assert path.read_bytes() == b"old" and not list(tmp_path.glob(".v.*"))
    with pytest.raises(ValueError, match="suffix"):
        VideoSink(tmp_path / "v.avi", fps=10)
    with pytest.raises(ValueError, match="fps"):
        VideoSink(path, fps=0)
    sink = VideoSink(path, fps=10)
    sink.add(_frames(1)[0])
    with pytest.raises(ValueError, match="shape"):
        sink.add(np.zeros((5, 5, 3), np.uint8))
    sink.close(ok=False)


def test_mp4_sink_pads_odd_sizes(tmp_path):
    pytest.importorskip("imageio_ffmpeg")
    import imageio.v3 as iio

    path = tmp_path / "v.mp4"
    with VideoSink(path, fps=10) as sink:
        for f in _frames(5, h=25, w=33):
            sink.add(f)
    assert iio.imread(path, index=None, plugin="FFMPEG").shape[1:3] == (26, 34)


# -------------------------------------------------------------- skill sources
def test_skill_sources_parse_and_merge(tmp_path):
    assert parse_skill_source("go-to-ball=runs/x/actor.pt") == ("go_to_ball", "runs/x/actor.pt")
    with pytest.raises(ValueError, match="SKILL=SOURCE"):
        parse_skill_source("go-to-ball")
    with pytest.raises(ValueError, match="unknown skill 'fly'"):
        parse_skill_source("fly=learned")
    ckpt = str(get_skill("go_to_ball").actor)
    assert team_skills("baseline", {"go-to-ball": ckpt}) == {"go_to_ball": ckpt, "aim_to_shoot": "baseline"}
    assert team_skills("learned", {}) == "learned"
    with pytest.raises(ValueError, match="STP team"):
        team_skills("random", {"go-to-ball": "learned"})
    with pytest.raises(FileNotFoundError, match="nope.pt"):
        team_skills("learned", {"go-to-ball": str(tmp_path / "nope.pt")})


def test_team_file_resolves_paths_against_its_folder(tmp_path):
    import shutil

    shutil.copy(get_skill("go_to_ball").actor, tmp_path / "gtb.pt")
    team = tmp_path / "team.json"
    team.write_text(json.dumps({"kind": "learned", "skills": {"go-to-ball": "gtb.pt", "aim-to-shoot": "baseline"}}))
    kind, sources, decision = load_team_file(team)
    assert kind == "learned" and sources == {"go-to-ball": str(tmp_path / "gtb.pt"), "aim-to-shoot": "baseline"}
    assert decision is None
    team.write_text(json.dumps({"kind": "learned", "colour": "blue"}))
    with pytest.raises(ValueError, match="unknown key"):
        load_team_file(team)
    with pytest.raises(FileNotFoundError, match="team file"):
        load_team_file(tmp_path / "missing.json")


def test_team_file_names_a_decision_actor_checked_before_any_match(tmp_path):
    import shutil

    from ssl_marl.decisions.learned import pretrained_path

    shutil.copy(pretrained_path("attack-drill"), tmp_path / "drill.pt")
    team = tmp_path / "team.json"
    team.write_text(json.dumps({"kind": "attack-learned", "decision": "drill.pt"}))
    assert load_team_file(team) == ("attack-learned", {}, str(tmp_path / "drill.pt"))
    team.write_text(json.dumps({"kind": "attack-baseline", "decision": "learned"}))
    assert load_team_file(team).decision == "learned"
    team.write_text(json.dumps({"kind": "baseline", "decision": "learned"}))
    with pytest.raises(ValueError, match="carrier decision"):  # the plain STP team has no carrier decision
        load_team_file(team)
    team.write_text(json.dumps({"kind": "attack-learned", "decision": 3}))
    with pytest.raises(ValueError, match="decision must be"):
        load_team_file(team)
    team.write_text(json.dumps({"kind": "attack-learned", "decision": "gone.pt"}))
    with pytest.raises(FileNotFoundError, match="gone.pt"):
        load_team_file(team)
    shutil.copy(pretrained_path("attack-3v2"), tmp_path / "3v2.pt")  # an Attack 3v2 actor offered to an attacking team
    team.write_text(json.dumps({"kind": "attack-learned", "decision": "3v2.pt"}))
    with pytest.raises(ValueError, match="obs_dim"):
        load_team_file(team)


def test_wrong_skill_checkpoint_fails_before_the_match_with_one_line(tmp_path, capsys):
    from ssl_marl.cli import main

    wrong = str(get_skill("aim_to_shoot").actor)
    rc = main(["match", "--blue", "learned", "--skill", f"go-to-ball={wrong}", "--seconds", "1", "--render", "none",
               "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "skill mismatch" in err and "go_to_ball" in err and len(err.splitlines()) == 1
    rc = main(["eval-tactic", "--skill", f"go-to-ball={tmp_path / 'missing.pt'}", "--episodes", "1", "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "missing.pt" in err and "does not exist" in err
    rc = main(["match", "--blue", "random", "--blue-skill", "go-to-ball=learned", "--render", "none", "--quiet"])
    assert rc == 2 and "STP team" in capsys.readouterr().err
    for argv in (["eval-skill", "go-to-ball"], ["eval-tactic"], ["match", "--matches", "2"]):
        assert main(argv + ["--address", "10.0.0.1:6379", "--quiet"]) == 2
        assert "ray" in capsys.readouterr().err


def test_a_checkpoint_source_plays_like_the_same_actor_shipped():
    from ssl_marl.runners.match import play_match
    from ssl_marl.runners.tactic_eval import evaluate_tactic

    ckpt = str(get_skill("go_to_ball").actor)
    a = evaluate_tactic("learned", episodes=2, seed=20_000, progress=False)
    b = evaluate_tactic({"go-to-ball": ckpt, "aim_to_shoot": "learned"}, episodes=2, seed=20_000, progress=False)
    assert a["episodes_detail"] == b["episodes_detail"]
    kw = dict(robots=2, seconds=2.0, seed=3, progress=False)
    m1 = play_match("learned", "baseline", **kw)
    m2 = play_match("learned", "baseline", blue_skills=team_skills("learned", {"go-to-ball": ckpt}), **kw)
    assert (m1.score, m1.shots, m1.possession, m1.steps) == (m2.score, m2.shots, m2.possession, m2.steps)
    assert m2.config["blue"] == {"kind": "learned", "skills": {"go_to_ball": ckpt, "aim_to_shoot": "learned"}}


# ----------------------------------------------------------------------- ray
def test_ray_backend_gives_the_local_results():  # ~15 s on 2 idle-ish cores (Ray start-up), ~100 s at load 25
    """Skill and tactic evaluations and a match series on a local Ray instance
    (started here, 2 CPUs) equal the local pool's results for the same seeds."""
    ray = pytest.importorskip("ray")
    from ssl_marl.runners.series import play_series
    from ssl_marl.runners.skill_eval import evaluate_skill
    from ssl_marl.runners.tactic_eval import evaluate_tactic

    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        kw = dict(episodes=6, seed=123, progress=False)
        t_ray = evaluate_tactic("baseline", workers=2, backend="ray", **kw)
        t_loc = evaluate_tactic("baseline", workers=1, **kw)
        assert t_ray["episodes_detail"] == t_loc["episodes_detail"]
        s_ray = evaluate_skill("go-to-ball", "baseline", workers=None, backend="ray", **kw)
        s_loc = evaluate_skill("go-to-ball", "baseline", workers=1, **kw)
        assert s_ray["episodes_detail"] == s_loc["episodes_detail"]
        mk = dict(matches=2, seed=30_000, robots=2, seconds=2.0, progress=False)
        r_ray, _ = play_series("baseline", "random", workers=2, backend="ray", **mk)
        r_loc, _ = play_series("baseline", "random", workers=1, **mk)
        key = (lambda r: (r.seed, r.score, r.goals, r.shots, r.possession, r.steps))
        assert [key(r) for r in r_ray] == [key(r) for r in r_loc]
    finally:
        ray.shutdown()


# --------------------------------------------------------------------- sweep
def test_training_sweep_runs_each_seed_like_a_single_run_and_resumes(tmp_path):
    """train.tools.sweep over 2 seeds = each seed trained on its own (the pool keeps job order and
    seeding, tested above); a second call resumes (finished runs are only re-evaluated)."""
    from train.offpolicy.config import DDPGConfig, TrainConfig
    from train.tools.sweep import main as sweep_main, sweep

    from train.offpolicy.toy import ENV_ID

    cfg = TrainConfig(skill="toy", env_id="train.offpolicy.toy:" + ENV_ID,
                      ddpg=DDPGConfig(actor_hidden=(16,), critic_hidden=(16,)), total_samples=300, warmup_samples=100,
                      batch_size=32, eval_interval=0, eval_episodes=3, checkpoint_interval=10_000, torch_threads=1,
                      log_interval=50)
    par = sweep(cfg, [3, 4], tmp_path / "par", workers=1, progress=False)
    one = sweep(cfg, [4], tmp_path / "one", workers=1, progress=False)
    assert [r["seed"] for r in par["runs"]] == [3, 4]
    assert par["runs"][1]["mean_return"] == one["runs"][0]["mean_return"]
    assert (tmp_path / "par" / "seed_3" / "actor.pt").exists() and (tmp_path / "par" / "sweep.json").exists()
    again = sweep(cfg, [3, 4], tmp_path / "par", workers=1, progress=False)
    assert all(r["resumed"] for r in again["runs"])
    assert [r["mean_return"] for r in again["runs"]] == [r["mean_return"] for r in par["runs"]]
    assert sweep_main(["pendulum", "--seeds", "1", "1", "--out", str(tmp_path / "x"), "--quiet"]) == 2


def test_team_spec_resolves_team_kinds_skills_and_decisions(tmp_path):
    from ssl_marl.plays.passing_play import passing_plays
    from ssl_marl.plays.team import TeamSpec, standard_team_plays
    from ssl_marl.runners.controllers import make_controller, resolve_team_option, team_spec

    assert team_spec("learned") == TeamSpec(plays=standard_team_plays, skills="learned")
    passing = team_spec("passing-baseline", where="blue")
    assert passing.plays is passing_plays and passing.decider is None
    assert passing.skills == {k: "baseline" for k in ("go_to_ball", "aim_to_shoot", "pass", "receive")}
    assert team_spec("passing-learned-decision").decider is not None
    assert team_spec("passing-learned", decision="handcoded").decider is None
    with pytest.raises(ValueError, match="carrier decision"):
        team_spec("baseline", decision="learned")
    with pytest.raises(ValueError, match="STP team"):
        team_spec("random")
    assert make_controller("idle", "blue", 2).agents == ["blue_0", "blue_1"]
    assert make_controller("baseline", "blue", 2, stickiness=0.2).stickiness == 0.2
    assert team_spec("attack-learned-decision").decider is not None
    assert team_spec("attack-learned-decision", decision="handcoded").decider is None
    assert resolve_team_option("baseline") == ("baseline", None, None)
    kind, skills, _ = resolve_team_option("learned", [("go_to_ball", "baseline")], where="--blue")
    assert kind == "learned" and skills["go_to_ball"] == "baseline"
    path = tmp_path / "team.json"
    path.write_text(json.dumps({"kind": "baseline", "skills": {"aim-to-shoot": "learned"}}))
    kind, skills, _ = resolve_team_option(str(path), [("aim_to_shoot", "baseline")])
    assert kind == "baseline" and skills["aim_to_shoot"] == "baseline"  # the option wins over the file
    path.write_text(json.dumps({"kind": "attack-learned", "decision": "learned"}))
    assert resolve_team_option(str(path)) == ("attack-learned", None, "learned")
    assert resolve_team_option(str(path), decision="handcoded")[2] == "handcoded"  # the option wins


def test_match_stats_count_fouls_by_the_offending_team():
    from types import SimpleNamespace

    from ssl_marl.runners.match import MatchStats

    st = MatchStats()
    truth = SimpleNamespace(blue=SimpleNamespace(ball_on_dribbler=np.zeros(2, bool)),
                            yellow=SimpleNamespace(ball_on_dribbler=np.zeros(2, bool)))
    st.record([{"type": "foul", "foul": "excessive_dribbling", "team": "blue", "agent": "blue_1"},
               {"type": "foul", "foul": "double_touch", "team": "yellow", "agent": "yellow_2"}], truth)
    st.record([{"type": "foul", "foul": "excessive_dribbling", "team": "blue", "agent": "blue_2"}], truth)
    assert st.fouls == {"blue": {"excessive_dribbling": 2}, "yellow": {"double_touch": 1}}
    assert st.referee == {"foul_excessive_dribbling": 2, "foul_double_touch": 1}
