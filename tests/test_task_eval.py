"""ssl-marl eval-task (ssl_marl/runners/task_eval.py): a tiny run through the CLI, results
independent of the worker count, bad arguments rejected."""

from __future__ import annotations


import numpy as np
import pytest

from ssl_marl.cli import main
from ssl_marl.runners.result import load_result
from ssl_marl.runners.statistics import t_interval
from ssl_marl.runners.task_eval import evaluate_task


def _run(tmp_path, name, workers):
    out = tmp_path / name
    rc = main(["eval-task", "keepaway", "--policy", "random", "--episodes", "2", "--seed", "7",
               "--workers", str(workers), "--out", str(out), "--quiet"])
    assert rc == 0
    return load_result(out), out


def test_cli_run_and_workers_do_not_change_results(tmp_path, capsys):
    r1, out1 = _run(tmp_path, "w1", 1)
    assert "mean duration" in capsys.readouterr().out
    assert (out1 / "duration_hist.png").stat().st_size > 0
    eps = r1["episodes_detail"]
    assert [e["seed"] for e in eps] == [7, 8]
    d = [e["duration_s"] for e in eps]
    assert r1["mean_duration_s"] == pytest.approx(np.mean(d))
    lo, hi = r1["mean_duration_ci95"]
    assert lo <= r1["mean_duration_s"] <= hi
    assert sum(r1["outcomes"].values()) == 2
    assert set(r1["outcomes"]) <= {"taker_control", "out", "time"}
    r2, _ = _run(tmp_path, "w2", 2)
    assert r2["episodes_detail"] == r1["episodes_detail"]
    assert r2["mean_duration_s"] == r1["mean_duration_s"] and r2["outcomes"] == r1["outcomes"]


def test_t_interval_matches_hand_computation():
    lo, hi = t_interval([1.0, 2.0, 3.0])
    # mean 2, s = 1, t_{0.975, 2} = 4.302653
    assert lo == pytest.approx(2.0 - 4.302653 / np.sqrt(3), rel=1e-5)
    assert hi == pytest.approx(2.0 + 4.302653 / np.sqrt(3), rel=1e-5)


@pytest.mark.parametrize("argv, needle", [
    (["eval-task", "keepaway", "--policy", "handcoded", "--actor", "x.pt", "--episodes", "1"], "--actor"),
    (["eval-task", "attack-3v2", "--policy", "always-hold", "--episodes", "1"], "always-hold"),
    (["eval-task", "keepaway", "--policy", "learned", "--actor", "/nonexistent/a.pt", "--episodes", "1"],
     "does not exist"),
])
def test_bad_arguments_exit_2_with_a_message(argv, needle, capsys):
    assert main(argv) == 2
    assert needle in capsys.readouterr().err


def test_argparse_rejects_bad_values(capsys):
    for argv in (["eval-task", "keepaway", "--episodes", "0"], ["eval-task", "soccer"],
                 ["eval-task", "keepaway", "--policy", "greedy"], ["eval-task", "keepaway", "--workers", "0"]):
        with pytest.raises(SystemExit) as e:
            main(argv)
        assert e.value.code == 2


def test_evaluate_task_rejects_bad_inputs():
    with pytest.raises(ValueError, match="realism"):
        evaluate_task("keepaway", "random", episodes=1, realism="foggy", progress=False)
    with pytest.raises(ValueError, match="episodes"):
        evaluate_task("keepaway", "random", episodes=0, progress=False)
    with pytest.raises(ValueError, match="unknown decision task"):
        evaluate_task("chess", "random", episodes=1, progress=False)


def test_every_decision_task_is_scored_and_seeded():
    """eval-task offers exactly the registered decision tasks, each with a score kind and a default seed."""
    from ssl_marl.decisions import DECISION_TASKS
    from ssl_marl.runners.task_eval import DEFAULT_SEEDS, TASK_SCORES

    assert set(TASK_SCORES) == set(DEFAULT_SEEDS) == set(DECISION_TASKS)
    with pytest.raises(SystemExit):
        main(["eval-task", "no-such-task", "--episodes", "1"])
