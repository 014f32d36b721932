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

import atexit
import ctypes
import ctypes.util
import functools
import os
import queue
import threading
import time
import weakref
from pathlib import Path

import mujoco
import numpy as np

from assistbot import catalogue
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
        return _finalised_safely(GLContext)(width, height)
    except UserError:
        raise
    except Exception as exc:  # noqa: BLE001 - any failure here means no usable GL
        raise UserError("rendering", f"MUJOCO_GL={backend}",
                        f"cannot create an offscreen GL context ({type(exc).__name__}: {exc}); "
                        "install libosmesa6 or libegl-mesa0 (make debs), or set MUJOCO_GL to a working backend") from None


@functools.cache
def _finalised_safely(cls: type) -> type:
    """``cls`` whose finaliser does nothing when its constructor was cut short.  A Ctrl-C in the main thread,
    or the interpreter exiting under the daemon render thread, can stop mujoco's GLContext constructor before
    it sets ``_context``; its own ``__del__`` then prints an AttributeError traceback as the run exits.  Made once
    per backend's class, not per context."""

    class Context(cls):  # type: ignore[valid-type, misc]
        def __del__(self) -> None:
            if getattr(self, "_context", None) is not None:
                super().__del__()

    return Context


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

    def _camera_id(self, camera: str) -> int:
        try:
            return self.model.camera(camera).id
        except KeyError:
            raise UserError("rendering", "camera", f"unknown camera {camera!r}") from None

    def new_scene(self) -> mujoco.MjvScene:
        """A scene with this renderer's settings, for `update_scene` and `draw`."""
        scene = mujoco.MjvScene(self.model, maxgeom=2000)
        scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = self._scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW]
        return scene

    def update_scene(self, data: mujoco.MjData, camera: str, scene: mujoco.MjvScene | None = None) -> mujoco.MjvScene:
        """What `camera` sees in ``data`` now, copied into ``scene`` (default: the renderer's own).
        No GL: any thread may call it, and ``data`` may change afterwards."""
        scene = self._scene if scene is None else scene
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._camera.fixedcamid = self._camera_id(camera)
        mujoco.mjv_updateScene(self.model, data, self._option, None, self._camera, mujoco.mjtCatBit.mjCAT_ALL, scene)
        return scene

    def draw(self, scene: mujoco.MjvScene) -> np.ndarray:
        """(height, width, 3) uint8 image of a scene made by `update_scene`, on the thread that made this renderer."""
        self._gl.make_current()
        mujoco.mjr_render(self._rect, scene, self._con)
        out = np.empty((self.height, self.width, 3), np.uint8)
        mujoco.mjr_readPixels(out, None, self._rect, self._con)
        return np.flipud(out).copy()

    def rgb(self, data: mujoco.MjData, camera: str) -> np.ndarray:
        """(height, width, 3) uint8 image from `camera`."""
        return self.draw(self.update_scene(data, camera))

    def depth(self, data: mujoco.MjData, camera: str) -> np.ndarray:
        """(height, width) float32 distance along the view axis in metres."""
        self._gl.make_current()
        self.update_scene(data, camera)
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
        self.update_scene(data, camera)
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


class RenderThread:
    """A `Renderer` that draws on a thread of its own, so the pictures are made while the caller
    steps the world: MuJoCo's and Mesa's C code run without the GIL, and a 2-core machine has a
    core the physics leaves idle.  The GL context is made, used and freed on that thread only.

    ``submit(scenes)`` hands over scenes made by ``renderer.update_scene`` (the caller's copies of
    the world at that instant); ``result()`` waits for their images.  One batch at a time."""

    _live: weakref.WeakSet = weakref.WeakSet()  # closed at exit: OSMesa crashes when a context outlives its thread

    def __init__(self, model: mujoco.MjModel, width: int, height: int) -> None:
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._done: queue.SimpleQueue = queue.SimpleQueue()
        self._busy = False
        self._thread = threading.Thread(target=self._run, args=(model, width, height), name="assistbot-render", daemon=True)
        self._thread.start()
        ready = self._done.get()
        if isinstance(ready, BaseException):
            self._thread.join()
            raise ready
        self.renderer: Renderer = ready
        RenderThread._live.add(self)
        # exit handlers run last-registered first: after the first context, mujoco's EGL registers the display's
        # termination, and a context freed after it raises; closing the threads comes first again
        atexit.unregister(_close_render_threads)
        atexit.register(_close_render_threads)

    def _run(self, model: mujoco.MjModel, width: int, height: int) -> None:
        try:
            renderer = Renderer(model, width, height, shadows=False)
        except BaseException as exc:  # noqa: BLE001 - handed to the constructor, which raises it
            self._done.put(exc)
            return
        self._done.put(renderer)
        try:
            while (scenes := self._jobs.get()) is not None:
                try:
                    t0 = time.perf_counter()
                    images = [renderer.draw(s) for s in scenes]
                    self._done.put((images, time.perf_counter() - t0))
                except BaseException as exc:  # noqa: BLE001 - raised again by result()
                    self._done.put(exc)
        finally:
            renderer.close()

    def submit(self, scenes: list[mujoco.MjvScene]) -> None:
        if self._busy:
            raise RuntimeError("RenderThread.submit: collect the previous result first")
        self._busy = True
        self._jobs.put(list(scenes))

    def result(self) -> tuple[list[np.ndarray], float]:
        """The images of the last submitted scenes and the seconds the thread spent drawing them."""
        if not self._busy:
            raise RuntimeError("RenderThread.result: nothing submitted")
        out = self._done.get()
        self._busy = False
        if isinstance(out, BaseException):
            raise out
        return out

    def close(self) -> None:
        if self._thread.is_alive():
            if self._busy:
                self._done.get()
                self._busy = False
            self._jobs.put(None)
            self._thread.join()
        RenderThread._live.discard(self)


@atexit.register
def _close_render_threads() -> None:
    for rt in list(RenderThread._live):
        rt.close()


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
        elif body in catalogue.NAMES or body == "table":
            labels[g] = inv[body]
        elif root.startswith("robot"):
            labels[g] = inv["robot"]
        elif root.startswith("human"):
            labels[g] = by_material.get(int(model.geom_matid[g]), inv["human"])
    return labels
