"""From a stereo pair to detections: blobs per part, stereo matching, 3-D positions, crops and features.

Everything here works on pixels and on the cameras' models only.  Positions are in table
coordinates (m): an object's position is the centre of the base it stands on.

* Blobs come from the half-resolution label image (`segment.ColourTable`); each object's blob is
  then re-labelled at full resolution in a small region of interest for its edges, its stopper
  and its liquid.
* An object's base: the bottom-centre points of its silhouette in both cameras, triangulated;
  standing on the table (that point within `ON_TABLE_TOL` of the table) it is the two rays'
  meeting points with the table plane instead (more precise than stereo depth at a 0.12 m
  baseline); then moved by the object's radius along the viewing direction (the lowest
  silhouette point is the base rim's front).
* An object is "visible" if both cameras show all of it: its blob off the image border and its
  silhouette's height and width at least `MIN_EXTENT` of what an upright object at that place
  projects to (`MIN_EXTENT_HELD` for one lifted in a hand, which always covers part of it).  One
  whole in one camera only, at least `MIN_EXTENT_HELD` of it in the other (its bottom hidden there,
  by the robot's gripper say), or whole in both but with bottoms that do not triangulate onto the
  table, is visible if it stands: its axis, triangulated from the rows that show its full width in
  both images, within `BASE_AGREE` of where each whole camera's base ray meets the table; it is
  placed by those rays.  A half-hidden object is reported unseen, not misplaced.
* A silhouette whose lowest row lies on the robot's own arm (`vision.body`: the arm's shape where
  its joints put it, which the robot knows) is not whole in that camera: the arm may hide its base,
  and its lowest row, placed on the table, would put it too far.  Nor is such an object taken for
  one lifted in the hand.
* The working hand: skin blobs, less the static skin (the resting left arm, the face) that the
  calibration located.  Its cloud of cells, projected into each image, takes the static skin's
  pixels out of the skin label before the blobs are found, so that a working hand touching the
  resting arm in the image is not merged with it; blobs centred on a static spot are skipped.
  The hand is the part of the skin blob farthest from the working arm's calibrated shoulder; the
  arm's root (a feature) is where the skin meets the sleeve (the shirt blob: its colour is
  distinct), or, with no sleeve in view, the shirt's centroid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import cv2
import numpy as np
from scipy.stats import theilslopes

from assistbot import catalogue
from assistbot.vision import _kernels
from assistbot.vision.body import RobotBody
from assistbot.vision.camera import CameraModel, expected_boxes, on_plane, triangulate
from assistbot.vision.segment import LABEL, Blob, ColourTable, blob_pixels, components_each, count_near, first_row_over, masked_saturation
from assistbot.world.layout import TABLE_HALF_X

cv2.setNumThreads(1)   # per-frame work on small images: OpenCV's thread pool costs more than it saves

MIN_EXTENT = 0.82
MIN_EXTENT_HELD = 0.55
MAX_EXTENT = 1.3           # more than this: merged with something of the same colour
MAX_TILT = 0.6             # rad in the image: a strongly tilted object (pouring) cannot be placed
AXIS_ROWS = 5              # rows showing a lifted object's full width in both cameras, to place it by its axis
HELD_DIST = 0.16           # m: a lifted object whose axis (base to top) is this close to the hand is held by it
#: height of the silhouette's centroid above the base (m) of a lifted, upright object
CENTROID_Z = {"bottle": 0.085, "glass": 0.05}
#: object heights (m) for the expected silhouettes
HEIGHT = {n: catalogue.height(n) for n in catalogue.TASK_OBJECTS}   # the bottle without its (red) stopper
CROP = {"glass": (16, 20), "hand": (24, 24)}   # template sizes (w, h)
ON_TABLE_TOL = 0.03
BASE_AGREE = 0.02          # m: a standing object's axis is where a camera that sees its base puts that base
BELOW_PX = 2.0             # px under a silhouette's lowest row where the robot's arm, if it is there, hides the base
#: rad: an object on the table whose silhouette lies this far from the image vertical in both cameras lies
#: on its side (standing: 0.1-0.2; lying across the line of sight: 1.5). Seen end-on, along a camera's line
#: of sight, a lying glass or bottle looks upright: that one vision cannot tell from one pair
LYING_TILT = 1.0
FACE_Z = 0.40              # m above the table: skin higher than this is the face, not the working hand
STATIC_SKIN_R = 0.08       # m: skin this close to a calibrated static spot is not the working hand
STATIC_MARGIN = 2          # half-resolution px (~1-2 cm at the table) around the static cells' projections
HAND_REACH = 0.10          # m: hand crop half-size
BEYOND_TIP_PX = 3.0        # px past the hand skin's farthest pixel where the robot's arm, if it is there, hides the rest
#: px: the head's cameras are a rectified pair (one orientation, side by side), so one point lies on the same image
#: row in both; hand ends whose rows differ by more are not one point (one view's skin is cut short)
SAME_ROW_PX = 4.0
#: the fewest skin rows both views share that place one view's end by the other's (`_one_point`)
MIN_SHARED_ROWS = 4
HOG_CELL, HOG_BINS = 8, 6  # the hand crops' gradient histograms: cells (px) and orientations
AT_GLASS_PX = 3            # half-resolution px (about 2-3 cm at the hand) around the hand's end ...
AT_GLASS_MIN = 2           # ... holding at least this many glass pixels in each camera: the hand is at the glass
_B, _S, _G, _L, _K, _T = (LABEL[p] for p in ("bottle", "stopper", "glass", "liquid", "skin", "shirt"))
assert _L == _G + 1      # the glass mask is one label range over both labels
#: the label ranges of the blob masks: bottle, glass or liquid (consecutive labels), skin
_BLOB_LABELS = ((_B, _B), (_G, _L), (_K, _K))
#: label -> 1 if it is one of these parts, per part set used for a silhouette, and for the hand's crop
_PART_LUT = {ps: np.isin(np.arange(256), ps).astype(np.uint8) for ps in ((_B,), (_G, _L))}
_SKIN_LUT = np.isin(np.arange(256), (_K,)).astype(np.uint8)
_ANG = np.linspace(0, 2 * np.pi, 8, endpoint=False)
#: an upright object's outline points (base and top rings) relative to its base centre
_OUTLINE = {n: np.vstack([np.column_stack([catalogue.radius(n) * np.cos(_ANG), catalogue.radius(n) * np.sin(_ANG), np.full(8, z)])
                          for z in (0.0, HEIGHT[n])]) for n in HEIGHT}
#: points all over an upright object's image, off its edges (an arm beside it does not lie across it): its axis at
#: five heights and its base and top rings drawn in to INSIDE_R of its radius
INSIDE_R = 0.6
_INSIDE = {n: np.vstack([_OUTLINE[n] * [INSIDE_R, INSIDE_R, 1.0],
                         np.column_stack([np.zeros(5), np.zeros(5), np.linspace(0.0, HEIGHT[n], 5)])]) for n in HEIGHT}


@dataclass
class ObjectDetection:
    name: str
    visible: bool
    position: np.ndarray | None = None
    blobs: tuple[Blob | None, Blob | None] = (None, None)
    crop: np.ndarray | None = None
    feat: np.ndarray | None = None      # shape features (template scores are added by the classifier)
    extent: float = 0.0                 # measured / expected silhouette extent (min over cameras, height and width)
    tilt: float = 0.0                   # rad, the silhouette's axis from the image vertical (max over cameras)
    occluded_top: float = 0.0           # share of the band above the object's top that is skin (max over cameras)
    stopper: tuple[float, float] = (0.0, 0.0)   # red pixels touching the bottle / expected stopper area, per camera
    top: np.ndarray | None = None       # triangulated top-centre point (m)
    on_table: bool = False
    inside: bool = False                # off the image borders in both cameras
    on_robot: bool = False              # its silhouette ends on the robot's arm in a camera (its base may be hidden)
    lying: bool = False                 # on the table, on its side (`LYING_TILT`)
    covered: bool = False               # the robot's arm over its left image: what tells its state may be hidden


@dataclass
class HandDetection:
    visible: bool
    position: np.ndarray | None = None       # distal end of the hand (m)
    proximal: np.ndarray | None = None       # the arm's root (sleeve end) or the skin blob's centre (m)
    blob: Blob | None = None
    crop: np.ndarray | None = None
    geo: np.ndarray | None = None
    uv: np.ndarray | None = None             # distal end in the left image
    at_glass: bool = False                   # its end touches the glass's image in both cameras
    end_on_robot: bool = False               # its skin ends on the robot's arm in a camera: the fingers may reach on, hidden


@dataclass
class Detections:
    objects: dict[str, ObjectDetection] = field(default_factory=dict)
    hand: HandDetection = field(default_factory=lambda: HandDetection(False))
    labels: tuple[np.ndarray, np.ndarray] | None = None   # half-resolution label images


def _pct(x: np.ndarray, q: float) -> float:
    """np.percentile(x, q) (linear interpolation) of a small 1-D array, without its overhead."""
    x = np.sort(x, axis=None)
    k = (x.size - 1) * q / 100.0
    lo = int(k)
    hi = min(lo + 1, x.size - 1)
    return float(x[lo] + (k - lo) * (x[hi] - x[lo]))


def _median0(X: np.ndarray) -> np.ndarray:
    """np.median(X, axis=0) of a (N, k) float array, N >= 1: the middle of each column sorted, or the
    mean of the two middle ones (their sum halved, as np.mean takes it); np.median itself if any is nan."""
    srt = np.sort(X, axis=0)
    n = len(srt)
    if np.isnan(srt[-1]).any():
        return np.median(X, axis=0)
    if n % 2:
        return srt[n // 2]
    return (srt[n // 2 - 1] + srt[n // 2]) / 2


def _crop(img: np.ndarray, x0: int, y0: int, x1: int, y1: int, size: tuple[int, int]) -> np.ndarray:
    h, w = img.shape[:2]
    pad = [max(0, -y0), max(0, y1 - h), max(0, -x0), max(0, x1 - w)]
    sub = img[max(0, y0):min(h, y1), max(0, x0):min(w, x1)]
    if any(pad):
        sub = cv2.copyMakeBorder(sub, *pad, cv2.BORDER_CONSTANT, value=0)
    if sub.size == 0:
        return np.zeros(size[::-1], np.float32)
    return cv2.resize(sub.astype(np.float32, copy=False), size, interpolation=cv2.INTER_AREA)


def _match(a: Blob, cands: list[Blob]) -> Blob | None:
    """The right-image blob for left-image blob a: same rows, positive disparity, similar area."""
    best, score = None, 1e9
    au, av = a.centroid.tolist()
    for b in cands:
        bu, bv = b.centroid.tolist()
        dv = abs(av - bv)
        du = au - bu
        if dv > 12 or not (-2 < du < 140):
            continue
        s = dv + 10 * abs(math.log((a.area + 1) / (b.area + 1)))     # math.log: the same values as np.log
        if s < score:
            best, score = b, s
    return best


def _one_point(ends: list[np.ndarray], roots: list[np.ndarray], skin: list[np.ndarray]) -> list[np.ndarray]:
    """The hand's end in the two images (u, v) as one point of the hand. In one view the fingers may be
    segmented off the palm (pale fingers on the pale table, a finger's shading), and that view's end then lies
    at the palm, rows short of the other's: triangulated as one point, the pair puts the hand tens of cm off.
    A row is the same in both views of a rectified pair (a length in pixels is not). Ends on rows more than
    SAME_ROW_PX apart, where the other view's skin stops short of the fuller view's end row (the view whose
    end lies farther along the arm), are taken from the fuller view; the other's end is put on the same row
    at the disparity the skin rows both views share give there. (u, v, disparity) being a projective image
    of the world, along the arm and hand the disparity is close to linear in the row: a line through the
    shared rows' disparities (their mean columns' differences) is carried on to the end's row. Where both
    views' skin reaches the row, each view's end is its own outline's and is kept."""
    if abs(float(ends[0][1] - ends[1][1])) <= SAME_ROW_PX:
        return ends
    down = float(np.sign(ends[0][1] - roots[0][1] + ends[1][1] - roots[1][1]))    # the way the arm runs in rows
    k = int(down * float(ends[1][1]) > down * float(ends[0][1]))
    v = float(ends[k][1])
    last = float((down * skin[1 - k][:, 1]).max())     # the other view's skin row farthest along the arm
    if down * v - last <= SAME_ROW_PX:
        return ends      # the other view's skin reaches the end's row: both see the hand's end, each its own way
    shared = np.intersect1d(np.unique(skin[0][:, 1]), np.unique(skin[1][:, 1]))
    if shared.size < MIN_SHARED_ROWS:
        return ends
    u = [np.array([P[P[:, 1] == r, 0].mean() for r in shared]) for P in skin]
    slope, at0, _, _ = theilslopes(u[0] - u[1], shared)     # robust to a row or two of one view's stray skin
    disparity = float(at0 + slope * v)
    out = [np.asarray(e, float).copy() for e in ends]
    out[1 - k] = np.array([float(ends[k][0]) + (disparity if k == 1 else -disparity), v])
    return out


