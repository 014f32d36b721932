"""Pinhole models of the head cameras: intrinsics from the model's fovy, extrinsics from the head's joints.

Frames.  MuJoCo cameras look along their -z axis with +y up; image pixels (u, v) have u to
the right and v down, so the optical frame is (x_cam, -y_cam, -z_cam).  Positions come out in
table coordinates (world x, y; z above the table top, see `assistbot.world`).

`CameraModel.from_data` reads ``data.cam_xpos`` / ``data.cam_xmat``: MuJoCo computes them by
forward kinematics from the model's head bodies and the pan/tilt joint angles in ``qpos``
(the head's joint sensors), so nothing here is hard-coded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import mujoco
import numpy as np

from assistbot.world.layout import TABLE_Z

#: optical frame (u right, v down, forward) in MuJoCo camera axes
_FLIP = np.diag([1.0, -1.0, -1.0])


_INV_K: dict[bytes, np.ndarray] = {}


def _inv_K(K: np.ndarray) -> np.ndarray:
    """np.linalg.inv(K), kept per distinct K: the intrinsics stay while each frame's cameras are new
    objects (their pose moves with the head), so each frame's `_Q` would invert the same K again."""
    key = (K.shape, K.dtype.str, K.tobytes())
    inv = _INV_K.get(key)
    if inv is None:
        if len(_INV_K) >= 16:
            _INV_K.clear()
        inv = _INV_K[key] = np.linalg.inv(K)
        inv.flags.writeable = False
    return inv


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

    @cached_property
    def P(self) -> np.ndarray:
        """3x4 projection matrix (table frame -> homogeneous pixels)."""
        return self.K @ np.hstack([self.R, (-self.R @ self.C)[:, None]])

    @cached_property
    def _Q(self) -> np.ndarray:
        """Homogeneous pixel (as a row) -> ray direction in the table frame: inv(K).T @ R (computed once:
        vision casts many small batches of rays a frame)."""
        return _inv_K(self.K).T @ self.R

    def project(self, X: np.ndarray) -> np.ndarray:
        """(N, 3) table points -> (N, 2) pixels (u, v); points behind the camera give nan."""
        X = np.atleast_2d(np.asarray(X, float))
        Xc = (X - self.C) @ self.R.T
        uv = Xc @ self.K.T
        z = uv[:, 2:3]
        out = uv[:, :2] / np.where(z > 1e-6, z, np.nan)
        return out

    @cached_property
    def _Q_parts(self) -> tuple[np.ndarray, np.ndarray]:
        """(the pixel rows of `_Q`, its constant row): views taken once."""
        Q = self._Q
        return Q[:2], Q[2]

    @cached_property
    def _P_parts(self) -> tuple[np.ndarray, np.ndarray]:
        """(P[:, :3].T, P[:, 3]): views of `P` taken once (the same arrays `expected_box` used to slice)."""
        P = self.P
        return P[:, :3].T, P[:, 3]

    def ray(self, uv) -> np.ndarray:
        """Unit direction (table frame) of the ray through pixel(s) (N, 2)."""
        Q2, q = self._Q_parts
        d = np.reshape(np.asarray(uv, float), (-1, 2)) @ Q2 + q
        if len(d) <= _FEW:
            return np.array(_unit_rows(d))
        return d / np.sqrt((d * d).sum(axis=1, keepdims=True))

    def expected_box(self, X: np.ndarray) -> tuple[float, float]:
        """(width, height) in pixels of the image of the table points X (N, 3); (1, 1) if any is behind the camera."""
        A, t = self._P_parts
        h = X @ A + t
        z = h[:, 2]
        if z.min() <= 1e-6:
            return 1.0, 1.0
        uv = h[:, :2] / z[:, None]          # u, v = h[:, 0] / z, h[:, 1] / z
        hi, lo = uv.max(axis=0), uv.min(axis=0)
        return float(hi[0] - lo[0]), float(hi[1] - lo[1])


#: up to this many points, per-point arithmetic runs on Python floats (numpy's per-call overhead
#: dominates on a few points); the products with the camera matrices stay numpy's (BLAS) calls
_FEW = 8


def _unit_rows(d) -> list[list[float]]:
    """The rows of d (N, 3; an array or rows of floats) over their lengths, computed as ``d / np.sqrt((d *
    d).sum(axis=1, keepdims=True))`` computes them: the squares summed left to right, the same sqrt and
    divisions."""
    out = []
    for x, y, z in (d.tolist() if isinstance(d, np.ndarray) else d):
        n = math.sqrt((x * x + y * y) + z * z)
        out.append([x / n, y / n, z / n])
    return out


#: the last camera pair and its stacked constants (see `_pair`): one tuple, read and replaced whole
_PAIR: list = [(None, None, None)]


