"""The ``ssl-marl`` command line: demo, match, league, eval-skill, eval-drill, eval-tactic, eval-task, bench, train,
export-onnx, serve, play.

One module per command (:data:`COMMANDS`). A command module has
``register(subparsers) -> None``, which adds its subparser (help, every option with
``--help`` text) and ``set_defaults(handler=run)``, and ``run(args) -> int``, the
handler, which returns the exit status. A new command is a new module listed in
:data:`COMMANDS`; shared argument types and options are in :mod:`ssl_marl.cli.options`.

Every long-running command shows a progress bar; ``ssl-marl COMMAND --help``
explains every option. Output paths follow one rule (:data:`~ssl_marl.cli.options.OUTPUT_RULE`),
checked before any simulation starts. A handler's ValueError, FileNotFoundError or
FileExistsError (bad input) is printed as one line and exits with status 2.

A command whose subparser has no ``--help`` of its own (``bench``, ``train``) owns its
options: everything after its name (a leading ``--`` dropped) goes to its handler
unchanged as ``args.rest``. ``train`` is the one command that imports ``train``,
lazily inside its handler, so importing ``ssl_marl`` never loads the trainer.
"""

from __future__ import annotations

import argparse
import sys

from ..bridge.commands import play, serve
from . import bench, demo, eval_drill, eval_skill, eval_tactic, eval_task, export_onnx, league, match, train
from .options import OUTPUT_RULE

#: the command modules, in the order ``ssl-marl --help`` lists them (``serve`` and ``play``, the SSL network
#: bridge, come from :mod:`ssl_marl.bridge.commands`)
COMMANDS = (demo, match, league, eval_skill, eval_drill, eval_tactic, eval_task, bench, train, export_onnx, serve,
            play)


def _parser_and_commands() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    """The ``ssl-marl`` parser and its subparsers by command name."""
    from .. import __version__

    p = argparse.ArgumentParser(prog="ssl-marl", description="RoboCup SSL simulator, learned skills and STP matches.",
                                epilog=OUTPUT_RULE)
    p.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.register(sub)
    return p, sub.choices


def build_parser() -> argparse.ArgumentParser:
    """The ``ssl-marl`` parser: ``--version`` and one subcommand per module of :data:`COMMANDS`."""
    return _parser_and_commands()[0]


def main(argv: list[str] | None = None) -> int:
    """Run ``ssl-marl`` with ``argv`` (default ``sys.argv[1:]``); return the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    parser, commands = _parser_and_commands()
    command = commands.get(argv[0]) if argv else None
    if command is not None and not command.add_help:  # the command owns its options (and --help): forward them
        rest = argv[1:][1:] if argv[1:2] == ["--"] else argv[1:]
        args = argparse.Namespace(command=argv[0], rest=rest, handler=command.get_default("handler"))
    else:
        args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except (ValueError, FileNotFoundError, FileExistsError) as exc:  # bad input: one clear line, exit 2
        print(f"ssl-marl {args.command}: error: {exc}", file=sys.stderr)
        return 2
