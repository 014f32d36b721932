"""The closed loop end to end with VISION: cognition sees only what the robot's head cameras show.

The seed's experiments must play out as with the oracle (tests/test_episode_closed_loop.py);
the same seed must give the same decisions; `assistbot run` must write a playable video with
the utterances as sound. Slow: run by .ci/run and `make test-all`.
"""

from __future__ import annotations

import dataclasses
import shutil
import subprocess
import sys
from functools import lru_cache
from pathlib import Path

import pytest

from assistbot.episode import run_scenario
from assistbot.scenario import load_scenario

from _closed_loop_checks import check_fig3_4, check_fig5

pytestmark = pytest.mark.slow


@lru_cache(maxsize=None)
def episode(name: str):
    return run_scenario(name, perception="vision", video=False)


def test_paper_fig3_4_with_vision_ends_with_the_drink_in_the_seeds_order():
    r = episode("paper-fig3-4")
    assert r.perception == "vision"
    check_fig3_4(r)


def test_paper_fig5_passive_user_with_vision():
    r = episode("paper-fig5")
    assert r.perception == "vision"
    check_fig5(r)


def short(name: str, seconds: float):
    return dataclasses.replace(load_scenario(name), time_limit=seconds)


def test_same_seed_same_decisions_and_percepts_with_vision():
    a = run_scenario(short("paper-fig3-4", 20.0), perception="vision", video=False)
    b = run_scenario(short("paper-fig3-4", 20.0), perception="vision", video=False)
    assert a.decisions and a.decisions == b.decisions
    assert a.utterances == b.utterances
    assert a.world_events == b.world_events


def test_run_writes_a_playable_video_with_the_overlay_and_speech(tmp_path):
    out = tmp_path / "run"
    p = subprocess.run([str(Path(sys.executable).parent / "assistbot"), "run", str(_short_file(tmp_path)), "--out", str(out)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode in (0, 1), p.stderr[-2000:]
    for f in ("video.mp4", "log.jsonl", "summary.json", "subtitles.srt"):
        assert (out / f).exists(), f
    import imageio.v2 as iio

    reader = iio.get_reader(out / "video.mp4")
    n = sum(1 for _ in reader)
    meta = reader.get_meta_data()
    reader.close()
    assert meta["codec"] == "h264"
    assert abs(n - 10 * 8.0) <= 2        # 10 frames per simulated second
    probe = subprocess.run([_ffmpeg(), "-hide_banner", "-i", str(out / "video.mp4")], capture_output=True, text=True)
    has_audio = "Audio:" in probe.stderr
    assert has_audio == (shutil.which("espeak-ng") is not None)


def _short_file(tmp_path):
    """paper-fig3-4 cut to its first 8 s: the SG grasp and the robot's spoken error."""
    src = load_scenario("paper-fig3-4").path.read_text()
    text = src.replace("time_limit: 240", "time_limit: 8")
    assert text != src
    f = tmp_path / "short.yaml"
    f.write_text(text.replace("name: paper-fig3-4", "name: fig3-start"))
    return f


def _ffmpeg() -> str:
    import imageio_ffmpeg

    return imageio_ffmpeg.get_ffmpeg_exe()
