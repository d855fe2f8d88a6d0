"""Regenerate the bridge's Python protobuf modules from ``ssl_marl/bridge/proto/*.proto``.

Run from the repository root::

    python -m ssl_marl.bridge.gen_proto          # rewrite the *_pb2.py files
    python -m ssl_marl.bridge.gen_proto --check  # exit 1 if regeneration would change them

The generator is ``grpcio-tools`` pinned to :data:`GRPCIO_TOOLS_VERSION` (its protoc
makes code for the protobuf runtime range declared in the ``ssl`` extra of
``pyproject.toml``); the generated modules are committed so that users need only the
runtime.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

GRPCIO_TOOLS_VERSION = "1.85.1"
PROTO_DIR = Path(__file__).resolve().parent / "proto"
REPO_ROOT = PROTO_DIR.parents[2]


def proto_files() -> list[Path]:
    """The schema files, sorted by name."""
    return sorted(PROTO_DIR.glob("*.proto"))


def generate(out_root: Path) -> list[Path]:
    """Run protoc on every schema file, writing ``ssl_marl/bridge/proto/*_pb2.py`` under
    ``out_root``; returns the generated paths. RuntimeError when grpcio-tools is missing,
    of another version, or protoc fails."""
    try:
        from importlib.metadata import version

        import grpc_tools
        from grpc_tools import protoc
    except ImportError as exc:
        raise RuntimeError(f"grpcio-tools=={GRPCIO_TOOLS_VERSION} is needed to regenerate ({exc})") from None
    have = version("grpcio-tools")
    if have != GRPCIO_TOOLS_VERSION:
        raise RuntimeError(f"grpcio-tools {have} is installed; the generated code is pinned to "
                           f"{GRPCIO_TOOLS_VERSION} (pip install grpcio-tools=={GRPCIO_TOOLS_VERSION})")
    include = Path(grpc_tools.__file__).parent / "_proto"
    rel = [str(p.relative_to(REPO_ROOT)) for p in proto_files()]
    rc = protoc.main(["protoc", f"-I{REPO_ROOT}", f"-I{include}", f"--python_out={out_root}", *rel])
    if rc != 0:
        raise RuntimeError(f"protoc failed with exit status {rc}")
    return [out_root / r.replace(".proto", "_pb2.py") for r in rel]


def changed_files() -> list[str]:
    """Generated modules that differ from (or are missing in) the committed tree."""
    with tempfile.TemporaryDirectory() as tmp:
        diffs = []
        for path in generate(Path(tmp)):
            committed = REPO_ROOT / path.relative_to(tmp)
            if not committed.is_file() or committed.read_bytes() != path.read_bytes():
                diffs.append(str(committed.relative_to(REPO_ROOT)))
        return diffs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="only report whether regeneration changes anything")
    args = parser.parse_args(argv)
    if args.check:
        diffs = changed_files()
        for d in diffs:
            print(f"out of date: {d}")
        return 1 if diffs else 0
    for path in generate(REPO_ROOT):
        print(f"wrote {path.relative_to(REPO_ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