def outline_hog(crop: np.ndarray) -> np.ndarray:
    """A histogram of oriented gradients of a hand crop (its skin mask, the template size: whole
    cells): per `HOG_CELL`-px cell, the gradient magnitude summed over `HOG_BINS` unsigned
    orientations, normalised over the crop.  The matched prototypes score the whole outline; this
    says where its edges run which way (an index finger's two long edges, an open hand's several),
    which tells reach from pointing.  One compiled pass: OpenCV's gradients and arctangent."""
    h, w = crop.shape
    if h % HOG_CELL or w % HOG_CELL:
        raise ValueError(f"a {w}x{h} crop is not whole {HOG_CELL}-px cells")
    c = np.ascontiguousarray(crop, np.float32)
    out = _kernels.gradient_histogram(c, HOG_CELL, HOG_BINS).astype(np.float32)
    return out / (np.linalg.norm(out) + 1e-3)


_OPEN = [cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (k, k)) for k in (3, 5)]


def _spans(disc: np.ndarray, rows: int) -> np.ndarray:
    """A structuring element's rows as (dy, dx0, dx1) from its centre, padded to ``rows`` with dy = 99."""
    out = np.full((rows, 3), 99, np.int64)
    r = disc.shape[0] // 2
    for i, y in enumerate(np.flatnonzero(disc.any(axis=1))):
        xs = np.flatnonzero(disc[y])
        out[i] = (y - r, xs[0] - r, xs[-1] - r)
    return out


