"""Command-line interface: ``dhfield <subcommand> ...``.

A thin layer: each subcommand parses its options and calls library functions;
no physics lives here.  Invalid input exits with status 2 and one line on
stderr (``dhfield: error: ...``), never a traceback.

One module per subcommand (``dhfield/cli/<name>.py``), each with
``add_parser(subparsers)`` that creates its parser and sets ``func`` to its
``run(args) -> int``.  To add a subcommand, write the module and list it in
:data:`SUBCOMMANDS`.
"""
from __future__ import annotations

import importlib
import sys

from ._common import OneLineParser, UsageError

__all__ = ["main", "build_parser", "SUBCOMMANDS"]

#: Subcommand modules, in the order ``dhfield --help`` lists them.
SUBCOMMANDS = ["curve", "pulloff", "field", "compare", "periphery", "sweep", "plot", "fit", "solve"]


def build_parser() -> OneLineParser:
    from .. import __version__

    parser = OneLineParser(prog="dhfield", description="Extended double-Hertz model of an adhesive "
                           "elliptical contact (Zini et al. 2018, doi:10.1007/s11249-017-0976-8)")
    parser.add_argument("--version", action="version", version=f"dhfield {__version__}")
    sub = parser.add_subparsers(dest="command", parser_class=OneLineParser, required=True)
    for name in SUBCOMMANDS:
        importlib.import_module(f".{name}", __name__).add_parser(sub)
    return parser


def main(argv=None) -> int:
    """Run the CLI; return the exit status (0 success, 2 bad input)."""
    try:
        args = build_parser().parse_args(argv)
        return int(args.func(args) or 0)
    except UsageError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2

