"""Colour segmentation: HSV ranges per part (from `assistbot calibrate`), morphology, blobs.

Parts: bottle (green), stopper (red), glass (cyan, translucent), liquid (purple, also as
seen through the glass), skin (the human's hands, arms, face).  A range is a list of boxes
(h_lo, h_hi, s_lo, s_hi, v_lo, v_hi) in OpenCV units (H 0..179, S and V 0..255); a red hue
that wraps around 0 is two boxes.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

PARTS = ("bottle", "stopper", "glass", "liquid", "skin")
_KERNEL = np.ones((3, 3), np.uint8)
MIN_AREA = {"bottle": 12, "stopper": 4, "glass": 12, "liquid": 3, "skin": 20}


@dataclass
class Blob:
    """One connected component: area (px), centroid (u, v), bbox (x, y, w, h), label image id."""

    part: str
    area: int
    centroid: np.ndarray
    bbox: tuple[int, int, int, int]
    label: int


def masks(hsv: np.ndarray, ranges: dict[str, list[list[int]]]) -> dict[str, np.ndarray]:
    """Binary masks (uint8 0/255) per part of an HSV image."""
    out = {}
    for part in PARTS:
        m = None
        for box in ranges[part]:
            lo = np.array(box[0::2], np.uint8)
            hi = np.array(box[1::2], np.uint8)
            mm = cv2.inRange(hsv, lo, hi)
            m = mm if m is None else cv2.bitwise_or(m, mm)
        if part in ("bottle", "glass", "skin"):
            m = cv2.morphologyEx(m, cv2.MORPH_OPEN, _KERNEL)
        out[part] = m
    return out


def blobs(mask: np.ndarray, part: str, keep: int = 4) -> tuple[list[Blob], np.ndarray]:
    """The `keep` largest connected components of a mask (area >= MIN_AREA[part]), and the label image."""
    n, lab, stats, cents = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if n <= 1:
        return [], lab
    areas = stats[1:, cv2.CC_STAT_AREA]
    order = np.argsort(-areas)[:keep]
    res = []
    for k in order:
        if areas[k] < MIN_AREA[part]:
            break
        i = k + 1
        x, y, w, h = (int(v) for v in stats[i, :4])
        res.append(Blob(part, int(areas[k]), cents[i].copy(), (x, y, w, h), int(i)))
    return res, lab
