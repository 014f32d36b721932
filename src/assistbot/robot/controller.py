"""The robot's body in the physics: arm (IK -> position servos), gripper, head gaze, proprioception.

`RobotController.move_toward(pose, dt)` is called once per control tick
(about 50 Hz): one IK solve from the commanded configuration toward the TCP
pose, the result sent to the arm's position actuators. Targets deeper into
the human's workspace than the hand-over zone are clamped to its edge.
"""

from __future__ import annotations

from dataclasses import dataclass

import mink
import mujoco
import numpy as np

from assistbot.robot.gaze import gaze_angles
from assistbot.robot.gripper import Gripper
from assistbot.robot.ik import ArmIK, IKParams, IKResult
from assistbot.robot.ik_model import ARM_JOINTS

#: the hand-over zone reaches this far past the middle line into the HWS (m, table x); it contains
#: the place where the human holds objects out (assistbot.human.behaviours.HOLD_OUT, x = -0.05,
#: with the object's centre up to ~2 cm further back), so the TCP may go to x = -0.08
HANDOVER_DEPTH = 0.18
#: how far the open fingers reach beyond the TCP along the approach (m: 0.08 straight in the MJCF; 0.095 measured while closing at an angle)
OPEN_HAND_REACH = 0.10
#: the TCP never goes deeper into the HWS than this (table x): the fingertips stay in the zone
TCP_MIN_X = -(HANDOVER_DEPTH - OPEN_HAND_REACH)
#: the arm's reach from the shoulder to the TCP (m): 0.35 + 0.33 + 0.138, less a margin off the singular straight arm
REACH = 0.78


@dataclass
class Proprioception:
    q: np.ndarray          # arm joint angles (rad)
    tcp: mink.SE3          # TCP pose from the joint angles (world)
    grasping: bool         # the hand's skin feels a grasp (two fingers, or a finger and the palm)
    fingers: np.ndarray    # proximal finger angles (rad)


class RobotController:
    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, ik: ArmIK | None = None,
                 ik_params: IKParams | None = None) -> None:
        self.model, self.data = model, data
        self.ik = ik or ArmIK(ik_params)
        self._qadr = np.array([model.jnt_qposadr[model.joint(j).id] for j in ARM_JOINTS])
        self._act = np.array([model.actuator(j).id for j in ARM_JOINTS])
        self._pan = model.actuator("robot_head_pan").id
        self._tilt = model.actuator("robot_head_tilt").id
        self._head_site = model.site("robot_head_center").id
        self._tcp_site = model.site("robot_tcp").id
        self.gripper = Gripper(model, data)
        self.shoulder = self.ik.shoulder.copy()
        self.q_cmd = self.q().copy()
        self.last: IKResult | None = None

    def q(self) -> np.ndarray:
        return self.data.qpos[self._qadr].copy()

    def tcp_pose(self) -> mink.SE3:
        """Measured TCP pose in world (from the physics)."""
        pos = self.data.site_xpos[self._tcp_site].copy()
        rot = self.data.site_xmat[self._tcp_site].reshape(3, 3).copy()
        return mink.SE3.from_rotation_and_translation(mink.SO3.from_matrix(rot), pos)

    def commanded_tcp_pose(self) -> mink.SE3:
        return self.ik.tcp_pose(self.q_cmd)

    def reset_command(self) -> None:
        """Command the measured configuration (after a block or at start)."""
        self.q_cmd = self.q()
        self.data.ctrl[self._act] = self.q_cmd

    def move_toward(self, pose: mink.SE3, dt: float) -> IKResult:
        """One IK step toward ``pose`` (TCP in world); sends the result to the arm servos."""
        pos = pose.translation().copy()
        pos[0] = max(pos[0], TCP_MIN_X)
        pose = mink.SE3.from_rotation_and_translation(pose.rotation(), pos)
        # if the arm is held back (a contact), plan from where it is, not where it was told to be
        if np.max(np.abs(self.q() - self.q_cmd)) > 0.25:
            self.q_cmd = self.q()
        res = self.ik.solve(self.q_cmd, pose, dt)
        self.last = res
        if res.ok:
            self.q_cmd = res.q
        self.data.ctrl[self._act] = self.q_cmd
        return res

    def hold(self) -> None:
        self.data.ctrl[self._act] = self.q_cmd

    def look_at(self, point: np.ndarray) -> None:
        pan, tilt = gaze_angles(self.data.site_xpos[self._head_site], point)
        self.data.ctrl[self._pan] = pan
        self.data.ctrl[self._tilt] = tilt

    def proprioception(self) -> Proprioception:
        return Proprioception(self.q(), self.tcp_pose(), self.gripper.grasps(), self.gripper.finger_angles())


    def reach_distance(self, point: np.ndarray) -> float:
        """Distance (m) from the shoulder to a world point."""
        return float(np.linalg.norm(np.asarray(point, float) - self.shoulder))
