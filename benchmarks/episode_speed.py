"""Where an episode's wall time goes, against physics alone and against real time.

Run: .venv/bin/python benchmarks/episode_speed.py [--scenario paper-fig3-4] [--seconds S] [--video-seconds 10]
     [--set vision.pipelined=false]

1. The scenario without video to the drink (or for ``--seconds`` of simulated
   time): wall time split into physics, rendering (the head cameras: with
   pipelined vision, the default, the time the loop waited for the render
   thread, whose own drawing time is printed below the table), perception
   (vision's processing, or the oracle), cognition, robot (IK + primitives),
   human control.
2. Physics alone: the same arrangement stepped for the same simulated time
   with nothing else running.
3. The same scenario with video for ``--video-seconds``: cost of a video
   frame (render scene + compose + encode) and of the audio track.
Prints the ratio of the whole episode to physics alone (goal <= 3) and the
real-time factor (goal >= 2x faster than real time).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "osmesa")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="paper-fig3-4")
    ap.add_argument("--seconds", type=float, default=None,
                    help="simulated seconds (default: the scenario's time limit; the episode ends earlier at the drink)")
    ap.add_argument("--video-seconds", type=float, default=10.0)
    ap.add_argument("--perception", choices=["vision", "oracle"], default="vision")
    ap.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                    help="a parameter override as for assistbot run, e.g. vision.pipelined=false")
    args = ap.parse_args()

    from assistbot.commands.run import parse_sets
    from assistbot.episode import run_scenario
    from assistbot.episode.builder import build_episode
    from assistbot.scenario import load_scenario
    from assistbot.world import build_world

    sc = load_scenario(args.scenario)
    if args.seconds is not None:
        sc.time_limit = args.seconds
    t0 = time.perf_counter()
    overrides = parse_sets(args.set)
    ep = build_episode(sc, perception=args.perception, overrides=overrides)
    setup = time.perf_counter() - t0
    t0 = time.perf_counter()
    result = ep.run()
    total = time.perf_counter() - t0
    sim = result.time

    world = build_world(sc.objects, seed=sc.seed)
    n = int(round(sim / world.model.opt.timestep))
    per_tick = max(1, int(round(0.02 / world.model.opt.timestep)))   # stepped as the episode steps it: a control tick a call
    t0 = time.perf_counter()
    for _ in range(n // per_tick):
        world.step(per_tick)
    physics_alone = time.perf_counter() - t0

    print(f"scenario {sc.name}, perception {args.perception}: {sim:.1f} simulated s ({result.end_reason}), set-up {setup:.2f} s")
    print(f"{'part':<14}{'wall s':>9}{'share':>8}{'ms per sim s':>15}")
    for part, w in sorted(result.wall.items(), key=lambda kv: -kv[1]):
        if part == "video":
            continue
        print(f"{part:<14}{w:>9.2f}{w / total:>8.0%}{1000 * w / sim:>15.1f}")
    other = total - sum(v for k, v in result.wall.items() if k != "video")
    print(f"{'loop/other':<14}{other:>9.2f}{other / total:>8.0%}{1000 * other / sim:>15.1f}")
    print(f"{'whole episode':<14}{total:>9.2f}")
    from assistbot.episode.vision_perception import VisionPerception

    if isinstance(ep.perception, VisionPerception) and ep.perception.pipelined:
        drawn = ep.perception.drawn_seconds
        print(f"(the head cameras' pictures took {drawn:.2f} s on the render thread, {1000 * drawn / sim:.1f} ms per sim s; "
              f"'rendering' above is what the loop waited for them)")
    print(f"physics alone: {physics_alone:.2f} s for the same {sim:.1f} simulated s ({sim / physics_alone:.1f}x real time)")
    print(f"episode / physics alone: {total / physics_alone:.2f} (goal <= 3)")
    print(f"real-time factor: {sim / total:.2f}x faster than real time (goal >= 2)")

    sc_v = load_scenario(args.scenario)
    sc_v.time_limit = args.video_seconds
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        r = run_scenario(sc_v, out=Path(tmp), perception=args.perception, overrides=overrides, video=True)
        with_video = time.perf_counter() - t0
        frames = round(r.time * 10)
        print(f"with video: {with_video:.1f} s for {r.time:.1f} simulated s; video frames (render + compose + encode) "
              f"{r.wall['video']:.2f} s = {1000 * r.wall['video'] / max(1, frames):.0f} ms per frame; "
              f"audio, figures and files {with_video - sum(r.wall.values()):.1f} s")


if __name__ == "__main__":
    from assistbot.errors import UserError

    try:
        main()
    except UserError as exc:  # a bad --set or scenario: one line, exit 2, as the CLI does
        print(exc.line(), file=sys.stderr)
        sys.exit(2)
