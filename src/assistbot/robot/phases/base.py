"""The phase: one step of a motion primitive (move the hand, close or open it, wait for something).

A primitive starts its phases one after the other (``start(prim)``) and ticks the running one once
per control tick (``tick(prim, dt, t)``) until it ends. A phase acts through the primitive that runs
it: its robot, the object it acts on, its perception callbacks.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import TYPE_CHECKING, Callable

from assistbot.interfaces import Status

if TYPE_CHECKING:
    from assistbot.robot.primitives import Primitive


class Phase(ABC):
    """One step of a primitive. ``fallback(prim)``, when a phase has one, gives the phases that end the
    primitive safely after that phase failed (setting down what the hand holds, say); the primitive then
    runs them and still reports the failure."""

    name = "phase"
    timeout = 5.0
    fallback: Callable[["Primitive"], list["Phase"]] | None = None
    #: set by ``start`` when there is nothing to do here (an upright hand to unroll): the primitive goes
    #: straight on to the next phase in the same tick, so such a phase costs no time
    idle = False

    def start(self, prim: "Primitive") -> None:
        pass

    @abstractmethod
    def tick(self, prim: "Primitive", dt: float, t: float) -> tuple[Status, str]:
        """Advance by ``dt`` (s), ``t`` s after the phase started: the status and, when it failed, why."""
