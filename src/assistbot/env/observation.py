"""A `Percept` as a fixed-size vector: what the robot perceives (or, in oracle mode, is told), never more.

One slot per fact, named (``OBSERVATION_NAMES``), built from the task's own lists (objects, states, zones,
hand postures, robot actions), so a new state or posture changes the layout with them. Positions are in
metres in the table frame; one-hot groups hold 1 for the value present; ``t`` is the time (s) of the
percept, scaled by the time limit so that every slot lies in [-2, 2].
"""

from __future__ import annotations

import numpy as np

from assistbot.cognition.percept import ROBOT_STATUSES, Percept
from assistbot.task import AEL_ITEMS, HAND_POSTURES, OBJECT_STATES, OBJECTS, ZONES

#: bounds of every slot: positions in metres within the robot's reach of the table, the rest in [0, 1]
LOW, HIGH = -2.0, 2.0


def _names() -> list[str]:
    names: list[str] = ["t"]
    for obj in OBJECTS:
        names += [f"{obj}.seen", f"{obj}.state_seen", f"{obj}.lying", f"{obj}.confidence",
                  f"{obj}.x", f"{obj}.y", f"{obj}.z"]
        names += [f"{obj}.zone={z}" for z in ZONES]
        names += [f"{obj}.state={s}" for s in OBJECT_STATES[obj]]
    names += ["hand.seen", "hand.held_out", "hand.confidence", "hand.x", "hand.y", "hand.z"]
    names += [f"hand.posture={p}" for p in HAND_POSTURES]
    for slot in ("object_in_hand", "directed_at", "pointed_at"):
        names += [f"hand.{slot}={o}" for o in ("none", *OBJECTS)]
    names += [f"robot.holding={o}" for o in ("none", *OBJECTS)]
    names += [f"robot.action={a}" for a in ("none", *AEL_ITEMS)]
    names += [f"robot.status={s}" for s in ROBOT_STATUSES]
    return names


OBSERVATION_NAMES: tuple[str, ...] = tuple(_names())
_INDEX = {n: i for i, n in enumerate(OBSERVATION_NAMES)}


def encode(percept: Percept, time_limit: float) -> np.ndarray:
    """The percept as a float32 vector laid out as ``OBSERVATION_NAMES``."""
    v = np.zeros(len(OBSERVATION_NAMES), dtype=np.float32)

    def put(name: str, value: float) -> None:
        v[_INDEX[name]] = value

    put("t", min(percept.t / time_limit, 1.0))
    for obj in OBJECTS:
        o = percept.objects.get(obj)
        if o is None:
            continue
        put(f"{obj}.seen", float(o.seen))
        put(f"{obj}.state_seen", float(o.state_seen))
        put(f"{obj}.lying", float(o.lying))
        put(f"{obj}.confidence", float(np.clip(o.confidence, 0.0, 1.0)))
        for axis, value in zip("xyz", o.position):
            put(f"{obj}.{axis}", float(np.clip(value, LOW, HIGH)))
        put(f"{obj}.zone={o.zone}", 1.0)
        if o.state:
            put(f"{obj}.state={o.state}", 1.0)
    h = percept.hand
    put("hand.seen", float(h.seen))
    put("hand.held_out", float(h.held_out))
    put("hand.confidence", float(np.clip(h.confidence, 0.0, 1.0)))
    for axis, value in zip("xyz", h.position):
        put(f"hand.{axis}", float(np.clip(value, LOW, HIGH)))
    put(f"hand.posture={h.posture}", 1.0)
    for slot in ("object_in_hand", "directed_at", "pointed_at"):
        put(f"hand.{slot}={getattr(h, slot) or 'none'}", 1.0)
    r = percept.robot
    put(f"robot.holding={r.holding or 'none'}", 1.0)
    put(f"robot.action={r.action or 'none'}", 1.0)
    put(f"robot.status={getattr(r.status, 'value', r.status)}", 1.0)
    return v
