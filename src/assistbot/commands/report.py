"""`assistbot report DIR`: a sweep's summary tables (with confidence intervals), plots and Markdown."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "report"
HELP = ("summarise a sweep folder: success rate and time to drink per parameter value with CIs, plots, report.md; "
        "several folders with --by: each one's report and an overview of all of them side by side")
ORDER = 35


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dirs", type=Path, nargs="+", metavar="DIR", help="a sweep's results folder (holding results.csv)")
    p.add_argument("--out", type=Path, default=None,
                   help="where to write the report (default: DIR/report); with several DIRs, the overview "
                        "(default: overview/ beside the first DIR)")
    p.add_argument("--expect", default=None, metavar="'A > B > ...'",
                   help="an AEL decision sequence: count per parameter value the episodes that made exactly it "
                        "(ending in '> ...': that began with it)")
    p.add_argument("--by", default=None, metavar="PATH",
                   help="split every other factor by this swept parameter (e.g. --by agent): a table per factor "
                        "with a row per pair of values, and plots with one line per value")


def run(args: argparse.Namespace) -> int:
    from assistbot.errors import UserError
    from assistbot.sweep.overview import write_overview
    from assistbot.sweep.report import write_report

    several = len(args.dirs) > 1
    if several and args.by is None:
        raise UserError("--by", "(missing)", "several DIRs are put side by side split by one swept parameter: "
                        "give it, e.g. --by agent")
    for d in args.dirs:
        paths = write_report(d, None if several else args.out, expect=args.expect, by=args.by)
        print(f"report: {paths[0]}")
        for p in paths[1:]:
            print(f"  {p}")
    if several:
        out = args.out if args.out is not None else args.dirs[0].parent / "overview"
        paths = write_overview(args.dirs, args.by, out)
        print(f"overview: {paths[0]}")
        print(f"  {paths[1]}")
    return 0
