"""Holding still: for a fixed time, or until a condition holds."""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

from assistbot.interfaces import Status
from assistbot.robot.phases.base import Phase

if TYPE_CHECKING:
    from assistbot.robot.primitives import Primitive


class Wait(Phase):
    """Hold still for ``seconds`` (liquid settling, a fixed pour time)."""

    def __init__(self, name: str, seconds: float) -> None:
        self.name, self.seconds, self.timeout = name, seconds, seconds + 1.0

    def tick(self, prim, dt, t):
        prim.robot.hold()
        return (Status.SUCCEEDED, "") if t >= self.seconds else (Status.RUNNING, "")


class WaitFor(Phase):
    """Hold still until ``condition(prim)`` is true: failing with ``reason`` after ``timeout`` s, or, with no
    reason, going on then either way (a wait that is only patience)."""

    def __init__(self, name: str, condition: Callable[["Primitive"], bool], timeout: float, reason: str | None) -> None:
        self.name, self.condition, self.timeout, self.reason = name, condition, timeout, reason

    def tick(self, prim, dt, t):
        prim.robot.hold()
        if self.condition(prim) or (t >= self.timeout and self.reason is None):
            return Status.SUCCEEDED, ""
        if t >= self.timeout:
            return Status.FAILED, f"{self.name}: {self.reason} within {self.timeout:.0f} s"
        return Status.RUNNING, ""
