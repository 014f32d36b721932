"""Vision's colour segmentation (`assistbot.vision.segment`): its compiled passes against OpenCV and hand-made expectations."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from assistbot.vision.library import load_calibration
from assistbot.vision.segment import (
    LABEL,
    ColourTable,
    LabelRange,
    blob_pixels,
    components,
    components_each,
    count_near,
    first_row_over,
    masked_saturation,
)


@pytest.fixture(scope="module")
def table():
    return ColourTable(load_calibration()["hsv"])


def _want(table: ColourTable, img: np.ndarray) -> np.ndarray:
    """Each pixel's label: the table's entry for its colour's top 6 bits per channel."""
    q = (img >> 2).astype(np.int64)
    return table.lut[(q[..., 0] << 12) | (q[..., 1] << 6) | q[..., 2]]


def _colour(table: ColourTable, label: int) -> np.ndarray:
    """An RGB colour that the table labels ``label``."""
    i = int(np.flatnonzero(table.lut == label)[0])
    return np.array([(i >> 12) << 2, ((i >> 6) & 63) << 2, (i & 63) << 2], np.uint8)


def _painted(table: ColourTable, labels: np.ndarray) -> np.ndarray:
    """An RGB image whose pixels the table labels as ``labels`` says."""
    pal = np.array([_colour(table, k) for k in range(int(labels.max()) + 1)])
    return pal[labels]


def test_colour_table_labels_every_colour_as_its_hsv_boxes_say(table):
    """Each pixel gets the label of its 6-bit colour bucket, at full resolution (of an image or of a
    region of interest in one) and at half resolution (every other pixel of every other row, odd sizes too)."""
    rng = np.random.default_rng(0)
    img = rng.integers(0, 256, (41, 51, 3), dtype=np.uint8)
    want = _want(table, img)
    part = np.isin(np.arange(256), (LABEL["skin"], LABEL["shirt"])).astype(np.uint8)
    lab, mask = table.region(img, part)
    assert np.array_equal(lab, want) and np.array_equal(mask, (want == LABEL["skin"]) | (want == LABEL["shirt"]))
    assert mask.any() and not mask.all()
    assert np.array_equal(table.region(img[5:17, 3:30], part)[0], want[5:17, 3:30])   # a non-contiguous region
    for h, w in ((40, 50), (41, 51), (41, 50)):
        assert np.array_equal(table.half(img[:h, :w])[0], want[:h:2, :w:2]), (h, w)


def test_half_resolution_labels_clear_the_stamped_label_and_box_each_range(table):
    """`half` removes label ``clear`` where the stamp around the points lies (as cv2.dilate of the
    points' pixels; points outside or non-finite left out), and boxes each label range as cv2.boundingRect does."""
    rng = np.random.default_rng(1)
    labels = rng.choice([0, LABEL["bottle"], LABEL["glass"], LABEL["liquid"], LABEL["skin"]], (60, 80), p=[0.6, 0.1, 0.1, 0.1, 0.1])
    img = _painted(table, labels)
    spots = np.array([[3.7, 5.2], [20.0, 14.9], [39.9, 29.9], [-1.0, 3.0], [12.0, np.nan], [45.0, 2.0]])
    stamp = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (5, 5))
    ranges = ((LABEL["bottle"], LABEL["bottle"]), (LABEL["glass"], LABEL["liquid"]), (LABEL["skin"], LABEL["skin"]))
    lab, masks, boxes = table.half(img, ranges, LABEL["skin"], spots, stamp)

    want = labels[::2, ::2].astype(np.uint8)
    points = np.zeros(want.shape, np.uint8)
    for u, v in ((3, 5), (20, 14), (39, 29)):      # the points inside, truncated to their pixels
        points[v, u] = 1
    covered = cv2.dilate(points, stamp).view(bool)
    assert (covered & (want == LABEL["skin"])).any()
    want[covered & (want == LABEL["skin"])] = 0
    assert np.array_equal(lab, want)
    for (lo, hi), m, box in zip(ranges, masks, boxes):
        assert isinstance(m, LabelRange) and (m.lo, m.hi) == (lo, hi)
        assert box == cv2.boundingRect(cv2.inRange(want, lo, hi))
    assert table.half(img, ((7, 7),))[2] == [(0, 0, 0, 0)]     # an empty range


