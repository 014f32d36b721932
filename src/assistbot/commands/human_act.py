"""`assistbot human-act BEHAVIOUR`: the scripted human performs one behaviour in the physics; a short mp4.

Each behaviour has a demo scene (`assistbot.human.demos`): an arrangement, a robot stand-in
(a grey block that holds objects through a weld) where the behaviour needs a robot, and what
the human is asked.  The video is rendered offscreen from the scene camera `scene_cam` with a
caption line (time, behaviour, status) and written to OUT/BEHAVIOUR.mp4; `all` makes one per
behaviour.  The printed outcome is the physics' own.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from assistbot.errors import UserError

NAME = "human-act"
HELP = "the scripted human performs one behaviour (or all) in the physics; writes render/human-act/<behaviour>.mp4"
ORDER = 61


def _names() -> list[str]:
    from assistbot.human.demos import DEMOS

    return list(DEMOS)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("behaviour", help="a behaviour demo (grasp, grasp_side, hold_out, put_down, hand_to_robot, take_from_robot, "
                                     "request, point, pull_stopper, pull_stopper_alone, turn_glass, drink) or all")
    p.add_argument("--out", type=Path, default=Path("render/human-act"), help="output folder (default render/human-act)")
    p.add_argument("--size", default="480x360", help="WIDTHxHEIGHT of the video (default 480x360)")
    p.add_argument("--fps", type=int, default=25, help="frames per second of the video (default 25; at most 50)")
    p.add_argument("--seed", type=int, default=0, help="seed of the liquid layout and the human (default 0)")
    p.add_argument("--camera", default="scene_cam", help="camera to render (default scene_cam)")


def _parse(args: argparse.Namespace) -> tuple[list[str], int, int, int]:
    names = _names()
    if args.behaviour == "all":
        todo = names
    elif args.behaviour in names:
        todo = [args.behaviour]
    else:
        raise UserError("arguments", "behaviour", f"unknown behaviour {args.behaviour!r}; use one of {', '.join(names)} or all")
    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        raise UserError("arguments", "--size", f"expected WIDTHxHEIGHT, e.g. 480x360, got {args.size!r}") from None
    if not (64 <= width <= 1280 and 48 <= height <= 960):
        raise UserError("arguments", "--size", f"{width}x{height} is out of range (64x48 .. 1280x960)")
    if not 1 <= args.fps <= 50:
        raise UserError("arguments", "--fps", f"between 1 and 50 (the control rate), got {args.fps}")
    from assistbot.world import CAMERAS

    if args.camera not in CAMERAS:
        raise UserError("arguments", "--camera", f"unknown camera {args.camera!r}; use one of {', '.join(CAMERAS)}")
    return todo, width, height, args.fps


def _caption(frame, text: str, sub: str) -> None:
    import cv2

    h = frame.shape[0]
    frame[h - 46:] = (frame[h - 46:] * 0.35).astype(frame.dtype)   # a dark band under the caption
    for line, y in ((text, h - 28), (sub, h - 9)):
        cv2.putText(frame, line, (8, y), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (255, 240, 170), 1, cv2.LINE_AA)


def run(args: argparse.Namespace) -> int:
    todo, width, height, fps = _parse(args)
    from assistbot.human.demos import DEMOS, run_demo
    from assistbot.video import VideoWriter
    from assistbot.world.render import Renderer

    args.out.mkdir(parents=True, exist_ok=True)
    worst = 0
    for name in todo:
        demo = DEMOS[name]
        path = args.out / f"{name}.mp4"
        state = {"k": 0, "renderer": None}
        every = max(1, round(50 / fps))

        with VideoWriter(path, fps) as video:
            def on_tick(world, hc) -> None:
                if state["k"] % every == 0:
                    if state["renderer"] is None:
                        state["renderer"] = Renderer(world.model, width, height)
                    world.sync_liquid()
                    frame = state["renderer"].rgb(world.data, args.camera)
                    b = hc.current or (hc.done[-1] if hc.done else None)
                    status = "" if b is None else f"{b.name}: {b.status}"
                    _caption(frame, f"t = {world.time:4.1f} s   {status}", demo.caption)
                    video.append(frame)
                state["k"] += 1

            try:
                result = run_demo(name, seed=args.seed, on_tick=on_tick)
            finally:
                if state["renderer"] is not None:
                    state["renderer"].close()
        liquid = result.world.state().liquid
        extra = f"; liquid drunk {liquid.drunk}/{liquid.total}" if demo.behaviour == "drink" else ""
        print(f"{name}: {result.status} after {result.world.time:.1f} s ({result.reason}){extra}; wrote {path} "
              f"({video.frames} frames)")
        if result.status != demo.expect:
            print(f"{name}: expected {demo.expect}, got {result.status}")
            worst = 1
    return worst
