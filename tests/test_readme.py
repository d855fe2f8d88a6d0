"""The README's opening commands and its Python blocks stay true: every ```python block
runs as written (in a scratch folder), so the how-tos cannot rot."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)


def test_readme_opens_with_exactly_two_commands():
    text = README.read_text()
    first = re.match(r"```bash\n(.*?)```", text, flags=re.S)
    assert first is not None, "the README must open with a bash block"
    lines = [ln for ln in first.group(1).splitlines() if ln.strip()]
    assert len(lines) == 2
    assert "pip install -e \".[dev]\"" in lines[0] and "ssl-marl match" in lines[0]
    assert "python -m pytest -q" in lines[1]


def test_readme_first_command_parses():
    import shlex

    from ssl_marl.cli import build_parser

    first = re.match(r"```bash\n(.*?)```", README.read_text(), flags=re.S).group(1).splitlines()[0]
    argv = shlex.split(first.split("&& ssl-marl ", 1)[1])
    args = build_parser().parse_args(argv)
    assert args.command == "match" and args.seconds > 0


def test_readme_has_python_how_tos():
    assert len(BLOCKS) >= 4  # env, skill, tactic, team


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_python_block_runs(index, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    exec(compile(BLOCKS[index], f"README.md python block {index}", "exec"), {"__name__": "__readme__"})


def test_readme_figures_exist_and_are_small():
    text = README.read_text()
    root = README.parent
    paths = set(re.findall(r"\((docs/figures/[^)\s]+)\)", text)) | set(re.findall(r'src="(docs/figures/[^"]+)"', text))
    assert paths, "the README shows a picture"
    for rel in paths:
        assert (root / rel).is_file(), rel
    total = sum(f.stat().st_size for f in (root / "docs" / "figures").iterdir() if f.is_file())
    assert total < 2_000_000
