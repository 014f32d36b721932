"""`assistbot think TIMELINE`: run the cognitive architecture on a percept timeline; write figures and a log."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "think"
HELP = ("run the field architecture (or another agent) on a percept timeline (YAML) and write the seed-style figures "
        "and a decision/utterance log")
ORDER = 40


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("timeline", type=Path, help="percept timeline file (see scenarios/timelines/)")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: render/think/<timeline name>)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="PATH=VALUE",
                   help="change a cognition parameter, e.g. --set fields.AEL.h=-4 or --set k=0.9 (repeatable)")
    p.add_argument("--backend", choices=["auto", "numpy", "numba"], default="auto", help="field stepping path (default: auto)")
    p.add_argument("--agent", default="dnf", metavar="AGENT",
                   help="dnf (the field architecture, default), fsm (the state-machine baseline: no figures) or package.module:factory")
    p.add_argument("--no-figures", action="store_true", help="write only the log")
    p.add_argument("--learn", type=Path, default=None, metavar="WEIGHTS.json",
                   help="learn the grip-to-chain weights from this timeline: start from the file (the priors if it does "
                        "not exist), write what was learnt back to it")


def _overrides(items: list[str]) -> dict[str, float]:
    from assistbot.errors import UserError

    out: dict[str, float] = {}
    for item in items:
        if "=" not in item:
            raise UserError("--set", item, "expected PATH=VALUE, e.g. fields.AEL.h=-4")
        path, value = item.split("=", 1)
        try:
            out[path.strip()] = float(value)
        except ValueError:
            raise UserError("--set", path.strip(), f"value must be a number, got {value!r}") from None
    return out


def run(args: argparse.Namespace) -> int:
    from assistbot.cognition.figures import write_figures
    from assistbot.cognition.replay import replay
    from assistbot.cognition.timeline import load_timeline

    tl = load_timeline(args.timeline)
    overrides = _overrides(args.overrides)
    figures = not args.no_figures and args.agent == "dnf"   # the figures show the fields
    rep = replay(tl, overrides=overrides, record=figures, backend=args.backend, agent=args.agent, learn=args.learn)
    out = args.out or Path("render/think") / tl.name
    out.mkdir(parents=True, exist_ok=True)
    lines = rep.log_lines()
    header = [f"# {tl.name}: {tl.description.strip()}",
              f"# timeline: {tl.source}; perception: ORACLE (ground truth); agent: {args.agent}", ""]
    (out / "log.txt").write_text("\n".join(header + lines) + "\n")
    paths = write_figures(tl.name, rep.recorder, rep.agent.decisions(), out) if figures else []
    print(f"think {tl.name}: {len(rep.chosen)} decisions, {len(rep.said)} utterances; wrote {out}/log.txt" +
          (f" and {len(paths)} figures" if paths else ""))
    for line in lines:
        if "DECIDE" in line or "RELEASE" in line:
            print("  " + line.strip())
    if args.learn is not None:
        print(f"learnt weights: {args.learn}")
    return 0
