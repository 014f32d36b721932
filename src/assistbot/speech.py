"""The robot's voice: utterances on a timed log, as subtitles, and as audio.

Utterances are logged in simulated time. ``write_srt`` makes subtitles;
``synthesize`` renders each utterance with espeak-ng and mixes them into one
WAV track at their times; ``mux`` puts that track under a video with the
ffmpeg that imageio-ffmpeg ships. Without espeak-ng, ``synthesize`` returns
None and warns once: the video stays silent, the run does not fail.
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
import wave
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

SAMPLE_RATE = 22050  # espeak-ng's native rate


@dataclass(frozen=True)
class Utterance:
    t: float  # simulated seconds
    text: str
    tag: str = ""  # semantic tag the human can react to
    source: str = ""  # e.g. "AEL:Communicate-Error"

    def to_dict(self) -> dict:
        return asdict(self)


class SpeechLog:
    """Utterances in the order they were spoken."""

    def __init__(self) -> None:
        self.utterances: list[Utterance] = []

    def say(self, t: float, text: str, tag: str = "", source: str = "") -> Utterance:
        u = Utterance(float(t), str(text), str(tag), str(source))
        self.utterances.append(u)
        return u

    def __len__(self) -> int:
        return len(self.utterances)

    def __iter__(self):
        return iter(self.utterances)


def reading_time(text: str) -> float:
    """How long a subtitle stays up: about 2.5 words per second, at least 1.5 s."""
    return max(1.5, len(text.split()) / 2.5)


def _srt_time(t: float) -> str:
    ms = int(round(max(t, 0.0) * 1000))
    h, ms = divmod(ms, 3_600_000)
    m, ms = divmod(ms, 60_000)
    s, ms = divmod(ms, 1000)
    return f"{h:02d}:{m:02d}:{s:02d},{ms:03d}"


def write_srt(utterances: list[Utterance], path: str | Path, time_scale: float = 1.0) -> Path:
    """Subtitles; an utterance ends when the next begins or after its reading time.

    ``time_scale`` maps simulated seconds to video seconds (a video played
    faster than real time divides by its speed-up).
    """
    path = Path(path)
    lines = []
    for i, u in enumerate(utterances):
        start = u.t * time_scale
        end = start + reading_time(u.text)
        if i + 1 < len(utterances):
            end = min(end, max(utterances[i + 1].t * time_scale, start + 0.3))
        lines += [str(i + 1), f"{_srt_time(start)} --> {_srt_time(end)}", u.text, ""]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def espeak_available() -> bool:
    return shutil.which("espeak-ng") is not None


def _speak_to_array(text: str, workdir: Path) -> np.ndarray:
    wav = workdir / "u.wav"
    subprocess.run(["espeak-ng", "-v", "en", "-s", "165", "-w", str(wav), text], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with wave.open(str(wav), "rb") as w:
        if w.getframerate() != SAMPLE_RATE or w.getsampwidth() != 2:
            raise RuntimeError(f"espeak-ng wrote {w.getframerate()} Hz / {8 * w.getsampwidth()} bit; expected {SAMPLE_RATE} Hz / 16 bit")
        data = np.frombuffer(w.readframes(w.getnframes()), dtype=np.int16)
        if w.getnchannels() > 1:
            data = data.reshape(-1, w.getnchannels())[:, 0]
    return data.astype(np.float32)


def synthesize(utterances: list[Utterance], duration: float, path: str | Path, time_scale: float = 1.0) -> Path | None:
    """One mono WAV of ``duration`` video seconds with every utterance at its time; None without espeak-ng."""
    if not espeak_available():
        import warnings

        warnings.warn("espeak-ng not found: the video will be silent (apt-get install espeak-ng)", stacklevel=2)
        return None
    track = np.zeros(int(np.ceil(duration * SAMPLE_RATE)) + 1, dtype=np.float32)
    with tempfile.TemporaryDirectory() as tmp:
        for u in utterances:
            clip = _speak_to_array(u.text, Path(tmp))
            start = int(u.t * time_scale * SAMPLE_RATE)
            if start >= track.size:
                continue
            end = min(track.size, start + clip.size)
            track[start:end] += clip[: end - start]
    peak = float(np.max(np.abs(track))) if track.size else 0.0
    if peak > 32767:  # overlapping utterances: scale rather than clip
        track *= 32767 / peak
    path = Path(path)
    with wave.open(str(path), "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(SAMPLE_RATE)
        w.writeframes(track.astype(np.int16).tobytes())
    return path


def mux(video: str | Path, audio: str | Path, out: str | Path) -> Path:
    """Video stream copied, audio encoded as AAC, into ``out`` (browser-playable MP4)."""
    import imageio_ffmpeg

    out = Path(out)
    cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-loglevel", "error", "-i", str(video), "-i", str(audio),
           "-map", "0:v:0", "-map", "1:a:0", "-c:v", "copy", "-c:a", "aac", "-b:a", "96k",
           "-movflags", "+faststart", str(out)]
    subprocess.run(cmd, check=True)
    return out
