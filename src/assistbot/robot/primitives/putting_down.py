"""The phases that put what the hand holds down on the table, and a failed action's safe end with them."""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from assistbot.robot.phases import BackOff, FreeIdleFingers, LowerUntilSupported, Move, Open, Phase, RiseClear, SetCarrying
from assistbot.robot.primitives.carry_over import CarryOver
from assistbot.robot.primitives.geometry import LIFT, grasp_pose_at, half_turn
from assistbot.robot.primitives.places import free_rws_spot
from assistbot.robot.primitives.reaching import retract_phases
from assistbot.world.layout import TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: m above the table that a put-down goes to by position before lowering the rest of the way by feel:
#: an object is not always held at the height assumed (one taken from the person's hand)
SET_DOWN_ABOVE = 0.025


def put_down_at(xy_of: Callable[[Primitive], np.ndarray], lift: float = LIFT) -> list[Phase]:
    """Carry the held object (upright, the hand keeping its half turn) above a table spot, lower it onto
    the table, let go, back off (first up clear of its top, if held above its wall: `RiseClear`)."""

    def at(p, up):
        x, y = xy_of(p)
        c = np.array([x, y, TABLE_Z + p.grasp_height + up])
        return grasp_pose_at(p, c, p.object, roll=half_turn(p))
    return [
        FreeIdleFingers(),
        CarryOver(lambda p: at(p, lift)),
        Move("carry", lambda p: at(p, lift), duration=1.8),
        # down to just above where the object would touch if held as assumed (held higher, it touches sooner and
        # the hand stops above that); the rest by feel
        Move("put down", lambda p: at(p, SET_DOWN_ABOVE), duration=1.2, tolerance=0.025, may_stop_above=True),
        LowerUntilSupported(),
        Open("release"), SetCarrying(False),
        RiseClear(), BackOff(),
    ]


def set_down_what_is_carried(p: Primitive) -> list[Phase]:
    """A failed action's safe end while the hand holds something: put it down at a free spot in the RWS
    and withdraw."""
    return put_down_at(free_rws_spot) + retract_phases()
