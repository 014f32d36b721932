"""`assistbot act ARRANGEMENT ACTION`: run one robot action's primitive in the world and write a short mp4.

ARRANGEMENT is a paper arrangement (fig3, fig4, fig5), a scenario YAML file (its
``objects:``), or ``custom`` with --bottle/--glass (ZONE:STATE[@x,y]). The scripted
human (passive) stands by and does its part where the action needs one: takes what the
robot holds out, pulls the stopper of the bottle the robot holds, or holds an object out
near the middle line for Receive-object. Targets come from ground truth here (a development
tool, not the closed loop).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from assistbot import catalogue
from assistbot.errors import UserError

NAME = "act"
HELP = "run one robot action's motion primitive from an arrangement and write a short video"
ORDER = 60

#: the human's grasp site when it holds an object out for Receive-object (the real hold-out is out of the robot's reach)
STAND_IN_HOLD_OUT = (-0.03, -0.05)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("arrangement", help="fig3 | fig4 | fig5 | SCENARIO.yaml | custom (with --bottle and --glass)")
    p.add_argument("action", help="an AEL action name, e.g. Reach-and-turn-glass")
    for name, states in catalogue.STATES.items():
        p.add_argument(f"--{name}", metavar="ZONE:STATE[@x,y]", help=f"with custom: the {name}, e.g. RWS:{states[0]}@0.2,0.1")
    p.add_argument("--out", type=Path, default=Path("render/act"), help="output folder")
    p.add_argument("--seconds", type=float, default=45.0, help="simulated time limit")


def _arrangement(args):
    from assistbot.world import PAPER_ARRANGEMENTS, Arrangement
    from assistbot.world.cli_support import arrangement_from_args

    if args.arrangement in PAPER_ARRANGEMENTS:
        return PAPER_ARRANGEMENTS[args.arrangement]
    if args.arrangement == "custom":
        given = [getattr(args, name) for name in catalogue.TASK_OBJECTS]
        if not all(given):
            options = [f"--{name}" for name in catalogue.TASK_OBJECTS]
            raise UserError("arguments", "/".join(options), f"custom needs all of {', '.join(options)}")
        return Arrangement.from_options(*given)
    ns = argparse.Namespace(scenario=args.arrangement, **{name: None for name in catalogue.TASK_OBJECTS})
    return arrangement_from_args(ns)


def run(args: argparse.Namespace) -> int:
    os.environ.setdefault("MUJOCO_GL", "osmesa")  # before mujoco is imported
    from assistbot.robot.actions import ACTION_PRIMITIVES

    if args.action not in ACTION_PRIMITIVES:
        raise UserError("arguments", "action", f"unknown action; use one of {', '.join(ACTION_PRIMITIVES)}")
    arrangement = _arrangement(args)
    entry = ACTION_PRIMITIVES[args.action]
    if entry is None:
        print(f"{args.action}: does not move the arm")
        return 0
    import imageio.v2 as imageio
    import numpy as np

    from assistbot.human.behaviours import HOLD_OUT_BASE_Z
    from assistbot.human.controller import HumanController
    from assistbot.robot.controller import RobotController
    from assistbot.robot.sim import body_xy, run as run_primitive
    from assistbot.world import build_world
    from assistbot.world.render import Renderer

    world = build_world(arrangement, seed=0)
    robot = RobotController(world.model, world.data)
    human = HumanController(world, "passive")
    cls, obj = entry
    hand = world.model.site("human_r_grasp").id
    prim = cls(robot, obj,
               human_holds=lambda: world.human_holding() is not None,
               locate=lambda name: body_xy(world, name)(),
               stopper_removed=lambda: not world.data.eq_active[world.eq_stopper])
    # an object the robot must take from the human's hand: Receive-object, or the bottle to hold for the stopper
    held = None
    if obj == "held_out":
        held = "bottle" if arrangement.bottle.zone == "HWS" else "glass"
        if getattr(arrangement, held).zone != "HWS":
            raise UserError("arguments", "arrangement", "Receive-object needs the bottle or the glass in the HWS")
        target = lambda: tuple(world.data.site_xpos[hand][:2])  # noqa: E731
    else:
        if getattr(arrangement, obj).zone == "HWS":
            if args.action != "Grasp-hold-bottle-to-remove-cup":
                raise UserError("arguments", "arrangement", f"{args.action} needs the {obj} in the RWS")
            held = obj
        target = body_xy(world, obj)
    if held is not None:
        human.start("grasp", object=held, grip="ag", lift=True)

    state = {"held_out": False}

    def human_part(t: float) -> None:
        phase = prim.progress.phase
        started = {b.name for b in human.done}
        if human.current is None and phase.startswith("wait for the human to take") and "take_from_robot" not in started:
            human.start("take_from_robot", object=prim.object)
        elif human.current is None and phase.startswith("hold steady for the stopper") and "pull_stopper" not in started:
            human.start("pull_stopper")
        if held is not None and world.human_holding() == held and world.robot_holding() == held:
            world.set_hand_posture("open")  # the human lets go once the robot holds it
        human.tick(t)

    renderer = Renderer(world.model, 320, 240)
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / f"{args.action}.mp4"
    frames = {"k": 0}
    try:
        with imageio.get_writer(path, fps=25) as w:
            def tick(t: float) -> None:
                human_part(t)
                if frames["k"] % 2 == 0:
                    world.sync_liquid()
                    w.append_data(renderer.rgb(world.data, "scene_cam"))
                frames["k"] += 1

            if held is not None:  # the human first grasps the object and holds it out near the middle line
                while world.time < 15.0 and not state["held_out"]:
                    tick(world.time)
                    world.step(10)
                    if human.current is None and world.human_holding():
                        above = 0.17 if world.human_holding() == "bottle" else 0.085
                        p = np.array([*STAND_IN_HOLD_OUT, HOLD_OUT_BASE_Z + above])
                        d = human.arm.move_to(p, human.arm.hand_pose()[1], t=world.time)
                        for _ in range(int((d + 0.5) / 0.02)):
                            tick(world.time)
                            world.step(10)
                        state["held_out"] = True
            pr, safety = run_primitive(world, prim, target, seconds=args.seconds, each_tick=tick)
    finally:
        renderer.close()
    print(f"{args.action}: {pr.status.value} after {pr.t:.1f} s {pr.reason}; wrote {path}")
    print(world.state().summary())
    if os.environ.get("ASSISTBOT_ACT_DEBUG"):
        for e in human.log:
            print(e)
    print(f"safety: {100 * safety.human:.0f} cm from the human's head/torso, hand reached x = {safety.min_x:.3f} m, "
          f"joint limits {'kept' if safety.limits else 'exceeded at ' + safety.worst_joint}")
    return 0
