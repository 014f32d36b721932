"""The shipped agents as policies of `assistbot/Drinking-v0`: the field architecture and the state machine.

Both watch the world all the time, so they run the environment one perception tick per step
(``step_until="perception"``): each step's percept goes to the agent, a new decision becomes the action,
the utterances of its other layers are said through `DrinkingEnv.say`. Any `assistbot.interfaces.Agent`
fits.
"""

from __future__ import annotations

from typing import Any

from assistbot.agents import AGENTS
from assistbot.env.decision import ACTION_NAMES, DrinkingEnv


class AgentPolicy:
    """``policy(env) -> action``: the agent takes in the env's last percept and decides."""

    def __init__(self, agent: Any) -> None:
        self.agent = agent

    @classmethod
    def named(cls, name: str, seed: int = 0, overrides: dict[str, Any] | None = None) -> "AgentPolicy":
        """``dnf`` or ``fsm`` (`assistbot.agents.AGENTS`) with its own overrides (``cognition.*`` without the
        prefix)."""
        return cls(AGENTS[name](seed, dict(overrides or {})))

    @classmethod
    def for_env(cls, env: DrinkingEnv, agent: str | None = None) -> "AgentPolicy":
        """The agent `assistbot run` would make for the env's scenario and its current episode's seed (after
        `reset`): the scenario's ``agent:`` unless ``agent`` names another, with its ``cognition.*`` overrides."""
        from assistbot.agents import agent_factory
        from assistbot.episode.builder import split_overrides

        sc = env.scenario
        name = agent or sc.agent
        where = str(sc.path or sc.name)
        parts = split_overrides({**sc.overrides, **env.overrides}, where, name)
        return cls(agent_factory(name, where)(env.episode.seed, parts.cognition))

    def __call__(self, env: DrinkingEnv) -> int:
        decision = self.agent.update(env.percept)
        for u in decision.utterances:
            if u.layer != "AEL":   # the env says the action's own utterance when it decides it
                env.say(u.layer, u.item)
        if decision.new and decision.action:
            return ACTION_NAMES.index(decision.action)
        return 0
