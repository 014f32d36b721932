"""Calibration of the colour ranges and of the geometry vision needs, by rendering labelled scenes.

`calibrate(seed)` renders scenes from the "calibrate" seed stream with both head cameras,
takes the pixels of each part from the renderer's segmentation (a calibration target: the
one place where labels touch pixels) and sets each part's HSV range from robust percentiles.
It also learns where static skin is (the partner's resting left arm and face: skin that is
never the working hand), so that the working hand can be told apart: as blob centres, and as a
cloud of 1 cm cells on the static skin's surface, found from the renderer's depth (the other
calibration target) as the skin cells occupied in most scenes, which the working arm, posed
anew in each scene, is not.  And where the working arm is rooted (its shoulder, which the
seated person does not move): the hand is the part of a skin blob farthest from it.  The result
is a small JSON file (`assets/templates/calibration.json`) that `assistbot calibrate` writes.
"""

from __future__ import annotations

import cv2
import numpy as np

from assistbot.vision.segment import PARTS
from assistbot.world.layout import TABLE_Z
from assistbot.world.render import SEGMENT_LABELS

_SEG = {v: k for k, v in SEGMENT_LABELS.items()}


def _circ_range(h: np.ndarray, pct: float = 98.0, pad: int = 4) -> list[tuple[int, int]]:
    """Hue interval(s) covering pct% of hues h (0..179, circular) around their circular mean."""
    ang = h.astype(float) * (2 * np.pi / 180.0)
    mean = (np.arctan2(np.sin(ang).mean(), np.cos(ang).mean()) * 180.0 / (2 * np.pi)) % 180.0
    diff = (h.astype(float) - mean + 90.0) % 180.0 - 90.0
    lo = int(np.floor(mean + np.percentile(diff, 100 - pct) - pad))
    hi = int(np.ceil(mean + np.percentile(diff, pct) + pad))
    if lo < 0:
        return [(0, hi), (180 + lo, 179)]
    if hi > 179:
        return [(lo, 179), (0, hi - 180)]
    return [(lo, hi)]


def hsv_boxes(pixels: np.ndarray, s_pad: int = 25, v_pad: int = 30, lo_pct: float = 2.0) -> list[list[int]]:
    """Boxes [h_lo, h_hi, s_lo, s_hi, v_lo, v_hi] for (N, 3) HSV pixels."""
    s_lo, s_hi = np.percentile(pixels[:, 1], [lo_pct, 99.5])
    v_lo, v_hi = np.percentile(pixels[:, 2], [lo_pct, 99.5])
    sv = [max(0, int(s_lo) - s_pad), min(255, int(s_hi) + s_pad), max(0, int(v_lo) - v_pad), min(255, int(v_hi) + v_pad)]
    return [[a, b, *sv] for a, b in _circ_range(pixels[:, 0])]