def _opencv_blobs(mask: np.ndarray, min_area: int) -> tuple[np.ndarray, list[tuple]]:
    """OpenCV's labels of a mask and its components of at least ``min_area`` px, larger first (ties in
    label order), as (label, area, centroid, bbox) at full resolution (twice the mask's)."""
    n, lab, st, cen = cv2.connectedComponentsWithStatsWithAlgorithm(mask.view(np.uint8), 8, cv2.CV_32S, cv2.CCL_GRANA)
    order = sorted((i for i in range(1, n) if st[i, cv2.CC_STAT_AREA] >= min_area), key=lambda i: -st[i, cv2.CC_STAT_AREA])
    return lab, [(i, 4.0 * st[i, cv2.CC_STAT_AREA], (cen[i] + 0.5) * 2 - 0.5, tuple(int(v) * 2 for v in st[i, :4])) for i in order]


def test_components_are_opencvs_numbered_as_it_numbers_them():
    """Blobs of random masks (several pieces, touching diagonally, at the borders): the components,
    label numbers, areas, centroids and boxes of OpenCV's connectedComponents (Grana), and each view
    holds its labels, whatever form the mask comes in."""
    rng = np.random.default_rng(2)
    for i in range(60):
        h, w = int(rng.integers(5, 40)), int(rng.integers(5, 40))
        mask = rng.random((h, w)) < rng.uniform(0.05, 0.6)
        if i % 3 == 0:
            mask[:, : int(rng.integers(0, w))] = False     # a box that starts at an odd column, say
        want_lab, want = _opencv_blobs(mask, 4)
        labels = np.where(mask, LABEL["skin"], LABEL["shirt"]).astype(np.uint8)
        for form in (mask, mask.astype(np.uint8) * 255, LabelRange(labels, LABEL["skin"], LABEL["skin"])):
            blobs, (sub, x0, y0) = components(form, "bottle", keep=1000)
            got = [(b.label, b.area, b.centroid, b.bbox) for b in blobs]
            assert len(got) == len(want), i
            for (gl, ga, gc, gb), (wl, wa, wc, wb) in zip(got, want):
                assert (gl, ga, gb) == (wl, wa, wb) and np.array_equal(gc, wc), i
            view = np.zeros((h, w), np.int32)
            view[y0:y0 + sub.shape[0], x0:x0 + sub.shape[1]] = sub
            assert np.array_equal(view, want_lab), i


def test_components_of_several_masks_pair_only_where_the_first_camera_has_a_blob():
    left = [np.zeros((10, 10), bool), np.zeros((10, 10), bool)]
    left[0][3:6, 3:6] = True
    right = [m.copy() for m in left]
    right[1][6:9, 6:9] = True          # a glass the left camera does not see: nothing to pair it with
    found, views = components_each([left, right], ("bottle", "glass"), (2, 2), pairs_only=True, views_of=(0,))
    assert [len(f) for f in found[0]] == [1, 0] and [len(f) for f in found[1]] == [1, 0]
    assert views[0][1] is None and views[1][0][0].shape == (4, 4)   # its box, from an even row and column


def test_region_silhouette_gives_opencvs_box_and_moments(table):
    """The silhouette of a region's mask: its rows with their first and last pixels, its bounding box and
    those of its bottom and top two rows (cv2.boundingRect), its moments (cv2.moments, binary)."""
    rng = np.random.default_rng(3)
    part = np.isin(np.arange(256), (LABEL["bottle"],)).astype(np.uint8)
    for i in range(40):
        h, w = int(rng.integers(3, 30)), int(rng.integers(3, 30))
        on = rng.random((h, w)) < rng.uniform(0.0, 0.5)
        labels = np.where(on, LABEL["bottle"], rng.choice([0, LABEL["skin"]], (h, w)))
        img = _painted(table, np.pad(labels, 2))[2:-2, 2:-2]          # a region of a larger image
        lab, mask, rows, first, last, ext, mom = table.region_silhouette(img, part)
        assert np.array_equal(lab, labels) and np.array_equal(mask, on)
        m8 = on.view(np.uint8)
        want_rows = np.flatnonzero(on.any(axis=1))
        assert np.array_equal(rows, want_rows)
        assert np.array_equal(first, [np.flatnonzero(on[y])[0] for y in want_rows])
        assert np.array_equal(last, [np.flatnonzero(on[y])[-1] for y in want_rows])
        x, y, bw, bh = cv2.boundingRect(m8)
        assert tuple(ext[:4]) == (x, y, bw, bh), i
        if bw:
            bx, _, bbw, _ = cv2.boundingRect(m8[max(y, y + bh - 2):y + bh])
            tx, _, tbw, _ = cv2.boundingRect(m8[y:y + 2])
            assert tuple(ext[4:]) == (bx, bx + bbw - 1, tx, tx + tbw - 1), i
        else:
            assert not ext.any()
        mo = cv2.moments(m8, binaryImage=True)
        assert np.array_equal(mom, [mo[k] for k in ("m00", "m10", "m01", "mu20", "mu11", "mu02")]), i


