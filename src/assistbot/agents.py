"""The agents a scenario's ``agent:`` key can name: a word from `AGENTS`, or ``package.module:factory``.

An agent factory takes ``(seed, overrides)`` -- the scenario's ``cognition.*`` overrides without the prefix --
and returns an `assistbot.interfaces.Agent`. This module imports no agent until one is made, so that
reading a scenario file stays cheap.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable

from assistbot.errors import UserError
from assistbot.interfaces import Agent

AgentFactory = Callable[[int, dict[str, Any]], Agent]


def _dnf_agent(seed: int, overrides: dict[str, Any]) -> Agent:
    from assistbot.cognition import Cognition

    return Cognition(overrides=overrides or None, seed=seed)


def _fsm_agent(seed: int, overrides: dict[str, Any]) -> Agent:
    from assistbot.statemachine.agent import fsm_agent

    return fsm_agent(seed, overrides)


#: the agents a scenario names by a word (``dnf``: the seed's field architecture; ``fsm``: the state-machine
#: baseline, `assistbot.statemachine`)
AGENTS: dict[str, AgentFactory] = {"dnf": _dnf_agent, "fsm": _fsm_agent}


def agent_factory(spec: str, where: str) -> AgentFactory:
    """The factory for a scenario's ``agent:`` value; an unknown one is a `UserError` saying what is allowed."""
    if spec in AGENTS:
        return AGENTS[spec]
    module, sep, attr = spec.partition(":")
    if sep and module and attr:
        try:
            factory = getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError) as exc:
            raise UserError(where, "agent", f"cannot load {spec!r}: {exc}") from None
        if callable(factory):
            return factory
    raise UserError(where, "agent", f"{spec!r}: use one of {', '.join(AGENTS)}, or package.module:factory")
