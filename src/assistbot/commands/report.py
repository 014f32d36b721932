"""`assistbot report DIR`: a sweep's summary tables (with confidence intervals), plots and Markdown."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "report"
HELP = "summarise a sweep folder: success rate and time to drink per parameter value with CIs, plots, report.md"
ORDER = 35


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dir", type=Path, metavar="DIR", help="a sweep's results folder (holding results.csv)")
    p.add_argument("--out", type=Path, default=None, help="where to write the report (default: DIR/report)")
    p.add_argument("--expect", default=None, metavar="'A > B > ...'",
                   help="an AEL decision sequence: count per parameter value the episodes that made exactly it "
                        "(ending in '> ...': that began with it)")
    p.add_argument("--by", default=None, metavar="PATH",
                   help="split every other factor by this swept parameter (e.g. --by agent): a table per factor "
                        "with a row per pair of values, and plots with one line per value")


def run(args: argparse.Namespace) -> int:
    from assistbot.sweep.report import write_report

    paths = write_report(args.dir, args.out, expect=args.expect, by=args.by)
    print(f"report: {paths[0]}")
    for p in paths[1:]:
        print(f"  {p}")
    return 0