_OPEN_SPANS = np.stack([_spans(d, 5) for d in _OPEN])


def finger_parts(skin: np.ndarray, cm_per_px: float) -> np.ndarray:
    """Fingers standing out of the hand, from its full-resolution skin mask: what an opening by a 3-px
    and by a 5-px disc removes (parts under 3 and under 5 px wide), each as its area, its largest
    piece's area and that piece's length (cm^2, cm^2, cm).  A pointing index finger is one long thin
    piece; fingers held together in an open hand are one wide part: they tell reach from pointing
    where the template-size crop has lost the finger."""
    out = np.zeros(3 * len(_OPEN), np.float32)
    if skin.size == 0:
        return out
    m = skin.view(np.uint8)
    a2 = cm_per_px * cm_per_px
    # one compiled call: the openings' residues and their pieces
    for k, (total, largest, w, h) in enumerate(_kernels.thin_pieces(m, _OPEN_SPANS).tolist()):
        if total:
            out[3 * k:3 * k + 3] = (float(total) * a2, float(largest) * a2, math.hypot(w, h) * cm_per_px)
    return out


def axis_distance(o: ObjectDetection, X: np.ndarray) -> float:
    """The distance (m) of point X (the hand's end) from an upright object's axis, base to top: from the
    axis point at X's height, or its end below or above.  A grip from above holds the top, whose fingers
    reach past it, a side grip the middle: both within `HELD_DIST` of the axis."""
    base = o.position
    rise = min(max(float(X[2] - base[2]), 0.0), HEIGHT[o.name])
    return float(np.linalg.norm(X - (base + [0.0, 0.0, rise])))


