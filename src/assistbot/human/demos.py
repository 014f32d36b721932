"""One short physical scene per behaviour of the human, for videos (`assistbot human-act`) and tests.

Each `Demo` names an arrangement, what the robot stand-in (`human.standin`) does, and what the
human is asked to do (a behaviour started directly, a heard utterance, or a script).  `run_demo`
builds the world, runs the controller with the stand-in until the human's last behaviour has
ended (plus `tail` seconds) or the time limit, and calls ``on_tick(world, controller)`` after
every control tick (e.g. to render a frame).  Outcomes are the physics' own: `run_demo` reports
them, it does not decide them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from assistbot.human.controller import HumanController
from assistbot.human.script import parse_human
from assistbot.human.standin import StandIn, build_world_with_standin
from assistbot.interfaces import Status
from assistbot.world import Arrangement, World, layout


@dataclass(frozen=True)
class Demo:
    """A behaviour shown from one arrangement.

    objects     the arrangement (as in a scenario's objects: mapping)
    behaviour   the behaviour whose outcome the demo shows
    start       (name, args) started at time 0, or None when `script`/`say` drives the human
    script      a human.script (list of steps) for the controller
    robot       what the stand-in does: None, "take" (takes what the human holds out),
                "hold_bottle_out" (holds the bottle out at the middle line for the stopper),
                "offer_glass" (brings the glass to the middle line, lets go when the human holds it),
                "open_hand" (holds its open hand out and takes what it is given)
    say         (time, tag): an utterance the human hears
    limit       s of simulated time at most
    expect      the outcome the physics should give (failed for the stopper pulled alone)
    """

    objects: dict
    behaviour: str
    start: tuple[str, dict] | None = None
    script: list = field(default_factory=list)
    robot: str | None = None
    say: tuple[float, str] | None = None
    profile: str = "passive"
    limit: float = 25.0
    caption: str = ""
    expect: Status = Status.SUCCEEDED    # the outcome the physics should give


_B_HWS = {"zone": "HWS", "state": "closed"}
_B_RWS = {"zone": "RWS", "state": "open"}
_G_RWS = {"zone": "RWS", "state": "empty"}

DEMOS: dict[str, Demo] = {
    "grasp": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "grasp", ("grasp", {"object": "bottle", "grip": "ag"}),
                  caption="grasps the bottle from above (AG)"),
    "grasp_side": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "grasp", ("grasp", {"object": "bottle", "grip": "sg"}),
                       caption="grasps the bottle from the side (SG)"),
    "hold_out": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "grasp",
                     ("grasp", {"object": "bottle", "grip": "ag", "hold_out": True}),
                     caption="grasps the bottle and holds it out toward the robot"),
    "put_down": Demo({"bottle": _B_RWS, "glass": {"zone": "HWS", "state": "empty", "position": [-0.28, 0.05]}}, "put_down",
                     script=[{"do": "grasp", "object": "glass", "grip": "sg"},
                             {"do": "put_down", "object": "glass", "at": [-0.20, -0.15]}],
                     caption="picks the glass up and puts it down elsewhere in the HWS"),
    "hand_to_robot": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "hand_to_robot",
                          ("hand_to_robot", {"object": "bottle", "grip": "ag"}), robot="take",
                          caption="hands the bottle to the robot (grey block: stand-in)"),
    "take_from_robot": Demo({"bottle": _B_RWS, "glass": _G_RWS}, "take_from_robot", robot="offer_glass",
                            say=(2.5, "offer:glass"),
                            caption="takes the glass the robot offers (told 'offer:glass')"),
    "request": Demo({"bottle": {"zone": "RWS", "state": "closed"}, "glass": _G_RWS}, "request",
                    ("request", {"hold": 2.0}), caption="holds out an open empty hand (a request)"),
    "point": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "point", ("point", {"object": "glass", "hold": 1.5}),
                  caption="points at the glass in the robot's workspace"),
    "pull_stopper": Demo({"bottle": {"zone": "RWS", "state": "closed", "position": [0.15, -0.05]},
                          "glass": {"zone": "HWS", "state": "empty"}}, "pull_stopper", robot="hold_bottle_out",
                         say=(3.0, "invite:remove_stopper"),
                         caption="pulls the stopper while the robot holds the bottle"),
    "pull_stopper_alone": Demo({"bottle": _B_HWS, "glass": _G_RWS}, "pull_stopper", ("pull_stopper", {}),
                               caption="tries to pull the stopper alone: the bottle lifts", expect=Status.FAILED),
    "turn_glass": Demo({"bottle": _B_RWS, "glass": {"zone": "HWS", "state": "inverted"}}, "turn_glass",
                       ("turn_glass", {}), caption="turns the inverted glass upright"),
    "drink": Demo({"bottle": _B_RWS, "glass": {"zone": "HWS", "state": "full"}}, "drink", ("drink", {}),
                  caption="drinks from the full glass"),
}


@dataclass
class DemoResult:
    name: str
    world: World
    controller: HumanController
    standin: StandIn
    status: Status       # succeeded, failed, or still running at the time limit
    reason: str


def build_demo(name: str, seed: int = 0) -> tuple[World, StandIn, HumanController]:
    """World, stand-in and controller of demo `name`, at time 0."""
    demo = DEMOS[name]
    w = build_world_with_standin(Arrangement.from_mapping(demo.objects, f"demo {name}"), seed)
    s = StandIn(w)
    cfg = parse_human({"profile": demo.profile, "script": demo.script}, f"demo {name}") if demo.script else None
    hc = HumanController(w, profile=demo.profile, seed=seed, config=cfg, see=s.view)
    if demo.robot == "take":
        s.take_when_offered = demo.start[1]["object"] if demo.start else "bottle"
    elif demo.robot == "hold_bottle_out":
        s.grasp_at("bottle")
        s.carry_to((-0.06, -0.03, layout.TABLE_Z + 0.03))
    elif demo.robot == "offer_glass":
        s.grasp_at("glass")
        s.release_when_taken = True
        s.carry_to((0.0, -0.05, layout.TABLE_Z + 0.03))
    elif demo.robot == "open_hand":
        s.move((0.03, -0.05, 0.95))
        s.take_when_offered = "bottle"
    if demo.start is not None:
        hc.start(demo.start[0], **demo.start[1])
    return w, s, hc


def run_demo(name: str, seed: int = 0, tail: float = 1.0,
             on_tick: Callable[[World, HumanController], None] | None = None) -> DemoResult:
    """Run demo `name` (see module docstring); the result carries the shown behaviour's outcome."""
    demo = DEMOS[name]
    w, s, hc = build_demo(name, seed)
    said = False
    t_done: float | None = None
    steps = hc.physics_steps
    while w.time < demo.limit:
        t = w.time
        if demo.say is not None and not said and t >= demo.say[0]:
            hc.hear(demo.say[1], t)
            said = True
        s.tick(t)
        hc.tick(t)
        for _ in range(steps):
            w.step(1)
        if on_tick is not None:
            on_tick(w, hc)
        ended = [b for b in hc.done if b.name == demo.behaviour]
        if t_done is None and ended and hc.current is None and not hc.script:
            t_done = w.time
        if t_done is not None and w.time >= t_done + tail:
            break
    ended = [b for b in hc.done if b.name == demo.behaviour]
    if not ended:
        return DemoResult(name, w, hc, s, Status.RUNNING, f"{demo.behaviour} did not end within {demo.limit:g} s")
    b = ended[-1]
    return DemoResult(name, w, hc, s, b.status, b.reason)
