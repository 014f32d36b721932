"""Vision's per-pixel passes, compiled with numba (`segment`, `detect` and `body` call them).

Why compiled: the benchmark (and the episode loop) renders each stereo pair right before vision
processes it, and the render evicts the CPU caches; every separate numpy/OpenCV pass over an
image then reads it back from memory, and every separate call runs its own cold code.  One loop
per image that labels, clears and masks in a single read replaces ~10 such passes.

Where a kernel stands for an OpenCV function (cv2.boundingRect, cv2.moments, connected components
numbered as cv2.connectedComponents numbers them, Sobel and cartToPolar, morphological opening) it
gives OpenCV's results bit for bit: integer work, or OpenCV's own float32 operations in its order;
the tests compare them.  Kernels at module level so numba's on-disk cache finds them again in a new
process.
"""

from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True, nogil=True, inline="always")
def _code(px):
    """A pixel's (r, g, b) top 6 bits each, packed r << 12 | g << 6 | b: its index in the 64^3 table."""
    return ((np.uint32(px[0]) & 0xFC) << 10) | ((np.uint32(px[1]) & 0xFC) << 4) | (np.uint32(px[2]) >> 2)


@numba.njit(cache=True, nogil=True)
def label_half(img, lut, spots, stamp, clear, lo, hi):
    """Labels of every 2nd pixel of every 2nd row of an RGB image (img[::2, ::2]), by the 64^3
    table of the colour's top 6 bits per channel; label ``clear`` removed (0) where the `stamp` (a
    structuring element, odd size, anchor at its centre) dilated around the points ``spots``
    (half-resolution (u, v) floats; non-finite ones and those truncated outside the image skipped)
    covers it; and the bounding box (x, y, w, h; as cv2.boundingRect, 0s if empty) of the pixels of
    each label range [lo[k], hi[k]]."""
    H2, W2 = (img.shape[0] + 1) // 2, (img.shape[1] + 1) // 2
    lab = np.empty((H2, W2), np.uint8)
    for y in range(H2):
        row = img[2 * y]
        for x in range(W2):
            lab[y, x] = lut[_code(row[2 * x])]
    # the dilation of the points by the stamp: pixel (y', x') is covered where stamp[i, j] and a point
    # sits at (y' + i - ay, x' + j - ax); clearing is idempotent, so each point clears its own cover
    sh, sw = stamp.shape
    ay, ax = sh // 2, sw // 2
    for n in range(spots.shape[0]):
        u, v = spots[n, 0], spots[n, 1]
        if not (math.isfinite(u) and math.isfinite(v)):
            continue
        x, y = int(u), int(v)            # truncation toward zero, as astype(int)
        if x < 0 or y < 0 or x >= W2 or y >= H2:
            continue
        for i in range(sh):
            yy = y - i + ay
            if 0 <= yy < H2:
                for j in range(sw):
                    xx = x - j + ax
                    if stamp[i, j] and 0 <= xx < W2 and lab[yy, xx] == clear:
                        lab[yy, xx] = 0
    boxes = np.zeros((lo.size, 4), np.intp)
    for k in range(lo.size):
        first, span = lo[k], np.uint8(hi[k] - lo[k])
        x0, y0, x1, y1 = W2, -1, -1, -1
        for y in range(H2):
            some = False
            for x in range(W2):
                some |= np.uint8(lab[y, x] - first) <= span     # first <= label <= hi[k] (branch-free: vectorises)
            if some:   # the row's first and last pixel in the range
                r0, r1 = 0, W2 - 1
                while np.uint8(lab[y, r0] - first) > span:
                    r0 += 1
                while np.uint8(lab[y, r1] - first) > span:
                    r1 -= 1
                y0 = y if y0 < 0 else y0
                y1 = y
                x0, x1 = min(x0, r0), max(x1, r1)
        if y1 >= 0:
            boxes[k, 0], boxes[k, 1], boxes[k, 2], boxes[k, 3] = x0, y0, x1 - x0 + 1, y1 - y0 + 1
    return lab, boxes


