"""Command-line interface: ``dhfield <subcommand> ...``.

A thin layer: each subcommand parses its options and calls library functions;
no physics lives here.  Invalid input exits with status 2 and one line on
stderr (``dhfield: error: ...``), never a traceback.

One module per subcommand (``dhfield/cli/<name>.py``, a hyphen of the name an underscore), each with
``add_parser(subparsers)`` that creates its parser and sets ``func`` to its
``run(args) -> int``.  To add a subcommand, write the module and list it in
:data:`SUBCOMMANDS`.
"""
from __future__ import annotations

import contextlib
import importlib
import sys

from ._common import OneLineParser, UsageError

__all__ = ["main", "build_parser", "SUBCOMMANDS", "EXIT_BROKEN_PIPE"]

#: Subcommand modules, in the order ``dhfield --help`` lists them.
SUBCOMMANDS = ["curve", "pulloff", "cycle", "field", "compare", "periphery", "sweep", "plot", "force-vs-angle", "fit",
               "solve"]


def build_parser() -> OneLineParser:
    """Build the ``dhfield`` argument parser with every subcommand.

    Returns
    -------
    OneLineParser
        The parser (bad arguments: one line on stderr, exit status 2).
    """
    from .. import __version__

    parser = OneLineParser(prog="dhfield", description="Extended double-Hertz model of an adhesive "
                           "elliptical contact (Zini et al. 2018, doi:10.1007/s11249-017-0976-8)")
    parser.add_argument("--version", action="version", version=f"dhfield {__version__}")
    sub = parser.add_subparsers(dest="command", parser_class=OneLineParser, required=True)
    for name in SUBCOMMANDS:
        importlib.import_module(f".{name.replace('-', '_')}", __name__).add_parser(sub)
    return parser


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text or type(exc).__name__


#: Exit status when stdout's reader closed the pipe: 128 + SIGPIPE, what a shell reports for a
#: command that SIGPIPE ended (Python ignores SIGPIPE and raises BrokenPipeError instead).
EXIT_BROKEN_PIPE = 141


def _stdout_closed() -> int:
    """Quiet end after the reader of stdout went away: no message, no flush error at exit."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout replaced by an object without a descriptor
        pass
    return EXIT_BROKEN_PIPE


@contextlib.contextmanager
def _warnings_as_lines():
    """Print each warning as one ``dhfield: warning:`` line on stderr, once per text (shared with the
    records' warnings): its message only, without Python's source path and line of code."""
    import warnings

    from ._common import _PRINTED_WARNINGS, print_warning_line

    _PRINTED_WARNINGS.clear()  # once per run of main()
    with warnings.catch_warnings():
        shown = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None):
            if file is not None and file is not sys.stderr:  # an explicit destination: as Python prints it
                shown(message, category, filename, lineno, file, line)
            else:
                print_warning_line(str(message))

        warnings.showwarning = show
        yield


def _left_behind(exc: BaseException, written: int) -> str:
    """What an interrupted run left: the notes of the interrupt (a sweep's stored cases), else the files it wrote."""
    from ..io import written_files

    notes = [" ".join(str(n).split()) for n in getattr(exc, "__notes__", ())]
    if notes:
        return "; ".join(notes)
    files = written_files()[written:]
    if not files:
        return "no output was written"
    return f"wrote only {', '.join(repr(str(f)) for f in files)} before that (nothing else was written)"


def main(argv=None) -> int:
    """Run the CLI.

    0 success; 141 (128 + SIGPIPE) silently when the reader of stdout went away
    (``dhfield curve ... | head``), as a command killed by SIGPIPE; 2 bad input (one line on stderr: usage, ``ValueError``, ``OSError``
    such as a full disk, ``MemoryError``); 1 an unexpected internal error (one
    line; set ``DHFIELD_DEBUG=1`` for the traceback); 128 + n when signal n
    stopped the run (130 for Ctrl-C, 143 for SIGTERM, 129 for SIGHUP), after any
    temporary file was removed, with one line saying what was written (nothing, the
    files moved into place before the signal, or a sweep's stored cases and how to
    resume).  ``--out`` is validated before anything is
    computed (:func:`dhfield.cli._common.check_output_argument`).

    Parameters
    ----------
    argv : list of str, optional
        The arguments; default ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit status.
    """
    import os

    from ..io import SignalExit, written_files
    from ._common import check_output_argument, termination_signals_as_exceptions

    def fail(message: str, status: int) -> int:
        print(f"dhfield: {message}", file=sys.stderr)
        return status

    written = len(written_files())   # the files this run moves into place come after these
    with termination_signals_as_exceptions(), _warnings_as_lines():
        try:
            args = build_parser().parse_args(argv)
            check_output_argument(args)
            return int(args.func(args) or 0)
        except BrokenPipeError:
            return _stdout_closed()
        except (UsageError, ValueError, OSError) as exc:
            return fail(f"error: {_one_line(exc)}", 2)
        except MemoryError as exc:
            return fail(f"error: out of memory ({_one_line(exc)}); choose a smaller problem", 2)
        except KeyboardInterrupt as exc:
            return fail(f"interrupted (SIGINT); {_left_behind(exc, written)}", 130)
        except SignalExit as exc:
            return fail(f"{exc}; {_left_behind(exc, written)}", exc.exit_status)
        except Exception as exc:  # noqa: BLE001 - one line instead of a traceback
            if os.environ.get("DHFIELD_DEBUG"):
                raise
            return fail(f"internal error: {type(exc).__name__}: {_one_line(exc)} (please report it; "
                        "DHFIELD_DEBUG=1 shows the traceback)", 1)
