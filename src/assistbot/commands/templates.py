"""`assistbot templates`: calibrate the colours and build the vision template library in assets/templates/.

Renders labelled scenes (the "library" seed stream: never used for scoring) from the head
cameras over random arrangements, object positions, hand postures and head angles, and writes
small prototype PNGs, index.json (classes, prototypes, labelled feature examples) and
calibration.json.  Deterministic for a seed: the same seed rewrites identical files.
30 % of the scenes show the default person and 70 % people of the population seeds --partners
(default: the library seeds 0-999, population.LIBRARY_SEEDS; experiments on unseen partners
use seeds from 1000); their scenes that a body cannot pose (out of its reach) are skipped.
--partners none builds a library of the default person alone.
With --check it only loads the library (exit 2 with a message if it is missing).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from assistbot.resources import LIBRARY_SCENES

NAME = "templates"
HELP = "build the vision template library (assets/templates/) from rendered labelled scenes"
ORDER = 40


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--seed", type=int, default=0, help="library seed (default 0)")
    p.add_argument("--scenes", type=int, default=LIBRARY_SCENES, help=f"labelled scenes to render (default {LIBRARY_SCENES})")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: the package's assistbot/assets/templates)")
    p.add_argument("--partners", default=None, metavar="A:B|none",
                   help="population seeds whose people 70 %% of the scenes show (default: population.LIBRARY_SEEDS, "
                        "as the shipped library); none: the default person only")
    p.add_argument("--check", action="store_true", help="only check that the library loads")


def _partners(text: str | None):
    """--partners: the library seeds when not given, () for 'none', or the population seeds A:B."""
    from assistbot.errors import UserError
    from assistbot.human.population import LIBRARY_SEEDS, parse_seed_range

    if text is None:
        return LIBRARY_SEEDS
    if text.strip().lower() == "none":
        return ()
    try:
        return parse_seed_range(text, "arguments", "--partners")
    except UserError as exc:
        raise UserError(exc.where, exc.key, f"{exc.message}; or none (the default person only)") from None


def run(args: argparse.Namespace) -> int:
    from assistbot.errors import UserError

    if args.check:
        from assistbot.vision.library import load
        clfs, _ = load(args.out)
        print(", ".join(f"{k}: {len(c.classes)} classes, {len(c.y)} examples" for k, c in clfs.items()))
        return 0
    if args.scenes < 12:
        raise UserError("arguments", "--scenes", f"need at least 12 scenes, got {args.scenes}")
    partners = _partners(args.partners)
    from assistbot.vision.pipeline import build_library

    def progress(i: int, n: int) -> None:
        if i % 20 == 0 or i == n:
            print(f"\rtemplates: {i}/{n} scenes", end="", file=sys.stderr, flush=True)

    files = build_library(args.seed, args.scenes, args.out, progress, partners=partners)
    print(file=sys.stderr)
    size = sum(f.stat().st_size for f in files)
    print(f"wrote {len(files)} files ({size / 1024:.0f} kB) to {files[0].parent}")
    return 0
