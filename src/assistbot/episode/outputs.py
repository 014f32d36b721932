"""What a run leaves in its folder: log.jsonl, summary.json, subtitles.srt, the seed-style figures, video.mp4.

A run folder is complete or says it is not. `claim` writes the marker PARTIAL first, then removes an
earlier run's files; the video is written frame by frame during the run (and gets its audio track at
the end); log, subtitles, figures and the field recording follow when the episode ends, then
summary.json, then the inspector page built from them, each file to a temporary name and renamed into
place; then the marker goes. A run killed at any moment leaves the earlier run's complete files
(killed before `claim`) or a folder with PARTIAL in it.
"""

from __future__ import annotations

import json
import os
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from assistbot.cognition.architecture import LAYERS_SHOWN
from assistbot.cognition.figures import FIGURES
from assistbot.episode.runner import Episode, EpisodeResult
from assistbot.interfaces import FieldAgent
from assistbot.speech import espeak_available, mux, synthesize, write_srt
from assistbot.video import VideoWriter, compose_frame

VIDEO_FPS = 10
FRAME_EVERY = 1.0 / VIDEO_FPS  # simulated seconds per frame: the video plays in real time
PANEL_NAMES = {"CSGL_past": "CSGL past", "CSGL_present": "CSGL present", "CSGL_future": "CSGL future"}


#: the marker of a run that has not finished (running, killed or interrupted): its files are incomplete
PARTIAL = "PARTIAL"
SUMMARY = "summary.json"
#: every file a run writes (with the temporaries of the audio track), so that a new run leaves none of an earlier one
FIELDS = "fields.npz"
INSPECTOR = "inspect.html"
RUN_FILES = ("video.mp4", "video.wav", "video.muxed.mp4", "log.jsonl", "subtitles.srt", *FIGURES, FIELDS, SUMMARY, INSPECTOR)


def earlier_run(out: Path) -> str | None:
    """What shows that ``out`` holds a run (its summary or its PARTIAL marker), or None."""
    for name in (SUMMARY, PARTIAL):
        if (out / name).exists():
            return name
    return None


def claim(out: Path) -> None:
    """Make ``out`` the folder of a run starting now: the PARTIAL marker first, then an earlier run's files go."""
    out.mkdir(parents=True, exist_ok=True)
    replace_text(out / PARTIAL, f"this run has not finished: started {time.strftime('%Y-%m-%d %H:%M:%S')}, "
                                f"process {os.getpid()}; the files here are incomplete\n")
    for name in RUN_FILES:
        (out / name).unlink(missing_ok=True)
        (out / f"{name}.tmp").unlink(missing_ok=True)


def finish(out: Path) -> None:
    """The run's files are all in place (summary.json last): the folder is complete."""
    (out / PARTIAL).unlink(missing_ok=True)


