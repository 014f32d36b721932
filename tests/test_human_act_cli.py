"""`assistbot human-act`: a short video per behaviour, the physics' outcome printed; bad arguments exit 2."""

import imageio.v2 as iio
import pytest

from assistbot.cli import main
from assistbot.human.demos import DEMOS, run_demo


@pytest.mark.parametrize("argv,key", [
    (["human-act", "juggle"], "behaviour"),
    (["human-act", "drink", "--size", "big"], "--size"),
    (["human-act", "drink", "--fps", "200"], "--fps"),
    (["human-act", "drink", "--camera", "nose_cam"], "--camera"),
])
def test_bad_arguments_are_one_line_and_exit_two(argv, key, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: arguments: {key}: ")


def test_writes_a_video_of_the_behaviour(tmp_path, capsys):
    assert main(["human-act", "point", "--out", str(tmp_path), "--size", "160x120", "--fps", "10"]) == 0
    out = capsys.readouterr().out
    assert "point: succeeded" in out
    frames = [f for f in iio.get_reader(str(tmp_path / "point.mp4"))]
    assert len(frames) >= 30 and frames[0].shape == (120, 160, 3)
    assert max(float(f.std()) for f in frames) > 10          # a picture, not a blank


@pytest.mark.slow
@pytest.mark.parametrize("name", list(DEMOS))
def test_every_demo_gives_its_outcome(name):
    r = run_demo(name)
    assert r.status == DEMOS[name].expect, r.reason
