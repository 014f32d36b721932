"""ReachAndGrasp: reach an object standing in the RWS from the side and grasp it."""

from __future__ import annotations

from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.reaching import reach_and_grasp_phases


class ReachAndGrasp(Primitive):
    """Reach the object from the side and grasp it (ends holding it, on the table)."""

    name = "reach_and_grasp"

    def phases(self):
        return reach_and_grasp_phases(self)
