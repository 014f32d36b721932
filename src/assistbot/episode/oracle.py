"""ORACLE perception for episodes: the world's ground truth turned into a `Percept`.

For debugging and for tests that isolate cognition from vision; every output
of an oracle run says so (`ORACLE_LABEL`). Vision produces the same Percept
from the robot's cameras.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from assistbot import catalogue
from assistbot.cognition.oracle import ORACLE_LABEL, oracle_percept
from assistbot.cognition.percept import Percept, RobotPercept
from assistbot.interfaces import PartnerView
from assistbot.world import TABLE_Z
from assistbot.world.layout import HANDOVER_ZONE_X
from assistbot.world.state import standing_end

__all__ = ["ORACLE_LABEL", "OraclePerception"]


def _hand_truth(world, partner: PartnerView) -> dict:
    """The hand posture a perfect observer would name, from what the person does and what the hand holds."""
    hand = world.site_pos("human_r_grasp")
    xyz = [float(hand[0]), float(hand[1]), float(hand[2] - TABLE_Z)]
    holding = world.human_holding()
    if holding not in catalogue.TASK_OBJECTS:
        holding = None  # the stopper in hand is part of removing it, not an object of the task
    posture, behaviour, args = partner.posture, partner.behaviour, partner.args
    out: dict = {"position": xyz, "posture": "none", "object_in_hand": holding}
    if behaviour == "pull_stopper":
        out["posture"] = "remove_stopper"
    elif behaviour == "drink" and holding == "glass":
        out["posture"] = "drink"
    elif behaviour == "pour" and holding == "bottle" and world.data.xmat[world.body_id["bottle"]][8] < 0.8:
        out["posture"] = "pour"        # the bottle tilted, not while it is still being grasped or put back
    elif holding is not None and posture in ("ag", "sg"):
        out["posture"] = "grasp_ag" if posture == "ag" else "grasp_sg"
    elif posture == "request":
        out["posture"] = "open_palm_request"
    elif posture == "point":
        out["posture"] = "pointing"
        out["pointed_at"] = args.get("object")
    elif behaviour in ("grasp", "hand_to_robot", "take_from_robot") and holding is None and args.get("object"):
        out["posture"] = "reach"
        out["directed_at"] = args.get("object")
    out["held_out"] = bool(xyz[0] > HANDOVER_ZONE_X[0] and (holding is not None or out["posture"] == "open_palm_request"))
    return out


class OraclePerception:
    """ORACLE: reads WorldState and what the person is seen to do (``partner_view``, the `Partner`'s
    `PartnerView`); never used by vision runs."""

    name = "oracle"
    label = ORACLE_LABEL
    render_seconds = 0.0   # it draws no images

    def __init__(self, world, partner_view: Callable[[], PartnerView]) -> None:
        self.world = world
        self.partner_view = partner_view

    def perceive(self, t: float, robot: RobotPercept) -> Percept:
        s = self.world.state()
        tz = TABLE_Z
        truth: dict = {"robot": {"holding": robot.holding, "action": robot.action, "status": robot.status},
                       "hand": _hand_truth(self.world, self.partner_view())}
        for name in catalogue.TASK_OBJECTS:
            o = s.objects[name]
            pos = standing_end(self.world, name)   # as vision places it: an inverted glass stands on its rim
            truth[name] = {
                "zone": o.zone,
                "state": s.state_of(name),
                "position": [float(pos[0]), float(pos[1]), float(pos[2] - tz)],
                # on its side on the table, in no one's hand
                "lying": bool(not (o.upright or o.inverted) and o.held_by is None),
            }
        return oracle_percept(t, truth)

    def overlay(self) -> np.ndarray | None:
        return None

    def close(self) -> None:
        pass
