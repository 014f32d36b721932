"""AEL robot actions (assistbot.task.drinking.ROBOT_ACTIONS) -> motion primitives.

``None`` means the action does not move the arm (speech, waiting). Every action
that moves maps to a primitive that physically achieves it (tests/test_robot_primitives.py).
Composite actions are one primitive whose phases chain the parts:

  Grasp-hold-bottle-to-remove-cup     HoldBottleForStopper: grasp, hold out at the middle line,
                                      wait for ``stopper_removed()``, put the bottle back, let go
  Reach-turn-and-hand-over-glass      TurnAndHandOver: grasp, turn in the air, hold out, release
                                      when ``human_holds()``
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

#: action name -> (primitive class, object it acts on)
ACTION_PRIMITIVES: dict[str, tuple[type[P.Primitive], str | None] | None] = {
    "Communicate-Error": None,
    "Suggest-drink": None,
    "Wait": None,
    "Reach-and-turn-glass": (P.TurnGlass, "glass"),
    "Request-glass": (P.Request, "glass"),
    "Request-bottle": (P.Request, "bottle"),
    "Grasp-hold-bottle-to-remove-cup": (P.HoldBottleForStopper, "bottle"),
    "Reach-turn-and-hand-over-glass": (P.TurnAndHandOver, "glass"),
    "Reach-grasp-open-bottle-fill-glass": (P.Pour, "bottle"),
    "Reach-full-glass-to-hand-over": (P.HandOver, "glass"),
    "Hand-over-bottle": (P.HandOver, "bottle"),
    "Receive-object": (P.Receive, "held_out"),
    "Take-from-table": (P.TakeFromTable, None),
}

#: actions whose primitive does not achieve the action physically yet (action -> reason): none left.
NOT_YET_PHYSICAL: dict[str, str] = {}
