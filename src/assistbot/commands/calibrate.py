"""`assistbot calibrate`: measure the HSV colour ranges of the parts from labelled head-camera renders.

Writes assets/templates/calibration.json (also written by `assistbot templates`, whose
prototypes depend on it: rebuild the templates after recalibrating).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

NAME = "calibrate"
HELP = "calibrate the vision's HSV colour ranges from rendered labelled scenes"
ORDER = 41


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--scenes", type=int, default=16)
    p.add_argument("--out", type=Path, default=None, help="output folder (default: the package's assistbot/assets/templates)")


def run(args: argparse.Namespace) -> int:
    from assistbot.resources import TEMPLATES
    from assistbot.vision.calibration import calibrate

    cal = calibrate(args.seed, args.scenes)
    root = args.out or TEMPLATES
    root.mkdir(parents=True, exist_ok=True)
    path = root / "calibration.json"
    path.write_text(json.dumps(cal, indent=1, sort_keys=True) + "\n")
    for part, boxes in cal["hsv"].items():
        print(f"{part:<8} " + "  ".join(f"H {b[0]}-{b[1]} S {b[2]}-{b[3]} V {b[4]}-{b[5]}" for b in boxes))
    print(f"wrote {path}")
    return 0
