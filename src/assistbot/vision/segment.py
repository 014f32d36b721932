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
(`_kernels`): vision runs right after each render, which leaves the CPU caches cold, and there one
pass over an image in compiled code costs much less than ~10 numpy and OpenCV calls that each
re-read it.  They follow OpenCV's conventions (cv2.boundingRect, cv2.moments, the component
numbering of cv2.connectedComponents), which the tests hold them to.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from assistbot.vision import _kernels

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
        # compile (or load from numba's cache) now, not in the first frame
        self.half(np.zeros((2, 2, 3), np.uint8), ((1, 1),), 1, np.zeros((1, 2)), np.ones((1, 1), np.uint8))
        for img in (np.zeros((2, 2, 3), np.uint8), np.zeros((2, 2, 3), np.uint8)[:, :1]):   # whole, strided
            lab, mask = self.region(img, np.zeros(256, np.uint8))
            self.region_silhouette(img, np.zeros(256, np.uint8))
            masked_saturation(img, mask)
        first_row_over(lab, mask, 1, 0, 1)
        blob_pixels((np.zeros((2, 2), np.int32), 0, 0), 1, lab, 1, 0, 0, 2, 2)
        count_near(lab, mask, 1, 1)
        _kernels.components8(lab, 1, 1, 0, 0, lab.shape[1], lab.shape[0])

    def region(self, img: np.ndarray, part: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The (uint8) labels of every pixel of an RGB (uint8) image or a region of one (any strides), and
        their mask (bool) of the labels that ``part`` (a 256-entry 0/1 table over the labels) selects."""
        return _kernels.label_region(img, self.lut, part)

    def region_silhouette(self, img: np.ndarray, part: np.ndarray) -> tuple:
        """`region` and its mask's silhouette in one call: (labels, mask, rows, first, last, extents,
        moments).  The silhouette: the mask's rows that have pixels, their first and last pixel's
        columns (intp), its extents (intp): x, y, w, h (as cv2.boundingRect), the first and last column
        of its bottom two rows and of its top two rows (all 0 if empty), and its moments m00, m10, m01,
        mu20, mu11, mu02 (float64, as cv2.moments(binaryImage=True))."""
        return _kernels.label_silhouette(img, self.lut, part)

    def half(self, img: np.ndarray, ranges: tuple[tuple[int, int], ...] = (), clear: int = 0, spots: np.ndarray | None = None,
             stamp: np.ndarray | None = None) -> tuple[np.ndarray, list[LabelRange], list[tuple[int, int, int, int]]]:
        """The (uint8) labels of every 2nd pixel of every 2nd row of an RGB (uint8) image (``img[::2, ::2]``),
        with label ``clear`` removed (0) where the structuring element ``stamp`` (odd size) dilated around
        the half-resolution points ``spots`` (u, v; floats truncated to pixels, non-finite ones and those
        outside left out) lies, a mask per label range (lo, hi) of the result (a `LabelRange`), and each
        mask's bounding box (as cv2.boundingRect).

        One compiled pass over the image: it comes fresh from the renderer, which has evicted the CPU
        caches, so separate passes (sub-sampling, colour packing, look-up, the stamp's dilation,
        clearing, one comparison per mask) would each read it from memory and run cold code of their own."""
        if spots is None or stamp is None:
            spots, stamp = np.zeros((0, 2)), np.ones((1, 1), np.uint8)
        lohi = self._ranges.get(ranges)
        if lohi is None:
            lohi = self._ranges[ranges] = tuple(np.array([r[i] for r in ranges], np.uint8) for i in (0, 1))
        # one compiled variant: the renders are contiguous already (no copy)
        lab, boxes = _kernels.label_half(np.ascontiguousarray(img), self.lut, np.ascontiguousarray(spots, np.float64), stamp, clear, *lohi)
        return lab, [LabelRange(lab, lo, hi) for lo, hi in ranges], [tuple(b) for b in boxes.tolist()]


def first_row_over(lab: np.ndarray, mask: np.ndarray, part: int, lo: int, hi: int) -> int:
    """The first row in [lo, hi] of a label image with a pixel labelled ``part`` in a column where the
    (bool) mask has pixels in any row; -1 if none."""
    return int(_kernels.first_row_over(lab, mask, part, lo, hi))


def blob_pixels(view: tuple, label: int, lab: np.ndarray, near: int, x0: int, y0: int, x1: int,
                y1: int) -> tuple[np.ndarray, int, int, int]:
    """In the window [y0, y1) x [x0, x1) of a half-resolution image: the centres (x, y) at full
    resolution of component ``label``'s pixels (``view``: the components' view, see `components_each`), row by row,
    and of those of them next to (3x3, within the window) a pixel labelled ``near`` in ``lab``: the
    count and the sums of their window columns and rows."""
    comp, ox, oy = view
    P, n, sx, sy = _kernels.blob_pixels(comp, ox, oy, label, lab, near, x0, y0, x1, y1)
    return P, int(n), int(sx), int(sy)


def count_near(lab: np.ndarray, mask: np.ndarray, part: int, r: int) -> int:
    """How many pixels labelled ``part`` lie in the (bool) mask dilated by a (2r+1)^2 box."""
    return int(_kernels.count_near(lab, mask, part, r))


def masked_saturation(img: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """HSV saturation (max - min) / max(max, 1) of an RGB (uint8) image's pixels, float32, 0 off the (bool) mask."""
    return _kernels.masked_saturation(img, mask)


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

    One compiled connected-components call per mask (`_kernels.components8`, numbered as OpenCV's
    Grana algorithm numbers them).  Each call sees only the mask's bounding box, widened to even
    rows and columns: components are numbered in the order of their first 2x2 block, so on that
    aligned box they are numbered as on the whole mask; the statistics are moved back to the whole
    mask's pixels (the centroids from their exact integer sums, as OpenCV divides them).  An empty mask, and with ``pairs_only`` a
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
            # OpenCV's labels and statistics, and the pixel sums (exact integers) behind its centroids
            sub, stats, sums = _kernels.components8(src, lo, hi, x0, y0, x1, y1)
            n = len(stats)
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
