"""Makes an episode's parts from a scenario: the world, the perception, the agent, the actor, the partner, the task.

The one place that names the concrete parts. The agent is chosen by the scenario's ``agent:`` key
(`assistbot.agents`: a word such as ``dnf``, or ``package.module:factory`` for an agent of one's own).
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import Any

from assistbot.agents import agent_factory
from assistbot.episode.drinking_task import DrinkingTask
from assistbot.episode.perturb import PERTURB_PARAMS, Perturbation, PerturbedPerception, check_perturb_value
from assistbot.episode.runner import Episode
from assistbot.errors import UserError
from assistbot.interfaces import CONTROL_DT, Perception
from assistbot.scenario import VISION_PARAMS, Scenario, check_vision_value

PERCEPTIONS = ("vision", "oracle")


@dataclass
class Overrides:
    """A scenario's overrides by the part they go to (each without its prefix, but ``perturb``)."""

    cognition: dict[str, Any] = field(default_factory=dict)   # the agent's parameters
    human: dict[str, Any] = field(default_factory=dict)
    vision: dict[str, Any] = field(default_factory=dict)
    perturb: dict[str, float] = field(default_factory=dict)


def override_paths() -> list[str]:
    """Every dotted path an override may name (``cognition.*`` as the field architecture has them)."""
    from assistbot.cognition.config import CognitionConfig
    from assistbot.human.script import PARAMS as HUMAN_PARAMS

    return (["cognition." + p for p in CognitionConfig().paths()] + [f"human.{p}" for p in HUMAN_PARAMS]
            + list(VISION_PARAMS) + list(PERTURB_PARAMS))


def split_overrides(overrides: dict[str, Any], where: str, agent: str = "dnf") -> Overrides:
    """Dotted paths -> the parts' overrides; an unknown path names the closest valid ones. ``cognition.*``
    paths are the field architecture's, checked here for ``agent`` dnf; another agent's factory checks its own."""
    from assistbot.cognition.config import check_overrides as check_cognition
    from assistbot.human.script import PARAMS as HUMAN_PARAMS, check_param as check_human_param

    out = Overrides()
    valid = override_paths()
    cog_paths = [p for p in valid if p.startswith("cognition.")]
    for path, value in overrides.items():
        if path.startswith("cognition.") and agent != "dnf":
            out.cognition[path[len("cognition."):]] = value
        elif path in cog_paths:
            out.cognition[path[len("cognition."):]] = value
        elif path.startswith("human.") and path[6:] in HUMAN_PARAMS:
            out.human[path[6:]] = check_human_param(path[6:], value, where)
        elif path in VISION_PARAMS:
            out.vision[VISION_PARAMS[path]] = check_vision_value(path, value, where)
        elif path in PERTURB_PARAMS:
            out.perturb[path[len("perturb."):]] = check_perturb_value(path, value, where)
        else:
            close = difflib.get_close_matches(path, valid, n=3)
            raise UserError(where, path, "unknown parameter path" + (f"; did you mean {', '.join(close)}?" if close else ""))
    if agent == "dnf" and out.cognition:
        check_cognition(out.cognition, where)
    return out


def build_episode(scenario: Scenario, perception: str = "vision", seed: int | None = None,
                  overrides: dict[str, Any] | None = None, frame_every: float | None = None,
                  record_truth: bool = False) -> Episode:
    """The episode of ``scenario``: ``perception`` "vision" (the robot's cameras) or "oracle" (labelled
    ground truth); ``seed`` and ``overrides`` (dotted paths) on top of the scenario's own. ``record_truth``:
    the log also keeps the oracle's percept beside vision's, for the experimenter (the agent never sees it)."""
    from assistbot.episode.cues import CueLedger
    from assistbot.episode.executor import RobotExecutor
    from assistbot.human.controller import HumanController
    from assistbot.human.population import Partner
    from assistbot.human.script import HumanConfig
    from assistbot.world import build_world

    if perception not in PERCEPTIONS:
        raise UserError("--perception", perception, f"use {' or '.join(PERCEPTIONS)}")
    where = str(scenario.path or scenario.name)
    seed = scenario.seed if seed is None else int(seed)
    overrides = {**scenario.overrides, **(overrides or {})}
    parts = split_overrides(overrides, where, scenario.agent)
    make_agent = agent_factory(scenario.agent, where)
    hc: HumanConfig = scenario.human
    if parts.human:
        hc = HumanConfig(hc.profile, {**hc.overrides, **parts.human}, hc.script)
    world = build_world(scenario.objects, seed=seed, body=hc.partner.body)
    partner = HumanController(world, config=hc, seed=seed, dt=CONTROL_DT)
    actor = RobotExecutor(world)
    agent = make_agent(seed, parts.cognition)
    seeing: Perception
    if perception == "oracle":
        from assistbot.episode.oracle import OraclePerception

        seeing = OraclePerception(world, partner.appearance)
    else:
        from assistbot.episode.vision_perception import VisionPerception

        seeing = VisionPerception(world, seed=seed, **parts.vision)
    perturbation = Perturbation(**parts.perturb)
    if perturbation.active:
        seeing = PerturbedPerception(seeing, perturbation, seed)
    truth = None
    if record_truth and perception != "oracle":
        from assistbot.episode.oracle import OraclePerception

        truth = OraclePerception(world, partner.appearance)
    return Episode(scenario, seed, world, seeing, agent, actor, partner, DrinkingTask(world, scenario.time_limit),
                   overrides=overrides, frame_every=frame_every, truth=truth, measures=(CueLedger(),),
                   person=hc.partner.to_dict() if hc.partner != Partner() else None)
