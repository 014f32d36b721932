"""Every named camera renders a non-empty image; segmentation shows each object; CLI errors are exit 2."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.world import CAMERAS, Arrangement, build_world
from assistbot.world.render import SEGMENT_LABELS, Renderer

LABEL = {v: k for k, v in SEGMENT_LABELS.items()}


@pytest.fixture(scope="module")
def renderer_and_worlds():
    # open bottle (liquid visible in the glass when full) with the stopper on the table
    # (a full glass near the robot: from the head the liquid in it is in view; from the far
    # side of the table the glass wall hides the one-layer liquid)
    worlds = [build_world(Arrangement.from_options("HWS:open", "RWS:full@0.30,-0.05")),
              build_world(Arrangement.from_options("RWS:closed", "HWS:empty"))]
    r = Renderer(worlds[0].model, 320, 240)
    yield r, worlds
    r.close()


@pytest.mark.parametrize("camera", CAMERAS)
def test_camera_renders_and_segments_every_object(renderer_and_worlds, camera):
    r, worlds = renderer_and_worlds
    seen = set()
    for w in worlds:
        img = r.rgb(w.data, camera)
        assert img.shape == (240, 320, 3) and img.std() > 10
        depth = r.depth(w.data, camera)
        assert depth.shape == (240, 320) and 0.05 < depth.min() < 5.0
        seen |= set(np.unique(r.segmentation(w.data, camera)).tolist())
    wanted = {"table", "bottle", "glass", "stopper"} | ({"liquid"} if camera != "scene_cam" else set())
    assert {LABEL[n] for n in wanted} <= seen, f"{camera} misses {[SEGMENT_LABELS[k] for k in {LABEL[n] for n in wanted} - seen]}"


def test_cli_snapshot_and_errors(tmp_path, capsys):
    from assistbot.cli import main

    assert main(["snapshot", "--bottle", "HWS:closed", "--glass", "RWS:inverted", "--out", str(tmp_path),
                 "--size", "160x120", "--settle", "0.02", "--camera", "head_cam_right"]) == 0
    assert len(list(tmp_path.glob("*.png"))) == 1
    assert main(["view", "--png", "--bottle", "HWS:closed", "--glass", "RWS:upside", "--out", str(tmp_path / "v.png")]) == 2
    assert capsys.readouterr().err.strip() == "error: arguments: --glass: unknown state 'upside'; use one of inverted, empty, full"
    bad = tmp_path / "s.yaml"
    bad.write_text("objects:\n  bottle: {zone: HWS, state: closed, position: [-0.2, 0.9]}\n  glass: {zone: RWS, state: empty}\n")
    assert main(["view", "--png", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {bad}: objects.bottle.position: ")


@pytest.mark.parametrize("camera", CAMERAS)
def test_particles_left_out_of_the_scene_are_ones_no_camera_sees(renderer_and_worlds, camera):
    # world 0: liquid in a full glass under its rendered surface; world 1: in a closed bottle
    r, worlds = renderer_and_worlds
    for w in worlds:
        w.step(50)
        w.sync_liquid()   # what every render of a stepped world does first
        m, geoms = w.model, w.particle_geoms
        left_out = m.geom_rgba[geoms, 3] == 0
        assert left_out.sum() >= len(geoms) // 2
        shown = r.rgb(w.data, camera)
        saved = m.geom_rgba[geoms, 3].copy()
        m.geom_rgba[geoms, 3] = w._particle_alpha
        try:
            every_particle = r.rgb(w.data, camera)
        finally:
            m.geom_rgba[geoms, 3] = saved
        assert np.array_equal(shown, every_particle)