def calibrate(seed: int = 0, n_scenes: int = 18, progress=None) -> dict:
    from assistbot.task import HAND_POSTURES
    from assistbot.vision.capture import StereoCapture
    from assistbot.vision.scenes import SceneSampler, pose
    from assistbot.world import PAPER_ARRANGEMENTS, build_world

    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed)
    sampler = SceneSampler(seed, "calibrate")
    samples: dict[str, list[np.ndarray]] = {p: [] for p in PARTS}
    full_glass: list[np.ndarray] = []
    frames = []
    cells: list[set] = []
    roots: list[np.ndarray] = []
    shoulder = world.model.body("human_r_upper_arm").id
    with StereoCapture(world.model) as cap:
        for i in range(n_scenes):
            lab = pose(world, sampler.sample(HAND_POSTURES[i % len(HAND_POSTURES)]))
            f = cap.grab(world.data)
            segs = cap.segmentation(world.data)
            cells.append(_skin_cells(f.cams, segs, cap.depth(world.data)))
            roots.append(world.data.xpos[shoulder] - [0.0, 0.0, TABLE_Z])
            for img, seg in zip((f.left, f.right), segs):
                hsv = cv2.cvtColor(img, cv2.COLOR_RGB2HSV)
                for part in samples:
                    sel = cv2.erode((seg == _SEG[part]).astype(np.uint8), np.ones((2, 2), np.uint8)) > 0
                    if part == "glass" and lab.objects["glass"]["state"] == "full":
                        full_glass.append(hsv[sel])
                    else:
                        samples[part].append(hsv[sel])
            frames.append((f, lab))
            if progress:
                progress(i + 1, n_scenes)
    pix = {k: np.concatenate(v) for k, v in samples.items()}
    ranges = {k: hsv_boxes(v) for k, v in pix.items() if k not in ("liquid", "skin")}
    # skin: its pale highlights reach the grey floor's saturation; keep the bulk only
    ranges["skin"] = hsv_boxes(pix["skin"], s_pad=6, v_pad=20, lo_pct=5.0)
    # liquid: as itself, and as seen through the glass (full-glass pixels whose hue is off the glass's)
    g = pix["glass"][:, 0].astype(float)
    gmean = (np.degrees(np.arctan2(np.sin(g * np.pi / 90).mean(), np.cos(g * np.pi / 90).mean())) / 2) % 180
    fg = np.concatenate(full_glass) if full_glass else np.zeros((0, 3), np.uint8)
    dh = (fg[:, 0].astype(float) - gmean + 90) % 180 - 90
    off = (dh > 10) & (dh < 60)          # the liquid (purple) through the cyan wall: bluer than the glass
    liquid = np.concatenate([pix["liquid"], fg[off]])
    ranges["liquid"] = hsv_boxes(liquid, s_pad=15, v_pad=20, lo_pct=5.0)
    # glass range must not swallow the liquid: keep its hue interval tight
    ranges["glass"] = [[a, b, *r[2:]] for (a, b), r in zip(_circ_range(g.astype(int), 97, 3), ranges["glass"])]
    static = _static_skin(frames, ranges)
    return {"version": 1, "seed": seed, "scenes": n_scenes, "hsv": ranges, "static_skin": static,
            "static_skin_cells": _static_cells(cells), "arm_root": [round(float(v), 4) for v in np.median(roots, axis=0)],
            "pixels": {k: int(len(v)) for k, v in pix.items()}}


STATIC_CELL = 0.01          # m: the static skin cloud's cell size
STATIC_SHARE = 0.3          # share of the scenes a static cell is occupied in (the working arm's cells: far fewer)


def _skin_cells(cams, segs, depths) -> set:
    """The 1 cm cells (integer keys) that skin pixels of either camera fall in, from the rendered depth."""
    keys = set()
    for cam, seg, z in zip(cams, segs, depths):
        v, u = np.nonzero(seg == _SEG["skin"])
        d = cam.ray(np.column_stack([u + 0.5, v + 0.5]))
        X = cam.C + d * (z[v, u] / (d @ cam.R[2]))[:, None]     # depth is along the optical axis
        keys.update(map(tuple, np.floor(X / STATIC_CELL).astype(int).tolist()))
    return keys


def _static_cells(cells: list[set]) -> list[list[float]]:
    """Centres (table frame, m) of the cells occupied in at least `STATIC_SHARE` of the scenes."""
    count: dict[tuple, int] = {}
    for keys in cells:
        for k in keys:
            count[k] = count.get(k, 0) + 1
    need = STATIC_SHARE * len(cells)
    return [[round((c + 0.5) * STATIC_CELL, 3) for c in k] for k in sorted(count) if count[k] >= need]


def _static_skin(frames, ranges) -> list[list[float]]:
    """3-D centres (table frame) of skin blobs that are never the working hand (left hand, face)."""
    from assistbot.vision.camera import triangulate
    from assistbot.vision.segment import LABEL, ColourTable, components

    table = ColourTable(ranges)
    pts = []
    for f, lab in frames:
        bl = [components(table.half(im)[0] == LABEL["skin"], "skin", 6)[0] for im in (f.left, f.right)]
        hand = np.array(lab.hand_position)
        for a in bl[0]:
            cands = [b for b in bl[1] if abs(b.centroid[1] - a.centroid[1]) < 12 and 0 < a.centroid[0] - b.centroid[0] < 120]
            if not cands:
                continue
            b = min(cands, key=lambda b: abs(b.area - a.area))
            X = triangulate(f.cams[0], f.cams[1], a.centroid, b.centroid)[0]
            if np.linalg.norm(X - hand) > 0.15:
                pts.append(X)
    if not pts:
        return []
    pts = np.array(pts)
    centres: list[np.ndarray] = []
    for p in pts:   # greedy clustering at 8 cm; keep clusters seen in >= 20% of the scenes
        for c in centres:
            if np.linalg.norm(c[:3] / c[3] - p) < 0.08:
                c[:3] += p
                c[3] += 1
                break
        else:
            centres.append(np.array([*p, 1.0]))
    return [[round(float(v), 4) for v in c[:3] / c[3]] for c in centres if c[3] >= 0.2 * len(frames)]
