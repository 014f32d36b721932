"""Where the robot puts an object down in its workspace: clear of the hand-over corridor and of what stands there.

The arm goes to every hand-over along the corridor from its shoulder to the hand-over place
(seen from above: the segment from the shoulder to the place where it holds objects out and
takes them). An object set down in that corridor is in the way of the next hand-over: the
forearm, coming down to a held-out object, sweeps it over; the same holds for the other ways the
hand passes low over the table (from the ready pose down to rest). So a put-down spot is chosen on a
grid of the robot's half of the table, within the arm's comfortable reach: of the spots that
keep CORRIDOR_CLEAR from those ways and OBJECT_CLEAR from the objects standing there, the one
nearest the middle of the robot's half (where the cameras see best and every motion has room);
if none does, the one with the most clearance.
"""

from __future__ import annotations

from typing import Iterable

import numpy as np

from assistbot.world import layout

#: the grid of candidate spots (table x, y): the robot's half, short of the far edge and the middle line
SPOT_X = (0.14, 0.30)
SPOT_Y = (-0.30, 0.30)
SPOT_STEP = 0.02
#: the arm reaches a spot comfortably when the grasp point there is this much within its reach (m)
REACH_MARGIN = 0.12
#: clearance (m, seen from above) of a put-down spot from the corridor and from a standing object's centre
CORRIDOR_CLEAR = 0.12
OBJECT_CLEAR = 0.14
#: the spot preferred among those clear enough (table x, y)
PREFERRED = (0.22, 0.0)


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from each point of p (..., 2) to the segment a-b."""
    ab = b - a
    s = np.clip(((p - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.linalg.norm(p - (a + s[..., None] * ab), axis=-1)


def candidate_spots() -> np.ndarray:
    xs = np.arange(SPOT_X[0], SPOT_X[1] + 1e-9, SPOT_STEP)
    ys = np.arange(SPOT_Y[0], SPOT_Y[1] + 1e-9, SPOT_STEP)
    return np.array([(x, y) for x in xs for y in ys])


def put_down_spot(shoulder: np.ndarray, reach: float, handover_xy, standing: Iterable, grasp_height: float,
                  ways: Iterable = ()) -> np.ndarray:
    """The spot (table x, y) for an object held at ``grasp_height`` above its base.

    ``shoulder``: the arm's shoulder (world, m); ``reach``: its reach (m); ``handover_xy``: the
    hand-over place (table x, y); ``standing``: the table x, y of the objects standing in the way;
    ``ways``: other segments (a, b; table x, y) the hand passes along low over the table, kept
    CORRIDOR_CLEAR like the corridor."""
    c = candidate_spots()
    grasp = np.column_stack([c, np.full(len(c), layout.TABLE_Z + grasp_height)])
    ok = np.linalg.norm(grasp - np.asarray(shoulder, float), axis=1) <= reach - REACH_MARGIN
    c = c[ok]
    sh = np.asarray(shoulder, float)[:2]
    clear = segment_distance(c, sh, np.asarray(handover_xy, float)) - CORRIDOR_CLEAR
    for a, b in ways:
        clear = np.minimum(clear, segment_distance(c, np.asarray(a, float)[:2], np.asarray(b, float)[:2]) - CORRIDOR_CLEAR)
    for o in standing:
        clear = np.minimum(clear, np.linalg.norm(c - np.asarray(o, float)[:2], axis=1) - OBJECT_CLEAR)
    if not (clear >= 0).any():
        return c[int(np.argmax(clear))].copy()
    free = c[clear >= 0]
    return free[int(np.argmin(np.linalg.norm(free - np.asarray(PREFERRED), axis=1)))].copy()


#: the table x of a spot the robot shares with the person: just on the person's side of the middle line,
#: where both can set an object down and take it from the table
SHARED_X = -0.045


def shared_spot(shoulder: np.ndarray, reach: float, handover_xy, standing: Iterable, grasp_height: float) -> np.ndarray:
    """A spot on the table at SHARED_X whose grasp point at ``grasp_height`` (the lowest grasp made there) lies
    within ``reach`` of the shoulder, nearest the hand-over place's y and OBJECT_CLEAR from the objects
    standing near it (if none is that clear, the reachable one nearest the hand-over place)."""
    ys = np.arange(SPOT_Y[0], SPOT_Y[1] + 1e-9, SPOT_STEP / 2)
    c = np.column_stack([np.full(len(ys), SHARED_X), ys])
    grasp = np.column_stack([c, np.full(len(c), layout.TABLE_Z + grasp_height)])
    within = np.linalg.norm(grasp - np.asarray(shoulder, float), axis=1) <= reach
    ok = within.copy()
    for o in standing:
        ok &= np.linalg.norm(c - np.asarray(o, float)[:2], axis=1) >= OBJECT_CLEAR
    if not ok.any():
        ok = within if within.any() else np.ones(len(c), bool)
    free = c[ok]
    return free[int(np.argmin(np.abs(free[:, 1] - float(handover_xy[1]))))].copy()