def _pair(left: CameraModel, right: CameraModel) -> tuple:
    """Constants of a camera pair for `triangulate` and `expected_boxes`, kept for the last pair (each
    frame's cameras are new objects): the ray matrices stacked ((2, 2, 3) and (2, 1, 3): the rows of
    each camera's `_Q`), the baseline C_l - C_r, C_l + C_r as floats, and both cameras' P[:, :3].T side
    by side (3, 6) with their P[:, 3] (6,), all from the cameras' own `_Q` and `P`."""
    ent = _PAIR[0]
    if ent[0] is left and ent[1] is right:
        return ent[2]
    (Ql, ql), (Qr, qr) = left._Q_parts, right._Q_parts
    (Al, tl), (Ar, tr) = left._P_parts, right._P_parts
    QS, qS = np.array([Ql, Qr]), np.array([ql, qr])[:, None, :]      # np.stack's arrays, for less call overhead
    A2, t2 = np.hstack([Al, Ar]), np.concatenate([tl, tr])
    consts = (QS, qS, left.C - right.C, (left.C + right.C).tolist(), A2, t2)
    _PAIR[0] = (left, right, consts)
    return consts


def triangulate(left: CameraModel, right: CameraModel, uv_left, uv_right) -> np.ndarray:
    """(N, 3) table points closest to both rays (midpoint of the common perpendicular)."""
    a = np.reshape(np.asarray(uv_left, float), (-1, 2))
    b = np.reshape(np.asarray(uv_right, float), (-1, 2))
    if len(a) <= _FEW and len(a) == len(b):
        # a few points: both cameras' rays in one stacked product (each slice is the same BLAS
        # product as the camera's own), then the same operations as below, point by point on
        # floats (unit rays: d1.d1 = d2.d2 = 1)
        QS, qS, w0, cc, _, _ = _pair(left, right)
        raw = (np.array([a, b]) @ QS + qS).tolist()      # np.array: np.stack's (2, N, 2) array, for less overhead
        r1, r2 = _unit_rows(raw[0]), _unit_rows(raw[1])
        d, e = (np.array([r1, r2]) @ w0).tolist()
        out = []
        for (x1, y1, z1), (x2, y2, z2), di, ei in zip(r1, r2, d, e):
            b = (x1 * x2 + y1 * y2) + z1 * z2
            den = max(1.0 - b * b, 1e-12)
            s = (b * ei - di) / den
            t = (ei - b * di) / den
            out.append([0.5 * ((cc[0] + s * x1) + t * x2), 0.5 * ((cc[1] + s * y1) + t * y2),
                        0.5 * ((cc[2] + s * z1) + t * z2)])
        return np.array(out)
    d1, d2 = left.ray(a), right.ray(b)
    c1, c2 = left.C, right.C
    w0 = c1 - c2
    d = d1 @ w0
    e = d2 @ w0
    b = (d1 * d2).sum(axis=1)              # unit rays: d1.d1 = d2.d2 = 1
    den = np.maximum(1.0 - b * b, 1e-12)
    s = ((b * e - d) / den)[:, None]
    t = ((e - b * d) / den)[:, None]
    return 0.5 * (c1 + c2 + s * d1 + t * d2)


def on_plane(cam: CameraModel, uv, z: float) -> np.ndarray:
    """(N, 3) points where the rays through pixels uv meet the horizontal plane at table height z."""
    d = cam.ray(uv)
    if len(d) <= _FEW:   # a few points: on floats (numpy's per-call overhead dominates)
        C = cam.C.tolist()
        h = float(z - cam.C[2])
        out = []
        for x, y, w in d.tolist():
            s = h / w if abs(w) > 1e-9 else math.nan
            out.append([C[0] + s * x, C[1] + s * y, C[2] + s * w])
        return np.array(out)
    s = (z - cam.C[2]) / np.where(np.abs(d[:, 2]) > 1e-9, d[:, 2], np.nan)
    return cam.C + s[:, None] * d


def expected_boxes(cams: tuple[CameraModel, CameraModel], X: np.ndarray) -> list[tuple[float, float]]:
    """`CameraModel.expected_box` of the same points in both cameras, with one product of X and both
    cameras' matrices side by side (each column is the same dot product as in the camera's own)."""
    *_, A2, t2 = _pair(*cams)
    h = (X @ A2 + t2).reshape(len(X), 2, 3)
    z = h[:, :, 2:]
    if not z.min() > 1e-6:
        return [cam.expected_box(X) for cam in cams]
    uv = h[:, :, :2] / z
    hi, lo = uv.max(axis=0).tolist(), uv.min(axis=0).tolist()
    return [(hi[c][0] - lo[c][0], hi[c][1] - lo[c][1]) for c in (0, 1)]
