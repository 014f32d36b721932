"""AEL robot actions (assistbot.task.drinking.ROBOT_ACTIONS) -> motion primitives.

Each action names its motion (`RobotAction.motion`, in the task); `MOTIONS` maps a motion to the
primitive that physically achieves it and the object that primitive acts on. An action that does
not move the arm (its motion "speak" or "none") has no primitive. Adding an action that moves means
a `RobotAction` with a motion that is a key here (a new key when no primitive does it yet).
Composite actions are one primitive whose phases chain the parts:

  Grasp-hold-bottle-to-remove-cup     HoldBottleForStopper: grasp, hold out at the middle line,
                                      wait for ``stopper_removed()``, put the bottle back, let go
  Reach-turn-and-hand-over-glass      TurnAndHandOver: grasp, turn in the air, hold out, release
                                      once the wrist feels the person take it
  Reach-grasp-open-bottle-fill-glass  Pour: grasp the bottle, pour into the glass at
                                      ``locate("glass")``, put the bottle back
  Reach-full-glass-to-hand-over       HandOver (glass); Hand-over-bottle: HandOver (bottle)
  Receive-object                      Receive: grasp what the human holds out, wait until the
                                      human lets go, put it down in the RWS
  Take-from-table                     TakeFromTable: show a spot both reach with the open hand, wait
                                      until something is set down there, take it to the RWS

The caller constructs ``cls(robot, obj, human_holds=..., locate=..., stopper_removed=...)``
(see `primitives.Primitive`); every primitive accepts all three callbacks. From perception,
e.g. in the episode's executor (``p`` the latest Percept, ``prim`` the running primitive):

    human_holds     = lambda: p.hand.seen and p.hand.object_in_hand is not None and
                              (obj == "held_out" or p.hand.object_in_hand == prim.object)
    locate          = lambda name: (p.objects[name].position[:2] if p.objects[name].seen else None)
    stopper_removed = lambda: p.objects["bottle"].seen and p.objects["bottle"].state == "open"

Without ``locate`` Pour fails at once ("the glass is not seen") and Request does not step
aside from objects in the RWS; without ``stopper_removed`` HoldBottleForStopper fails after
its 30 s timeout; for Receive-object, ``human_holds`` must be true while the human's hand
holds whatever it holds out (the robot waits for it to let go).
"""

from __future__ import annotations

from assistbot.robot import primitives as P
from assistbot.task import ROBOT_ACTIONS

#: motion (`RobotAction.motion`) -> (the primitive that performs it, the object it acts on)
MOTIONS: dict[str, tuple[type[P.Primitive], str | None]] = {
    "turn_glass": (P.TurnGlass, "glass"),
    "request_glass": (P.Request, "glass"),
    "request_bottle": (P.Request, "bottle"),
    "grasp_hold_bottle": (P.HoldBottleForStopper, "bottle"),
    "turn_and_hand_over_glass": (P.TurnAndHandOver, "glass"),
    "fill_glass": (P.Pour, "bottle"),
    "hand_over_glass": (P.HandOver, "glass"),
    "hand_over_bottle": (P.HandOver, "bottle"),
    "receive_object": (P.Receive, "held_out"),
    "take_from_table": (P.TakeFromTable, None),
}

#: action name -> (primitive class, object it acts on), or None for an action that does not move the arm
ACTION_PRIMITIVES: dict[str, tuple[type[P.Primitive], str | None] | None] = {
    a.name: MOTIONS[a.motion] if a.moves else None for a in ROBOT_ACTIONS}
