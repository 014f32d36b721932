"""The active default policy takes a first step within 5 s where it has one; passive never starts."""

import numpy as np
import pytest

from assistbot.human.controller import HumanController
from assistbot.world import Arrangement, all_arrangements, build_world


@pytest.mark.parametrize("bottle,glass,first", [
    ("HWS:closed", "RWS:inverted", "grasp"),
    ("RWS:open", "HWS:inverted", "turn_glass"),
    ("RWS:closed", "RWS:empty", "request"),
])
def test_active_first_step_within_5_s(bottle, glass, first):
    w = build_world(Arrangement.from_options(bottle, glass), seed=1)
    hc = HumanController(w, profile="active", seed=1)
    p0 = hc.arm.hand_pose()[0]
    hc.run(5.0)
    starts = hc.events("start")
    assert starts and starts[0].what == first and starts[0].t <= 5.0
    assert np.linalg.norm(hc.arm.hand_pose()[0] - p0) > 0.05   # the hand really moved


@pytest.mark.slow
@pytest.mark.parametrize("arr", all_arrangements(), ids=lambda a: a.label())
def test_active_first_step_in_every_arrangement_with_one(arr):
    w = build_world(arr, seed=0)
    hc = HumanController(w, profile="active", seed=0)
    hc.run(5.0)
    has_move = arr.bottle.zone == "HWS" and arr.bottle.state == "closed" or arr.glass.zone == "RWS" \
        or (arr.glass.zone == "HWS" and arr.glass.state in ("inverted", "full"))
    assert bool(hc.events("start")) == has_move
