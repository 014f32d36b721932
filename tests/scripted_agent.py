"""An agent without fields, for the tests of the episode's interfaces: it carries out a fixed list of robot
actions, one after the other, each once the previous one has been reported ended. It says each action's
AEL utterance as it decides, as the DNF agent does. Named in a scenario as ``agent: scripted_agent:fill_and_hand_over``."""

from __future__ import annotations

from typing import Any

from assistbot.cognition.percept import Decision, Percept, Said
from assistbot.task import UTTERANCES


class ScriptedAgent:
    def __init__(self, actions: list[str]) -> None:
        self.todo = list(actions)
        self.doing: str | None = None
        self.history: list[tuple[float, str, str]] = []
        self._t = 0.0

    def update(self, percept: Percept) -> Decision:
        self._t = percept.t
        released = None
        if self.doing is not None and percept.robot.status.ended and percept.robot.action == self.doing:
            self.history.append((percept.t, f"release ({percept.robot.status.value})", self.doing))
            released, self.doing = self.doing, None
        if self.doing is None and self.todo:
            self.doing = self.todo.pop(0)
            self.history.append((percept.t, "decide", self.doing))
            u = UTTERANCES["AEL"][self.doing]
            return Decision(percept.t, action=self.doing, new=True, released=released,
                            utterances=[Said(percept.t, u.layer, u.item, u.text, u.tag)])
        return Decision(percept.t, action=self.doing, released=released)

    def between(self, t: float) -> Decision:
        return Decision(t, action=self.doing)

    def decisions(self) -> list[tuple[float, str, str]]:
        return list(self.history)

    def trace(self) -> dict[str, Any]:
        return {"doing": self.doing}


def fill_and_hand_over(seed: int, overrides: dict[str, Any]) -> ScriptedAgent:
    if overrides:
        raise ValueError("the scripted agent has no parameters")
    return ScriptedAgent(["Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over", "Suggest-drink"])
