"""`assistbot list`: the shipped scenarios with their arrangements and users."""

from __future__ import annotations

import argparse

NAME = "list"
HELP = "list the shipped scenarios"
ORDER = 5


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("-v", "--verbose", action="store_true", help="also print each description")


def run(args: argparse.Namespace) -> int:
    from assistbot.errors import UserError
    from assistbot.resources import SCENARIOS
    from assistbot.scenario import load_scenario, shipped_scenarios

    paths = shipped_scenarios()
    if not paths:   # an installation without its data: say so rather than list nothing
        raise UserError(str(SCENARIOS), "scenarios", "no shipped scenario found; reinstall assistbot")
    for path in paths:
        s = load_scenario(path)
        b, g = s.objects.bottle, s.objects.glass
        script = f", script of {len(s.human.script)} steps" if s.human.script else ""
        print(f"{s.name:<28} bottle {b.zone} {b.state:<6} glass {g.zone} {g.state:<8} user {s.human.profile}{script}")
        if args.verbose and s.description:
            print(f"    {' '.join(s.description.split())}")
    return 0