def _rim_to_axis(cam: CameraModel, uv, z: float, r: float) -> tuple[float, float, float]:
    """Where the ray through pixel uv, the front of a rim at height z, meets that height, moved
    horizontally by r away from the camera: the axis of an upright object of radius r whose
    silhouette's lowest point (its base's front rim) uv is.  On floats, the operations of
    P = on_plane(...)[0]; P[:2] += r * (P[:2] - C[:2]) / np.linalg.norm(P[:2] - C[:2])."""
    px, py, pz = on_plane(cam, uv, z)[0].tolist()
    cx, cy = cam.C[:2].tolist()
    hx, hy = px - cx, py - cy
    n = math.sqrt(hx * hx + hy * hy)
    return px + r * hx / n, py + r * hy / n, pz


def _rim_height(cam: CameraModel, uv, axis: np.ndarray, r: float) -> float:
    """The height of the point on the ray through pixel uv that passes nearest (seen from above) the front
    of the rim of an upright object of radius r on ``axis`` (x, y): the rim's height, if uv is where its
    silhouette's lowest point shows it."""
    d = cam.ray(np.array([uv]))[0]
    C = cam.C
    toward = C[:2] - axis
    front = axis + r * toward / math.sqrt(float(toward @ toward))
    s = float((front - C[:2]) @ d[:2]) / float(d[:2] @ d[:2])
    return float(C[2] + s * d[2])


def _lifted_base_z(cams, rois, axis: np.ndarray, r: float) -> float | None:
    """Height of a lifted, upright object's base from its silhouette's lowest point in both cameras (the
    front of its base's rim, on the axis found from its full-width rows), or None where skin hides it in
    either or the two disagree by more than BASE_AGREE. A hand that holds it from above hides its top,
    and then the silhouette's centroid lies several cm low; the base's rim it does not hide."""
    if any(roi.skin_below() for roi in rois):
        return None
    a, b = (_rim_height(cam, roi.bottom, axis, r) for cam, roi in zip(cams, rois))
    return 0.5 * (a + b) if abs(a - b) <= BASE_AGREE else None


def _axis_xy(cams, rois) -> np.ndarray | None:
    """x, y of an upright object's axis from the rows showing its full width in both images (the
    middles of their edges, triangulated; the median), or None with fewer than `AXIS_ROWS` such rows."""
    (vl, ul), (vr, ur) = rois[0].axis(), rois[1].axis()
    # the head's cameras are parallel and side by side, so a point shows in the same row of both
    # rows in both (sorted, unique): where each of vl is in vr
    ir = np.minimum(np.searchsorted(vr, vl), max(0, vr.size - 1))
    il = np.flatnonzero(vr[ir] == vl) if vr.size else np.zeros(0, int)
    ir = ir[il]
    common = vl[il]
    if common.size < AXIS_ROWS:
        return None
    v = common + 0.5
    X = triangulate(cams[0], cams[1], np.column_stack([ul[il], v]), np.column_stack([ur[ir], v]))
    return _median0(X[:, :2])


def _labels_near(lab: np.ndarray, uv, lo: int, hi: int, r: int) -> int:
    """Pixels labelled lo..hi within r half-resolution px (a square) of full-resolution point uv."""
    u, v = int(uv[0]) // 2, int(uv[1]) // 2
    win = lab[max(0, v - r):max(0, v + r + 1), max(0, u - r):max(0, u + r + 1)]
    return int(np.count_nonzero((win >= lo) & (win <= hi)))


