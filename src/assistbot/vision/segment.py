"""Colour segmentation: one label image per camera from a colour look-up table, blobs per part.

Parts: bottle (green), stopper (red), glass (cyan, translucent), liquid (purple, also as seen
through the glass), skin (hands, arms, face) and shirt (torso, sleeves).  The calibrated HSV
ranges (`assistbot calibrate`) are a list of boxes (h_lo, h_hi, s_lo, s_hi, v_lo, v_hi) per part in
OpenCV units (H 0..179, S and V 0..255; a red hue that wraps around 0 is two boxes).

Speed: the boxes are compiled once into a 64x64x64 RGB -> label table (`ColourTable`); labelling
an image is then one look-up per pixel by its packed colour (no per-frame HSV conversion or
per-part inRange).  Blobs are found on the half-resolution label image (`ColourTable.half`), with
one connected-components pass per part group; fine measurements (stopper, liquid, edges) label
only small full-resolution regions of interest.  The per-pixel passes are numba kernels
(`_kernels`) when numba is there, numpy and OpenCV otherwise, with the same results bit for bit:
vision runs right after each render, which leaves the CPU caches cold, and there one pass over an
image in compiled code costs much less than ~10 numpy and OpenCV calls that each re-read it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import cv2
import numpy as np

try:   # the compiled per-pixel pass (numba, a dependency of the fields too); numpy without it
    from assistbot.vision import _kernels
except ImportError:  # pragma: no cover
    _kernels = None

PARTS = ("bottle", "stopper", "glass", "liquid", "skin", "shirt")
#: label values of the label image (0: none of the parts)
LABEL = {p: i + 1 for i, p in enumerate(PARTS)}
#: minimum blob areas at half resolution (px)
MIN_AREA = {"bottle": 4, "glass": 4, "skin": 6, "shirt": 20}
_BITS = 6


@dataclass(frozen=True)
class LabelRange:
    """The mask lo <= labels <= hi of a label image, not written out: `components_each` reads it from the
    labels (writing three masks per image was a pass over cold memory each)."""

    labels: np.ndarray
    lo: int
    hi: int


@dataclass
class Blob:
    """One connected component: area (px), centroid (u, v), bbox (x, y, w, h), label id; full-resolution pixels."""

    part: str
    area: float
    centroid: np.ndarray
    bbox: tuple[int, int, int, int]
    label: int


class ColourTable:
    """RGB (6 bits per channel) -> part label, compiled from the calibrated HSV boxes."""

    def __init__(self, ranges: dict[str, list[list[int]]]) -> None:
        n = 1 << _BITS
        q = (np.arange(n) << (8 - _BITS)) + (1 << (7 - _BITS))
        r, g, b = np.meshgrid(q, q, q, indexing="ij")
        rgb = np.stack([r, g, b], -1).reshape(-1, 1, 3).astype(np.uint8)
        hsv = cv2.cvtColor(rgb, cv2.COLOR_RGB2HSV).reshape(-1, 3).astype(int)
        lut = np.zeros(len(hsv), np.uint8)
        # later parts win where boxes overlap: liquid over glass (seen through it), stopper over skin
        for part in ("shirt", "skin", "bottle", "glass", "liquid", "stopper"):
            for box in ranges.get(part, []):
                sel = ((hsv[:, 0] >= box[0]) & (hsv[:, 0] <= box[1]) & (hsv[:, 1] >= box[2]) & (hsv[:, 1] <= box[3])
                       & (hsv[:, 2] >= box[4]) & (hsv[:, 2] <= box[5]))
                lut[sel] = LABEL[part]
        self.lut = lut              # index r6 << 12 | g6 << 6 | b6: the compiled passes' table (262 KB)
        self._ranges: dict = {}     # `half`'s label ranges as the kernel's arrays (lo, hi), per ranges tuple
        if _kernels is not None:   # compile (or load from numba's cache) now, not in the first frame
            self.half(np.zeros((2, 2, 3), np.uint8), ((1, 1),), 1, np.zeros((1, 2)), np.ones((1, 1), np.uint8))
            for img in (np.zeros((2, 2, 3), np.uint8), np.zeros((2, 2, 3), np.uint8)[:, :1]):   # whole, strided
                lab, mask = self.region(img, np.zeros(256, np.uint8))
                self.region_silhouette(img, np.zeros(256, np.uint8))
                masked_saturation(img, mask)
            silhouette(mask)
            first_row_over(lab, mask, 1, 0, 1)
            blob_pixels((np.zeros((2, 2), np.int32), 0, 0), 1, lab, 1, 0, 0, 2, 2)
            count_near(lab, mask, 1, 1)
            _kernels.components8(lab, 1, 1, 0, 0, lab.shape[1], lab.shape[0])

    @cached_property
    def lut24(self) -> np.ndarray:
        """The table laid out for the numpy path's one gather by the pixel's packed colour, with each
        channel first shifted to its top 6 bits (one pass over the bytes): cv2.cvtColor to BGRA packs
        (r >> 2) << 16 | (g >> 2) << 8 | (b >> 2) into a 32-bit word, so the labels sit at those
        (sparse) offsets in a 2^24-entry table, of which the gather touches only the first 4 MB and 64
        colours per cache line (spreading the table over all 2^24 colours instead made the gather ~3x
        slower in the running pipeline: cache and TLB misses).  Made when first used."""
        n = 1 << _BITS
        q6 = np.arange(n)
        lut24 = np.zeros(1 << 24, np.uint8)
        lut24[(q6[:, None, None] << 16) | (q6[None, :, None] << 8) | q6[None, None, :]] = self.lut.reshape(n, n, n)
        return lut24

    def labels(self, img: np.ndarray, step: int = 1) -> np.ndarray:
        """(H/step, W/step) uint8 labels of an RGB image (every `step`-th pixel)."""
        sub = cv2.resize(img, None, fx=1 / step, fy=1 / step, interpolation=cv2.INTER_NEAREST) if step > 1 else img
        h, w = sub.shape[:2]
        if h == 0 or w == 0:
            return np.zeros((h, w), np.uint8)
        # BGRA bytes read as a little-endian int32: A << 24 | R << 16 | G << 8 | B with A = 255, i.e.
        # (R << 16 | G << 8 | B) - 2^24: a negative index that counts from the end of the 2^24-entry
        # table, so it gathers the colour's label directly (no masking pass over the image)
        code = cv2.cvtColor(sub >> (8 - _BITS), cv2.COLOR_RGB2BGRA).view(np.int32).reshape(h, w)
        return np.take(self.lut24, code)

    def region(self, img: np.ndarray, part: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``labels(img)`` of an image or a region of one, and its mask (bool) of the labels that ``part``
        (a 256-entry 0/1 table over the labels) selects: one compiled pass with numba (see `half`)."""
        if _kernels is not None and img.dtype == np.uint8 and img.ndim == 3 and img.shape[2] == 3:
            return _kernels.label_region(img, self.lut, part)
        lab = self.labels(img)
        return lab, np.take(part, lab).view(bool)

    def region_silhouette(self, img: np.ndarray, part: np.ndarray) -> tuple:
        """`region` and `silhouette` of its mask: (labels, mask, rows, first, last, extents, moments), in
        one compiled call with numba."""
        if _kernels is not None and img.dtype == np.uint8 and img.ndim == 3 and img.shape[2] == 3:
            return _kernels.label_silhouette(img, self.lut, part)
        lab, mask = self.region(img, part)
        return (lab, mask, *silhouette(mask))

    def half(self, img: np.ndarray, ranges: tuple[tuple[int, int], ...], clear: int = 0, spots: np.ndarray | None = None,
             stamp: np.ndarray | None = None) -> tuple[np.ndarray, list, list[tuple[int, int, int, int]]]:
        """``labels(img, 2)`` with label ``clear`` removed (0) where `cover` of the half-resolution points
        ``spots`` (u, v) by ``stamp`` lies, a mask per label range (lo, hi) of the result (a `LabelRange`;
        uint8 0/255 arrays on the numpy path), and each mask's bounding box (as cv2.boundingRect).

        One compiled pass over the image when numba is there (see `_kernels`): the image comes fresh
        from the renderer, which has evicted the CPU caches, so each of the numpy path's passes (resize,
        shift, colour packing, gather, the cover's dilation, clearing, one comparison per mask) would
        read from memory and run cold code of its own; the same integers either way."""
        H, W = img.shape[:2]
        if spots is None or stamp is None:
            spots, stamp = np.zeros((0, 2)), np.ones((1, 1), np.uint8)
        if (_kernels is not None and img.dtype == np.uint8 and img.ndim == 3 and img.shape[2] == 3 and H % 2 == 0
                and W % 2 == 0 and H > 0 and W > 0 and img.flags.c_contiguous):
            lohi = self._ranges.get(ranges)
            if lohi is None:
                lohi = self._ranges[ranges] = tuple(np.array([r[i] for r in ranges], np.uint8) for i in (0, 1))
            lab, boxes = _kernels.label_half(img, self.lut, np.ascontiguousarray(spots, np.float64), stamp, clear, *lohi)
            return lab, [LabelRange(lab, lo, hi) for lo, hi in ranges], [tuple(b) for b in boxes.tolist()]
        lab = self.labels(img, 2)
        if len(spots):
            lab[cover(spots, stamp, lab.shape) & (lab == clear)] = 0
        masks = [cv2.inRange(lab, lo, hi) for lo, hi in ranges]     # 0/255: components take nonzero
        return lab, masks, [cv2.boundingRect(m) for m in masks]


