"""``ssl-marl train``: the trainer's command line (``python -m train``), forwarded.

The one place ``ssl_marl`` imports ``train``, lazily inside :func:`run`: importing
the library never loads the trainer, and one command line covers the whole workflow.
"""

from __future__ import annotations

import argparse

from .options import add_forwarded_parser


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``train`` subparser (its options are the trainer's)."""
    tr = add_forwarded_parser(subparsers, "train", "train a skill with DDPG, as python -m train (ssl-marl train --help)",
                              "python -m train")
    tr.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Forward everything after ``train`` to ``python -m train`` (same options, same behaviour)."""
    from train.__main__ import main as train_main

    return int(train_main(args.rest, prog="ssl-marl train") or 0)
