"""docs/RESULTS.md's tables (train/report.py): regenerating them from results/ changes nothing,
and only the text between a table's markers is rewritten."""

from __future__ import annotations

from pathlib import Path

from train.tools.report import TABLES, regenerate, render

ROOT = Path(__file__).resolve().parents[1]


def test_results_doc_tables_match_the_records():
    doc = (ROOT / "docs" / "RESULTS.md").read_text()
    text, changed = regenerate(doc, ROOT / "results")
    assert changed == [] and text == doc


def test_only_the_text_between_markers_is_rewritten():
    results = ROOT / "results"
    doc = "intro\n<!-- table:keepaway -->\nhand-typed row\n<!-- /table:keepaway -->\nafter\n<!-- table:nope -->\nx\n<!-- /table:nope -->\n"
    text, changed = regenerate(doc, results)
    assert text.startswith("intro\n<!-- table:keepaway -->\n| keepers |")
    assert text.endswith("<!-- /table:keepaway -->\nafter\n<!-- table:nope -->\nx\n<!-- /table:nope -->\n")
    assert "keepaway" in changed and "nope (no such table)" in changed
    assert sum(c.endswith("(no marker in the doc)") for c in changed) == len(TABLES) - 1
    again, changed_again = regenerate(text, results)
    assert again == text and "keepaway" not in changed_again


def test_decision_task_slot_lists_realistic_records(tmp_path):
    assert render("decision_tasks_realistic", tmp_path).startswith("No records match")


def test_pooled_attack_turns_a_series_to_the_named_side():
    """One series seen from blue and from yellow: wins and losses swap, the goals per match
    swap, and the named side's goals and passes are its own counts."""
    import pytest

    from ssl_marl.runners.result import load_result
    from train.tools.report_match_tables import pooled_attack

    results, name = ROOT / "results", "match_attack_learned_vs_baseline_600_90000"
    s = load_result(results / f"{name}.json")["summary"]
    blue, yellow = (pooled_attack(results, [(side, ((name, side),))])[2].split(" | ") for side in ("blue", "yellow"))
    assert blue[4] == f"{s['wins']}-{s['draws']}-{s['losses']}" and yellow[4] == f"{s['losses']}-{s['draws']}-{s['wins']}"
    assert blue[6].split()[0] == "-".join(reversed(yellow[6].split()[0].split("-")))
    assert blue[8] == " / ".join(str(s["stats"]["blue"][f"goals_{g}"])
                                 for g in ("direct", "redirect", "after_chip_pass", "other"))
    with pytest.raises(ValueError, match="side must be blue or yellow"):
        pooled_attack(results, [("x", ((name, "green"),))])