class _Roi:
    """A blob re-labelled at full resolution: its mask, edges and neighbours."""

    def __init__(self, table: ColourTable, img: np.ndarray, b: Blob, parts: tuple[int, ...], pad_top: int) -> None:
        H, W = img.shape[:2]
        x, y, w, h = b.bbox
        self.x0, self.y0 = max(0, x - 4), max(0, y - pad_top)
        x1, y1 = min(W, x + w + 4), min(H, y + h + 4)
        self.img = img[self.y0:y1, self.x0:x1]
        # the labels, where they are one of the parts (the silhouette), its rows' first and last pixels
        # (for `axis`), its extents and moments
        self.lab, m, *rows, ext, mom = table.region_silhouette(self.img, _PART_LUT[parts])
        self.mask = m
        self._rows = rows
        _, by, bw, bh, bl, br, tl, tr = ext.tolist()
        self.ok = bw > 0
        if not self.ok:
            return
        self.top_r, self.bot_r = by, by + bh - 1
        self.w = float(bw)
        self.h = float(bh)
        # the bottom (top) two rows' leftmost and rightmost pixels
        self.bottom = np.array([self.x0 + bl + 0.5 * (br - bl), self.y0 + self.bot_r + 0.5])
        self._bottom_lr = (self.x0 + bl + 0.5, self.x0 + br + 0.5)
        self.top = np.array([self.x0 + tl + 0.5 * (tr - tl), self.y0 + self.top_r - 0.5])
        n, m10, m01, mu20, mu11, mu02 = mom.tolist()     # as cv2.moments(binaryImage=True) gives them
        self.centroid = np.array([m10 / n + self.x0 + 0.5, m01 / n + self.y0 + 0.5])
        self.tilt = 0.0
        if n > 3:   # the silhouette's main axis from its central moments
            a, b, c = mu20 / n, mu11 / n, mu02 / n
            root = math.sqrt(max(0.0, 0.25 * (a - c) ** 2 + b * b))
            l1, l0 = 0.5 * (a + c) + root, 0.5 * (a + c) - root
            if l1 > 1.5 * l0:   # elongated: the angle of the main axis (b, l1 - a) from the image vertical
                vx, vy = (b, l1 - a) if abs(b) > 1e-12 else ((1.0, 0.0) if a >= c else (0.0, 1.0))
                self.tilt = math.acos(min(1.0, abs(vy) / np.hypot(vx, vy)))   # math.acos: libm's acos, as np.arccos
        self.area = float(n)
        self.h_capped = self.h
        self._axis: tuple[np.ndarray, np.ndarray] | None = None

    def below(self) -> np.ndarray:
        """Pixels just under the silhouette's lowest row, at its ends and middle: what it stands on,
        or what hides its base."""
        v = self.y0 + self.bot_r + 0.5 + BELOW_PX
        return np.array([[self._bottom_lr[0], v], [self.bottom[0], v], [self._bottom_lr[1], v]])

    def skin_below(self) -> bool:
        """Skin just under the silhouette's lowest row, anywhere across it: a hand hides its base."""
        v = self.bot_r + int(BELOW_PX)
        if v >= self.lab.shape[0]:
            return False
        u0, u1 = (int(u) - self.x0 for u in self._bottom_lr)
        return bool(np.any(self.lab[v, max(0, u0):u1 + 1] == _K))

    def above(self) -> np.ndarray:
        """Pixels just over the silhouette's highest row, at its middle and a few px to each side: what
        hides its top, if anything does."""
        v = self.y0 + self.top_r - 0.5 - BELOW_PX
        return np.array([[self.top[0] - 3.0, v], [self.top[0], v], [self.top[0] + 3.0, v]])

    def cap(self, part: int) -> None:
        """Count pixels of ``part`` right on top of the silhouette (a stopper in the bottle's neck, which
        a camera looking down at a near bottle sees in front of the neck) into its height."""
        row = first_row_over(self.lab, self.mask, part, self.top_r - max(3, int(0.3 * self.h)), self.bot_r)
        if row >= 0:
            self.h_capped = float(self.bot_r - min(self.top_r, row) + 1)

    def upright_tilt(self) -> float:
        """The silhouette's tilt from the image vertical: of its axis (the line through its full-width
        rows' middles) when it is taller than wide, which fingers draped over an upright object's top
        cut into strips that skew its moments; else of its moments' main axis (a lying object)."""
        if self.h < self.w:
            return self.tilt
        v, u = self.axis()
        if v.size < AXIS_ROWS:
            return self.tilt
        dv = v - v.sum() / v.size              # v.mean(), u.mean(): the same sums and division
        slope = float(dv @ (u - u.sum() / u.size)) / float(dv @ dv)   # the least-squares line's slope
        return math.atan(abs(slope))            # libm's atan, as np.arctan

    def axis(self) -> tuple[np.ndarray, np.ndarray]:
        """(rows, mid-columns), absolute pixels, of the rows that show the silhouette's full width: there
        the middle of the two edges is an upright cylinder's axis, wherever a hand or fingers cover its
        top, bottom or part of a side (which the silhouette's centroid is not).  Computed once."""
        if self._axis is not None:
            return self._axis
        rows, first, last = self._rows
        width = last - first + 1
        full = _pct(width, 80)
        ok = np.abs(width - full) <= max(1.5, 0.12 * full)
        self._axis = (self.y0 + rows[ok], self.x0 + 0.5 * (first[ok] + last[ok]) + 0.5)
        return self._axis


