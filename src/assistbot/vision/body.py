"""The robot's own arm in its camera images: which pixels it may cover.

A real robot knows its joint angles and its own shape; from them (forward kinematics) it knows
where its arm is in its cameras' images.  Vision uses that to tell the edge of an object from the
edge of the arm in front of it: an object whose silhouette ends on the arm is cut by it, and its
lowest visible row is not the base it stands on.

`RobotBody.of(model, data)` takes the arm's visual geoms (links, gripper, fingers) as capsules in
table coordinates: a cylinder or capsule as its axis and radius, a box as a capsule along its
longest side whose radius reaches its corners (it covers the box).  `covers(cam, uv)` tells whether
any of some pixels lies within a capsule's image (with `MARGIN_PX`).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import mujoco
import numpy as np

from assistbot.vision import _kernels
from assistbot.vision.camera import CameraModel
from assistbot.world import layout

#: the arm's bodies: what can come between the head's cameras and the table top (the base, its
#: torus and the column stand below and behind the cameras, whose rays to the table pass above them)
ARM_BODIES = ("robot_link", "robot_gripper", "robot_f")
MARGIN_PX = 1.5              # px added to each capsule's image radius (pixel rounding of the render)
VISUAL_GROUP = 2

_GEOMS: "weakref.WeakKeyDictionary[mujoco.MjModel, tuple]" = weakref.WeakKeyDictionary()


def _arm_geoms(model: mujoco.MjModel) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(geom ids, local axis index per geom, half-lengths, radii) of the arm's visual geoms; per model."""
    got = _GEOMS.get(model)
    if got is None:
        rows = []     # (geom, local axis of its long side, half-length, radius)
        for g in range(model.ngeom):
            body = model.body(int(model.geom_bodyid[g])).name
            if model.geom_group[g] != VISUAL_GROUP or not body.startswith(ARM_BODIES):
                continue
            t, s = int(model.geom_type[g]), model.geom_size[g]
            if t in (mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_CAPSULE):
                rows.append((g, 2, s[1], s[0]))
            elif t == mujoco.mjtGeom.mjGEOM_BOX:
                k = int(np.argmax(s[:3]))
                rows.append((g, k, s[k], float(np.hypot(*np.delete(s[:3], k)))))
            elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
                rows.append((g, 2, 0.0, s[0]))
        ids, axes, half, rad = zip(*rows)
        got = _GEOMS[model] = (np.array(ids, int), np.array(axes, int), np.array(half, float), np.array(rad, float))
    return got


@dataclass
class RobotBody:
    """Capsules in table coordinates: segment ends a, b (N, 3) and radii r (N,)."""

    a: np.ndarray
    b: np.ndarray
    r: np.ndarray

    @classmethod
    def of(cls, model: mujoco.MjModel, data: mujoco.MjData) -> "RobotBody":
        ids, axes, half, rad = _arm_geoms(model)
        centre = data.geom_xpos[ids].copy()
        centre[:, 2] -= layout.TABLE_Z
        axis = data.geom_xmat[ids].reshape(-1, 3, 3)[np.arange(len(ids)), :, axes]   # the column of the long side
        return cls(np.ascontiguousarray(centre - half[:, None] * axis), np.ascontiguousarray(centre + half[:, None] * axis), rad)

    def covers(self, cam: CameraModel, uv) -> bool:
        """Whether any pixel of uv (M, 2) lies on the image of a capsule: its ends projected, the
        segment between them as wide as the capsule at its nearer end's depth (+ `MARGIN_PX`);
        capsules (partly) behind the camera are left out.  One compiled loop."""
        pts = np.ascontiguousarray(np.asarray(uv, float).reshape(-1, 2))
        return bool(_kernels.capsules_cover(self.a, self.b, self.r, cam.P, float(cam.K[0, 0]), MARGIN_PX, pts))
