"""The closed loop end to end: the seed's experiments as whole episodes, with VISION (cognition sees
only what the robot's head cameras show) and with the labelled ORACLE perception (ground truth,
which isolates physics + cognition + robot + human from vision).

The same seed must give the same decisions; `assistbot run` must write a playable video with the
utterances as sound. Slow: run by .ci/run and `make test-all`.
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
from assistbot.episode.touch import TouchMonitor
from assistbot.scenario import load_scenario

pytestmark = pytest.mark.slow
PERCEPTIONS = ["vision", "oracle"]


@lru_cache(maxsize=None)
def episode(name: str, perception: str):
    r = run_scenario(name, perception=perception, video=False)
    assert r.perception == perception
    return r


def in_order(seq: list[str], wanted: list[str]) -> bool:
    it = iter(seq)
    return all(any(x == w for x in it) for w in wanted)


def check_hands_kept_apart(r) -> None:
    """No robot geom went more than 1 cm into the person's (her hand taking the glass from the robot's
    included): the hands meet where there is room for both. Not yet where the person hands the glass to the
    robot (`Receive-object`): her fingers over its rim still meet the robot's palm, up to 2 cm deep
    (docs/measurements.md, "Each hand on the part the other leaves free")."""
    if "Receive-object" in [a for _, a in r.decisions]:
        return
    assert r.touched_person["depth"] <= TouchMonitor.DEEP, r.touched_person


def check_glass_handed_over(r) -> None:
    """The robot let go of the glass on the person's side only once the person held it, the first time;
    the hands kept apart."""
    check_hands_kept_apart(r)
    ev = [(e["event"], e.get("object")) for e in r.world_events]
    crossed = ev.index(("crossed_middle_line", "glass"), max(i for i, e in enumerate(ev) if e == ("robot_grasped", "glass")))
    assert ev[crossed + 1:crossed + 3] == [("human_grasped", "glass"), ("robot_released", "glass")], ev
    assert [a for _, a in r.decisions].count("Reach-full-glass-to-hand-over") == 1


def check_fig3_4(r) -> None:
    """SG grasp -> error; robot holds, human removes the stopper; A6 (never A7); fill; hand over; drink."""
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert in_order(decisions, ["Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                                "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]), decisions
    assert "Reach-turn-and-hand-over-glass" not in decisions  # A6 wins over A7: the open bottle is in the RWS
    spoken = {u["source"] for u in r.utterances}
    for action in ("Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                   "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"):
        assert f"AEL:{action}" in spoken, action
    events = [e["event"] for e in r.world_events]
    # the physical story: stopper off while the robot holds the bottle, glass turned, then filled, then drunk
    assert in_order(events, ["stopper_removed", "glass_turned", "glass_filled", "drink"]), events
    removed = next(e for e in r.world_events if e["event"] == "stopper_removed")
    assert removed["robot_holds"] == "bottle"
    check_glass_handed_over(r)
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10


def check_fig5(r) -> None:
    """A passive person: hold for the stopper, request the glass (not hand over the bottle), fill, hand over, drink."""
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert in_order(decisions, ["Grasp-hold-bottle-to-remove-cup", "Request-glass",
                                "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]), decisions
    assert "Hand-over-bottle" not in decisions[: decisions.index("Request-glass")]
    # the passive person starts nothing before the robot first speaks to them
    first_said = min(u["t"] for u in r.utterances if u["source"].startswith("AEL:"))
    starts = [e for e in r.human_events if e["kind"] == "start"]
    assert starts and all(e["t"] > first_said for e in starts)
    # the seed's fallback: the passive person shows nothing, so the robot's first step is taken without a cue;
    # the glass she then holds out when asked is answered by receiving it (episode.cues)
    cued = r.measures["cues"]["decisions"]
    assert [d["action"] for d in cued] == decisions and cued[0]["kind"] == "without cue", cued
    assert all(d["kind"] == "answered" for d in cued if d["action"] == "Receive-object"), cued
    events = [e["event"] for e in r.world_events]
    assert in_order(events, ["stopper_removed", "glass_filled", "drink"]), events
    check_glass_handed_over(r)
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10


@pytest.mark.parametrize("perception", PERCEPTIONS)
def test_paper_fig3_4_ends_with_the_drink_in_the_seeds_order(perception):
    check_fig3_4(episode("paper-fig3-4", perception))


@pytest.mark.parametrize("perception", PERCEPTIONS)
def test_paper_fig5_passive_user(perception):
    check_fig5(episode("paper-fig5", perception))


OTHER_SCENARIOS = ["active-closed-bottle-hws", "active-inverted-glass-hws", "active-open-bottle-hws",
                   "fig4-fill-and-hand-over", "slow-open-bottle-rws"]


#: where the robot has the empty glass and the open bottle (from the start, or once the person has
#: handed the glass over and holds out an open hand), it fills the glass rather than hand the bottle
#: over: the seed's Fig. 4 order, and no detour
FILLS_FIRST = {"fig4-fill-and-hand-over": ["Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"],
               "active-inverted-glass-hws": ["Request-glass", "Receive-object", "Reach-grasp-open-bottle-fill-glass",
                                             "Reach-full-glass-to-hand-over"]}


@pytest.mark.parametrize("name", OTHER_SCENARIOS)
def test_every_other_shipped_scenario_ends_with_the_drink_with_vision(name):
    r = episode(name, "vision")
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10
    check_hands_kept_apart(r)
    if name in FILLS_FIRST:
        assert in_order(decisions, FILLS_FIRST[name]) and "Hand-over-bottle" not in decisions, decisions


def test_the_shipped_scenarios_are_the_ones_tested():
    from assistbot.scenario import shipped_scenarios

    tested = {"paper-fig3-4", "paper-fig5"} | set(OTHER_SCENARIOS)
    assert {p.stem for p in shipped_scenarios()} == tested


def short(name: str, seconds: float):
    return dataclasses.replace(load_scenario(name), time_limit=seconds)


def test_same_seed_same_decisions_utterances_and_events_with_vision():
    a = run_scenario(short("paper-fig3-4", 20.0), perception="vision", video=False)
    b = run_scenario(short("paper-fig3-4", 20.0), perception="vision", video=False)
    assert a.decisions and a.decisions == b.decisions
    assert a.utterances == b.utterances
    assert a.world_events == b.world_events


def test_run_writes_a_playable_video_with_speech(tmp_path):
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
