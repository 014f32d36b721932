"""Makes an episode's parts from a scenario: the world, the perception, the agent, the actor, the partner, the task.

The one place that names the concrete parts. The agent is chosen by the scenario's ``agent:`` key
(`assistbot.agents`: a word such as ``dnf``, or ``package.module:factory`` for an agent of one's own).
"""

from __future__ import annotations

import difflib
from typing import Any

from assistbot.agents import agent_factory
from assistbot.episode.drinking_task import DrinkingTask
from assistbot.episode.runner import Episode
from assistbot.errors import UserError
from assistbot.interfaces import CONTROL_DT, Perception
from assistbot.scenario import VISION_PARAMS, Scenario, check_vision_value

PERCEPTIONS = ("vision", "oracle")


def split_overrides(overrides: dict[str, Any], where: str) -> tuple[dict, dict, dict]:
    """Dotted paths -> (cognition, human, vision) overrides; an unknown path names the closest valid ones."""
    from assistbot.cognition.config import CognitionConfig
    from assistbot.human.script import PARAMS as HUMAN_PARAMS

    cog, hum, vis = {}, {}, {}
    cog_paths = ["cognition." + p for p in CognitionConfig().paths()]
    valid = cog_paths + [f"human.{p}" for p in HUMAN_PARAMS] + list(VISION_PARAMS)
    for path, value in overrides.items():
        if path in cog_paths:
            try:
                CognitionConfig().set(path[len("cognition."):], value)
            except UserError as exc:
                raise UserError(where, path, exc.message) from None
            cog[path[len("cognition."):]] = value
        elif path.startswith("human.") and path[6:] in HUMAN_PARAMS:
            hum[path[6:]] = value
        elif path in VISION_PARAMS:
            vis[VISION_PARAMS[path]] = check_vision_value(path, value, where)
        else:
            close = difflib.get_close_matches(path, valid, n=3)
            raise UserError(where, path, "unknown parameter path" + (f"; did you mean {', '.join(close)}?" if close else ""))
    return cog, hum, vis


def build_episode(scenario: Scenario, perception: str = "vision", seed: int | None = None,
                  overrides: dict[str, Any] | None = None, frame_every: float | None = None) -> Episode:
    """The episode of ``scenario``: ``perception`` "vision" (the robot's cameras) or "oracle" (labelled
    ground truth); ``seed`` and ``overrides`` (dotted paths) on top of the scenario's own."""
    from assistbot.episode.executor import RobotExecutor
    from assistbot.human.controller import HumanController
    from assistbot.human.script import HumanConfig
    from assistbot.world import build_world

    if perception not in PERCEPTIONS:
        raise UserError("--perception", perception, f"use {' or '.join(PERCEPTIONS)}")
    where = str(scenario.path or scenario.name)
    seed = scenario.seed if seed is None else int(seed)
    overrides = {**scenario.overrides, **(overrides or {})}
    cog_o, hum_o, vis_o = split_overrides(overrides, where)
    make_agent = agent_factory(scenario.agent, where)
    world = build_world(scenario.objects, seed=seed)
    hc: HumanConfig = scenario.human
    if hum_o:
        hc = HumanConfig(hc.profile, {**hc.overrides, **hum_o}, hc.script)
    partner = HumanController(world, config=hc, seed=seed, dt=CONTROL_DT)
    actor = RobotExecutor(world)
    agent = make_agent(seed, cog_o)
    seeing: Perception
    if perception == "oracle":
        from assistbot.episode.oracle import OraclePerception

        seeing = OraclePerception(world, partner.appearance)
    else:
        from assistbot.episode.vision_perception import VisionPerception

        seeing = VisionPerception(world, seed=seed, **vis_o)
    return Episode(scenario, seed, world, seeing, agent, actor, partner, DrinkingTask(world, scenario.time_limit),
                   overrides=overrides, frame_every=frame_every)
