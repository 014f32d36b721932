"""`assistbot inspect RUN_DIR`: (re)build a run folder's inspect.html from its files."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "inspect"
HELP = "build inspect.html in a run folder: the video, the fields, the percept and the events on one page"
ORDER = 15


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("run_dir", type=Path, help="a folder written by 'assistbot run'")


def run(args: argparse.Namespace) -> int:
    from assistbot.errors import UserError
    from assistbot.inspector import write_inspector

    if not args.run_dir.is_dir():
        raise UserError(str(args.run_dir), "RUN_DIR", "no such folder")
    print(f"inspector: {write_inspector(args.run_dir)}")
    return 0