@numba.njit(cache=True, nogil=True)
def label_region(img, lut, part):
    """Labels of all pixels of an RGB image or a region of one (any strides), by the 64^3 table, and
    the mask of the labels that ``part`` (256 entries, 0 or 1) selects."""
    H, W = img.shape[0], img.shape[1]
    lab = np.empty((H, W), np.uint8)
    mask = np.empty((H, W), np.bool_)
    for y in range(H):
        for x in range(W):
            c = lut[_code(img[y, x])]
            lab[y, x] = c
            mask[y, x] = part[c] != 0
    return lab, mask


@numba.njit(cache=True, nogil=True)
def silhouette(mask):
    """A mask's rows that have pixels, their first and last pixel's columns, the extents [x, y, w, h
    (cv2.boundingRect), first and last column of its bottom two rows, of its top two rows] (all 0 for
    an empty mask), and its moments [m00, m10, m01, mu20, mu11, mu02] as cv2.moments(binaryImage=True)
    gives them: the raw ones are sums of small integers (exact in float64, in any order), the central
    ones computed from them by OpenCV's own formulas (completeMomentState)."""
    H, W = mask.shape
    rows = np.empty(H, np.intp)
    first = np.empty(H, np.intp)
    last = np.empty(H, np.intp)
    n = 0
    s00, s10, s01, s20, s11, s02 = 0, 0, 0, 0, 0, 0
    for y in range(H):
        f = -1
        for x in range(W):
            if mask[y, x]:
                f = x
                break
        if f < 0:
            continue
        lx = f
        for x in range(W - 1, f, -1):
            if mask[y, x]:
                lx = x
                break
        rows[n], first[n], last[n] = y, f, lx
        n += 1
        c, sx, sxx = 0, 0, 0
        for x in range(f, lx + 1):
            if mask[y, x]:
                c += 1
                sx += x
                sxx += x * x
        s00 += c
        s10 += sx
        s01 += y * c
        s20 += sxx
        s11 += y * sx
        s02 += y * y * c
    ext = np.zeros(8, np.intp)
    if n:
        top, bot = rows[0], rows[n - 1]
        ext[0], ext[2] = W, 0
        ext[4], ext[5], ext[6], ext[7] = W, -1, W, -1
        for i in range(n):
            ext[0] = min(ext[0], first[i])
            ext[2] = max(ext[2], last[i])
            if rows[i] >= max(top, bot - 1):       # the bottom two rows
                ext[4], ext[5] = min(ext[4], first[i]), max(ext[5], last[i])
            if rows[i] <= top + 1:                 # the top two rows
                ext[6], ext[7] = min(ext[6], first[i]), max(ext[7], last[i])
        ext[1], ext[3] = top, bot - top + 1
        ext[2] = ext[2] - ext[0] + 1
    m00, m10, m01 = float(s00), float(s10), float(s01)
    cx, cy = 0.0, 0.0
    if abs(m00) > 2.220446049250313e-16:   # DBL_EPSILON
        inv = 1.0 / m00
        cx, cy = m10 * inv, m01 * inv
    mom = np.empty(6, np.float64)
    mom[0], mom[1], mom[2] = m00, m10, m01
    mom[3] = float(s20) - m10 * cx
    mom[4] = float(s11) - m10 * cy
    mom[5] = float(s02) - m01 * cy
    return rows[:n], first[:n], last[:n], ext, mom


@numba.njit(cache=True, nogil=True)
def label_silhouette(img, lut, part):
    """`label_region` and `silhouette` of its mask, in one call."""
    lab, mask = label_region(img, lut, part)
    rows, first, last, ext, mom = silhouette(mask)
    return lab, mask, rows, first, last, ext, mom


