"""Video frames and files: layout, highlighted peaks, decodable H.264 with the right frame count."""

from __future__ import annotations

import numpy as np

from assistbot.video import VideoWriter, compose_frame


def scene_image(color):
    img = np.zeros((240, 320, 3), dtype=np.uint8)
    img[:] = color
    return img


def test_frame_layout_places_scene_camera_and_panels():
    layers = [("AEL", {"Communicate-Error": 6.0, "Wait": -4.0}), ("IL", {"remove-stopper": 3.0})]
    f = compose_frame(scene_image((0, 200, 0)), scene_image((200, 0, 0)), layers, subtitle="I cannot remove the stopper.",
                      header="paper-fig3-4  t=12.3 s", size=(1280, 720))
    assert f.shape == (720, 1280, 3) and f.dtype == np.uint8
    # scene on the left, camera top right
    assert (f[360, 300] == [0, 200, 0]).all()
    assert (f[80, 1000] == [200, 0, 0]).all()
    # an active item draws an orange bar somewhere in the panel area, an inactive one blue
    panel = f[300:660, 720:]
    assert ((panel[..., 0] > 240) & (panel[..., 1] > 120) & (panel[..., 1] < 160)).any()
    assert ((panel[..., 2] > 240) & (panel[..., 0] < 100)).any()


def test_video_decodes_with_expected_frames(tmp_path):

    path = tmp_path / "v.mp4"
    with VideoWriter(path, fps=10) as w:
        for k in range(25):
            w.append(compose_frame(scene_image((k * 8, 0, 0)), None, [], size=(320, 192)))
    import imageio.v2 as iio

    reader = iio.get_reader(path)
    n = sum(1 for _ in reader)
    meta = reader.get_meta_data()
    reader.close()
    assert n == 25
    assert meta["codec"] == "h264" and abs(meta["fps"] - 10) < 1e-6
