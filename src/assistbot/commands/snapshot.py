"""`assistbot snapshot`: PNG stills of arrangements (by default the seed paper's three)."""

from __future__ import annotations

NAME = "snapshot"
HELP = "write PNG stills of an arrangement (default: the paper's Fig. 3-5 arrangements) to render/snapshots/"
ORDER = 21


def add_arguments(parser) -> None:
    from assistbot.world.cli_support import add_arrangement_arguments

    add_arrangement_arguments(parser)
    parser.add_argument("--camera", action="append", help="camera name (repeatable; default scene_cam and head_cam_left)")
    parser.add_argument("--out", default="render/snapshots", help="output folder (default render/snapshots)")
    parser.add_argument("--settle", type=float, default=0.5, help="simulated seconds before the picture (default 0.5)")
    parser.add_argument("--size", default="640x480", help="WIDTHxHEIGHT (default 640x480)")


def run(args) -> int:
    from pathlib import Path

    from assistbot.errors import UserError
    from assistbot.world import CAMERAS, PAPER_ARRANGEMENTS, build_world
    from assistbot.world.cli_support import arrangement_from_args, write_png

    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        raise UserError("arguments", "--size", f"expected WIDTHxHEIGHT, got {args.size!r}") from None
    cameras = args.camera or ["scene_cam", "head_cam_left"]
    for cam in cameras:
        if cam not in CAMERAS:
            raise UserError("arguments", "--camera", f"unknown camera {cam!r}; use one of {', '.join(CAMERAS)}")
    arr = arrangement_from_args(args)
    todo = {arr.label(): arr} if arr is not None else {f"{k}_{a.label()}": a for k, a in PAPER_ARRANGEMENTS.items()}
    out = Path(args.out)
    for name, a in todo.items():
        world = build_world(a)
        world.step(int(round(args.settle / world.model.opt.timestep)))
        for cam in cameras:
            path = write_png(world, out / f"{name}_{cam}.png", cam, width, height)
            print(path)
    return 0
