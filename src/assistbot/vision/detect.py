"""From a stereo pair to detections: blobs per part, stereo matching, 3-D positions, crops and features.

Everything here works on pixels and on the cameras' models only.  Positions are in table
coordinates (m): an object's position is the centre of the base it stands on.

* An object standing on the table (its stereo centroid sits at the height an object on the
  table has) is placed by the rays through the bottom of its silhouette meeting the table
  plane (more precise than stereo depth at a 0.12 m baseline), averaged over both cameras.
* A lifted object is placed by its triangulated centroid minus its centroid height.
* An object is "visible" only if both cameras show it with at least `MIN_VISIBLE` of the
  silhouette area its distance implies: a half-hidden object is reported unseen, not misplaced.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import cv2
import numpy as np

from assistbot.vision.camera import CameraModel, on_plane, triangulate
from assistbot.vision.segment import Blob, blobs, masks
from assistbot.world import layout

MIN_VISIBLE = 0.35
#: height of the visible silhouette's centre above the base (m) and the silhouette (width, height)
CENTROID_Z = {"bottle": 0.090, "glass": 0.050}
SILHOUETTE = {"bottle": (0.07, 0.18), "glass": (0.08, 0.10)}
CROP = {"bottle": (16, 40), "glass": (20, 24), "hand": (32, 32)}   # template sizes (w, h)
ON_TABLE_TOL = 0.035
FACE_Z = 0.33               # skin above this table height is the face, not a hand


@dataclass
class ObjectDetection:
    name: str
    visible: bool
    position: np.ndarray | None = None
    blobs: tuple[Blob | None, Blob | None] = (None, None)
    crop: np.ndarray | None = None
    feat: np.ndarray | None = None      # shape features (templates scores are added by the classifier)
    area_ratio: float = 0.0


@dataclass
class HandDetection:
    visible: bool
    position: np.ndarray | None = None       # distal end of the hand (m)
    proximal: np.ndarray | None = None       # forearm centroid (m)
    blob: Blob | None = None
    crop: np.ndarray | None = None
    geo: np.ndarray | None = None


@dataclass
class Detections:
    objects: dict[str, ObjectDetection] = field(default_factory=dict)
    hand: HandDetection = field(default_factory=lambda: HandDetection(False))
    masks: tuple[dict, dict] | None = None


def _crop(img: np.ndarray, x0: int, y0: int, x1: int, y1: int, size: tuple[int, int]) -> np.ndarray:
    h, w = img.shape[:2]
    pad = [max(0, -y0), max(0, y1 - h), max(0, -x0), max(0, x1 - w)]
    sub = img[max(0, y0):min(h, y1), max(0, x0):min(w, x1)]
    if any(pad):
        sub = cv2.copyMakeBorder(sub, *pad, cv2.BORDER_CONSTANT, value=0)
    if sub.size == 0:
        return np.zeros(size[::-1], np.float32)
    return cv2.resize(sub.astype(np.float32), size, interpolation=cv2.INTER_AREA)


def _match(a: Blob, cands: list[Blob]) -> Blob | None:
    """The right-image blob for left-image blob a: same rows, positive disparity, similar area."""
    best, score = None, 1e9
    for b in cands:
        dv = abs(a.centroid[1] - b.centroid[1])
        du = a.centroid[0] - b.centroid[0]
        if dv > 10 or not (-2 < du < 140):
            continue
        s = dv + 10 * abs(np.log((a.area + 1) / (b.area + 1)))
        if s < score:
            best, score = b, s
    return best


def _bottom_uv(lab: np.ndarray, b: Blob) -> np.ndarray:
    x, y, w, h = b.bbox
    sub = lab[y:y + h, x:x + w] == b.label
    cu = int(round(b.centroid[0])) - x
    cols = sub[:, max(0, cu - 1):cu + 2]
    rows = np.flatnonzero(cols.any(axis=1))
    v = (rows.max() if rows.size else h - 1) + y + 0.5
    return np.array([b.centroid[0], v])


class Detector:
    """Stateless per-frame detection with a calibration (HSV ranges, static skin spots)."""

    def __init__(self, calibration: dict) -> None:
        self.ranges = calibration["hsv"]
        self.static_skin = np.array(calibration.get("static_skin", []), float).reshape(-1, 3)

    def __call__(self, left: np.ndarray, right: np.ndarray, cams: tuple[CameraModel, CameraModel]) -> Detections:
        hsv = (cv2.cvtColor(left, cv2.COLOR_RGB2HSV), cv2.cvtColor(right, cv2.COLOR_RGB2HSV))
        mk = (masks(hsv[0], self.ranges), masks(hsv[1], self.ranges))
        det = Detections(masks=mk)
        for name in ("bottle", "glass"):
            det.objects[name] = self._object(name, mk, hsv, cams)
        det.hand = self._hand(mk, cams, det)
        return det

    # ------------------------------------------------------------------ objects
    def _object(self, name, mk, hsv, cams) -> ObjectDetection:
        part = [m[name] if name == "bottle" else cv2.bitwise_or(m["glass"], m["liquid"]) for m in mk]
        if name == "glass":
            part = [cv2.morphologyEx(p, cv2.MORPH_CLOSE, np.ones((3, 3), np.uint8)) for p in part]
        (bl, lab_l), (br, lab_r) = blobs(part[0], name, 2), blobs(part[1], name, 2)
        if not bl or not br:
            return ObjectDetection(name, False)
        a = bl[0]
        b = _match(a, br)
        if b is None:
            return ObjectDetection(name, False, blobs=(a, None))
        Xc = triangulate(cams[0], cams[1], a.centroid, b.centroid)[0]
        depth = float(np.linalg.norm(Xc - cams[0].C))
        f = cams[0].K[0, 0]
        sw, sh = SILHOUETTE[name]
        expected = (f / depth) ** 2 * sw * sh * 0.8
        ratio = min(a.area, b.area) / expected
        r = layout.OBJECT_RADIUS[name]
        base_z = Xc[2] - CENTROID_Z[name]
        if abs(base_z) < ON_TABLE_TOL:
            pts = []
            for cam, lab, bb in ((cams[0], lab_l, a), (cams[1], lab_r, b)):
                P = on_plane(cam, _bottom_uv(lab, bb), 0.0)[0]
                hdir = P[:2] - cam.C[:2]
                P[:2] += r * hdir / np.linalg.norm(hdir)
                pts.append(P)
            pos = np.mean(pts, axis=0)
        else:
            pos = Xc.copy()
            hdir = Xc[:2] - cams[0].C[:2]
            pos[:2] += 0.5 * r * hdir / np.linalg.norm(hdir)
            pos[2] = base_z
        H, W = part[0].shape
        inside = all(bb.bbox[0] > 0 and bb.bbox[1] > 0 and bb.bbox[0] + bb.bbox[2] < W and bb.bbox[1] + bb.bbox[3] < H for bb in (a, b))
        det = ObjectDetection(name, bool(ratio >= MIN_VISIBLE and inside), pos, (a, b), area_ratio=float(ratio))
        det.crop, det.feat = self._object_features(name, a, b, mk, hsv)
        return det

    def _object_features(self, name, a: Blob, b: Blob, mk, hsv):
        x, y, w, h = a.bbox
        if name == "bottle":
            # the stopper: red pixels just above the top of the green silhouette, in both images
            red = []
            for bb, m in ((a, mk[0]), (b, mk[1])):
                bx, by, bw, bh = bb.bbox
                top = m["stopper"][max(0, by - int(0.25 * bh) - 2):by + int(0.12 * bh) + 2, max(0, bx - 1):bx + bw + 1]
                red.append(min(1.0, float(np.count_nonzero(top)) / max(4.0, 0.02 * bb.area)))
            y0 = y - int(0.25 * h) - 2
            img = 0.5 * (mk[0]["bottle"] > 0) + 1.0 * (mk[0]["stopper"] > 0)
            crop = _crop(img, x - 1, y0, x + w + 1, y + h + 1, CROP["bottle"])
            return crop, np.array([red[0], red[1]], np.float32)
        m = mk[0]
        sel_g = m["glass"][y:y + h, x:x + w] > 0
        sel_l = m["liquid"][y:y + h, x:x + w] > 0
        liquid = float(sel_l.sum()) / max(1.0, float(sel_g.sum() + sel_l.sum()))
        sat = hsv[0][y:y + h, x:x + w, 1].astype(np.float32) / 255.0 * sel_g
        third = max(1, h // 3)
        top = sat[:third].sum() / max(1.0, sel_g[:third].sum())
        bottom = sat[-third:].sum() / max(1.0, sel_g[-third:].sum())
        img = hsv[0][..., 1].astype(np.float32) / 255.0 * (m["glass"] > 0) + 1.0 * (m["liquid"] > 0)
        crop = _crop(img, x - 1, y - 1, x + w + 1, y + h + 1, CROP["glass"])
        return crop, np.array([liquid, top - bottom], np.float32)

    # ------------------------------------------------------------------ hand
    def _hand(self, mk, cams, det: Detections) -> HandDetection:
        (bl, lab_l), (br, _) = blobs(mk[0]["skin"], "skin", 6), blobs(mk[1]["skin"], "skin", 6)
        best = None
        for a in bl:
            b = _match(a, br)
            if b is None:
                continue
            X = triangulate(cams[0], cams[1], a.centroid, b.centroid)[0]
            if X[2] > FACE_Z:
                continue
            if len(self.static_skin) and np.min(np.linalg.norm(self.static_skin - X, axis=1)) < 0.07:
                continue
            if best is None or a.area > best[0].area:
                best = (a, b, X)
        if best is None:
            return HandDetection(False)
        a, b, X = best
        # distal end: the blob's pixels farthest from the forearm's root (the end nearest the partner)
        pts = []
        for cam, bb, m in ((cams[0], a, mk[0]["skin"]), (cams[1], b, mk[1]["skin"])):
            x, y, w, h = bb.bbox
            ys, xs = np.nonzero(m[y:y + h, x:x + w])
            P = np.column_stack([xs + x + 0.5, ys + y + 0.5])
            root = cam.project(np.array([-0.45, X[1] * 0.5 - 0.1, 0.1]))[0]
            dist = np.linalg.norm(P - root, axis=1)
            far = P[dist >= np.percentile(dist, 70)]
            pts.append(far.mean(axis=0))
        Xd = triangulate(cams[0], cams[1], pts[0], pts[1])[0]
        depth = float(np.linalg.norm(Xd - cams[0].C))
        half = int(round(cams[0].K[0, 0] * 0.09 / depth))
        u, v = pts[0]
        crop = _crop((mk[0]["skin"] > 0).astype(np.float32), int(u) - half, int(v) - half, int(u) + half, int(v) + half, CROP["hand"])
        geo = self._hand_geo(Xd, X, det)
        return HandDetection(True, Xd, X, a, crop, geo)

    @staticmethod
    def _hand_geo(Xd: np.ndarray, Xp: np.ndarray, det: Detections) -> np.ndarray:
        """Hand geometry: position, forearm direction, and where the nearest object is relative to it."""
        d = Xd - Xp
        d = d / max(1e-6, float(np.linalg.norm(d)))
        near_xy, near_dz = 0.4, 0.0
        for o in det.objects.values():
            if o.position is None:
                continue
            dxy = float(np.linalg.norm(Xd[:2] - o.position[:2]))
            if dxy < near_xy:
                near_xy, near_dz = dxy, float(Xd[2] - o.position[2]) / (0.2 if o.name == "bottle" else 0.1)
        return np.array([Xd[0], Xd[1], Xd[2], d[0], d[1], d[2], near_xy, near_dz], np.float32)
