"""Speech: timed subtitles, audio placed at the utterances' times, and muxing under a video."""

from __future__ import annotations

import subprocess
import wave

import numpy as np
import pytest

from assistbot.speech import SAMPLE_RATE, SpeechLog, espeak_available, mux, synthesize, write_srt


def log_of_two() -> SpeechLog:
    log = SpeechLog()
    log.say(1.0, "I cannot remove the stopper.", tag="cannot_remove_stopper", source="AML:x")
    log.say(4.0, "I will hold the bottle for you.", tag="hold_bottle", source="AEL:y")
    return log


def test_srt_times_and_order(tmp_path):
    path = write_srt(list(log_of_two()), tmp_path / "s.srt", time_scale=0.5)
    blocks = path.read_text().strip().split("\n\n")
    assert blocks[0].splitlines() == ["1", "00:00:00,500 --> 00:00:02,000", "I cannot remove the stopper."]
    assert blocks[1].splitlines()[1].startswith("00:00:02,000 --> ")


@pytest.mark.skipif(not espeak_available(), reason="espeak-ng not installed")
def test_audio_is_placed_at_the_utterance_times(tmp_path):
    wav = synthesize(list(log_of_two()), duration=8.0, path=tmp_path / "a.wav")
    with wave.open(str(wav)) as w:
        assert w.getframerate() == SAMPLE_RATE
        data = np.frombuffer(w.readframes(w.getnframes()), dtype=np.int16).astype(float)
    assert abs(data.size / SAMPLE_RATE - 8.0) < 0.01
    loud = np.abs(data) > 500
    first = np.argmax(loud) / SAMPLE_RATE
    assert 1.0 <= first < 1.4, first  # silence before the first utterance
    assert not loud[: SAMPLE_RATE].any()
    assert loud[int(4.0 * SAMPLE_RATE): int(5.0 * SAMPLE_RATE)].any()


def test_without_espeak_a_warning_and_no_track(tmp_path, monkeypatch):
    import assistbot.speech as speech

    monkeypatch.setattr(speech.shutil, "which", lambda _name: None)
    with pytest.warns(UserWarning, match="espeak-ng"):
        assert speech.synthesize(list(log_of_two()), 5.0, tmp_path / "a.wav") is None
    assert not (tmp_path / "a.wav").exists()


@pytest.mark.skipif(not espeak_available(), reason="espeak-ng not installed")
def test_mux_gives_a_video_with_an_audio_stream(tmp_path):
    import imageio.v2 as iio
    import imageio_ffmpeg

    video = tmp_path / "v.mp4"
    with iio.get_writer(video, fps=10, codec="libx264", macro_block_size=8) as w:
        for k in range(60):
            w.append_data(np.full((64, 96, 3), k * 4, dtype=np.uint8))
    wav = synthesize(list(log_of_two()), duration=6.0, path=tmp_path / "a.wav")
    out = mux(video, wav, tmp_path / "out.mp4")
    probe = subprocess.run([imageio_ffmpeg.get_ffmpeg_exe(), "-i", str(out)], capture_output=True, text=True).stderr
    assert "Audio: aac" in probe and "Video: h264" in probe
