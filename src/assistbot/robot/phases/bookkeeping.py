"""Phases that only note something for the primitive, without moving: what it carries, where it took from."""

from __future__ import annotations

from assistbot.interfaces import Status
from assistbot.robot.phases.base import Phase


class SetCarrying(Phase):
    """Marks the end of carrying (after a release) without moving."""

    def __init__(self, carrying: bool) -> None:
        self.carrying, self.name = carrying, "release done"

    def tick(self, prim, dt, t):
        prim.carrying = self.carrying
        prim.robot.hold()
        return Status.SUCCEEDED, ""


class RememberPlace(Phase):
    """Remember where the object stood (for putting it back) before it is lifted."""

    name = "remember place"

    def tick(self, prim, dt, t):
        prim.home_xy = prim.xy().copy()
        prim.robot.hold()
        return Status.SUCCEEDED, ""


class HoldAt(Phase):
    """From here on the hand takes its object ``height`` m above the object's base (`Primitive.held_at`)."""

    name = "hold at"

    def __init__(self, height: float) -> None:
        self.height = height

    def tick(self, prim, dt, t):
        prim.held_at = self.height
        prim.robot.hold()
        return Status.SUCCEEDED, ""