def silhouette(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A (bool) mask's rows that have pixels, their first and last pixel's columns (intp), its extents
    (intp): x, y, w, h (as cv2.boundingRect), the first and last column of its bottom two rows and of
    its top two rows (all 0 if empty), and its moments m00, m10, m01, mu20, mu11, mu02 (float64, as
    cv2.moments(binaryImage=True)).  One compiled pass with numba (see `ColourTable.half`)."""
    if _kernels is not None and mask.dtype == np.bool_ and mask.ndim == 2:
        return _kernels.silhouette(mask)
    m8 = mask.view(np.uint8)
    rows = np.flatnonzero(mask.any(axis=1))
    sub = mask[rows]
    first = sub.argmax(axis=1)
    last = mask.shape[1] - 1 - sub[:, ::-1].argmax(axis=1)
    mo = cv2.moments(m8, binaryImage=True)
    mom = np.array([mo[k] for k in ("m00", "m10", "m01", "mu20", "mu11", "mu02")])
    x, y, w, h = cv2.boundingRect(m8)
    if w == 0:
        return rows, first, last, np.zeros(8, np.intp), mom
    bot = y + h - 1
    bx, _, bw, _ = cv2.boundingRect(m8[max(y, bot - 1):bot + 1])
    tx, _, tw, _ = cv2.boundingRect(m8[y:y + 2])
    return rows, first, last, np.array([x, y, w, h, bx, bx + bw - 1, tx, tx + tw - 1], np.intp), mom


def first_row_over(lab: np.ndarray, mask: np.ndarray, part: int, lo: int, hi: int) -> int:
    """The first row in [lo, hi] of a label image with a pixel labelled ``part`` in a column where the
    (bool) mask has pixels in any row; -1 if none.  Compiled with numba (see `ColourTable.half`)."""
    if _kernels is not None and mask.dtype == np.bool_:
        return _kernels.first_row_over(lab, mask, part, lo, hi)
    rows = np.flatnonzero(((lab[:hi + 1] == part) & mask.any(axis=0)).any(axis=1))
    rows = rows[rows >= lo]
    return int(rows[0]) if rows.size else -1


def blob_pixels(view: tuple, label: int, lab: np.ndarray, near: int, x0: int, y0: int, x1: int,
                y1: int) -> tuple[np.ndarray, int, int, int]:
    """In the window [y0, y1) x [x0, x1) of a half-resolution image: the centres (x, y) at full
    resolution of component ``label``'s pixels (``view``: the components' view, see `components_each`), row by row,
    and of those of them next to (3x3, within the window) a pixel labelled ``near`` in ``lab``: the
    count and the sums of their window columns and rows.  Compiled with numba (see `ColourTable.half`)."""
    comp, ox, oy = view
    if _kernels is not None:
        P, n, sx, sy = _kernels.blob_pixels(comp, ox, oy, label, lab, near, x0, y0, x1, y1)
        return P, int(n), int(sx), int(sy)
    own = np.zeros((y1 - y0, x1 - x0), bool)
    ix0, iy0, ix1, iy1 = max(x0, ox), max(y0, oy), min(x1, ox + comp.shape[1]), min(y1, oy + comp.shape[0])
    if ix1 > ix0 and iy1 > iy0:
        own[iy0 - y0:iy1 - y0, ix0 - x0:ix1 - x0] = comp[iy0 - oy:iy1 - oy, ix0 - ox:ix1 - ox] == label
    # small integers and halves: exact in any order
    P = np.argwhere(own)[:, ::-1] * 2.0 + [2 * x0 + 0.5, 2 * y0 + 0.5]
    touch = np.nonzero(own & (cv2.dilate((lab[y0:y1, x0:x1] == near).view(np.uint8), np.ones((3, 3), np.uint8)) > 0))
    return P, int(touch[0].size), int(touch[1].sum()), int(touch[0].sum())


def count_near(lab: np.ndarray, mask: np.ndarray, part: int, r: int) -> int:
    """How many pixels labelled ``part`` lie in the (bool) mask dilated by a (2r+1)^2 box.  Compiled
    with numba (see `ColourTable.half`)."""
    if _kernels is not None and mask.dtype == np.bool_:
        return int(_kernels.count_near(lab, mask, part, r))
    near = cv2.dilate(mask.view(np.uint8), np.ones((2 * r + 1, 2 * r + 1), np.uint8)) > 0
    return int(np.count_nonzero(near & (lab == part)))


def masked_saturation(img: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """HSV saturation (max - min) / max(max, 1) of an RGB image's pixels, float32, 0 off the (bool) mask.
    Compiled with numba (see `ColourTable.half`): the same float32 operations."""
    if _kernels is not None and img.dtype == np.uint8 and mask.dtype == np.bool_:
        return _kernels.masked_saturation(img, mask)
    r, g, b = cv2.split(img)
    mx = cv2.max(cv2.max(r, g), b).astype(np.float32)
    return (mx - cv2.min(cv2.min(r, g), b)) / np.maximum(mx, 1.0) * mask


def cover(spots: np.ndarray, stamp: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Where points (u, v) (floats, truncated to pixels; non-finite ones and those outside left out),
    dilated by the structuring element ``stamp``, lie in an image of this shape (bool)."""
    ok = np.isfinite(spots).all(axis=1)
    u, v = spots[ok, 0].astype(int), spots[ok, 1].astype(int)
    ok = (u >= 0) & (v >= 0) & (u < shape[1]) & (v < shape[0])
    m = np.zeros(shape, np.uint8)
    m[v[ok], u[ok]] = 1
    return cv2.dilate(m, stamp).view(bool)


