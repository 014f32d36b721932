"""`assistbot act ARRANGEMENT ACTION`: run one robot primitive in the physics and write a short mp4.

ARRANGEMENT is "inverted" / "upright" (the glass in the RWS) for now; the
scenario loader takes over once assistbot.world is in. The target x, y comes
from ground truth here (a development tool, not the closed loop).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from assistbot.errors import UserError

NAME = "act"
HELP = "run one robot action's motion primitive from an arrangement and write a short video"
ORDER = 60


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("arrangement", help="inverted | upright (glass in the RWS)")
    p.add_argument("action", help="an AEL action name, e.g. Reach-and-turn-glass")
    p.add_argument("--glass", default="0.20,-0.12", help="glass table x,y in m (default 0.20,-0.12)")
    p.add_argument("--out", type=Path, default=Path("render/act"), help="output folder")
    p.add_argument("--seconds", type=float, default=20.0)


def run(args: argparse.Namespace) -> int:
    os.environ.setdefault("MUJOCO_GL", "osmesa")  # before mujoco is imported
    from assistbot.robot.actions import ACTION_PRIMITIVES

    if args.arrangement not in ("inverted", "upright"):
        raise UserError("arguments", "arrangement", "use inverted or upright")
    if args.action not in ACTION_PRIMITIVES:
        raise UserError("arguments", "action", f"unknown action; use one of {', '.join(ACTION_PRIMITIVES)}")
    entry = ACTION_PRIMITIVES[args.action]
    if entry is None:
        print(f"{args.action}: does not move the arm")
        return 0
    try:
        gx, gy = (float(v) for v in args.glass.split(","))
    except ValueError:
        raise UserError("arguments", "--glass", "expected x,y in metres, e.g. 0.20,-0.12") from None
    import imageio.v2 as imageio
    import mujoco

    from assistbot.robot.controller import RobotController
    from assistbot.robot.primitives import Status
    from assistbot.robot.sim import CONTROL_DT, Bench, Placement

    bench = Bench(Placement(glass=(gx, gy), bottle=(0.25, 0.32), glass_inverted=args.arrangement == "inverted"))
    robot = RobotController(bench.model, bench.data)
    cls, obj = entry
    prim = cls(robot, "glass" if obj == "held_out" else obj)
    target = lambda: tuple(bench.body_pos(prim.object or "glass")[:2])  # noqa: E731
    renderer = mujoco.Renderer(bench.model, 240, 320)
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / f"{args.action}.mp4"
    try:
        with imageio.get_writer(path, fps=25) as w:
            prim.start(target())
            for k in range(int(args.seconds / CONTROL_DT)):
                pr = prim.tick(CONTROL_DT, target())
                bench.step()
                if k % 2 == 0:
                    renderer.update_scene(bench.data, "scene_cam")
                    w.append_data(renderer.render())
                if pr.status is not Status.RUNNING:
                    break
    finally:
        renderer.close()
    print(f"{args.action}: {pr.status.value} after {pr.t:.1f} s {pr.reason}; wrote {path}")
    return 0