@numba.njit(cache=True, nogil=True)
def first_row_over(lab, mask, part, lo, hi):
    """The first row in [lo, hi] with a pixel labelled ``part`` in a column where ``mask`` has pixels
    (in any row); -1 if none."""
    H, W = mask.shape
    cols = np.zeros(W, np.bool_)
    for y in range(H):
        for x in range(W):
            if mask[y, x]:
                cols[x] = True
    for y in range(max(lo, 0), min(hi, H - 1) + 1):
        for x in range(W):
            if lab[y, x] == part and cols[x]:
                return y
    return -1


@numba.njit(cache=True, nogil=True, inline="always")
def _at(comp, ox, oy, x, y):
    """comp's value at image pixel (x, y), comp placed at (ox, oy); 0 outside it."""
    if 0 <= y - oy < comp.shape[0] and 0 <= x - ox < comp.shape[1]:
        return comp[y - oy, x - ox]
    return 0


@numba.njit(cache=True, nogil=True)
def blob_pixels(comp, ox, oy, label, lab, near_label, x0, y0, x1, y1):
    """In the window [y0, y1) x [x0, x1) of a half-resolution image: the centres (x, y), at full
    resolution, of the pixels of component ``label`` (of the components' label image ``comp``, placed
    at column ox, row oy of the image; 0 outside it) in row-major order, and of those next to (3x3, within the window) a
    pixel labelled ``near_label`` in ``lab``: their count and the sums of their window columns and rows."""
    n = 0
    for y in range(y0, y1):
        for x in range(x0, x1):
            if _at(comp, ox, oy, x, y) == label:
                n += 1
    P = np.empty((n, 2), np.float64)
    i = 0
    touch, sx, sy = 0, 0, 0
    for y in range(y0, y1):
        for x in range(x0, x1):
            if _at(comp, ox, oy, x, y) != label:
                continue
            P[i, 0] = (x - x0) * 2.0 + (2 * x0 + 0.5)
            P[i, 1] = (y - y0) * 2.0 + (2 * y0 + 0.5)
            i += 1
            near = False
            for yy in range(max(y0, y - 1), min(y1, y + 2)):
                for xx in range(max(x0, x - 1), min(x1, x + 2)):
                    if lab[yy, xx] == near_label:
                        near = True
            if near:
                touch += 1
                sx += x - x0
                sy += y - y0
    return P, touch, sx, sy


@numba.njit(cache=True, nogil=True)
def count_near(lab, mask, part, r):
    """The number of pixels labelled ``part`` with a ``mask`` pixel within r pixels (a (2r+1)^2 box,
    inside the image): the count of ``part`` in the mask dilated by that box."""
    H, W = lab.shape
    n = 0
    for y in range(H):
        for x in range(W):
            if lab[y, x] != part:
                continue
            hit = False
            for yy in range(max(0, y - r), min(H, y + r + 1)):
                for xx in range(max(0, x - r), min(W, x + r + 1)):
                    if mask[yy, xx]:
                        hit = True
            if hit:
                n += 1
    return n


@numba.njit(cache=True, nogil=True)
def masked_saturation(img, mask):
    """HSV saturation (max - min) / max(max, 1) of an RGB image (any strides) in float32, 0 off the mask."""
    H, W = mask.shape
    out = np.zeros((H, W), np.float32)
    for y in range(H):
        for x in range(W):
            if mask[y, x]:
                r, g, b = img[y, x, 0], img[y, x, 1], img[y, x, 2]
                mx = np.float32(max(r, g, b))
                out[y, x] = (mx - np.float32(min(r, g, b))) / max(mx, np.float32(1.0))
    return out