def components(mask: np.ndarray, part: str, keep: int = 4, scale: int = 2) -> tuple[list[Blob], tuple]:
    """The `keep` largest connected components of a (half-resolution) mask, in full-resolution pixels,
    and its view (see `components_each`): `components_each` of one mask."""
    found, views = components_each([[mask]], (part,), (keep,), scale)
    return found[0][0], views[0][0]


def components_each(masks: list[list[np.ndarray]], parts: tuple[str, ...], keep: tuple[int, ...], scale: int = 2,
                     pairs_only: bool = False, views_of: tuple[int, ...] | None = None, boxes=None):
    """Connected components of several (half-resolution) masks: masks[camera][k] (bool, uint8 with
    nonzero pixels in, or a `LabelRange`).  Returns, per camera
    and part, the `keep[k]` largest blobs (full-resolution pixels; ``Blob.label`` indexes the views) and
    per camera and part the view of that mask: (labels, x0, y0), the label image of the part of the mask
    at column x0, row y0 (it covers all the mask's pixels; 0 elsewhere), as `blob_pixels` reads it
    (not the whole mask's label image: zeroing and filling one was a pass over cold memory per call).

    One connected-components call per mask (Grana's algorithm, ~3x faster than the default on these
    sparse masks): measured faster than one call on the masks tiled into one image (~0.3 vs ~0.9 ms
    for 2 x 3 masks of 160x120).  Each call sees only the mask's bounding box, widened to even
    rows and columns (~0.035 vs ~0.064 ms a call): Grana's algorithm scans 2x2 blocks, so on that
    aligned box it meets the same foreground blocks in the same order and numbers the components as
    on the whole mask; the statistics are moved back to the whole mask's pixels (the centroids from
    their exact integer sums, as OpenCV divides them).  An empty mask, and with ``pairs_only`` a
    later camera's mask of a part the first camera has no blob of (nothing to pair it with), get no
    blobs and an empty view without the call.  ``views_of``: the mask indices k whose views the caller
    reads (None: all); the others' views are None.
    ``boxes``: the masks' bounding boxes (boxes[camera][k], as cv2.boundingRect) when known already."""
    out: list[list[list[Blob]]] = []
    views = []
    for c, cm in enumerate(masks):
        oc, vc = [], []
        for k, m in enumerate(cm):
            # the mask as a range of values of an array: a label image's range, or a mask's nonzero
            src, lo, hi = (m.labels, m.lo, m.hi) if isinstance(m, LabelRange) else (m.view(np.uint8), 1, 255)
            if pairs_only and c > 0 and not out[0][k]:
                bw = 0
            else:
                bx, by, bw, bh = boxes[c][k] if boxes is not None else cv2.boundingRect(cv2.inRange(src, lo, hi))
            want = views_of is None or k in views_of
            if bw == 0:
                oc.append([])
                vc.append((np.zeros((0, 0), np.int32), 0, 0) if want else None)
                continue
            x0, y0 = bx & ~1, by & ~1
            x1, y1 = bx + bw, by + bh
            if _kernels is not None:
                # the same labels, statistics and (as exact sums) centroids as OpenCV's, compiled
                sub, stats, sums = _kernels.components8(src, lo, hi, x0, y0, x1, y1)
                n = len(stats)
            else:
                m8 = cv2.inRange(src[y0:y1, x0:x1], lo, hi)
                n, sub, stats, cents = cv2.connectedComponentsWithStatsWithAlgorithm(m8, 8, cv2.CV_32S, cv2.CCL_GRANA)
                # the pixel sums of this crop (exact integers) from OpenCV's centroids (sum / area)
                sums = np.round(cents * stats[:, cv2.CC_STAT_AREA:cv2.CC_STAT_AREA + 1])
            vc.append((sub, x0, y0) if want else None)
            res: list[Blob] = []
            if n > 1:
                # the largest components of at least the minimum area, larger first, ties in label order
                areas = stats[:, cv2.CC_STAT_AREA].tolist()
                min_area = MIN_AREA[parts[k]]
                big = sorted((i for i in range(1, n) if areas[i] >= min_area), key=lambda i: -areas[i])[:keep[k]]
                for i in big:
                    x, y, w, h = stats[i, :4].tolist()
                    a = float(areas[i])
                    sx, sy = sums[i].tolist()
                    # the pixel sums moved by the crop's offset, over the area (as OpenCV divides them)
                    cx = (sx + x0 * a) / a
                    cy = (sy + y0 * a) / a
                    res.append(Blob(parts[k], a * scale * scale, np.array([(cx + 0.5) * scale - 0.5, (cy + 0.5) * scale - 0.5]),
                                    ((x + x0) * scale, (y + y0) * scale, w * scale, h * scale), i))
            oc.append(res)
        out.append(oc)
        views.append(vc)
    return out, views
