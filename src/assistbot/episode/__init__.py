"""The closed loop: one scenario run in simulated time, with its log, summary, figures and video.

``run_scenario("paper-fig3-4", out="render/paper-fig3-4")`` runs an episode and
writes its outputs; `Episode` is the loop itself (see `runner`), `build_episode` makes its parts
from a scenario (see `builder`; the parts' interfaces are in `assistbot.interfaces`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from assistbot.scenario import Scenario, load_scenario


def run_scenario(spec: str | Path | Scenario, out: str | Path | None = None, perception: str = "vision",
                 seed: int | None = None, overrides: dict[str, Any] | None = None, video: bool = True,
                 progress: bool = False, record_truth: bool = False, learn: Path | None = None):
    """Run one episode; with ``out``, write log.jsonl, summary.json, subtitles.srt, figures and video.mp4 there
    (replacing an earlier run's; `assistbot.episode.outputs` says in which order, and how a killed run shows).
    ``learn``: a weights file the field architecture starts from (if it exists) and writes what it learnt back
    to (`assistbot.cognition.learning`; learning is switched on for this episode)."""
    from assistbot.cognition import learning
    from assistbot.cognition.architecture import SPOKEN_LAYERS
    from assistbot.episode.builder import build_episode
    from assistbot.episode.outputs import (
        FIELDS,
        FRAME_EVERY,
        VideoRecorder,
        add_audio,
        claim,
        finish,
        write_fields,
        write_figures,
        write_log,
        write_srt_for,
        write_summary,
    )
    from assistbot.inspector import write_inspector
    from assistbot.interfaces import FieldAgent

    scenario = spec if isinstance(spec, Scenario) else load_scenario(spec)
    if learn is not None:
        learning.check_learner(scenario.agent)
        # a rate the scenario file or the caller sets stays; without one, learning's own
        overrides = {**(overrides or {}), **learning.learning_overrides({**scenario.overrides, **(overrides or {})})}
    ep = build_episode(scenario, perception=perception, seed=seed, overrides=overrides,
                       frame_every=FRAME_EVERY if (video and out is not None) else None, record_truth=record_truth)
    episodes = learning.load_into(ep.agent, learn) if learn is not None else 0
    out_dir = Path(out) if out is not None else None
    rec_video = None
    if out_dir is not None:
        claim(out_dir)
        if video:
            rec_video = VideoRecorder(ep, out_dir / "video.mp4")
            ep.on_frame = rec_video
    # 10 Hz, with each coupling's part of the input for the layers that speak (the inspector plots them)
    recorder = (ep.agent.record(every=20, couplings=SPOKEN_LAYERS)
                if out_dir is not None and isinstance(ep.agent, FieldAgent) else None)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=round(scenario.time_limit, 1), unit="sim s", desc=scenario.name, leave=True, mininterval=1.0,
                   bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.0f} sim s [{elapsed}<{remaining}]")

        def tick(t: float) -> None:
            bar.n = round(min(t, scenario.time_limit), 1)
            if int(t * 50) % 25 == 0:
                bar.refresh()
    else:
        tick = None
    try:
        result = ep.run(progress=tick)
    finally:
        if bar is not None:
            bar.close()
        if rec_video is not None:
            rec_video.close()
        ep.perception.close()
    if learn is not None:
        learning.write_weights(learn, ep.agent.learned_weights(), episodes + 1)   # type: ignore[attr-defined]
    if out_dir is not None:
        write_log(ep, out_dir / "log.jsonl")
        write_srt_for(ep, out_dir / "subtitles.srt")
        audio = False
        if rec_video is not None and rec_video.writer.frames:
            audio = add_audio(ep, out_dir / "video.mp4", rec_video.writer.frames / rec_video.writer.fps)
        figures = [str(p) for p in write_figures(ep, recorder, out_dir)]
        write_fields(ep, recorder, out_dir / FIELDS)
        extra: dict[str, Any] = {"figures": figures, "video_has_audio": audio}
        if learn is not None:
            extra["learned_weights"] = {"file": str(learn), "episodes": episodes + 1}
        write_summary(result, out_dir / "summary.json", extra)
        write_inspector(out_dir)
        finish(out_dir)
    return result
