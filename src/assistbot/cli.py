"""`assistbot` command line: subcommands are registered by modules in `assistbot.commands`.

Each module there defines ``NAME``, ``HELP``, ``ORDER`` (position in --help),
``add_arguments(parser)`` and ``run(args) -> int``; it is found by discovery, so
adding a command is adding a file. Heavy imports happen inside ``run`` so that
``--help`` stays fast. Mistakes a user can make end in one line on stderr and
exit 2.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from typing import Sequence

from assistbot.errors import UserError


def _command_modules() -> list:
    import pkgutil

    import assistbot.commands as pkg

    modules = [importlib.import_module(f"{pkg.__name__}.{m.name}") for m in pkgutil.iter_modules(pkg.__path__)]
    return sorted((m for m in modules if hasattr(m, "NAME")), key=lambda m: (getattr(m, "ORDER", 100), m.NAME))


class _Parser(argparse.ArgumentParser):
    """argparse that reports a bad option as one line and exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        option = "arguments"
        if ": " in message and message.startswith("argument "):
            option, message = message[len("argument "):].split(": ", 1)
        sys.stderr.write(f"error: {self.prog}: {option}: {message} (see '{self.prog} --help')\n")
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="assistbot", description="Pro-active assistant robot simulation (MuJoCo + dynamic neural fields).")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for module in _command_modules():
        p = sub.add_parser(module.NAME, help=module.HELP, description=module.HELP)
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def _user_error_types() -> tuple[type[BaseException], ...]:
    # fields is standalone (imports nothing of the project), so its error type is its own.
    from assistbot.fields.errors import FieldError

    return (UserError, FieldError)


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        return 0
    try:
        return int(args._run(args) or 0)
    except _user_error_types() as exc:
        line = exc.line() if hasattr(exc, "line") else f"error: {exc}"
        sys.stderr.write(line + "\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        return 130
    except BrokenPipeError:
        # the reader stopped reading (`assistbot list | head -1`): nothing more to say, and no traceback;
        # what is still buffered goes nowhere, so that Python's flush at exit does not fail again
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError):
            pass
        return 1


if __name__ == "__main__":
    raise SystemExit(main())
