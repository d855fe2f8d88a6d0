"""Argument types and options shared by the ``ssl-marl`` commands.

A type (``positive_int("--episodes")`` etc.) turns one command-line string into a
value or raises :class:`argparse.ArgumentTypeError` with a message that names the
option and the rule it broke; argparse prints it and exits with status 2.
"""

from __future__ import annotations

import argparse
from typing import Callable

from ..runners.controllers import TEAM_KINDS
from ..runners.pool import BACKENDS

FIELDS = ("div_a", "div_b")
OUTPUT_RULE = ("Output paths (--out, --render, --json, export-onnx OUT): missing parent folders are created; a path that "
               "cannot be written is refused before any simulation starts.")
SKILL_SOURCE_HELP = ("SKILL=SOURCE: run SKILL (go-to-ball, aim-to-shoot; pass, receive for the passing and "
                     "attacking teams; chip-pass, redirect for the attacking teams) from SOURCE: baseline, learned "
                     "(shipped actor) or an actor checkpoint path, e.g. go-to-ball=runs/gtb/actor.pt (repeatable)")


# ------------------------------------------------------------------- types
def int_at_least(name: str, lowest: int) -> Callable[[str], int]:
    """Type of an integer option ``name`` that must be >= ``lowest``."""
    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}") from None
        if v < lowest:
            raise argparse.ArgumentTypeError(f"{name} must be >= {lowest}, got {v}")
        return v
    return parse


def positive_int(name: str) -> Callable[[str], int]:
    """Type of an integer option ``name`` that must be >= 1."""
    return int_at_least(name, 1)


def robots(text: str) -> int:
    """Type of ``--robots``: robots per team, 1 to 11 (the SSL maximum)."""
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--robots must be an integer, got {text!r}") from None
    if not 1 <= v <= 11:
        raise argparse.ArgumentTypeError(f"--robots must be between 1 and 11 (SSL allows at most 11), got {v}")
    return v


def finite_float(name: str, lowest: float, inclusive: bool, rule: str) -> Callable[[str], float]:
    """Type of a finite float option ``name`` above ``lowest`` (or equal to it when
    ``inclusive``); ``rule`` completes "NAME must be ..." in the error."""
    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not ((v >= lowest if inclusive else v > lowest) and v < float("inf")):
            raise argparse.ArgumentTypeError(f"{name} must be {rule}, got {text}")
        return v
    return parse


def positive_float(name: str) -> Callable[[str], float]:
    """Type of a finite float option ``name`` that must be > 0."""
    return finite_float(name, 0.0, False, "a positive number")


def non_negative_float(name: str) -> Callable[[str], float]:
    """Type of a finite float option ``name`` that must be >= 0."""
    return finite_float(name, 0.0, True, "a finite number >= 0")


def team(text: str) -> str:
    """Type of ``--blue`` / ``--yellow``: a team kind or a JSON team file."""
    if text in TEAM_KINDS or text.lower().endswith(".json"):
        return text
    raise argparse.ArgumentTypeError(f"invalid choice: {text!r} (choose from {', '.join(TEAM_KINDS)}, "
                                     "or a JSON team file ending in .json)")


def skill_source(text: str) -> tuple[str, str]:
    """Type of ``--skill SKILL=SOURCE``: (skill name, source)."""
    from ..runners.controllers import parse_skill_source

    try:
        return parse_skill_source(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


# ----------------------------------------------------------------- options
def add_backend(p: argparse.ArgumentParser, what: str) -> None:
    """``--backend`` and ``--address``: where ``what`` (e.g. "the episodes") run."""
    p.add_argument("--backend", choices=BACKENDS, default="local",
                   help=f"where {what} run: local (process pool of --workers, default) or ray (a Ray cluster; "
                        "--workers = tasks in flight)")
    p.add_argument("--address", default=None, metavar="ADDR",
                   help="Ray cluster address (HOST:6379 or auto; default: start a local Ray instance); "
                        "needs --backend ray")


def workers(args: argparse.Namespace) -> int | None:
    """--workers, defaulting to 1 locally and to the whole cluster with Ray."""
    return args.workers if args.workers is not None else (None if args.backend == "ray" else 1)


def add_tracker_option(p: argparse.ArgumentParser) -> None:
    """``--tracker auto|on|off``."""
    p.add_argument("--tracker", choices=("auto", "on", "off"), default="auto",
                   help="vision tracker between the env's vision and the skills/tactics (Kalman filters, latency "
                        "compensation, ball on the dribbler, outlier gates): auto = on unless --realism none "
                        "(default auto)")


def add_forwarded_parser(subparsers: argparse._SubParsersAction, name: str, help: str,
                         program: str) -> argparse.ArgumentParser:
    """Subparser of a command whose options belong to another program (``program``).

    It has no ``--help`` of its own: :func:`ssl_marl.cli.main` hands everything after
    the command's name (a leading ``--`` dropped) to the handler as ``args.rest``, so
    ``ssl-marl NAME --help`` shows the other program's help."""
    p = subparsers.add_parser(name, help=help, add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER, help=f"options of {program}")
    return p