def test_first_row_over_finds_the_part_above_the_masks_columns():
    lab = np.zeros((8, 6), np.uint8)
    mask = np.zeros((8, 6), bool)
    mask[5:8, 2:4] = True             # a silhouette in columns 2 and 3
    lab[1, 0] = 2                     # the part, but not over the silhouette's columns
    lab[3, 3] = 2
    lab[4, 2] = 2
    assert first_row_over(lab, mask, 2, 0, 7) == 3
    assert first_row_over(lab, mask, 2, 4, 7) == 4      # rows from lo on
    assert first_row_over(lab, mask, 2, 0, 2) == -1     # up to hi
    assert first_row_over(lab, mask, 5, 0, 7) == -1


def test_count_near_counts_the_part_in_the_dilated_mask():
    """As cv2.dilate of the mask by a (2r+1)^2 box, and the part's pixels counted in it."""
    rng = np.random.default_rng(5)
    for _ in range(30):
        h, w = int(rng.integers(1, 25)), int(rng.integers(1, 25))
        lab = rng.integers(0, 4, (h, w)).astype(np.uint8)
        mask = rng.random((h, w)) < 0.1
        for r in (0, 1, 2):
            near = cv2.dilate(mask.view(np.uint8), np.ones((2 * r + 1, 2 * r + 1), np.uint8)).view(bool)
            assert count_near(lab, mask, 3, r) == np.count_nonzero(near & (lab == 3))


def test_masked_saturation_is_hsv_saturation_on_the_mask():
    """OpenCV's HSV saturation (of the image in floats) on the mask, 0 off it."""
    rng = np.random.default_rng(6)
    img = rng.integers(0, 256, (30, 40, 3), dtype=np.uint8)
    img[0, :3] = 0                    # black: saturation 0
    mask = rng.random((30, 40)) < 0.5
    mask[0, :3] = True
    sat = masked_saturation(img, mask)
    want = cv2.cvtColor(img.astype(np.float32) / 255, cv2.COLOR_RGB2HSV)[..., 1]
    assert sat.dtype == np.float32
    assert np.all(sat[~mask] == 0) and np.abs(sat[mask] - want[mask]).max() < 1e-6
    sub = masked_saturation(img[3:20, 5:30], mask[3:20, 5:30])     # a region of interest
    assert np.array_equal(sub, sat[3:20, 5:30])


def test_blob_pixels_lists_the_components_pixels_and_those_by_the_neighbour():
    """A component's pixels in a window (full-resolution centres, row by row) and those of them with a
    ``near`` pixel in their 3x3 neighbourhood inside the window: their count and coordinate sums."""
    comp = np.zeros((4, 5), np.int32)          # the view: placed at column 3, row 2
    comp[1, 1:4] = 7
    comp[2, 3] = 7
    comp[3, 0] = 5                              # another component
    lab = np.zeros((10, 12), np.uint8)
    lab[2, 6] = 9                               # next to the pixels (5, 3), (6, 3) of the image
    lab[8, 8] = 9                               # next to none
    P, n, sx, sy = blob_pixels((comp, 3, 2), 7, lab, 9, 3, 1, 9, 9)
    pixels = [(4, 3), (5, 3), (6, 3), (6, 4)]   # (x, y) in the half-resolution image
    assert np.array_equal(P, [[2 * x + 0.5, 2 * y + 0.5] for x, y in pixels])
    assert (n, sx, sy) == (2, (5 - 3) + (6 - 3), 2 * (3 - 1))
    P, n, _, _ = blob_pixels((comp, 3, 2), 7, lab, 9, 5, 3, 9, 9)    # a window that leaves out the neighbour
    assert len(P) == 3 and n == 0