@numba.njit(cache=True, nogil=True, inline="always")
def _root(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@numba.njit(cache=True, nogil=True)
def components8(src, lo, hi, x0, y0, x1, y1):
    """8-connected components of the mask lo <= src <= hi in [y0, y1) x [x0, x1) (x0, y0 even), numbered
    as OpenCV's Grana (BBDT)
    algorithm numbers them: in the order of each component's first 2x2 block in a raster scan of the
    blocks (a 2x2 block's pixels are all 8-connected, so each block is one component's; its first block
    makes the component's smallest provisional label, and OpenCV numbers the label sets' roots, the
    smallest, in order).  Returns the labels (int32, 0 background), per label 0..n the statistics
    [left, top, width, height, area] (int32; row 0, the background's, left at 0) and the sums of the
    pixels' x and y (int64), all in the crop's coordinates."""
    h, w = y1 - y0, x1 - x0
    lab = np.zeros((h, w), np.int32)
    # provisional labels' union-find parents and first blocks: written only when a label is made (np.empty:
    # zeroing them, 12 bytes a pixel of the box, would be a pass over cold memory)
    parent = np.empty(h * w + 1, np.int32)
    key = np.empty(h * w + 1, np.int64)
    bw = (w + 1) // 2
    nl = 0
    for y in range(h):
        for x in range(w):
            v = src[y0 + y, x0 + x]
            if v < lo or v > hi:
                continue
            k = (y >> 1) * bw + (x >> 1)
            best = 0
            for dy, dx in ((0, -1), (-1, -1), (-1, 0), (-1, 1)):
                yy, xx = y + dy, x + dx
                if yy >= 0 and 0 <= xx < w and lab[yy, xx]:
                    r = _root(parent, lab[yy, xx])
                    if best == 0 or r < best:
                        best = r
            if best == 0:
                nl += 1
                parent[nl] = nl
                key[nl] = k
                best = nl
            else:
                for dy, dx in ((0, -1), (-1, -1), (-1, 0), (-1, 1)):
                    yy, xx = y + dy, x + dx
                    if yy >= 0 and 0 <= xx < w and lab[yy, xx]:
                        r = _root(parent, lab[yy, xx])
                        if r != best:
                            parent[r] = best
                            key[best] = min(key[best], key[r])
                key[best] = min(key[best], k)
            lab[y, x] = best
    # the roots in the order of their first block
    n = 0
    roots = np.empty(nl, np.int32)
    keys = np.empty(nl, np.int64)
    for i in range(1, nl + 1):
        if _root(parent, i) == i:
            roots[n], keys[n] = i, key[i]
            n += 1
    order = np.argsort(keys[:n], kind="mergesort")
    final = np.zeros(nl + 1, np.int32)
    for j in range(n):
        final[roots[order[j]]] = j + 1
    stats = np.zeros((n + 1, 5), np.int32)
    sums = np.zeros((n + 1, 2), np.int64)
    mins = np.full((n + 1, 2), 1 << 30, np.int64)    # each component's smallest and largest x, y
    maxs = np.full((n + 1, 2), -1, np.int64)
    for y in range(h):
        for x in range(w):
            if lab[y, x]:
                f = final[_root(parent, lab[y, x])]
                lab[y, x] = f
                stats[f, 4] += 1
                sums[f, 0] += x
                sums[f, 1] += y
                mins[f, 0], mins[f, 1] = min(mins[f, 0], x), min(mins[f, 1], y)
                maxs[f, 0], maxs[f, 1] = max(maxs[f, 0], x), max(maxs[f, 1], y)
    for f in range(1, n + 1):
        stats[f, 0], stats[f, 1] = mins[f, 0], mins[f, 1]
        stats[f, 2], stats[f, 3] = maxs[f, 0] - mins[f, 0] + 1, maxs[f, 1] - mins[f, 1] + 1
    return lab, stats, sums


@numba.njit(cache=True, nogil=True, inline="always")
def _row_counts(m):
    """Per row, the running count of set pixels: c[y, x] = number set in m[y, :x]."""
    H, W = m.shape
    c = np.zeros((H, W + 1), np.int32)
    for y in range(H):
        for x in range(W):
            c[y, x + 1] = c[y, x] + (1 if m[y, x] else 0)
    return c


@numba.njit(cache=True, nogil=True, inline="always")
def _spans_test(c, y, x, spans, all_set):
    """The structuring element's spans placed at (y, x), the parts inside the image, tested by a mask's
    running counts c: whether every span is wholly set (``all_set``: erosion keeps the pixel), or else
    whether any span has a set pixel (dilation sets it)."""
    H, W = c.shape[0], c.shape[1] - 1
    for s in range(spans.shape[0]):
        yy = y + spans[s, 0]
        a, b = max(0, x + spans[s, 1]), min(W - 1, x + spans[s, 2])
        if 0 <= yy < H and a <= b:
            n = c[yy, b + 1] - c[yy, a]
            if all_set and n != b - a + 1:
                return False
            if not all_set and n > 0:
                return True
    return all_set


@numba.njit(cache=True, nogil=True)
def opening_residue(m, spans):
    """What an opening (erosion, then dilation, as cv2.morphologyEx(MORPH_OPEN) with its default border:
    pixels outside the image neither erode nor dilate) of the 0/1 mask m by a symmetric structuring
    element removes: m minus its opening (uint8 0/1).  The element is given as its rows' spans,
    (dy, dx0, dx1) relative to its centre; a span is tested in O(1) by running counts of each row."""
    H, W = m.shape
    c = _row_counts(m)
    er = np.zeros((H, W), np.uint8)
    for y in range(H):
        for x in range(W):
            if m[y, x] and _spans_test(c, y, x, spans, True):
                er[y, x] = 1
    e = _row_counts(er)
    out = np.zeros((H, W), np.uint8)
    for y in range(H):
        for x in range(W):
            if m[y, x] and not _spans_test(e, y, x, spans, False):
                out[y, x] = 1
    return out


@numba.njit(cache=True, nogil=True)
def thin_pieces(m, spans):
    """For the residue of an opening of m by each element (spans[k], padded rows with dy = 99 unused):
    its total area, its largest 8-connected piece's area (the first such piece in OpenCV's numbering)
    and that piece's bounding box width and height; (k, 4) int64."""
    out = np.zeros((spans.shape[0], 4), np.int64)
    H, W = m.shape
    for k in range(spans.shape[0]):
        n = 0
        while n < spans.shape[1] and spans[k, n, 0] != 99:
            n += 1
        thin = opening_residue(m, spans[k, :n])
        _, st, _ = components8(thin, 1, 1, 0, 0, W, H)
        best = 0
        for j in range(1, st.shape[0]):
            out[k, 0] += st[j, 4]
            if best == 0 or st[j, 4] > st[best, 4]:
                best = j
        if best:
            out[k, 1], out[k, 2], out[k, 3] = st[best, 4], st[best, 2], st[best, 3]
    return out


#: OpenCV's fast arctangent (hal fastAtan32f, in degrees): its polynomial's coefficients, each a float
#: literal times (float)(180 / pi), multiplied in float32 as OpenCV's static initialisers do
_ATAN_P = tuple(np.float32(p) * np.float32(180 / np.pi) for p in (0.9997878412794807, -0.3258083974640975,
                                                                   0.1555786518463281, -0.04432655554792128))


@numba.njit(cache=True, nogil=True, inline="always")
def _fma32(a, b, c):
    """a * b + c rounded once to float32, as a fused multiply-add (the product is exact in float64)."""
    return np.float32(np.float64(a) * np.float64(b) + np.float64(c))


@numba.njit(cache=True, nogil=True)
def gradient_histogram(c, cell, bins):
    """`detect.outline_hog`'s sums: per cell x cell block (row-major) and orientation bin, the gradient
    magnitude summed in float64 in pixel order, as np.bincount sums them.  The gradient, magnitude
    and angle as OpenCV computes them: Sobel ksize=1 (central differences, reflected border),
    cartToPolar (fused multiply-adds, its fast arctangent in degrees times float32(pi / 180))."""
    H, W = c.shape
    n = W // cell
    hist = np.zeros(n * (H // cell) * bins, np.float64)
    eps = np.float32(2.220446049250313e-16)
    scale = np.float32(np.pi / 180)
    tobin = np.float32(bins / np.pi)
    p1, p3, p5, p7 = _ATAN_P
    for y in range(H):
        ym, yp = (y - 1 if y > 0 else 1), (y + 1 if y < H - 1 else H - 2)
        for x in range(W):
            xm, xp = (x - 1 if x > 0 else 1), (x + 1 if x < W - 1 else W - 2)
            gx = np.float32(c[y, xp] - c[y, xm])
            gy = np.float32(c[yp, x] - c[ym, x])
            mag = np.float32(np.sqrt(_fma32(gx, gx, np.float32(gy * gy))))
            ax, ay = abs(gx), abs(gy)
            q = np.float32(min(ax, ay) / np.float32(max(ax, ay) + eps))
            qq = np.float32(q * q)
            a = np.float32(_fma32(_fma32(_fma32(qq, p7, p5), qq, p3), qq, p1) * q)
            if not ax >= ay:
                a = np.float32(np.float32(90.0) - a)
            if gx < 0:
                a = np.float32(np.float32(180.0) - a)
            if gy < 0:
                a = np.float32(np.float32(360.0) - a)
            ang = np.float32(a * scale)
            b = int(np.float32(ang * tobin)) % bins
            hist[((y // cell) * n + x // cell) * bins + b] += np.float64(mag)
    return hist


@numba.njit(cache=True, nogil=True, inline="always")
def _homog(P, k, X, i):
    """Row k of the camera matrix P (3, 4) times point X[i] with a 1 appended, summed left to right."""
    return P[k, 0] * X[i, 0] + P[k, 1] * X[i, 1] + P[k, 2] * X[i, 2] + P[k, 3]


@numba.njit(cache=True, nogil=True)
def capsules_cover(a, b, r, P, f, margin, pts):
    """`body.RobotBody.covers`: whether any pixel of pts (M, 2) lies on the image of a capsule (ends
    a, b (N, 3), radius r, in the frame of the camera matrix P (3, 4)): its ends projected, the
    segment between them widened by f * r over the nearer end's depth plus margin px."""
    for i in range(r.shape[0]):
        za, zb = _homog(P, 2, a, i), _homog(P, 2, b, i)
        if not (za > 1e-6 and zb > 1e-6):
            continue                     # (partly) behind the camera
        ua, va = _homog(P, 0, a, i) / za, _homog(P, 1, a, i) / za
        ub, vb = _homog(P, 0, b, i) / zb, _homog(P, 1, b, i) / zb
        rad = f * r[i] / min(za, zb) + margin
        dx, dy = ub - ua, vb - va
        L2 = max(dx * dx + dy * dy, 1e-12)
        for j in range(pts.shape[0]):
            px, py = pts[j, 0] - ua, pts[j, 1] - va
            t = min(max((px * dx + py * dy) / L2, 0.0), 1.0)
            ex, ey = px - t * dx, py - t * dy
            if ex * ex + ey * ey < rad * rad:
                return True
    return False


@numba.njit(cache=True, nogil=True)
def project_half(X, C, R, K):
    """`CameraModel.project` of the points X (N, 3) times 0.5 (half-resolution pixels), in one loop:
    (X - C) @ R.T @ K.T over its depth, nan behind the camera; the sums term by term."""
    out = np.empty((X.shape[0], 2))
    for n in range(X.shape[0]):
        x0, x1, x2 = X[n, 0] - C[0], X[n, 1] - C[1], X[n, 2] - C[2]
        y0 = x0 * R[0, 0] + x1 * R[0, 1] + x2 * R[0, 2]
        y1 = x0 * R[1, 0] + x1 * R[1, 1] + x2 * R[1, 2]
        y2 = x0 * R[2, 0] + x1 * R[2, 1] + x2 * R[2, 2]
        z = y0 * K[2, 0] + y1 * K[2, 1] + y2 * K[2, 2]
        if z > 1e-6:
            out[n, 0] = (y0 * K[0, 0] + y1 * K[0, 1] + y2 * K[0, 2]) / z * 0.5
            out[n, 1] = (y0 * K[1, 0] + y1 * K[1, 1] + y2 * K[1, 2]) / z * 0.5
        else:
            out[n, 0] = out[n, 1] = np.nan
    return out
