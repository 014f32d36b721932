"""Retract: the hand back to rest."""

from __future__ import annotations

from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.reaching import retract_phases


class Retract(Primitive):
    """Back to the rest posture above the robot's side of the table (hand open unless carrying)."""

    name = "retract"

    def phases(self):
        return retract_phases()
