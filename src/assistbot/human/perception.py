"""What the human sees of the robot: its visible state, never its internals.

A person at the table sees whether the robot's gripper has an object in it, whether the
robot's hand is held out toward him (near the middle line, in the hand-over zone), and
whether that hand is open and empty.  `see_robot` computes exactly that from the scene's
ground truth (positions and contacts that a person's eyes would give), and nothing of the
robot's cognition, plans or commands.  Tests may pass another callable with the same
signature (e.g. for a stand-in robot).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from assistbot.world.layout import HANDOVER_ZONE_X

OPEN_FINGERS = 0.3   # rad, finger flexion below which the robot's hand looks open
SHOULDER_BODY = "robot_link1"   # the robot's shoulder: where its arm comes from, as a person sees it


@dataclass(frozen=True)
class RobotView:
    """The robot as the human sees it."""

    holds: str | None                  # object in the robot's hand ("bottle"/"glass") or None
    hand_pos: tuple[float, float, float]
    held_out: bool                     # the hand is near the middle line, toward the human
    open_hand: bool                    # the hand is open and empty
    shoulder: tuple[float, float, float] = (0.62, 0.2, 1.2)   # where the robot's arm comes from

    @property
    def offers(self) -> str | None:
        """An object held out toward the human."""
        return self.holds if self.held_out else None

    @property
    def requests(self) -> bool:
        """An open empty hand held out toward the human."""
        return self.held_out and self.open_hand and self.holds is None


def held_out_x(x: float) -> bool:
    """The robot's hand at table x is held out toward the person: in the hand-over zone, not at work at
    the robot's own places."""
    return bool(HANDOVER_ZONE_X[0] < x < HANDOVER_ZONE_X[1])


_INDEX: "weakref.WeakKeyDictionary[object, tuple[int, np.ndarray]]" = weakref.WeakKeyDictionary()


def _index(world) -> tuple[int, np.ndarray, int]:
    """(tcp site id, finger joint qpos addresses, shoulder body id) of a world, looked up once."""
    got = _INDEX.get(world)
    if got is None:
        m = world.model
        qadr = np.array([m.jnt_qposadr[m.actuator_trnid[m.actuator(a).id, 0]]
                         for a in ("robot_finger1", "robot_finger2", "robot_finger3")])
        got = _INDEX[world] = (world.site_id["robot_tcp"], qadr, m.body(SHOULDER_BODY).id)
    return got


def see_robot(world) -> RobotView:
    tcp_id, finger_qadr, shoulder_id = _index(world)
    d = world.data
    tcp = d.site_xpos[tcp_id]
    holds = world.robot_holding()
    return RobotView(holds, (float(tcp[0]), float(tcp[1]), float(tcp[2])), held_out_x(tcp[0]),
                     bool(holds is None and float(d.qpos[finger_qadr].max()) < OPEN_FINGERS),
                     tuple(float(v) for v in d.xpos[shoulder_id]))
