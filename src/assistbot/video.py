"""Video frames of an episode: scene view, the robot's camera with vision overlay, live field panels, subtitles.

Panels are drawn with OpenCV (a matplotlib figure per frame would cost more
than the physics); the video is H.264 in yuv420p so browsers play it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import cv2
import numpy as np

FONT = cv2.FONT_HERSHEY_SIMPLEX
BG = (24, 24, 28)
TEXT = (235, 235, 235)
DIM = (150, 150, 150)
BAR = (90, 170, 250)
BAR_ACTIVE = (250, 140, 60)


def _fit(img: np.ndarray, width: int, height: int) -> np.ndarray:
    """Scale to fit inside (width, height) keeping the aspect ratio, letterboxed on BG."""
    h, w = img.shape[:2]
    s = min(width / w, height / h)
    nw, nh = max(1, int(w * s)), max(1, int(h * s))
    out = np.full((height, width, 3), BG, dtype=np.uint8)
    y0, x0 = (height - nh) // 2, (width - nw) // 2
    out[y0:y0 + nh, x0:x0 + nw] = cv2.resize(img, (nw, nh), interpolation=cv2.INTER_AREA)
    return out


def draw_layer(canvas: np.ndarray, x: int, y: int, w: int, h: int, title: str,
               activities: Mapping[str, float], threshold: float = 0.0, lo: float = -8.0, hi: float = 8.0) -> None:
    """One layer as horizontal bars of item activity (u at each item's centre); items above threshold highlighted."""
    cv2.putText(canvas, title, (x + 4, y + 14), FONT, 0.45, TEXT, 1, cv2.LINE_AA)
    items = list(activities.items())
    if not items:
        return
    row = max(8, min(15, (h - 20) // len(items)))
    label_w = int(w * 0.58)
    zero = x + label_w + int((0 - lo) / (hi - lo) * (w - label_w - 6))
    for k, (name, u) in enumerate(items):
        ry = y + 20 + k * row
        if ry + row > y + h:
            break
        active = u > threshold
        cv2.putText(canvas, name[:34], (x + 4, ry + row - 3), FONT, 0.33, TEXT if active else DIM, 1, cv2.LINE_AA)
        end = x + label_w + int((np.clip(u, lo, hi) - lo) / (hi - lo) * (w - label_w - 6))
        cv2.rectangle(canvas, (min(zero, end), ry + 2), (max(zero, end), ry + row - 2), BAR_ACTIVE if active else BAR, -1)
    cv2.line(canvas, (zero, y + 18), (zero, y + h - 2), DIM, 1)


def compose_frame(scene: np.ndarray, camera: np.ndarray | None, layers: Sequence[tuple[str, Mapping[str, float]]],
                  subtitle: str = "", header: str = "", size: tuple[int, int] = (1280, 720)) -> np.ndarray:
    """One video frame: scene (left, large), robot camera (top right), layer panels (right), subtitle and header lines."""
    W, H = size
    frame = np.full((H, W, 3), BG, dtype=np.uint8)
    left_w = int(W * 0.56)
    top = 26
    bottom = 52
    frame[top:H - bottom, :left_w] = _fit(scene, left_w, H - top - bottom)
    right_x = left_w + 6
    right_w = W - right_x - 4
    cam_h = 0
    if camera is not None:
        cam_h = int(right_w * camera.shape[0] / camera.shape[1])
        cam_h = min(cam_h, int(H * 0.36))
        frame[top:top + cam_h, right_x:right_x + right_w] = _fit(camera, right_w, cam_h)
    if layers:
        py = top + cam_h + 4
        avail = H - bottom - py
        cols = 2
        per_col = int(np.ceil(len(layers) / cols))
        col_w = right_w // cols
        sizes = [max(1, len(a)) + 2 for _, a in layers]
        for c in range(cols):
            chunk = list(range(c * per_col, min(len(layers), (c + 1) * per_col)))
            total = sum(sizes[i] for i in chunk) or 1
            yy = py
            for i in chunk:
                lh = int(avail * sizes[i] / total)
                title, acts = layers[i]
                draw_layer(frame, right_x + c * col_w, yy, col_w - 4, lh, title, acts)
                yy += lh
    if header:
        cv2.putText(frame, header, (8, 18), FONT, 0.5, TEXT, 1, cv2.LINE_AA)
    if subtitle:
        (tw, _), _ = cv2.getTextSize(subtitle, FONT, 0.7, 2)
        sx = max(8, (left_w - tw) // 2)
        cv2.putText(frame, subtitle, (sx, H - 18), FONT, 0.7, (255, 230, 120), 2, cv2.LINE_AA)
    return frame


class VideoWriter:
    """H.264/yuv420p MP4 through imageio-ffmpeg; use as a context manager so the file is closed."""

    def __init__(self, path: str | Path, fps: float) -> None:
        import imageio.v2 as iio

        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.fps = float(fps)
        self.frames = 0
        self._w = iio.get_writer(self.path, fps=self.fps, codec="libx264", pixelformat="yuv420p",
                                 macro_block_size=8, ffmpeg_log_level="error", quality=7)

    def append(self, frame: np.ndarray) -> None:
        self._w.append_data(np.ascontiguousarray(frame, dtype=np.uint8))
        self.frames += 1

    def close(self) -> None:
        if self._w is not None:
            self._w.close()
            self._w = None

    def __enter__(self) -> "VideoWriter":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