class Detector:
    """Stateless per-frame detection with a calibration (HSV ranges, static skin spots)."""

    def __init__(self, calibration: dict) -> None:
        self.table = ColourTable(calibration["hsv"])
        self.static_skin = np.array(calibration.get("static_skin", []), float).reshape(-1, 3)
        self.static_cells = np.ascontiguousarray(np.array(calibration.get("static_skin_cells", []), float).reshape(-1, 3))
        self.arm_root = np.array(calibration["arm_root"], float) if "arm_root" in calibration else None
        self._margin = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * STATIC_MARGIN + 1,) * 2)
        # compile (or load from numba's cache) the hand's and the arm's kernels now, not in the first frame
        outline_hog(np.zeros(CROP["hand"][::-1], np.float32))
        finger_parts(np.ones((3, 3), bool), 1.0)
        z = np.zeros((1, 3))
        _kernels.capsules_cover(z, z, np.zeros(1), np.eye(3, 4), 1.0, 1.0, np.zeros((1, 2)))
        _kernels.project_half(z, np.zeros(3), np.eye(3), np.eye(3))

    def __call__(self, left: np.ndarray, right: np.ndarray, cams: tuple[CameraModel, CameraModel],
                 body: RobotBody | None = None) -> Detections:
        """body: the robot's own shape in this pair (see `vision.body`); without it, no silhouette
        edge is taken for the robot's."""
        imgs = (left, right)
        # half-resolution labels without the static skin, the masks of bottle, glass (or liquid) and skin, their boxes
        spots = [self.static_spots(cam) if len(self.static_cells) else None for cam in cams]
        lab, masks, boxes = zip(*(self.table.half(im, _BLOB_LABELS, _K, sp, self._margin) for im, sp in zip(imgs, spots)))
        det = Detections(labels=lab)
        # the blobs of each part in each camera (a right-image part only where the left has one to pair with)
        found, views = components_each(masks, ("bottle", "glass", "skin"), (2, 2, 6), pairs_only=True, views_of=(2,), boxes=boxes)
        blobs = [{"bottle": f[0], "glass": f[1], "skin": (f[2], v[2])} for f, v in zip(found, views)]
        for name in catalogue.TASK_OBJECTS:
            det.objects[name] = self._object(name, blobs, imgs, cams, body)
        det.hand = self._hand(blobs, lab, imgs, cams, det, body)
        for o in det.objects.values():
            self._held(o, det.hand)
        return det

    def static_spots(self, cam: CameraModel) -> np.ndarray:
        """The static skin cells' projections in a half-resolution image of this camera ((N, 2) u, v),
        in one compiled loop."""
        return _kernels.project_half(self.static_cells, cam.C, cam.R, cam.K)

    @staticmethod
    def _held(o: ObjectDetection, hand: HandDetection) -> None:
        """A lifted object is seen only in the hand (else: a hidden bottom edge, a bad match)."""
        if o.visible or o.on_table or o.position is None or not o.inside or not hand.visible or o.on_robot:
            return      # (one whose silhouette ends on the robot's arm may stand behind it: its bottoms say nothing)
        o.visible = bool(axis_distance(o, hand.position) < HELD_DIST and MIN_EXTENT_HELD <= o.extent <= MAX_EXTENT
                         and o.tilt < MAX_TILT and o.position[2] > 0.02)

    # ------------------------------------------------------------------ objects
    def _object(self, name, blobs, imgs, cams, body: RobotBody | None = None) -> ObjectDetection:
        bl, br = blobs[0][name], blobs[1][name]
        if not bl or not br:
            return ObjectDetection(name, False, blobs=(bl[0] if bl else None, None))
        a = bl[0]
        b = _match(a, br)
        if b is None:
            return ObjectDetection(name, False, blobs=(a, None))
        parts = (_B,) if name == "bottle" else (_G, _L)
        rois = []
        for img, bb in zip(imgs, (a, b)):
            pad = int(0.35 * bb.bbox[3]) + 6 if name == "bottle" else 6
            r = _Roi(self.table, img, bb, parts, pad)
            if not r.ok:
                return ObjectDetection(name, False, blobs=(a, b))
            if name == "bottle":
                r.cap(_S)
            rois.append(r)
        Xb, Xt = triangulate(cams[0], cams[1], np.array([rois[0].bottom, rois[0].top]), np.array([rois[1].bottom, rois[1].top]))
        r_obj = catalogue.radius(name)
        on_table = abs(Xb[2]) < ON_TABLE_TOL
        bases = [_rim_to_axis(cam, roi.bottom, 0.0, r_obj) for cam, roi in zip(cams, rois)]
        axis = None if on_table else _axis_xy(cams, rois)
        if on_table:
            (ax, ay, az), (bx, by, bz) = bases
            pos = np.array([(ax + bx) / 2, (ay + by) / 2, (az + bz) / 2])
        else:   # lifted: x, y from the axis in both images; the height from the silhouette's centroid
            # (the features and the expected outline use that one; the position reported, its base's
            # front rim where both cameras see it: `_lifted_base_z`)
            pos = triangulate(cams[0], cams[1], rois[0].centroid, rois[1].centroid)[0]
            pos[2] -= CENTROID_Z[name]
            if axis is not None:
                pos[:2] = axis
            else:
                hdir = pos[:2] - 0.5 * (cams[0].C[:2] + cams[1].C[:2])
                pos[:2] += 0.5 * r_obj * hdir / np.linalg.norm(hdir)
        H, W = imgs[0].shape[:2]
        exts, ins = [], []
        for (ew, eh), roi, bb in zip(expected_boxes(cams, pos + _OUTLINE[name]), rois, (a, b)):
            exts.append(min(roi.h_capped / max(eh, 1.0), roi.w / max(ew, 1.0)))
            x, y, w, h = bb.bbox
            ins.append(x > 1 and y > 1 and x + w < W - 1 and y + h < H - 1)
        extent, inside = min(9.0, *exts), ins[0] and ins[1]
        whole = [i and MIN_EXTENT <= e <= MAX_EXTENT for e, i in zip(exts, ins)]
        on_robot = [body is not None and body.covers(cam, roi.below()) for cam, roi in zip(cams, rois)]
        # a silhouette that ends on the robot's arm: its lowest row is the arm's edge, not its base
        whole = [w and not r for w, r in zip(whole, on_robot)]
        tilt = max(roi.upright_tilt() for roi in rois)
        # standing on the table and whole; a lifted one is decided once the hand is known (`_held`)
        visible = bool(on_table and whole[0] and whole[1] and tilt < MAX_TILT)
        if (not visible and any(whole) and ins[0] and ins[1] and tilt < MAX_TILT
                and MIN_EXTENT_HELD <= extent and max(exts) <= MAX_EXTENT):
            # whole in a camera but its bottom hidden in the other (by the robot's gripper, say), or the
            # two bottoms not one point: standing if its axis (from the rows showing its full width in
            # both) stands where each whole camera's base ray meets the table; placed by those rays
            whole_bases = [bases[c] for c in (0, 1) if whole[c]]
            if on_table:   # (a lifted one's axis is found above)
                axis = _axis_xy(cams, rois)
            if axis is not None and all(math.hypot(x - axis[0], y - axis[1]) < BASE_AGREE for x, y, _ in whole_bases):
                pos = np.array([sum(p[0] for p in whole_bases), sum(p[1] for p in whole_bases), 0.0]) / len(whole_bases)
                on_table = visible = True
        det = ObjectDetection(name, visible, pos, (a, b), extent=float(extent), tilt=float(tilt), top=Xt)
        det.on_table, det.inside, det.on_robot = on_table, inside, any(on_robot)
        # on the table, its silhouette's axis near horizontal in both images, and not because the robot's arm
        # covers part of it. (The triangulated top is no cue: the top rows of the two images are different
        # points of the rim, and the height it gives is off by several cm near the cameras)
        top_hidden = body is not None and any(body.covers(cam, roi.above()) for cam, roi in zip(cams, rois))
        # (in the left camera, whose image the state is read from: its crop and shape)
        det.covered = body is not None and body.covers(cams[0], cams[0].project(pos + _INSIDE[name]))
        det.lying = bool(on_table and inside and not det.on_robot and not top_hidden
                         and min(roi.upright_tilt() for roi in rois) >= LYING_TILT)
        self._object_features(det, rois, cams, pos)
        if not on_table and axis is not None and not det.on_robot:
            z = _lifted_base_z(cams, rois, axis, r_obj)
            if z is not None:
                det.position = np.array([pos[0], pos[1], z])
        return det

    def _object_features(self, det: ObjectDetection, rois, cams, pos) -> None:
        dp = pos - cams[0].C
        depth = math.sqrt(dp.dot(dp))          # np.linalg.norm(pos - C)
        f = cams[0].K[0, 0]
        if det.name == "bottle":
            # the stopper: red pixels touching the bottle's silhouette (any tilt); the band above the
            # top: how much of it is skin (a hand over the stopper hides it)
            exp = np.pi * (0.019 * f / depth) ** 2 * 0.5
            red, occ = [], []
            for roi in rois:
                red.append(min(1.5, float(count_near(roi.lab, roi.mask, _S, 2)) / exp))    # within 2 px
                band = roi.lab[max(0, roi.top_r - int(0.3 * roi.h)):roi.top_r + 3]
                occ.append(float(np.count_nonzero(band == _K)) / max(1.0, 0.3 * roi.h * roi.w))
            det.stopper = (red[0], red[1])
            det.occluded_top = float(max(occ))
            lift = float(pos[2])
            det.feat = np.array([max(red), min(red), det.occluded_top, det.tilt, lift], np.float32)
            return
        roi = rois[0]
        m = roi.mask
        liq = [float(count_near(r.lab, r.mask, _L, 0)) / max(1.0, r.area) for r in rois]
        third = max(1, int(roi.h) // 3)
        rows = m[roi.top_r:roi.bot_r + 1]
        width_top = float(rows[:third].sum()) / third
        width_bot = float(rows[-third:].sum()) / third
        shape = (width_top - width_bot) / max(1.0, roi.w)
        det.crop = _crop(masked_saturation(roi.img, m), 0, roi.top_r - 1, m.shape[1], roi.bot_r + 2, CROP["glass"])
        det.feat = np.array([max(liq), min(liq), shape, det.tilt, float(pos[2])], np.float32)

    # ------------------------------------------------------------------ hand
    def _hand(self, blobs, lab, imgs, cams, det: Detections, body: RobotBody | None = None) -> HandDetection:
        (bl, cl), (br, cr) = blobs[0]["skin"], blobs[1]["skin"]
        best = None
        pairs = [(a, b) for a in bl for b in (_match(a, br),) if b is not None]
        if pairs:   # all candidates triangulated at once
            Xs = triangulate(cams[0], cams[1], np.array([a.centroid for a, _ in pairs]), np.array([b.centroid for _, b in pairs]))
            near_static = np.zeros(len(pairs), bool)
            if len(self.static_skin):
                d2 = ((Xs[:, None, :] - self.static_skin[None]) ** 2).sum(-1)
                near_static = d2.min(axis=1) < STATIC_SKIN_R ** 2
            for (a, b), X, ns in zip(pairs, Xs, near_static):
                if not (-0.05 < X[2] < 0.7 and -0.7 < X[0] < 0.3 and abs(X[1]) < 0.7):
                    continue      # not over the table: floor, background
                if X[2] > FACE_Z:
                    continue      # the face (a hand at the mouth merges with it: the drink is read from the glass)
                if min(a.bbox[1], b.bbox[1]) <= 1 and X[0] < -TABLE_HALF_X:
                    continue      # cut by the image's top beyond the table's edge: the face with the head tilted down (its
                    # chin's centroid is lower than FACE_Z); a hand raised over the table (round the stopper) is cut there too
                if ns:
                    continue
                if best is None or a.area > best[0].area:
                    best = (a, b, X)
        if best is None:
            return HandDetection(False)
        a, b, X = best
        ends, roots, spread, skin = [], [], [], []
        end_on_robot = False
        for L, bb, cc, cam in ((lab[0], a, cl, cams[0]), (lab[1], b, cr, cams[1])):
            x, y, w, h = (v // 2 for v in bb.bbox)
            x0, y0, x1, y1 = max(0, x - 2), max(0, y - 2), min(L.shape[1], x + w + 2), min(L.shape[0], y + h + 2)
            # this blob's own pixels (from the one components pass): their centres (x, y) at full
            # resolution, and those touching the sleeve: count, sums of columns and rows in the window
            P, nt, sx, sy = blob_pixels(cc, bb.label, L, _T, x0, y0, x1, y1)
            if nt >= 2:                           # the means as np.mean takes them: sum / count
                root = np.array([sx / nt + x0, sy / nt + y0]) * 2 + 0.5
            else:
                tm = cv2.moments((L == _T).view(np.uint8), binaryImage=True)
                root = np.array([tm["m10"] / tm["m00"], tm["m01"] / tm["m00"]]) * 2 if tm["m00"] > 0 else bb.centroid + [0, -40]
            # the hand: the blob's part farthest from the shoulder (a hand in front of the torso touches
            # the shirt all along its edge, which puts the sleeve's end in the hand's middle)
            dp = P - (cam.project(self.arm_root)[0] if self.arm_root is not None else root)
            dist2 = np.einsum("ij,ij->i", dp, dp)       # squared: the same 75th-percentile selection as distances
            far = P[dist2 >= _pct(dist2, 75)]
            end = far.sum(axis=0) / len(far)           # far.mean(axis=0)
            ends.append(end)
            roots.append(root)
            skin.append(P)
            if body is not None and not end_on_robot:
                # just beyond the skin's farthest pixel, along the arm and to either side: the robot's arm
                # there hides the rest of the hand (its fingers), and the end seen falls short
                tip = P[int(np.argmax(dist2))]
                along = end - root
                along = along / max(1e-6, float(np.hypot(along[0], along[1])))
                across = np.array([-along[1], along[0]])
                beyond = tip + BEYOND_TIP_PX * along
                end_on_robot = body.covers(cam, np.array([beyond, beyond + BEYOND_TIP_PX * across, beyond - BEYOND_TIP_PX * across]))
            if not spread:   # the hand's own outline (left camera): spread along and across the arm, in px
                ax = end - root
                ax = ax / max(1e-6, float(np.hypot(ax[0], ax[1])))
                q = far - end
                pr = q @ np.array([[ax[0], -ax[1]], [ax[1], ax[0]]])
                # pr.std(axis=0), step by step as np.std takes it
                dev = pr - pr.sum(axis=0, keepdims=True) / len(pr)
                sd = np.sqrt((dev * dev).sum(axis=0) / len(pr))
                spread = [float(sd[0]), float(sd[1]), float(len(far))]
        ends = _one_point(ends, roots, skin)
        Xd, Xr = triangulate(cams[0], cams[1], np.array([ends[0], roots[0]]), np.array([ends[1], roots[1]]))
        at_glass = all(_labels_near(L, end, _G, _L, AT_GLASS_PX) >= AT_GLASS_MIN for L, end in zip(lab, ends))
        # the hand's skin around its end in each camera: the left one, at the template size, is matched
        # against the prototypes; both give their outline's gradient histogram and their thin parts
        # (two views of the fingers)
        hogs, fingers = [], []
        for img, cam, end in zip(imgs, cams, ends):
            dd = Xd - cam.C
            dist = math.sqrt(dd.dot(dd))          # np.linalg.norm(Xd - C)
            half = int(round(cam.K[0, 0] * HAND_REACH / dist))
            u, v = (int(round(c)) for c in end)
            skin = self.table.region(img[max(0, v - half):v + half, max(0, u - half):u + half], _SKIN_LUT)[1]
            c = _crop(skin.astype(np.float32), 0, 0, skin.shape[1], skin.shape[0], CROP["hand"]) \
                if skin.size else np.zeros(CROP["hand"][::-1], np.float32)
            if not hogs:       # the left camera's
                crop, depth = c, dist
            hogs.append(outline_hog(c))
            fingers.append(finger_parts(skin, dist / cam.K[0, 0] * 100))
        px = depth / cams[0].K[0, 0]                                # m per pixel at the hand
        area = a.area * px ** 2 * 1e4                               # cm^2 of skin in view
        shape = [spread[0] * px * 100, spread[1] * px * 100, spread[2] * px * px * 1e4]   # cm, cm, cm^2
        geo = np.concatenate([self._hand_geo(Xd, Xr, det, area, shape), *hogs, *fingers])
        return HandDetection(True, Xd, Xr, a, crop, geo, np.asarray(ends[0]), at_glass, bool(end_on_robot))

    @staticmethod
    def _hand_geo(Xd: np.ndarray, Xr: np.ndarray, det: Detections, area: float, shape) -> np.ndarray:
        """Hand features: position, arm root and direction, skin area and outline spread, and per object
        (bottle, glass) the horizontal distance, the height over its (upright) top, its base height
        and tilt, and the bottle's stopper in view."""
        d = Xd - Xr
        d = d / max(1e-6, math.sqrt(d.dot(d)))     # np.linalg.norm(d)
        rel = []
        for o in (det.objects[n] for n in catalogue.TASK_OBJECTS):
            if o.position is None:
                rel += [0.5, 0.0, 0.0, 0.0]
                continue
            dxy = Xd[:2] - o.position[:2]
            rel += [math.sqrt(dxy.dot(dxy)), float(Xd[2] - o.position[2] - HEIGHT[o.name]),
                    float(o.position[2]), float(o.tilt)]
        red = float(max(det.objects["bottle"].stopper))
        return np.array([*Xd, *d, *Xr, area, *shape, *rel, red], np.float32)