def replace_text(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` whole or not at all: to a temporary name, then renamed into place."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)
    return path


class VideoRecorder:
    """Renders the scene camera and the robot's left camera (with the vision overlay) each frame."""

    def __init__(self, episode: Episode, path: Path, size: tuple[int, int] = (1280, 720)) -> None:
        from assistbot.world.render import Renderer

        self.path = path
        self.size = size
        self.renderer = Renderer(episode.world.model, width=640, height=480)
        self.writer = VideoWriter(path, fps=VIDEO_FPS)
        self.header_base = f"{episode.scenario.name}  |  seed {episode.seed}  |  {episode.perception.label}"

    def __call__(self, ep: Episode) -> None:
        ep.world.sync_liquid()
        scene = self.renderer.rgb(ep.world.data, "scene_cam")
        camera = ep.perception.overlay()
        if camera is None:
            camera = self.renderer.rgb(ep.world.data, "head_cam_left")
        layers = []
        if isinstance(ep.agent, FieldAgent):
            layers = [(PANEL_NAMES.get(L, L), ep.agent.net.activities(L)) for L in LAYERS_SHOWN]
        now = ep.world.time
        # the robot's reasoning while it is fresh, else what it says it is doing for as long as it does it
        recent = [u for u in ep.speech.utterances if now - u.t < 2.5]
        if not recent and ep.actor.action:
            recent = [u for u in ep.speech.utterances if u.source == f"AEL:{ep.actor.action}"]
        subtitle = recent[-1].text if recent else ""
        action = ep.actor.action or "-"
        header = f"{self.header_base}  |  t = {ep.world.time:6.1f} s  |  robot: {action}"
        self.writer.append(compose_frame(scene, camera, layers, subtitle=subtitle, header=header, size=self.size))

    def close(self) -> None:
        self.writer.close()
        self.renderer.close()


def write_log(episode: Episode, path: Path) -> Path:
    rows = sorted(episode.log, key=lambda r: r["t"])
    return replace_text(path, "".join(json.dumps(row, default=_jsonable) + "\n" for row in rows))


def _jsonable(v):
    if isinstance(v, (np.floating, np.integer)):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    return str(v)


def write_summary(result: EpisodeResult, path: Path, extra: dict | None = None) -> Path:
    data = result.summary()
    if extra:
        data.update(extra)
    return replace_text(path, json.dumps(data, indent=2, default=_jsonable) + "\n")


def write_figures(episode: Episode, recorder, out: Path) -> list[Path]:
    """The seed's figures (ASL/AEL input and activity, CSGL panels) from the run's field recording; none
    for an agent without fields."""
    from assistbot.cognition.figures import write_figures as cognition_figures

    if recorder is None or not isinstance(episode.agent, FieldAgent):
        return []
    label = f"{episode.scenario.name}" + (" (ORACLE perception)" if episode.perception.name == "oracle" else "")
    return cognition_figures(label, recorder, episode.agent.decisions(), out)


def write_fields(episode: Episode, recorder, path: Path) -> Path | None:
    """The field recording for the inspector (`assistbot.inspector`): per layer, the activity u over the whole
    field and u and the input S at each item's centre, and for the layers recorded with them each incoming
    coupling's part of S there ("ASL.in.OL->ASL"); float16 at the recorder's rate; none without fields."""
    if recorder is None or not isinstance(episode.agent, FieldAgent):
        return None
    spec = episode.agent.net.spec
    arrays: dict[str, Any] = {"t": recorder.times.astype(np.float32)}
    u, s, parts = recorder.u, recorder.s, recorder.coupling_items
    for layer, by_coupling in parts.items():
        for name, part in by_coupling.items():
            arrays[f"{layer}.in.{name}"] = part.astype(np.float16)
    for layer in recorder.fields:
        idx = spec.fields[layer].item_indices
        arrays[f"{layer}.u"] = u[layer].astype(np.float16)
        arrays[f"{layer}.u_items"] = u[layer][:, idx].astype(np.float16)
        arrays[f"{layer}.s_items"] = s[layer][:, idx].astype(np.float16)
        arrays[f"{layer}.items"] = np.array(spec.fields[layer].items)
        arrays[f"{layer}.item_idx"] = np.asarray(idx, np.int32)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as f:      # a file object: numpy adds no suffix
        np.savez_compressed(f, **arrays)
    os.replace(tmp, path)
    return path


def add_audio(episode: Episode, video: Path, duration: float) -> bool:
    """Speak the utterances under the video; False (and one warning) without espeak-ng."""
    if not espeak_available():
        warnings.warn("espeak-ng not found: video.mp4 is silent (apt-get install espeak-ng)", stacklevel=2)
        return False
    wav = synthesize(list(episode.speech), duration, video.with_suffix(".wav"))
    if wav is None:     # espeak-ng went away between the check and the synthesis
        return False
    tmp = video.with_name("video.muxed.mp4")
    mux(video, wav, tmp)
    tmp.replace(video)
    wav.unlink()
    return True


def write_srt_for(episode: Episode, path: Path) -> Path:
    tmp = write_srt(list(episode.speech), path.with_name(path.name + ".tmp"))
    os.replace(tmp, path)
    return path
