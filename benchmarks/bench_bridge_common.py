"""Shared by the bridge benchmarks: the provenance block of a results JSON."""

from __future__ import annotations

import os
import platform
import subprocess
import sys
from datetime import datetime, timezone


def provenance() -> dict:
    """Command, commit, machine, UTC date and load average of this run."""
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                                check=False).stdout.strip()
    except OSError:
        commit = ""
    return {"command": " ".join([os.path.basename(sys.executable), *sys.argv]), "commit": commit,
            "machine": f"{platform.node()} {platform.machine()} {os.cpu_count()} cpus {platform.python_version()}",
            "date": datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "load_average": list(os.getloadavg())}
