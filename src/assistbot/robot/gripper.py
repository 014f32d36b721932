"""The three-finger gripper: open, close with bounded force, grasp sensing from finger contacts.

The finger servos (``robot_finger1..3``) are position actuators with a torque
limit (1.5 N m, about 20 N at a fingertip): commanding "closed" beyond the
contact squeezes with at most that force, which is the bound. What the hand
holds is read from contacts, as a hand with touch sensors would: a body is
held when at least two different fingers touch it (palm contact counts as a
third side).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from assistbot.world import GRIPPER_CLOSED, GRIPPER_OPEN

FINGER_ACTUATORS = ("robot_finger1", "robot_finger2", "robot_finger3")
SPREAD_ACTUATOR = "robot_spread"
FINGER_JOINTS = ("robot_f1_prox", "robot_f2_prox", "robot_f3_prox")
FINGER_GEOMS = {
    "f1": ("robot_f1_prox", "robot_f1_dist"),
    "f2": ("robot_f2_prox", "robot_f2_dist"),
    "f3": ("robot_f3_prox", "robot_f3_dist"),
    "palm": ("robot_palm",),
}
OPEN = GRIPPER_OPEN      # fingers splayed: the widest opening (the glass, 80 mm, fits)
CLOSED = GRIPPER_CLOSED  # beyond any grasp: the torque limit bounds the squeeze


@dataclass
class Touch:
    """Per body touched by the hand: which parts touch it and the total normal force (N)."""

    body: str
    parts: frozenset[str]
    force: float

    @property
    def fingers(self) -> int:
        return len(self.parts - {"palm"})


class Gripper:
    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model, self.data = model, data
        self._act = np.array([model.actuator(n).id for n in FINGER_ACTUATORS])
        self._spread = model.actuator(SPREAD_ACTUATOR).id
        self._qadr = np.array([model.jnt_qposadr[model.joint(j).id] for j in FINGER_JOINTS])
        self._part_of_geom: dict[int, str] = {}
        for part, geoms in FINGER_GEOMS.items():
            for g in geoms:
                self._part_of_geom[model.geom(g).id] = part
        self._part_code = np.zeros(model.ngeom, dtype=np.int8)  # 1 for the hand's geoms
        self._part_code[list(self._part_of_geom)] = 1
        self.command = OPEN
        self._force = np.zeros(6)
        ws = model.sensor("robot_wrist_force")
        self._wrist = slice(int(ws.adr[0]), int(ws.adr[0]) + 3)

    def open(self, amount: float = 1.0) -> None:
        """Open the fingers (amount 1: fully; 0.5: half way to closed)."""
        self.command = OPEN + (1.0 - amount) * (CLOSED - OPEN)
        self.data.ctrl[self._act] = self.command

    def close(self) -> None:
        self.command = CLOSED
        self.data.ctrl[self._act] = CLOSED

    def set_spread(self, angle: float) -> None:
        self.data.ctrl[self._spread] = angle

    def apply(self) -> None:
        """Re-send the last command (call after anything else wrote ctrl)."""
        self.data.ctrl[self._act] = self.command

    def finger_angles(self) -> np.ndarray:
        return self.data.qpos[self._qadr].copy()

    def touches(self) -> list[Touch]:
        """Bodies in contact with the hand now, with the touching parts and the normal force."""
        m, d = self.model, self.data
        n = d.ncon
        if n == 0:
            return []
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        p1, p2 = self._part_code[g1], self._part_code[g2]
        # contacts between a hand part and something that is not the hand
        sel = np.flatnonzero((p1 > 0) != (p2 > 0))
        if sel.size == 0:
            return []
        parts: dict[int, set[str]] = {}
        force: dict[int, float] = {}
        for i in sel:
            mine, other = (g1[i], g2[i]) if p1[i] > 0 else (g2[i], g1[i])
            body = int(m.geom_bodyid[other])
            mujoco.mj_contactForce(m, d, int(i), self._force)
            parts.setdefault(body, set()).add(self._part_of_geom[int(mine)])
            force[body] = force.get(body, 0.0) + abs(float(self._force[0]))
        return [Touch(m.body(b).name, frozenset(p), force[b]) for b, p in parts.items()]

    def holding(self) -> str | None:
        """The body the hand grasps (two fingers or a finger and the palm opposite), else None."""
        best = None
        for t in self.touches():
            if (t.fingers >= 2 or (t.fingers >= 1 and "palm" in t.parts)) and t.force > 0.5:
                if best is None or t.force > best.force:
                    best = t
        return None if best is None else best.body

    def wrist_force(self) -> np.ndarray:
        """The wrist force-torque sensor's force (N, in the wrist frame): the hand's and its load's weight and pulls."""
        return self.data.sensordata[self._wrist].copy()

    def fully_closed(self) -> bool:
        """True when the fingers closed on nothing (all near the end of their range)."""
        return bool(np.all(self.finger_angles() > CLOSED - 0.25))
