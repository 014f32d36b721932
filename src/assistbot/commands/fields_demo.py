"""`assistbot fields-demo`: plots of selection, self-sustained memory, coincidence detection, continuous and 2-D
couplings, and learning."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "fields-demo"
HELP = "run a small dynamic-field network and write its plots (selection, memory, coupled coincidence)"
ORDER = 90


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("render/fields-demo"), help="output folder (default: render/fields-demo)")
    p.add_argument("--backend", choices=["auto", "numpy", "numba"], default="auto", help="stepping path (default: auto)")


def run(args: argparse.Namespace) -> int:
    from assistbot.fields.demo import run_demo

    paths = run_demo(args.out, backend=args.backend)
    print(f"fields demo: wrote {len(paths)} plots to {args.out}/")
    for p in paths:
        print(f"  {p}")
    return 0
