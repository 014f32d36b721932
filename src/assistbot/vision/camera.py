"""Pinhole models of the head cameras: intrinsics from the model's fovy, extrinsics from the head's joints.

Frames.  MuJoCo cameras look along their -z axis with +y up; image pixels (u, v) have u to
the right and v down, so the optical frame is (x_cam, -y_cam, -z_cam).  Positions come out in
table coordinates (world x, y; z above the table top, see `assistbot.world`).

`CameraModel.from_data` reads ``data.cam_xpos`` / ``data.cam_xmat``: MuJoCo computes them by
forward kinematics from the model's head bodies and the pan/tilt joint angles in ``qpos``
(the head's joint sensors), so nothing here is hard-coded.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from assistbot.world.layout import TABLE_Z

#: optical frame (u right, v down, forward) in MuJoCo camera axes
_FLIP = np.diag([1.0, -1.0, -1.0])


@dataclass(frozen=True)
class CameraModel:
    """One camera: K (3x3, pixels), R (world->optical rotation), centre C (table frame, m)."""

    name: str
    width: int
    height: int
    K: np.ndarray
    R: np.ndarray
    C: np.ndarray

    @staticmethod
    def intrinsics(model: mujoco.MjModel, camera: str, width: int, height: int) -> np.ndarray:
        """K from the camera's vertical field of view (square pixels, principal point at the centre)."""
        fovy = np.radians(model.cam_fovy[model.camera(camera).id])
        f = 0.5 * height / np.tan(0.5 * fovy)
        return np.array([[f, 0.0, 0.5 * width], [0.0, f, 0.5 * height], [0.0, 0.0, 1.0]])

    @classmethod
    def from_data(cls, model: mujoco.MjModel, data: mujoco.MjData, camera: str, width: int, height: int) -> "CameraModel":
        cid = model.camera(camera).id
        Rc = data.cam_xmat[cid].reshape(3, 3)           # columns: camera axes in the world
        C = data.cam_xpos[cid].copy()
        C[2] -= TABLE_Z
        return cls(camera, width, height, cls.intrinsics(model, camera, width, height), _FLIP @ Rc.T, C)

    @property
    def P(self) -> np.ndarray:
        """3x4 projection matrix (table frame -> homogeneous pixels)."""
        return self.K @ np.hstack([self.R, (-self.R @ self.C)[:, None]])

    def project(self, X: np.ndarray) -> np.ndarray:
        """(N, 3) table points -> (N, 2) pixels (u, v); points behind the camera give nan."""
        X = np.atleast_2d(np.asarray(X, float))
        Xc = (X - self.C) @ self.R.T
        uv = Xc @ self.K.T
        z = uv[:, 2:3]
        out = uv[:, :2] / np.where(z > 1e-6, z, np.nan)
        return out

    def ray(self, uv) -> np.ndarray:
        """Unit direction (table frame) of the ray through pixel(s) (N, 2)."""
        uv = np.atleast_2d(np.asarray(uv, float))
        K = self.K
        d = np.column_stack([(uv[:, 0] - K[0, 2]) / K[0, 0], (uv[:, 1] - K[1, 2]) / K[1, 1], np.ones(len(uv))]) @ self.R  # optical -> table
        return d / np.linalg.norm(d, axis=1, keepdims=True)


def triangulate(left: CameraModel, right: CameraModel, uv_left, uv_right) -> np.ndarray:
    """(N, 3) table points closest to both rays (midpoint of the common perpendicular)."""
    d1, d2 = left.ray(uv_left), right.ray(uv_right)
    c1, c2 = left.C, right.C
    w0 = c1 - c2
    a = np.einsum("ij,ij->i", d1, d1)
    b = np.einsum("ij,ij->i", d1, d2)
    c = np.einsum("ij,ij->i", d2, d2)
    d = d1 @ w0
    e = d2 @ w0
    den = np.maximum(a * c - b * b, 1e-12)
    s = (b * e - c * d) / den
    t = (a * e - b * d) / den
    return 0.5 * ((c1 + s[:, None] * d1) + (c2 + t[:, None] * d2))


def on_plane(cam: CameraModel, uv, z: float) -> np.ndarray:
    """(N, 3) points where the rays through pixels uv meet the horizontal plane at table height z."""
    d = cam.ray(uv)
    s = (z - cam.C[2]) / np.where(np.abs(d[:, 2]) > 1e-9, d[:, 2], np.nan)
    return cam.C + s[:, None] * d
