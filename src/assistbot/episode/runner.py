"""One episode in simulated time: physics ~2 ms, control 50 Hz, perception 10 Hz.

    physics --render--> perception --Percept--> cognition --Decision--> robot executor --> actuators
                                                    |utterances--> speech log, the human hears the tags
    the human ticks on what it hears and sees; the world steps.

Cognition sees only the Percept (vision's, or the labelled oracle's) plus the
robot's proprioception. The log (one JSON object per perception tick and per
event) and the summary are written by `assistbot.episode.outputs`.
"""

from __future__ import annotations

import difflib
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable

import mujoco
import numpy as np

from assistbot.cognition import Cognition
from assistbot.episode.executor import RobotExecutor
from assistbot.episode.judge import Judge
from assistbot.episode.touch import TouchMonitor
from assistbot.errors import UserError
from assistbot.human.controller import HumanController
from assistbot.human.script import PARAMS as HUMAN_PARAMS, HumanConfig
from assistbot.scenario import VISION_PARAMS, Scenario, check_vision_value
from assistbot.speech import SpeechLog
from assistbot.world import build_world

CONTROL_DT = 0.02
PERCEPTION_EVERY = 5  # control ticks: 10 Hz
DRINK_FRACTION = 0.75  # of the glass's particles at the drink's start
LAYERS_SHOWN = ("ASL", "IL", "AML", "AEL", "CSGL_past", "CSGL_present", "CSGL_future")


@dataclass
class EpisodeResult:
    scenario: str
    seed: int
    perception: str
    success: bool
    end_reason: str
    time: float
    time_to_drink: float | None
    decisions: list[tuple[float, str]]
    releases: list[tuple[float, str, str]]
    utterances: list[dict]
    human_events: list[dict]
    world_events: list[dict]
    actions: list[dict]
    spilled_fraction: float
    min_distance_human: float
    errors_communicated: int
    wall: dict[str, float]
    overrides: dict[str, Any] = field(default_factory=dict)
    touched_person: dict = field(default_factory=dict)
    end_detail: dict = field(default_factory=dict)

    def summary(self) -> dict:
        return {
            "scenario": self.scenario, "seed": self.seed, "perception": self.perception,
            "success": self.success, "end_reason": self.end_reason, "end_detail": self.end_detail,
            "time": round(self.time, 3),
            "time_to_drink": None if self.time_to_drink is None else round(self.time_to_drink, 3),
            "decisions": [a for _, a in self.decisions],
            "decision_times": [round(t, 3) for t, _ in self.decisions],
            "utterances": self.utterances, "actions": self.actions, "world_events": self.world_events,
            "human_events": self.human_events,
            "spilled_fraction": round(self.spilled_fraction, 4),
            "min_distance_human": round(self.min_distance_human, 4),
            "touched_person": self.touched_person,
            "errors_communicated": self.errors_communicated,
            "wall_seconds": {k: round(v, 3) for k, v in self.wall.items()},
            "overrides": self.overrides,
        }


def split_overrides(overrides: dict[str, Any], where: str) -> tuple[dict, dict, dict]:
    """Dotted paths -> (cognition, human, vision) overrides; an unknown path names the closest valid ones."""
    cog, hum, vis = {}, {}, {}
    from assistbot.cognition.config import CognitionConfig

    cog_paths = ["cognition." + p for p in CognitionConfig().paths()]
    valid = cog_paths + [f"human.{p}" for p in HUMAN_PARAMS] + list(VISION_PARAMS)
    for path, value in overrides.items():
        if path in cog_paths:
            try:
                CognitionConfig().set(path[len("cognition."):], value)
            except UserError as exc:
                raise UserError(where, path, exc.message) from None
            cog[path[len("cognition."):]] = value
        elif path.startswith("human.") and path[6:] in HUMAN_PARAMS:
            hum[path[6:]] = value
        elif path in VISION_PARAMS:
            vis[VISION_PARAMS[path]] = check_vision_value(path, value, where)
        else:
            close = difflib.get_close_matches(path, valid, n=3)
            raise UserError(where, path, "unknown parameter path" + (f"; did you mean {', '.join(close)}?" if close else ""))
    return cog, hum, vis


