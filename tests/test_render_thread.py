"""The head cameras drawn on a render thread: the same pixels as on the caller's thread, of the
instant the pair was taken; pipelined vision delivers that pair one perception tick later."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from assistbot.cognition.percept import RobotPercept
from assistbot.episode.builder import split_overrides
from assistbot.episode.vision_perception import VisionPerception
from assistbot.errors import UserError
from assistbot.vision import CaptureConfig, StereoCapture
from assistbot.world import PAPER_ARRANGEMENTS, build_world


@pytest.fixture()
def world():
    return build_world(PAPER_ARRANGEMENTS["fig3"], 0)


def _move_glass(world, dx: float) -> None:
    m, d = world.model, world.data
    adr = m.jnt_qposadr[m.body_jntadr[world.body_id["glass"]]]
    d.qpos[adr] += dx
    mujoco.mj_forward(m, d)


def test_threaded_capture_draws_the_pixels_of_the_instant_it_was_started(world):
    with StereoCapture(world.model) as plain, StereoCapture(world.model, threaded=True) as threaded:
        before = plain.grab(world.data)
        frame = threaded.start(world.data)
        _move_glass(world, 0.10)  # the world goes on while the thread draws
        after = plain.grab(world.data)
        threaded.collect(frame)
        assert np.array_equal(frame.left, before.left) and np.array_equal(frame.right, before.right)
        assert not np.array_equal(after.left, before.left)
        assert frame.t == before.t and frame.render_ms > 0
        # grab on a threaded capture is start + collect: same pixels again
        assert np.array_equal(threaded.grab(world.data).left, after.left)


def test_threaded_capture_is_used_in_order(world):
    with StereoCapture(world.model, threaded=True) as cap:
        first = cap.start(world.data)
        with pytest.raises(RuntimeError, match="collect"):
            cap.start(world.data)
        cap.collect(first)
        with pytest.raises(RuntimeError, match="threaded=False"):
            cap.segmentation(world.data)


def test_dropped_frames_follow_the_seed_with_or_without_the_thread(world):
    cfg = CaptureConfig(dropout=0.5, seed=3)
    with StereoCapture(world.model, cfg) as plain, StereoCapture(world.model, cfg, threaded=True) as threaded:
        a = [plain.grab(world.data).dropped for _ in range(12)]
        b = [threaded.collect(threaded.start(world.data)).dropped for _ in range(12)]
    assert a == b and any(a) and not all(a)


@pytest.mark.parametrize("p", [0.2, 0.6])
def test_the_dropout_rate_is_within_its_binomial_interval(world, p):
    n = 300
    with StereoCapture(world.model, CaptureConfig(dropout=p, seed=5)) as cap:
        dropped = sum(cap.grab(world.data).dropped for _ in range(n))
    assert abs(dropped / n - p) < 4 * (p * (1 - p) / n) ** 0.5


def test_pipelined_vision_sees_the_world_one_perception_tick_late(world):
    robot = RobotPercept()   # idle, holding nothing
    sync, piped = VisionPerception(world, pipelined=False), VisionPerception(world, pipelined=True)
    try:
        first = piped.perceive(0.0, robot)
        assert first.t == 0.0 and not first.objects["glass"].seen  # nothing drawn yet at the first tick
        was = sync.perceive(0.0, robot).objects["glass"]
        _move_glass(world, 0.10)
        late = piped.perceive(0.1, robot)
        assert late.t == 0.1  # delivered now, showing the pair taken at 0.0
        assert late.objects["glass"].seen and np.allclose(late.objects["glass"].position, was.position)
        now = sync.perceive(0.1, robot).objects["glass"]
        assert now.position[0] - was.position[0] > 0.07
    finally:
        sync.close()
        piped.close()


def test_pipelined_is_a_boolean_override():
    assert split_overrides({"vision.pipelined": False}, "s.yaml").vision == {"pipelined": False}
    with pytest.raises(UserError, match="vision.pipelined.*true or false"):
        split_overrides({"vision.pipelined": "no"}, "s.yaml")


@pytest.mark.parametrize("bad", [1.0, -0.1, True, "half"])
def test_dropout_is_a_probability_override(bad):
    assert split_overrides({"vision.dropout": 0.25}, "s.yaml").vision == {"dropout": 0.25}
    with pytest.raises(UserError, match=r"vision.dropout.*a probability in \[0, 1\)"):
        split_overrides({"vision.dropout": bad}, "s.yaml")
