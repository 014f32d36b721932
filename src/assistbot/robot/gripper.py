"""The three-finger gripper: open, close with bounded force, grasp sensing from its skin.

The finger servos (``robot_finger1..3``) are position actuators with a torque
limit (1.5 N m, about 20 N at a fingertip): commanding "closed" beyond the
contact squeezes with at most that force, which is the bound. That the hand
holds something is felt by its touch sensors (the MJCF's ``robot_*_touch``:
the normal force on the palm and on each finger link), as a real hand's
skin would: two fingers press, or a finger and the palm opposite. The hand
does not know *what* it holds; that follows from what it set out to grasp
and from what the cameras see (`assistbot.episode.executor`).
"""

from __future__ import annotations

import mujoco
import numpy as np

from assistbot.world import GRIPPER_CLOSED, GRIPPER_OPEN

FINGER_ACTUATORS = ("robot_finger1", "robot_finger2", "robot_finger3")
SPREAD_ACTUATOR = "robot_spread"
FINGER_JOINTS = ("robot_f1_prox", "robot_f2_prox", "robot_f3_prox")
#: the hand's parts and the touch sensors on each
TOUCH_SENSORS = {
    "f1": ("robot_f1_prox_touch", "robot_f1_dist_touch"),
    "f2": ("robot_f2_prox_touch", "robot_f2_dist_touch"),
    "f3": ("robot_f3_prox_touch", "robot_f3_dist_touch"),
    "palm": ("robot_palm_touch",),
}
#: N on a part for it to count as pressing, and in all for a grasp
PRESS_N = 0.05
GRASP_N = 0.5
#: rad: closing on nothing, each finger stops with its tip on the palm at about 1.18 rad, where the skin
#: feels the hand itself (tests/test_robot_gripper.py); all fingers past this angle hold nothing
EMPTY_CLOSED = 1.1
OPEN = GRIPPER_OPEN      # fingers splayed: the widest opening (the glass, 80 mm, fits)
CLOSED = GRIPPER_CLOSED  # beyond any grasp: the torque limit bounds the squeeze


def hand_extent(model: mujoco.MjModel) -> tuple[float, float]:
    """How far (m) the hand reaches above and below its TCP in a side grasp (the hand's z up), from the
    MJCF: the upper finger's outer edge (finger 1's base and its link's radius) and the palm's lower edge.
    What it grasps from the side lies between the two: the fingers close around nothing above the first."""
    tcp_z = float(model.site_pos[model.site("robot_tcp").id][2])
    above = float(model.body_pos[model.body("robot_f1_base").id][2] + model.geom_size[model.geom("robot_f1_prox").id][0])
    palm = model.geom("robot_palm").id
    below = float(model.geom_size[palm][2] - model.geom_pos[palm][2])
    return above - tcp_z, below + tcp_z


def middle_finger_reach(model: mujoco.MjModel) -> float:
    """How far (m) above the TCP the middle finger (finger 3, level with it in a side grasp) reaches: its
    link's radius, from the MJCF. A side grasp holds by that finger and the lower one while it stays on the
    wall; the upper finger may then close over the top."""
    f3 = model.body("robot_f3_prox").id
    return float(model.body_pos[f3][2] - model.site_pos[model.site("robot_tcp").id][2]
                 + model.geom_size[model.geom("robot_f3_prox").id][0])


class Gripper:
    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model, self.data = model, data
        self._act = np.array([model.actuator(n).id for n in FINGER_ACTUATORS])
        self._spread = model.actuator(SPREAD_ACTUATOR).id
        self._qadr = np.array([model.jnt_qposadr[model.joint(j).id] for j in FINGER_JOINTS])
        self._touch = {part: np.array([int(model.sensor(n).adr[0]) for n in names]) for part, names in TOUCH_SENSORS.items()}
        self.command: float | np.ndarray = OPEN   # one angle for all fingers, or one each while easing open
        ws = model.sensor("robot_wrist_force")
        self._wrist = slice(int(ws.adr[0]), int(ws.adr[0]) + 3)
        self._wrist_site = int(ws.objid[0])     # the sensor's frame: where the arm's joints put it
        self.reach_above, self.reach_below = hand_extent(model)
        self.middle_reach = middle_finger_reach(model)

    def open(self, amount: float = 1.0) -> None:
        """Open the fingers (amount 1: fully; 0.5: half way to closed)."""
        self.command = OPEN + (1.0 - amount) * (CLOSED - OPEN)
        self.data.ctrl[self._act] = self.command

    def ease_open(self, amount: float, start: np.ndarray) -> None:
        """Let go gently: each finger's command ``amount`` (0..1) of the way from ``start`` (its angles when
        letting go began) to fully open.  At 0 the fingers hold where they are and stop squeezing."""
        self.command = np.asarray(start, float) + float(amount) * (OPEN - np.asarray(start, float))
        self.data.ctrl[self._act] = self.command

    def idle_fingers(self) -> np.ndarray:
        """Which fingers closed onto the palm past what they hold: they touch nothing of it."""
        return self.finger_angles() > EMPTY_CLOSED

    def open_idle_fingers(self) -> None:
        """Open the fingers that hold nothing while the others keep squeezing: a finger curled past a
        held object may lie under it, where it tilts the object set down and kicks it when it opens."""
        self.command = np.where(self.idle_fingers(), OPEN, CLOSED)
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

    def pressure(self) -> dict[str, float]:
        """The normal force (N) each part of the hand feels: fingers f1, f2, f3 and the palm."""
        sd = self.data.sensordata
        return {part: float(sd[adr].sum()) for part, adr in self._touch.items()}

    def grasps(self) -> bool:
        """The hand holds something: two fingers press on it, or a finger and the palm opposite, and the
        fingers have not all closed onto the palm (the skin also feels the hand touching itself)."""
        if self.fully_closed():
            return False
        p = self.pressure()
        fingers = sum(p[f] > PRESS_N for f in ("f1", "f2", "f3"))
        return (fingers >= 2 or (fingers >= 1 and p["palm"] > PRESS_N)) and sum(p.values()) > GRASP_N

    def wrist_force(self) -> np.ndarray:
        """The wrist force-torque sensor's force (N, in the wrist frame): the hand's and its load's weight and pulls."""
        return self.data.sensordata[self._wrist].copy()

    def wrist_force_world(self) -> np.ndarray:
        """`wrist_force` turned into the world's axes by the wrist's orientation (the arm's own kinematics): the
        same load reads the same however the hand has turned."""
        return self.data.site_xmat[self._wrist_site].reshape(3, 3) @ self.wrist_force()

    def fully_closed(self) -> bool:
        """True when the fingers closed on nothing (all curled onto the palm)."""
        return bool(np.all(self.idle_fingers()))
