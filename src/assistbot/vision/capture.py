"""Stereo capture: both head cameras rendered offscreen at a fixed rate of simulated time.

`StereoCapture.grab(data)` renders head_cam_left and head_cam_right (default 320x240, no
shadows) and returns a `StereoFrame` with the two RGB images and the two `CameraModel`s taken
from the same ``data`` (so the extrinsics match the head pose of the images), and the robot arm's
shape where its joints put it (`body.RobotBody`: the robot knows its own body).  A seeded
dropout probability drops whole frames (``frame.dropped``: no images): vision then reports
everything as not seen.

With ``threaded=True`` a pair can also be taken in two halves: `start(data)` copies what both
cameras see now, a render thread draws it while the caller steps the world on, and
`collect(frame)` waits for the images.  Same pixels as `grab`, made on the core the physics
leaves idle.

Rendering uses `assistbot.world.render.Renderer` on the world's own model (its glass is
translucent in the MJCF, so the cameras see the liquid through the wall).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import mujoco
import numpy as np

from assistbot.vision.body import RobotBody
from assistbot.vision.camera import CameraModel
from assistbot.world.render import Renderer, RenderThread

CAMERAS = ("head_cam_left", "head_cam_right")


@dataclass
class CaptureConfig:
    """Rate (Hz of simulated time), image size, frame dropout probability and its seed."""

    rate: float = 10.0
    width: int = 320
    height: int = 240
    dropout: float = 0.0
    seed: int = 0

    def validate(self) -> "CaptureConfig":
        from assistbot.errors import UserError
        if not self.rate > 0:
            raise UserError("vision", "rate", f"must be > 0 Hz, got {self.rate}")
        if not (16 <= self.width <= 1280 and 16 <= self.height <= 960):
            raise UserError("vision", "size", f"{self.width}x{self.height} outside 16x16 .. 1280x960")
        if not 0.0 <= self.dropout <= 1.0:
            raise UserError("vision", "--vision-dropout", f"a probability in [0, 1], got {self.dropout}")
        return self


@dataclass
class StereoFrame:
    t: float
    left: np.ndarray | None
    right: np.ndarray | None
    cams: tuple[CameraModel, CameraModel]
    dropped: bool = False
    render_ms: float = 0.0
    meta: dict = field(default_factory=dict)
    body: RobotBody | None = None      # the robot's own shape where its joints put it (proprioception)


class StereoCapture:
    """Renders the head cameras; close it (or use ``with``) when done."""

    def __init__(self, model: mujoco.MjModel, config: CaptureConfig | None = None, threaded: bool = False) -> None:
        self.config = (config or CaptureConfig()).validate()
        self.model = model
        c = self.config
        if threaded:
            self._thread: RenderThread | None = RenderThread(model, c.width, c.height)
            self.renderer = self._thread.renderer
            self._scenes = [self.renderer.new_scene() for _ in CAMERAS]
        else:
            self._thread = None
            self.renderer = Renderer(model, c.width, c.height, shadows=False)
        self._pending: StereoFrame | None = None
        self._rng = np.random.default_rng(self.config.seed)
        self._next_t = 0.0

    def due(self, t: float) -> bool:
        """True once per 1/rate seconds of simulated time (call every control tick)."""
        if t + 1e-9 >= self._next_t:
            period = 1.0 / self.config.rate
            self._next_t = (np.floor((t + 1e-9) / period) + 1) * period
            return True
        return False

    def cameras(self, data: mujoco.MjData) -> tuple[CameraModel, CameraModel]:
        c = self.config
        return tuple(CameraModel.from_data(self.model, data, n, c.width, c.height) for n in CAMERAS)  # type: ignore[return-value]

    def _dropped(self) -> bool:
        return self.config.dropout > 0 and self._rng.random() < self.config.dropout

    def grab(self, data: mujoco.MjData) -> StereoFrame:
        if self._thread is not None:
            return self.collect(self.start(data))
        cams = self.cameras(data)
        if self._dropped():
            return StereoFrame(float(data.time), None, None, cams, dropped=True)
        body = RobotBody.of(self.model, data)
        t0 = time.perf_counter()
        left = self.renderer.rgb(data, CAMERAS[0])
        right = self.renderer.rgb(data, CAMERAS[1])
        ms = (time.perf_counter() - t0) * 1000.0
        return StereoFrame(float(data.time), left, right, cams, render_ms=ms, body=body)

    def start(self, data: mujoco.MjData, meta: dict | None = None) -> StereoFrame:
        """Take the pair now; its images are drawn on the render thread (``threaded=True`` only)
        and filled in by `collect`.  ``data`` may be stepped on meanwhile."""
        if self._thread is None:
            raise RuntimeError("StereoCapture.start needs threaded=True")
        if self._pending is not None:
            raise RuntimeError("StereoCapture.start: collect the frame started before first")
        frame = StereoFrame(float(data.time), None, None, self.cameras(data), meta=dict(meta or {}))
        if self._dropped():
            frame.dropped = True
            return frame
        frame.body = RobotBody.of(self.model, data)   # only a frame that will be processed needs it
        self._thread.submit([self.renderer.update_scene(data, cam, s) for cam, s in zip(CAMERAS, self._scenes)])
        self._pending = frame
        return frame

    def collect(self, frame: StereoFrame) -> StereoFrame:
        """The frame from `start` with its images (waits for the render thread if it is still drawing);
        ``frame.render_ms`` is the thread's drawing time."""
        if frame.dropped or frame.left is not None:
            return frame
        if frame is not self._pending:
            raise RuntimeError("StereoCapture.collect: not the frame started last")
        (frame.left, frame.right), seconds = self._thread.result()
        frame.render_ms = 1000.0 * seconds
        self._pending = None
        return frame

    def segmentation(self, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
        """Ground-truth pixel labels of both cameras: for calibration and labelling only, never inference."""
        if self._thread is not None:
            raise RuntimeError("StereoCapture.segmentation renders on the calling thread: use threaded=False")
        return self.renderer.segmentation(data, CAMERAS[0]), self.renderer.segmentation(data, CAMERAS[1])

    def depth(self, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
        """Rendered depth (m along each camera's optical axis) of both cameras: for calibration only, never inference."""
        if self._thread is not None:
            raise RuntimeError("StereoCapture.depth renders on the calling thread: use threaded=False")
        return self.renderer.depth(data, CAMERAS[0]), self.renderer.depth(data, CAMERAS[1])

    def close(self) -> None:
        if self._thread is not None:
            self._thread.close()
        else:
            self.renderer.close()

    def __enter__(self) -> "StereoCapture":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
