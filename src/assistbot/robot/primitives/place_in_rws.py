"""PlaceInRWS: grasp an object, carry it and put it down upright at a spot in the RWS."""

from __future__ import annotations

import numpy as np

from assistbot.robot.phases import Move
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import LIFT, side_grasp_pose
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, retract_phases


class PlaceInRWS(Primitive):
    """Grasp the object and put it down at ``spot`` (table x, y in the RWS), then let go and back off."""

    name = "place"

    def __init__(self, robot, obj, spot=(0.25, 0.0), **kw):
        super().__init__(robot, obj, **kw)
        self.spot = np.array(spot, float)

    def phases(self):
        return (reach_and_grasp_phases(self) + [Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2)]
                + put_down_at(lambda p: p.spot) + retract_phases())
