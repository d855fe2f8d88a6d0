"""Wall time of the README's first command (after setup): the match with its GIF.

Runs the ``ssl-marl match ...`` that ends the README's first command (read from README.md) in a
temporary folder under ``/usr/bin/time`` and records the process's wall
time and peak memory, the match's own wall time and score (from its summary line), the GIF's
size and the load average before and after. A benchmark: run it on an idle machine.

    python benchmarks/bench_readme_match.py [--out results/bench_readme_match.json]
    python benchmarks/bench_readme_match.py --args "match --blue attack-learned --yellow attack-learned --seconds 450 --seed 1 --render-fps 5"

``--args`` times another ``ssl-marl match`` command the same way (e.g. an earlier first command beside the
current one on the same host).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shlex
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from ssl_marl.cli import build_parser
from ssl_marl.io import atomic_write_json
from ssl_marl.runners.provenance import build_manifest

README = Path(__file__).resolve().parent.parent / "README.md"


def readme_args() -> list[str]:
    """The arguments after ``ssl-marl`` in the README's first command (its opening bash block's first line)."""
    first = re.match(r"```bash\n(.*?)```", README.read_text(), flags=re.S).group(1).splitlines()[0]
    return shlex.split(first.split("&& ssl-marl ", 1)[1])


ARGS = readme_args()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=None, help="write the record (JSON) here")
    ap.add_argument("--args", default=None,
                    help="time these ssl-marl match arguments instead of the README's (a quoted string, e.g. an "
                         "earlier first command, for a side-by-side run)")
    a = ap.parse_args()
    args = ARGS if a.args is None else shlex.split(a.args)
    parsed = build_parser().parse_args(args)  # the CLI's own parser: its defaults, its errors
    if parsed.command != "match":
        raise SystemExit(f"bench_readme_match: --args must be an ssl-marl match command, got {parsed.command!r}")
    exe = shutil.which("ssl-marl")
    if exe is None:
        raise SystemExit("bench_readme_match: the ssl-marl command is not on PATH (install the package)")
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "SDL_VIDEODRIVER": "dummy"}
        proc = subprocess.run(["/usr/bin/time", "-f", "TIME %e %M", exe, *args], cwd=tmp, env=env,
                              capture_output=True, text=True, check=True)
        gif = Path(tmp, "match.gif").stat().st_size
    out = proc.stdout + proc.stderr
    wall, rss = re.findall(r"TIME ([\d.]+) (\d+)", out)[-1]
    line = re.findall(r"blue \([^)]*\) (\d+) - (\d+) yellow .*? ([\d.]+) s simulated in ([\d.]+) s wall", out)[-1]
    what = "the README's first command (after setup)" if a.args is None else "the ssl-marl command given by --args"
    rec = {"what": f"{what}: wall time of the match with its GIF, /usr/bin/time",
           "command": ["ssl-marl", *args], "readme_command": a.args is None, "score": {"blue": int(line[0]), "yellow": int(line[1])},
           "simulated_s": float(line[2]), "match_wall_s": float(line[3]), "process_wall_s": float(wall),
           "max_rss_kb": int(rss), "gif_bytes": gif,
           "load_average_1min_before_after": [load_before, os.getloadavg()[0]], "date": time.strftime("%Y-%m-%d %H:%M"),
           "manifest": build_manifest(rules={"blue": parsed.blue, "yellow": parsed.yellow}, seeds={"seed": parsed.seed})}
    print(json.dumps({k: v for k, v in rec.items() if k != "manifest"}, indent=1))
    if a.out:
        atomic_write_json(a.out, rec)


if __name__ == "__main__":
    main()
