"""assistbot.statemachine: a finite-state controller for the drinking task, the baseline the field
architecture is compared with (``agent: fsm`` in a scenario). Same Percept in, same Decision out."""

from assistbot.statemachine.agent import Phase, StateMachineAgent, StateMachineConfig, fsm_agent

__all__ = ["Phase", "StateMachineAgent", "StateMachineConfig", "fsm_agent"]
