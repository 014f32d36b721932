"""Headless offscreen rendering of named cameras: RGB, depth and segmentation.

GL backend choice (made once per process, before OpenGL is first imported):
  1. MUJOCO_GL when set (egl, osmesa or glfw);
  2. egl when an NVIDIA driver is present (/proc/driver/nvidia/version);
  3. osmesa when libOSMesa can create a context (probed with ctypes, no OpenGL import);
  4. Mesa's egl otherwise.
A backend that fails to make a context is a UserError (exit 2) saying what to install or set.
Close renderers explicitly (`close()` or a `with` block): OSMesa crashes at interpreter
exit when a context is left to the garbage collector.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
from pathlib import Path

import mujoco
import numpy as np

from assistbot.errors import UserError

_BACKEND: str | None = None

#: segmentation labels of `Renderer.segmentation`.  The person is split by material: "skin"
#: (hands, arms, face), "shirt" (torso and sleeves) and "human" (the rest: hair, trousers, chair)
#: -- vision calibrates its colour ranges from these labels
SEGMENT_LABELS = {0: "background", 1: "table", 2: "robot", 3: "human", 4: "bottle", 5: "stopper", 6: "glass", 7: "liquid",
                  8: "skin", 9: "shirt"}


def _osmesa_works() -> bool:
    name = ctypes.util.find_library("OSMesa")
    if not name:
        return False
    try:
        lib = ctypes.CDLL(name)
        lib.OSMesaCreateContextExt.restype = ctypes.c_void_p
        ctx = lib.OSMesaCreateContextExt(0x1908, 24, 8, 0, None)  # OSMESA_RGBA
        if not ctx:
            return False
        lib.OSMesaDestroyContext.argtypes = [ctypes.c_void_p]
        lib.OSMesaDestroyContext(ctx)
        return True
    except (OSError, AttributeError):
        return False


def gl_backend() -> str:
    """The GL backend this process renders with (chosen on first call, see module doc)."""
    global _BACKEND
    if _BACKEND is None:
        env = os.environ.get("MUJOCO_GL", "").strip().lower()
        if env:
            _BACKEND = env
        elif Path("/proc/driver/nvidia/version").exists():
            _BACKEND = "egl"
        elif _osmesa_works():
            _BACKEND = "osmesa"
        else:
            _BACKEND = "egl"
        if _BACKEND in ("egl", "osmesa"):
            os.environ.setdefault("PYOPENGL_PLATFORM", _BACKEND)
    return _BACKEND


def _context(width: int, height: int):
    backend = gl_backend()
    try:
        if backend == "osmesa":
            from mujoco.osmesa import GLContext
        elif backend == "egl":
            from mujoco.egl import GLContext
        elif backend == "glfw":
            from mujoco.glfw import GLContext
        else:
            raise UserError("MUJOCO_GL", backend, "unknown GL backend; use egl, osmesa or glfw")
        return GLContext(width, height)
    except UserError:
        raise
    except Exception as exc:  # noqa: BLE001 - any failure here means no usable GL
        raise UserError("rendering", f"MUJOCO_GL={backend}",
                        f"cannot create an offscreen GL context ({type(exc).__name__}: {exc}); "
                        "install libosmesa6 or libegl-mesa0 (make debs), or set MUJOCO_GL to a working backend") from None


class Renderer:
    """Offscreen renderer of one model at a fixed size.  Use ``with Renderer(...) as r:``."""

    def __init__(self, model: mujoco.MjModel, width: int = 640, height: int = 480, shadows: bool = False) -> None:
        """shadows: off by default: on Mesa (CPU) the shadow pass costs ~120 ms per frame, everything else ~20 ms."""
        if width > model.vis.global_.offwidth or height > model.vis.global_.offheight:
            raise UserError("rendering", "size", f"{width}x{height} exceeds the model's offscreen buffer "
                            f"{model.vis.global_.offwidth}x{model.vis.global_.offheight}")
        self.model, self.width, self.height = model, int(width), int(height)
        self._gl = _context(self.width, self.height)
        self._gl.make_current()
        self._scene = mujoco.MjvScene(model, maxgeom=2000)
        self._scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = shadows
        self._option = mujoco.MjvOption()
        self._camera = mujoco.MjvCamera()
        self._con = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self._con)
        self._rect = mujoco.MjrRect(0, 0, self.width, self.height)
        self._labels = _geom_labels(model)

    def _update(self, data: mujoco.MjData, camera: str) -> None:
        try:
            cam_id = self.model.camera(camera).id
        except KeyError:
            raise UserError("rendering", "camera", f"unknown camera {camera!r}") from None
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._camera.fixedcamid = cam_id
        mujoco.mjv_updateScene(self.model, data, self._option, None, self._camera, mujoco.mjtCatBit.mjCAT_ALL, self._scene)

    def rgb(self, data: mujoco.MjData, camera: str) -> np.ndarray:
        """(height, width, 3) uint8 image from `camera`."""
        self._gl.make_current()
        self._update(data, camera)
        mujoco.mjr_render(self._rect, self._scene, self._con)
        out = np.empty((self.height, self.width, 3), np.uint8)
        mujoco.mjr_readPixels(out, None, self._rect, self._con)
        return np.flipud(out).copy()

    def depth(self, data: mujoco.MjData, camera: str) -> np.ndarray:
        """(height, width) float32 distance along the view axis in metres."""
        self._gl.make_current()
        self._update(data, camera)
        mujoco.mjr_render(self._rect, self._scene, self._con)
        z = np.empty((self.height, self.width), np.float32)
        mujoco.mjr_readPixels(None, z, self._rect, self._con)
        ext = self.model.stat.extent
        near, far = self.model.vis.map.znear * ext, self.model.vis.map.zfar * ext
        z = near / (1.0 - z.astype(np.float64) * (1.0 - near / far))
        return np.flipud(z).astype(np.float32)

    def segmentation(self, data: mujoco.MjData, camera: str) -> np.ndarray:
        """(height, width) uint8 labels (SEGMENT_LABELS) of what each pixel shows."""
        self._gl.make_current()
        self._update(data, camera)
        s = self._scene
        s.flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = True
        s.flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = True
        try:
            mujoco.mjr_render(self._rect, s, self._con)
        finally:
            s.flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = False
            s.flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = False
        img = np.empty((self.height, self.width, 3), np.uint8)
        mujoco.mjr_readPixels(img, None, self._rect, self._con)
        segid = img[..., 0].astype(np.int32) + (img[..., 1].astype(np.int32) << 8) + (img[..., 2].astype(np.int32) << 16)
        lut = np.zeros(s.ngeom + 2, np.uint8)
        for i in range(s.ngeom):
            g = s.geoms[i]
            if g.objtype == mujoco.mjtObj.mjOBJ_GEOM and g.segid >= 0:
                lut[g.segid + 1] = self._labels[g.objid]
        segid = np.clip(segid, 0, len(lut) - 1)
        return np.flipud(lut[segid]).copy()

    def close(self) -> None:
        if getattr(self, "_gl", None) is not None:
            self._con.free()
            self._gl.free()
            self._gl = None

    def __enter__(self) -> "Renderer":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _geom_labels(model: mujoco.MjModel) -> np.ndarray:
    inv = {v: k for k, v in SEGMENT_LABELS.items()}
    labels = np.zeros(model.ngeom, np.uint8)
    mats = {model.material(i).name: i for i in range(model.nmat)}
    by_material = {mats[m]: inv[m] for m in ("skin", "shirt") if m in mats}
    for g in range(model.ngeom):
        body = model.body(model.geom_bodyid[g]).name
        root = model.body(model.body_rootid[model.geom_bodyid[g]]).name
        if body.startswith("particle") or model.geom(g).name == "glass_visual_liquid":
            labels[g] = inv["liquid"]
        elif body in ("bottle", "stopper", "glass", "table"):
            labels[g] = inv[body]
        elif root.startswith("robot"):
            labels[g] = inv["robot"]
        elif root.startswith("human"):
            labels[g] = by_material.get(int(model.geom_matid[g]), inv["human"])
    return labels
