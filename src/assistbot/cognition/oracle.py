"""ORACLE perception: ground truth turned into a `Percept`, for debugging and for tests that isolate cognition.

This is not vision. It reads a ground-truth description (what the world
module knows, or what a percept timeline states) and reports it as if the
cameras had seen it perfectly: confidence 1 unless the description says
otherwise, objects and hand ``seen`` unless marked ``seen: false``.

Ground-truth description (all parts optional)::

    {"bottle": {"zone": "HWS", "state": "closed", "position": [x, y, z], "seen": True, "confidence": 1.0},
     "glass":  {"zone": "RWS", "state": "inverted", ...},
     "hand":   {"posture": "grasp_sg", "object_in_hand": "bottle", "held_out": True,
                "directed_at": None, "pointed_at": None, "position": [x, y, z], "seen": True},
     "robot":  {"holding": None, "action": None, "status": "idle"}}
"""

from __future__ import annotations

from typing import Any, Mapping

from assistbot import task
from assistbot.cognition.percept import HandPercept, ObjectPercept, Percept, RobotPercept

ORACLE_LABEL = "oracle perception (ground truth, not vision)"

OBJECT_KEYS = ("zone", "state", "position", "seen", "confidence", "lying")
HAND_KEYS = ("posture", "object_in_hand", "held_out", "directed_at", "pointed_at", "position", "seen", "confidence")
ROBOT_KEYS = ("holding", "action", "status")


def _pos(v: Any) -> tuple[float, float, float]:
    if v is None:
        return (0.0, 0.0, 0.0)
    x = [float(a) for a in v]
    if len(x) != 3:
        raise ValueError(f"a position is [x, y, z] in metres, got {v!r}")
    return (x[0], x[1], x[2])


def oracle_percept(t: float, truth: Mapping[str, Mapping[str, Any]]) -> Percept:
    """ORACLE: a perfect `Percept` at time ``t`` from a ground-truth description (see module docstring).

    Raises ValueError naming the bad value.
    """
    objects: dict[str, ObjectPercept] = {}
    for obj in task.OBJECTS:
        d = truth.get(obj)
        if d is None:
            continue
        objects[obj] = ObjectPercept(
            type=obj, zone=d.get("zone", "HWS"), state=d.get("state", task.OBJECT_STATES[obj][0]),
            position=_pos(d.get("position")), confidence=float(d.get("confidence", 1.0)), seen=bool(d.get("seen", True)),
            lying=bool(d.get("lying", False)),
        )
    hd = truth.get("hand", {}) or {}
    hand = HandPercept(
        posture=hd.get("posture", "none"), object_in_hand=hd.get("object_in_hand"), held_out=bool(hd.get("held_out", False)),
        directed_at=hd.get("directed_at"), pointed_at=hd.get("pointed_at"),
        position=_pos(hd.get("position", (0.0, -0.4, 0.1))), confidence=float(hd.get("confidence", 1.0)), seen=bool(hd.get("seen", True)),
    )
    rd = truth.get("robot", {}) or {}
    robot = RobotPercept(holding=rd.get("holding"), action=rd.get("action"), status=rd.get("status", "idle"))
    return Percept(t=float(t), objects=objects, hand=hand, robot=robot).validate()