class Episode:
    def __init__(self, scenario: Scenario, perception: str = "vision", seed: int | None = None,
                 overrides: dict[str, Any] | None = None, frame_every: float | None = None) -> None:
        if perception not in ("vision", "oracle"):
            raise UserError("--perception", perception, "use vision or oracle")
        self.scenario = scenario
        self.seed = scenario.seed if seed is None else int(seed)
        self.overrides = {**scenario.overrides, **(overrides or {})}
        cog_o, hum_o, vis_o = split_overrides(self.overrides, str(scenario.path or scenario.name))
        self.world = build_world(scenario.objects, seed=self.seed)
        hc: HumanConfig = scenario.human
        if hum_o:
            hc = HumanConfig(hc.profile, {**hc.overrides, **hum_o}, hc.script)
        self.human = HumanController(self.world, config=hc, seed=self.seed, dt=CONTROL_DT)
        self.robot = RobotExecutor(self.world)
        self.cognition = Cognition(overrides=cog_o or None, seed=self.seed)
        self.perception_mode = perception
        if perception == "oracle":
            from assistbot.episode.oracle import OraclePerception

            self.perception = OraclePerception(self.world, self.human)
        else:
            from assistbot.episode.vision_perception import VisionPerception

            self.perception = VisionPerception(self.world, seed=self.seed, **vis_o)
        self.speech = SpeechLog()
        self.log: list[dict] = []
        self.world_events: list[dict] = []
        self.frame_every = frame_every
        self.on_frame: Callable[["Episode"], None] | None = None
        # perception is what turns the world into a Percept (vision's processing, or the oracle);
        # rendering, the head cameras' images it starts from
        self.wall = {"physics": 0.0, "rendering": 0.0, "perception": 0.0, "cognition": 0.0, "robot": 0.0, "human": 0.0,
                     "video": 0.0}
        self._n_sub = max(1, int(round(CONTROL_DT / self.world.model.opt.timestep)))
        self._drink_base: int | None = None
        self._prev = None
        self.min_distance = math.inf
        self._distance_pairs = self._robot_human_pairs()
        self.judge = Judge(self.world, scenario.time_limit)
        self.touch = TouchMonitor(self.world.model, self.world.data)
        self.last_percept = None
        self.last_decision = None

    # -- safety measure: robot to the human's head and torso --------------------------------------
    def _robot_human_pairs(self) -> tuple[np.ndarray, np.ndarray]:
        m = self.world.model
        robot_bodies = {i for i in range(m.nbody) if m.body(i).name.startswith("robot_")}
        human_parts = {i for i in range(m.nbody) if m.body(i).name in ("human_body", "human_head", "human_torso")}
        rg = [g for g in range(m.ngeom) if m.geom_bodyid[g] in robot_bodies]
        hg = [g for g in range(m.ngeom) if m.geom_bodyid[g] in human_parts]
        pairs = np.array([(a, b) for a in rg for b in hg], dtype=int).reshape(-1, 2)
        return pairs[:, 0], pairs[:, 1]

    def _distance_to_human(self) -> float:
        """Smallest robot-to-head/torso surface distance.  Pairs are tried nearest bounding
        spheres first and the search stops once no remaining pair can be closer, so the
        exact distance costs a few geometry queries instead of one per pair."""
        m, d = self.world.model, self.world.data
        a, b = self._distance_pairs
        bound = np.linalg.norm(d.geom_xpos[a] - d.geom_xpos[b], axis=1) - m.geom_rbound[a] - m.geom_rbound[b]
        best = math.inf
        for k in np.argsort(bound):
            if bound[k] >= best:
                break
            best = min(best, mujoco.mj_geomDistance(m, d, int(a[k]), int(b[k]), 2.0, None))
        return best

    # -- world events ------------------------------------------------------------------------------
    def _watch(self, t: float) -> None:
        s = self.world.state()
        cur = {
            "stopper": s.stopper_attached, "glass_state": s.glass_state, "robot_holds": s.robot_holds,
            "human_holds": s.human_holds, "bottle_zone": s.objects["bottle"].zone, "glass_zone": s.objects["glass"].zone,
        }
        if self._prev is not None:
            p = self._prev
            if p["stopper"] and not cur["stopper"]:
                self._event(t, "stopper_removed", robot_holds=s.robot_holds, human_holds=s.human_holds)
            if p["glass_state"] != cur["glass_state"]:
                name = {"empty": "glass_turned" if p["glass_state"] == "inverted" else "glass_emptied",
                        "full": "glass_filled", "inverted": "glass_inverted"}[cur["glass_state"]]
                self._event(t, name, before=p["glass_state"], after=cur["glass_state"])
            for who in ("robot_holds", "human_holds"):
                if p[who] != cur[who]:
                    self._event(t, f"{who.split('_')[0]}_{'grasped' if cur[who] else 'released'}", object=cur[who] or p[who])
            for obj in ("bottle", "glass"):
                if p[f"{obj}_zone"] != cur[f"{obj}_zone"]:
                    self._event(t, "crossed_middle_line", object=obj, to=cur[f"{obj}_zone"])
        self._prev = cur
        self._state = s

    def _event(self, t: float, name: str, **detail) -> None:
        ev = {"t": round(t, 3), "event": name, **detail}
        self.world_events.append(ev)
        self.log.append({"t": round(t, 3), "kind": "world", **ev})

    # -- the loop -----------------------------------------------------------------------------------
    def run(self, progress: Callable[[float], None] | None = None) -> EpisodeResult:
        w, wall = self.world, self.wall
        tick = 0
        t_drink = None
        next_frame = 0.0
        n_human_events = 0
        while True:
            t = w.time
            if tick % PERCEPTION_EVERY == 0:
                c0 = time.perf_counter()
                percept = self.perception.perceive(t, self.robot.proprioception())
                c1 = time.perf_counter()
                self.robot.see(percept)
                decision = self.cognition.update(percept)
                if self.robot.status in ("finished", "failed"):
                    rec = self.robot.records[-1]
                    self.judge.action_ended(t, rec.action, rec.status, rec.reason)
                    self.robot.acknowledge()
                rendered = getattr(self.perception, "render_seconds", 0.0)
                wall["rendering"] += rendered
                wall["perception"] += c1 - c0 - rendered
                wall["cognition"] += time.perf_counter() - c1
                self.last_percept = percept
                self._watch(t)
                self.min_distance = min(self.min_distance, self._distance_to_human())
                self._log_tick(t, percept, decision)
            else:
                c0 = time.perf_counter()
                self.cognition.advance(t)
                decision = self.cognition.current()
                wall["cognition"] += time.perf_counter() - c0
            self.last_decision = decision
            for u in decision.utterances:
                self.speech.say(u.t, u.text, u.tag, f"{u.layer}:{u.item}")
                self.human.hear(u.tag, u.t)
                self.judge.said(u.t, u.tag)
                self.log.append({"t": round(u.t, 3), "kind": "say", "layer": u.layer, "item": u.item, "text": u.text, "tag": u.tag})
            if decision.released:
                self.log.append({"t": round(t, 3), "kind": "release", "action": decision.released})
            if decision.new and decision.action:
                said = [u.text for u in decision.utterances if u.layer == "AEL"]
                self.robot.begin(decision.action, t, said[0] if said else "")
                self.judge.decided(t, decision.action)
                self.log.append({"t": round(t, 3), "kind": "decide", "action": decision.action, "target": decision.target})
            c0 = time.perf_counter()
            self.robot.tick(t, CONTROL_DT)
            c1 = time.perf_counter()
            self.human.tick(t)
            c2 = time.perf_counter()
            wall["robot"] += c1 - c0
            wall["human"] += c2 - c1
            for ev in self.human.log[n_human_events:]:
                self.log.append({"t": round(ev.t, 3), "kind": "human", "what": ev.kind, "behaviour": ev.what,
                                 "detail": {k: v for k, v in ev.detail.items() if isinstance(v, (str, int, float, bool, type(None)))}})
                if ev.kind == "start" and ev.what == "drink":
                    s = w.state()
                    self._drink_base = s.liquid.in_glass + s.liquid.drunk
            n_human_events = len(self.human.log)
            if self.frame_every is not None and t >= next_frame and self.on_frame is not None:
                c0 = time.perf_counter()
                self.on_frame(self)
                wall["video"] += time.perf_counter() - c0
                next_frame += self.frame_every
            c0 = time.perf_counter()
            w.step(self._n_sub)
            wall["physics"] += time.perf_counter() - c0
            tick += 1
            if progress is not None:
                progress(w.time)
            self.touch.update(w.time, CONTROL_DT)
            drank = self._drunk_enough()
            if drank:
                t_drink = w.time
                self._event(t_drink, "drink", drunk=int(w.drunk.sum()))
            if self.judge.verdict(w.time, drank) is not None:
                break
        if self.judge.reason != "drink":
            self._event(w.time, "end", reason=self.judge.end_reason(), **self.judge.detail)
        return self._result(self.judge.end_reason(), t_drink)

    def _drunk_enough(self) -> bool:
        if self._drink_base is None or self._drink_base <= 0:
            return False
        return int(self.world.drunk.sum()) >= DRINK_FRACTION * self._drink_base

    def _log_tick(self, t: float, percept, decision) -> None:
        objs = {k: {"zone": o.zone, "state": o.state, "seen": o.seen, "state_seen": o.state_seen, "conf": round(o.confidence, 2),
                    "pos": [round(float(v), 3) for v in o.position]} for k, o in percept.objects.items()}
        h = percept.hand
        self.log.append({
            "t": round(t, 3), "kind": "tick",
            "percept": {"objects": objs, "hand": {"posture": h.posture, "seen": h.seen, "object": h.object_in_hand,
                                                  "held_out": h.held_out}, "robot": self.robot.proprioception()},
            "peaks": {L: self.cognition.peaks(L) for L in LAYERS_SHOWN},
            "decision": decision.action, "robot_status": self.robot.status,
            "human": self.human.current.name if self.human.current else None,
        })

    def _result(self, end_reason: str, t_drink: float | None) -> EpisodeResult:
        s = self.world.state()
        total = max(1, s.liquid.total)
        decisions = [(t, a) for t, kind, a in self.cognition.history if kind == "decide"]
        releases = [(t, kind, a) for t, kind, a in self.cognition.history if kind != "decide"]
        errors = sum(1 for _, a in decisions if a == "Communicate-Error")
        return EpisodeResult(
            scenario=self.scenario.name, seed=self.seed, perception=self.perception_mode,
            success=end_reason == "drink", end_reason=end_reason, time=self.world.time, time_to_drink=t_drink,
            decisions=decisions, releases=releases,
            utterances=[u.to_dict() for u in self.speech],
            human_events=[{"t": round(e.t, 3), "kind": e.kind, "what": e.what} for e in self.human.log
                          if e.kind in ("start", "success", "failure")],
            world_events=self.world_events,
            actions=[{"action": r.action, "start": round(r.start, 3), "end": None if r.end is None else round(r.end, 3),
                      "status": r.status, "reason": r.reason} for r in self.robot.records],
            spilled_fraction=s.liquid.spilled / total,
            min_distance_human=self.min_distance,
            errors_communicated=errors,
            wall=dict(self.wall),
            overrides=self.overrides,
            touched_person=self.touch.worst.to_dict(),
            end_detail=dict(self.judge.detail),
        )
