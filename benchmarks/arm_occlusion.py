"""How much of the robot's workspace its own arm hides from its head cameras, with the hand at the ready pose
(where a reach starts) and at the rest pose (where it waits between actions).

Run: MUJOCO_GL=egl .venv/bin/python benchmarks/arm_occlusion.py

A grid of points 5 cm above the robot's half of the table (x 0-0.42 m, y -0.3-0.3 m) is projected into both
head cameras' segmentation images while the head looks at the middle of that half and at the middle line; a
point counts as hidden when either camera sees a robot geom there or does not see it at all (stereo needs
both). The grid's outer corners fall outside the cameras' view at any pose of the arm: that share is the
floor no rest pose can go below.
"""

from __future__ import annotations

import mink
import mujoco
import numpy as np

from assistbot.robot import poses
from assistbot.robot.controller import RobotController
from assistbot.robot.gaze import gaze_angles
from assistbot.robot.primitives.reaching import READY_POSE_POS, REST_POSE_POS
from assistbot.world import Arrangement, build_world
from assistbot.world.layout import TABLE_Z

W, H = 320, 240
CAMERAS = ("head_cam_left", "head_cam_right")
LOOKS = {"the robot's half": (0.15, 0.0, TABLE_Z + 0.05), "the middle line": (0.0, 0.0, TABLE_Z + 0.10)}


def _project(data: mujoco.MjData, model: mujoco.MjModel, cam: str, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    pos, R = data.cam(cam).xpos, data.cam(cam).xmat.reshape(3, 3)
    f = 0.5 * H / np.tan(np.radians(model.cam(cam).fovy[0]) / 2)
    v = (pts - pos) @ R                       # camera frame: x right, y up, looking along -z
    return (W / 2 + f * v[:, 0] / -v[:, 2]).astype(int), (H / 2 - f * v[:, 1] / -v[:, 2]).astype(int)


def hidden_share(world, robot: RobotController, hand: np.ndarray, look: tuple[float, float, float],
                 renderer: mujoco.Renderer, robot_geom: np.ndarray, pts: np.ndarray) -> tuple[float, float]:
    """(share hidden, share outside the view) of ``pts`` with the hand at ``hand`` and the head looking at ``look``."""
    m, d = world.model, world.data
    q = robot.q()
    for _ in range(300):
        q = robot.ik.solve(q, poses.pose(mink.SO3.identity(), hand), 0.02, collision=False).q
    d.qpos[robot._qadr] = q
    mujoco.mj_forward(m, d)
    pan, tilt = gaze_angles(d.site("robot_head_center").xpos, np.array(look))
    d.qpos[m.joint("robot_head_pan").qposadr[0]] = pan
    d.qpos[m.joint("robot_head_tilt").qposadr[0]] = tilt
    mujoco.mj_forward(m, d)
    hidden, outside = np.zeros(len(pts), bool), np.zeros(len(pts), bool)
    for cam in CAMERAS:
        renderer.update_scene(d, cam)
        seg = renderer.render()[..., 0]
        u, v = _project(d, m, cam, pts)
        inside = (u >= 0) & (u < W) & (v >= 0) & (v < H)
        geom = np.full(len(pts), -1)
        geom[inside] = seg[v[inside], u[inside]]
        outside |= ~inside
        hidden |= ~inside | ((geom >= 0) & robot_geom[np.clip(geom, 0, m.ngeom - 1)])
    return float(hidden.mean()), float(outside.mean())


def main() -> None:
    world = build_world(Arrangement.from_options("HWS:closed", "HWS:inverted"), seed=0)
    m = world.model
    robot = RobotController(m, world.data)
    renderer = mujoco.Renderer(m, H, W)
    renderer.enable_segmentation_rendering()
    robot_geom = np.array([m.body(m.geom_bodyid[g]).name.startswith("robot_") for g in range(m.ngeom)])
    gx, gy = np.meshgrid(np.linspace(0.0, 0.42, 15), np.linspace(-0.3, 0.3, 21))
    pts = np.stack([gx.ravel(), gy.ravel(), np.full(gx.size, TABLE_Z + 0.05)], 1)
    print("share of the robot's half of the table hidden from the head cameras")
    print(f"{'hand at':<30}" + "".join(f"{'looking at ' + k:>30}" for k in LOOKS))
    floor = []
    for name, hand in (("the ready pose", READY_POSE_POS), ("the rest pose", REST_POSE_POS)):
        shares = [hidden_share(world, robot, hand, look, renderer, robot_geom, pts) for look in LOOKS.values()]
        floor = [outside for _, outside in shares]
        print(f"{name + ' ' + np.array2string(hand, precision=2):<30}" + "".join(f"{h:>30.3f}" for h, _ in shares))
    print(f"{'outside the view (the floor)':<30}" + "".join(f"{f:>30.3f}" for f in floor))
    renderer.close()


if __name__ == "__main__":
    main()
