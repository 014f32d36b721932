"""`assistbot run SCENARIO`: one episode to a folder with video, log, summary, subtitles and figures."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

NAME = "run"
HELP = "run a scenario (closed loop) and write video.mp4, log.jsonl, summary.json, subtitles.srt and figures"
ORDER = 10


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scenario", help="a scenario file or the name of a shipped one (see 'assistbot list')")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: render/<scenario name>)")
    p.add_argument("--seed", type=int, default=None, help="seed (default: the scenario's)")
    p.add_argument("--perception", choices=["vision", "oracle"], default="vision",
                   help="vision (the robot's cameras) or oracle (ground truth, for debugging; labelled in every output)")
    p.add_argument("--set", dest="sets", action="append", default=[], metavar="PATH=VALUE",
                   help="override a parameter by dotted path, e.g. --set cognition.k=0.9, or set the arrangement and the "
                        "partner as a sweep's row does, e.g. --set objects.glass.zone=HWS --set human.profile=slow (repeatable)")
    p.add_argument("--agent", default=None, metavar="AGENT",
                   help="the robot's mind instead of the scenario's: dnf (the field architecture), fsm (the "
                        "state-machine baseline) or package.module:factory")
    p.add_argument("--no-video", action="store_true", help="skip the video (faster)")
    p.add_argument("--record-truth", action="store_true",
                   help="also log the ground truth beside what vision reported (the inspector shows vision's mistakes; "
                        "the robot never sees it)")
    p.add_argument("--learn", type=Path, default=None, metavar="WEIGHTS.json",
                   help="learn from this person: the field architecture starts from the grip-to-chain weights in the "
                        "file (the priors if it does not exist), learns while it runs, and writes them back")
    p.add_argument("--force", action="store_true",
                   help="replace an earlier run in the output folder (without it, such a folder is refused)")


def parse_sets(sets: list[str]) -> dict:
    import yaml

    from assistbot.errors import UserError

    out = {}
    for s in sets:
        path, eq, value = s.partition("=")
        if not eq or not path.strip():
            raise UserError("--set", s, "expected PATH=VALUE, e.g. cognition.k=0.9")
        try:
            v = yaml.safe_load(value)
        except yaml.YAMLError:
            raise UserError("--set", path, f"cannot read the value {value!r}") from None
        if isinstance(v, str):   # YAML 1.1 reads 1e-3 (no dot) as text; a user means the number, as a sweep reads it
            try:
                v = float(v)
            except ValueError:
                pass
        out[path.strip()] = v
    return out


def scenario_with_sets(spec: str, sets: list[str]):
    """The scenario ``spec`` with the ``--set`` values that edit it (as a sweep's row sets them:
    objects.NAME.zone/state/position, human.profile, agent) applied, and the other ``--set`` values as overrides."""
    from assistbot.scenario import load_scenario
    from assistbot.sweep.spec import is_scenario_path

    scenario = load_scenario(spec)
    overrides = parse_sets(sets)
    edits = {k: v for k, v in overrides.items() if is_scenario_path(k)}
    if edits:
        from assistbot.scenario import parse_scenario
        from assistbot.sweep.jobs import scenario_data_with

        scenario = parse_scenario(scenario_data_with(scenario, edits, "--set"), scenario.path)
        overrides = {k: v for k, v in overrides.items() if k not in edits}
    return scenario, overrides


def run(args: argparse.Namespace) -> int:
    from assistbot.episode import run_scenario
    from assistbot.episode.builder import split_overrides
    from assistbot.episode.outputs import PARTIAL, earlier_run
    from assistbot.errors import UserError

    scenario, overrides = scenario_with_sets(args.scenario, args.sets)
    if args.agent is not None:
        import dataclasses

        from assistbot.agents import agent_factory

        agent_factory(args.agent, "--agent")
        scenario = dataclasses.replace(scenario, agent=args.agent)
    split_overrides(overrides, "--set", scenario.agent)   # a mistake names --set, not the scenario file
    out = args.out or Path("render") / scenario.name
    if out.exists() and not out.is_dir():
        raise UserError(str(out), "--out", "is a file; name a folder")
    writable = next(p for p in (out, *out.parents) if p.exists())
    if not os.access(writable, os.W_OK):
        raise UserError(str(out), "--out", f"cannot write in {writable}")
    earlier = earlier_run(out)
    if earlier and not args.force:
        state = "an unfinished run (PARTIAL)" if earlier == PARTIAL else "an earlier run (summary.json)"
        raise UserError(str(out), "--out", f"holds {state}; pass --force to replace it, or name another folder with --out")
    result = run_scenario(scenario, out=out, perception=args.perception, seed=args.seed, overrides=overrides,
                          video=not args.no_video, progress=True, record_truth=args.record_truth, learn=args.learn)
    verdict = f"drank at t = {result.time_to_drink:.1f} s" if result.success else f"did not drink ({result.end_reason})"
    print(f"{scenario.name}: {verdict}; decisions: {', '.join(a for _, a in result.decisions) or '(none)'}")
    if not args.no_video:
        print(f"video: {out / 'video.mp4'}")
    print(f"inspector: {out / 'inspect.html'}")
    if args.learn is not None:
        print(f"learnt weights: {args.learn}")
    print(f"outputs: {out}/")
    return 0 if result.success else 1
