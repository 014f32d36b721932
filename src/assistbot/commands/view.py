"""`assistbot view`: the scene for an arrangement in the interactive viewer, or a PNG without a display."""

from __future__ import annotations

NAME = "view"
HELP = "open the scene for a scenario arrangement in the MuJoCo viewer (a PNG from the scene camera without a display)"
ORDER = 20


def add_arguments(parser) -> None:
    from assistbot.world.cli_support import add_arrangement_arguments

    add_arrangement_arguments(parser)
    parser.add_argument("--png", action="store_true", help="write a still PNG even where a display exists")
    parser.add_argument("--out", default="render/view.png", help="PNG path when no viewer opens (default render/view.png)")


def run(args) -> int:
    import os
    from pathlib import Path

    from assistbot.world import PAPER_ARRANGEMENTS, build_world
    from assistbot.world.cli_support import arrangement_from_args, write_png

    arr = arrangement_from_args(args, default=PAPER_ARRANGEMENTS["fig3"])
    world = build_world(arr)
    if not args.png and (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        import mujoco.viewer

        mujoco.viewer.launch(world.model, world.data)
        return 0
    world.step(250)
    print(write_png(world, Path(args.out)))
    return 0
