"""Vision reads a hand held out toward the robot by people who hold it out short of the hand-over zone.

Short arms, a seat farther back or a habit of holding things near put the hand short of the zone's
near end (`layout.HANDOVER_ZONE_X`), which the zone rule alone takes for a hand kept at the body. The
library's held-out classifier, learnt from people of the library seeds, reads how the arm and hand
are held; these scenes show people of an unseen seed range."""

from __future__ import annotations

import pytest

from assistbot.vision import StereoCapture, Vision, library
from assistbot.vision.pipeline import OFFERING
from assistbot.vision.scenes import POSE_TOLERANCE, SceneSampler, by_person, pose
from assistbot.world.layout import HANDOVER_ZONE_X

UNSEEN = range(1000, 1100)

pytestmark = pytest.mark.slow     # about 90 people built in the physics


@pytest.fixture(scope="module")
def readings():
    """(held out in truth, read held out with the library, read held out by the zone rule alone) for
    the scenes whose hand is short of the zone: things held out, and things lifted at their place."""
    clfs, cal = library.load()
    learnt = Vision(library_data=(clfs, cal))
    zone_only = Vision(library_data=({k: c for k, c in clfs.items() if k != library.HELD_OUT}, cal))
    sampler = SceneSampler(1, "test", UNSEEN)
    specs = [sampler.sample(OFFERING[i % 3]) for i in range(300)]
    out = []
    for world, group in by_person(specs, 1):
        with StereoCapture(world.model, threaded=False) as cap:
            for spec in group:
                lab = pose(world, spec)
                short = lab.hand_position[0] < HANDOVER_ZONE_X[0]
                if lab.pose_miss > POSE_TOLERANCE or not short or not (lab.held_out or spec.variant == "lifted"):
                    continue
                f = cap.grab(world.data)
                a, b = learnt.perceive(f).hand, zone_only.perceive(f).hand
                out.append((bool(lab.held_out), a.seen and a.held_out, b.seen and b.held_out))
    return out


def test_a_hand_held_out_short_of_the_zone_is_read_held_out(readings):
    held = [r for r in readings if r[0]]
    assert len(held) >= 8
    assert sum(r[1] for r in held) >= 2 * len(held) / 3, held
    assert sum(r[2] for r in held) <= len(held) / 3, "the zone rule alone reads them: the test shows nothing"


def test_a_thing_lifted_at_its_place_short_of_the_zone_is_mostly_not_read_held_out(readings):
    lifted = [r for r in readings if not r[0]]
    assert len(lifted) >= 8
    assert sum(r[1] for r in lifted) <= len(lifted) / 3, lifted
