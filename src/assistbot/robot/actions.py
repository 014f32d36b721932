"""AEL robot actions (assistbot.task.drinking.ROBOT_ACTIONS) -> motion primitives.

``None`` means the action does not move the arm (speech, waiting). Actions
whose primitive is not physically working yet map to the closest working
primitive and are listed in `NOT_YET_PHYSICAL` with the reason.
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
    "Grasp-hold-bottle-to-remove-cup": (P.ReachGraspLift, "bottle"),
    "Reach-turn-and-hand-over-glass": (P.TurnGlass, "glass"),
    "Reach-grasp-open-bottle-fill-glass": (P.ReachGraspLift, "bottle"),
    "Reach-full-glass-to-hand-over": (P.ReachGraspLift, "glass"),
    "Hand-over-bottle": (P.ReachGraspLift, "bottle"),
    "Receive-object": (P.Request, "held_out"),
}

NOT_YET_PHYSICAL: dict[str, str] = {
    "Grasp-hold-bottle-to-remove-cup": "hold pose for the stopper pull not written yet; grasps and lifts the bottle",
    "Reach-turn-and-hand-over-glass": "hand-over phase not written yet; turns the glass only",
    "Reach-grasp-open-bottle-fill-glass": "pour phase not written yet; grasps and lifts the bottle",
    "Reach-full-glass-to-hand-over": "hold-out-and-release not written yet; grasps and lifts the glass",
    "Hand-over-bottle": "hold-out-and-release not written yet; grasps and lifts the bottle",
    "Receive-object": "closing on the held-out object not written yet; holds out the open hand",
}
