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
