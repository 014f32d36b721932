"""CarryOver: the phase that carries what the hand holds over the objects standing in its way."""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import mink
import numpy as np

from assistbot import catalogue
from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.phases import Move, Phase
from assistbot.robot.placement import segment_distance
from assistbot.robot.primitives.geometry import RADIUS
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: m by which what the robot carries passes over the objects standing in its way
CARRY_CLEARANCE = 0.03
#: m: a straight way that passes within this below the height needed is high enough
HIGH_ENOUGH_WITHIN = 0.005


class CarryOver(Phase):
    """Before carrying the object in the hand to ``goal(prim)``: if the straight way passes by an object
    standing on the table (``locate``), first rise until what the hand carries clears that object's top
    by CARRY_CLEARANCE, and cross at that height; nothing to do otherwise. The IK keeps the arm clear of
    standing objects, not what it carries."""

    name = "carry over"

    def __init__(self, goal: Callable[["Primitive"], mink.SE3]) -> None:
        self.goal = goal

    def start(self, prim):
        self.moves: list[Move] = []
        obj = prim.object
        if obj not in catalogue.TASK_OBJECTS:
            return
        here = prim.robot.commanded_tcp_pose()
        goal = self.goal(prim)
        a, b = here.translation(), goal.translation()
        below = prim.grasp_height          # the carried object's base below the TCP
        need = -np.inf
        for other in OBJECTS:
            xy = prim.locate(other) if other != obj else None
            if xy is None:
                continue
            d = float(segment_distance(np.asarray(xy, float), a[:2], b[:2]))
            if d < RADIUS[obj] + RADIUS[other] + CARRY_CLEARANCE:
                top = TABLE_Z + catalogue.top(other)
                need = max(need, top + CARRY_CLEARANCE + below)
        if need <= max(a[2], b[2]) - HIGH_ENOUGH_WITHIN:
            return
        rot = here.rotation()
        self.moves = [Move("carry over: rise", lambda p, q=np.array([a[0], a[1], need]): poses.pose(rot, q), duration=1.0,
                           tolerance=0.03),
                      Move("carry over: across", lambda p, q=np.array([b[0], b[1], need]): poses.pose(goal.rotation(), q),
                           duration=1.8, tolerance=0.03)]
        self.moves[0].start(prim)
        self.t0 = 0.0

    def tick(self, prim, dt, t):
        if not self.moves:
            prim.robot.hold()
            return Status.SUCCEEDED, ""
        status, reason = self.moves[0].tick(prim, dt, t - self.t0)
        if status is Status.SUCCEEDED:
            self.moves.pop(0)
            if self.moves:
                self.moves[0].start(prim)
                self.t0 = t
            return Status.RUNNING, ""
        return status, reason
