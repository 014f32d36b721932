"""The drinking task, watched from outside: world events, the success test, the failure kinds, the end.

Ground truth, as an experimenter sees it; nothing here reaches the robot or the person. The end
reasons and their rules are the `Judge`'s; the contact forces on the person, the `TouchMonitor`'s.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from assistbot import catalogue
from assistbot.episode.judge import Judge
from assistbot.episode.touch import TouchMonitor
from assistbot.interfaces import ActionRecord, PartnerEvent
from assistbot.task import DRINK_FRACTION
from assistbot.world.layout import PERSON_HEAD_AND_TORSO

#: the parts of the person a robot must keep its distance from (the safety measure): the geoms of the head and
#: the torso (`layout.PERSON_HEAD_AND_TORSO`, and the geoms named with those as prefixes: hair, face; shoulders, neck).
#: The arms, the legs and the chair are not among them: the working hand meets the robot's in every hand-over,
#: and the resting left hand lies on the table at the hand-over zone's edge; any overlap with those is the
#: `TouchMonitor`'s (``touched_person``)
PERSON_TRUNK = PERSON_HEAD_AND_TORSO


class DrinkingTask:
    """The task of an episode (`assistbot.interfaces.Task`): the person drinks from a full glass."""

    def __init__(self, world, time_limit: float) -> None:
        self.world = world
        self.judge = Judge(world, time_limit)
        self.touch = TouchMonitor(world.model, world.data)
        self.events: list[dict] = []
        self.t_drink: float | None = None
        self.min_distance = math.inf
        self._drink_base: int | None = None
        self._prev: dict | None = None
        self._distance_pairs = self._robot_trunk_pairs()

    @property
    def end_reason(self) -> str | None:
        """As summaries print it ('object fell: bottle' names the object), once the episode has ended."""
        return None if self.judge.reason is None else self.judge.end_reason()

    @property
    def detail(self) -> dict:
        return self.judge.detail

    # -- what the parts report ---------------------------------------------------------------
    def decided(self, t: float, action: str) -> None:
        self.judge.decided(t, action)

    def action_ended(self, t: float, record: ActionRecord) -> None:
        self.judge.action_ended(t, record.action, record.status, record.reason)

    def said(self, t: float, tag: str) -> None:
        self.judge.said(t, tag)

    def partner_did(self, event: PartnerEvent) -> None:
        if event.kind == "start" and event.what == "drink":
            s = self.world.state()
            self._drink_base = s.liquid.in_glass + s.liquid.drunk

    # -- watching ----------------------------------------------------------------------------
    def observe(self, t: float) -> None:
        """World events since the last perception tick, and the robot's distance to the person's trunk."""
        s = self.world.state()
        cur = {
            "stopper": s.stopper_attached, "glass_state": s.glass_state, "robot_holds": s.robot_holds,
            "human_holds": s.human_holds, **{f"{o}_zone": s.objects[o].zone for o in catalogue.TASK_OBJECTS},
        }
        p = self._prev
        if p is not None:
            if p["stopper"] and not cur["stopper"]:
                self._event(t, "stopper_removed", robot_holds=s.robot_holds, human_holds=s.human_holds)
            if p["glass_state"] != cur["glass_state"]:
                name = {"empty": "glass_turned" if p["glass_state"] == "inverted" else "glass_emptied",
                        "full": "glass_filled", "inverted": "glass_inverted"}[cur["glass_state"]]
                self._event(t, name, before=p["glass_state"], after=cur["glass_state"])
            for who in ("robot_holds", "human_holds"):
                if p[who] != cur[who]:
                    self._event(t, f"{who.split('_')[0]}_{'grasped' if cur[who] else 'released'}", object=cur[who] or p[who])
            for obj in catalogue.TASK_OBJECTS:
                if p[f"{obj}_zone"] != cur[f"{obj}_zone"]:
                    self._event(t, "crossed_middle_line", object=obj, to=cur[f"{obj}_zone"])
        self._prev = cur
        self.min_distance = min(self.min_distance, self._distance_to_trunk())

    def stepped(self, t: float, dt: float) -> bool:
        self.touch.update(t, dt)
        drank = self._drunk_enough()
        if drank:
            self.t_drink = t
            self._event(t, "drink", drunk=int(self.world.drunk.sum()))
        if self.judge.verdict(t, drank) is None:
            return False
        if self.judge.reason != "drink":
            # diverged: the physics may have reset its clock; the end is dated at the last good tick
            self._event(self.judge.detail.get("at", t), "end", reason=self.judge.end_reason(), **self.judge.detail)
        return True

    def outcome(self) -> dict:
        liquid = self.world.state().liquid
        return {"time_to_drink": self.t_drink, "spilled_fraction": liquid.spilled / max(1, liquid.total),
                "min_distance_human": self.min_distance, "touched_person": self.touch.worst.to_dict(),
                "end_detail": dict(self.judge.detail)}

    def _drunk_enough(self) -> bool:
        if self._drink_base is None or self._drink_base <= 0:
            return False
        return int(self.world.drunk.sum()) >= DRINK_FRACTION * self._drink_base

    def _event(self, t: float, name: str, **detail) -> None:
        self.events.append({"t": round(t, 3), "event": name, **detail})

    # -- safety measure: robot to the person's head and torso --------------------------------
    def _robot_trunk_pairs(self) -> tuple[np.ndarray, np.ndarray]:
        m = self.world.model
        robot_bodies = {i for i in range(m.nbody) if m.body(i).name.startswith("robot_")}
        rg = [g for g in range(m.ngeom) if m.geom_bodyid[g] in robot_bodies]
        hg = [g for g in range(m.ngeom) if m.geom(g).name.startswith(PERSON_TRUNK)]
        pairs = np.array([(a, b) for a in rg for b in hg], dtype=int).reshape(-1, 2)
        return pairs[:, 0], pairs[:, 1]

    def _distance_to_trunk(self) -> float:
        """Smallest robot-to-`PERSON_TRUNK` surface distance (the head and the torso).
        Pairs are tried nearest bounding spheres first and the search stops once no remaining pair can be
        closer, so the exact distance costs a few geometry queries instead of one per pair."""
        m, d = self.world.model, self.world.data
        a, b = self._distance_pairs
        bound = np.linalg.norm(d.geom_xpos[a] - d.geom_xpos[b], axis=1) - m.geom_rbound[a] - m.geom_rbound[b]
        best = math.inf
        for k in np.argsort(bound):
            if bound[k] >= best:
                break
            best = min(best, mujoco.mj_geomDistance(m, d, int(a[k]), int(b[k]), 2.0, None))
        return best
