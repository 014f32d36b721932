"""HumanController: the simulated partner — perceives the robot, picks behaviours, drives the arm.

Call `tick(t)` once per control period (`dt`, 20 ms; the world then advances
`physics_steps` physics steps) and `hear(tag, t)` whenever the robot utters something (the
utterance's semantic tag from `assistbot.task.drinking.UTTERANCES`).  The human reacts
only to those tags and to what `see` (default `perception.see_robot`) shows of the robot,
each after the profile's reaction delay.

What it does next, in this order: a running behaviour continues; a pending response to the
robot or follow-up of a finished behaviour (passive and active alike: e.g. a full glass taken
from the robot is drunk from) starts -- one that answers only a sight (the robot holding
something out) while the sight lasts; otherwise the scenario script's next step whose
`after:` event has happened; otherwise, for a profile with initiative and no script, the
default policy (`policy.next_move`).  Every start and end (`Status`) goes to `log`
(as `assistbot.interfaces.PartnerEvent`s). The episode's `Partner`.
"""

from __future__ import annotations

from collections import deque
from typing import Callable

import numpy as np

from assistbot import catalogue
from assistbot.human import policy
from assistbot.human.arm import HumanArm
from assistbot.human.behaviours import BEHAVIOURS, Behaviour
from assistbot.human.perception import RobotView, see_robot
from assistbot.human.profiles import PROFILES, Profile
from assistbot.human.script import HumanConfig, Step
from assistbot.interfaces import CONTROL_DT, PartnerEvent as Event, PartnerView, Status

#: s between two looks at the robot (a person's eyes sample the scene ~10 times a second)
LOOK_PERIOD = 0.1
#: s between two consultations of the default policy while idle
DECISION_PERIOD = 0.1


def _key(resp: tuple[str, dict]) -> tuple:
    name, args = resp
    return name, tuple(sorted(args.items()))


class HumanController:
    def __init__(self, world, profile: str | Profile = "active", seed: int = 0, config: HumanConfig | None = None,
                 see: Callable[[object], RobotView] = see_robot, dt: float = CONTROL_DT) -> None:
        if config is not None:
            self.profile = config.profile_params()
        else:
            self.profile = PROFILES[profile] if isinstance(profile, str) else profile
        self.world = world
        self.dt = float(dt)
        self.physics_steps = max(1, int(round(self.dt / world.model.opt.timestep)))
        self.rng = np.random.default_rng(seed)
        self.arm = HumanArm(world, speed=self.profile.speed, dt=self.dt, tremor_amplitude=self.profile.tremor_amplitude,
                            tremor_frequency=self.profile.tremor_frequency)
        self.see = see
        self.script: list[Step] = list(config.script) if config is not None else []
        self._scripted = bool(self.script)
        self.t = 0.0
        self.log: list[Event] = []
        self.current: Behaviour | None = None
        self.done: list[Behaviour] = []
        self._heard: deque[tuple[float, str]] = deque()     # (time it takes effect, tag)
        self.heard_tags: list[tuple[float, str]] = []       # after the reaction delay
        self._views: deque[tuple[float, RobotView]] = deque()
        self.view: RobotView = see(world)
        self._seen: set[str] = set()
        self._pending: list[tuple[str, dict]] = []           # responses waiting to start
        self._answers_sight: dict[tuple, str] = {}           # of those, the ones only a sight asked for: that sight
        self._next_look = 0.0                                # next time the robot is looked at
        self._next_decision = 0.0                            # next time the default policy is consulted
        self._n_clamped = 0
        self.policy_state: dict = {}

    # ------------------------------------------------------------------ perception
    def hear(self, tag: str, t: float) -> None:
        """The robot said something with semantic tag `tag` at time t."""
        self._heard.append((float(t) + self.profile.reaction_delay, str(tag)))

    def note(self, what: str, detail: dict | None = None) -> None:
        self.log.append(Event(self.t, "note", what, dict(detail or {})))

    def _perceive(self, t: float) -> None:
        if t >= self._next_look - 1e-9:
            self._views.append((t, self.see(self.world)))
            self._next_look = t + LOOK_PERIOD
        delay = self.profile.reaction_delay
        while len(self._views) > 1 and self._views[1][0] <= t - delay + 1e-9:
            self._views.popleft()
        self.view = self._views[0][1]
        now = [key for key, on in (("robot_holds:" + str(self.view.holds), self.view.holds is not None),
                                   ("robot_offers:" + str(self.view.offers), self.view.offers is not None),
                                   ("robot_requests", self.view.requests)) if on]
        for key in now:
            if key not in self._seen:
                self._seen.add(key)
                self.log.append(Event(t, "saw", key, {}))
                self._on_seen(key)
        # what is no longer to be seen (the robot has put the bottle it held out back, say): seen anew next time
        self._seen.intersection_update(now)
        while self._heard and self._heard[0][0] <= t + 1e-9:
            _, tag = self._heard.popleft()
            self.heard_tags.append((t, tag))
            self.log.append(Event(t, "heard", tag, {}))
            self._on_heard(tag)

    # ------------------------------------------------------------------ responses to the robot
    def _on_heard(self, tag: str) -> None:
        answers = policy.response_to_tag(self, tag)
        if answers:
            # the robot's latest request is the one answered: what an earlier one asked, not begun yet, is dropped
            for resp in [r for r in self._pending if _key(r) not in self._answers_sight and r not in answers]:
                self._pending.remove(resp)
                self.log.append(Event(self.t, "note", "dropped", {"behaviour": resp[0], "reason": f"superseded by {tag}", **resp[1]}))
        for resp in answers:
            if resp not in self._pending:
                self._pending.append(resp)
            else:   # asked for in words too: it no longer hangs on the sight
                self._answers_sight.pop(_key(resp), None)
        busy = self.current is not None and self.current.name in policy.UNINTERRUPTIBLE
        goes_on = self.current is not None and any(name in policy.CONTINUES.get(self.current.name, ()) for name, _ in self._pending)
        if answers and self.current is not None and (not busy or goes_on):
            # the robot asked for something: stop waiting for what we were doing, answer it (a remark asks
            # nothing: what she does, at an earlier request say, goes on)
            b = self.current
            b.status, b.reason, b.t_end = Status.FAILED, f"interrupted by the robot ({tag})", self.t
            self.log.append(Event(self.t, Status.FAILED.value, b.name, {"reason": b.reason, **b.args}))
            self.done.append(b)
            self.current = None

    def _on_seen(self, key: str) -> None:
        if self._scripted:
            return  # spontaneous reactions to a sight belong to the default policy; a script decides itself
        for resp in policy.response_to_sight(self, key):
            if resp not in self._pending:
                self._pending.append(resp)
                self._answers_sight[_key(resp)] = key

    # ------------------------------------------------------------------ events for scripts
    def happened(self, event: tuple[str, str | None] | None) -> bool:
        if event is None:
            return True
        kind, arg = event
        if kind == "robot_said":
            return any(tag == arg for _, tag in self.heard_tags)
        if kind == "robot_holds":
            return self.view.holds == arg
        if kind == "robot_offers":
            return self.view.offers == arg
        if kind == "robot_requests":
            return self.view.requests
        st = self.world
        if kind == "stopper_removed":
            return not st.data.eq_active[st.eq_stopper]
        if kind == "glass_full":
            return st.state().glass_state == "full"
        if kind == "glass_upright":
            return st.data.xmat[st.body_id["glass"]][8] > 0.9
        if kind == "done":
            return any(b.name == arg and b.status is Status.SUCCEEDED for b in self.done)
        if kind == "time":
            return self.t >= float(arg)
        raise ValueError(f"unknown event {kind!r}")

    # ------------------------------------------------------------------ control
    def start(self, name: str, **args) -> Behaviour:
        gen = BEHAVIOURS[name](self, **args)
        self.current = Behaviour(name, args, gen, self.t)
        self.log.append(Event(self.t, "start", name, dict(args)))
        return self.current

    def _next(self) -> None:
        while self._pending:
            name, args = self._pending.pop(0)
            sight = self._answers_sight.pop(_key((name, args)), None)
            if sight is not None and sight not in self._seen:
                # e.g. the bottle the robot held out while the hand was busy pulling its stopper: the
                # robot has put it back since, and waiting for it to come again would ignore the robot
                self.log.append(Event(self.t, "note", "dropped", {"behaviour": name, "reason": f"no longer sees {sight}", **args}))
                continue
            if policy.still_relevant(self, name, args):
                if name in policy.NEEDS_FREE_HAND and self.world.human_holding() in catalogue.TASK_OBJECTS:
                    self._pending.insert(0, (name, args))
                    self.start("put_down")
                    return
                self.start(name, **args)
                return
            self.log.append(Event(self.t, "note", "dropped", {"behaviour": name, **args}))
        if self.script:
            step = self.script[0]
            if self.happened(step.after):
                self.script.pop(0)
                self.start(step.behaviour, **step.behaviour_args(self.profile))
            return
        if self.profile.initiative and not self._scripted and self.t >= self._next_decision - 1e-9:
            self._next_decision = self.t + DECISION_PERIOD
            move = policy.next_move(self)
            if move is not None:
                self.start(move[0], **move[1])

    def tick(self, t: float) -> None:
        """One control tick at simulated time t (call, then step the world `physics_steps`)."""
        self.t = float(t)
        self._perceive(self.t)
        if self.current is not None:
            status = self.current.step(self.t)
            if status.ended:
                b = self.current
                self.log.append(Event(self.t, status.value, b.name, {"reason": b.reason, **b.args}))
                self.done.append(b)
                self.current = None
                if status is Status.SUCCEEDED:
                    for resp in policy.follow_up(self, b):
                        if resp not in self._pending:
                            self._pending.append(resp)
        if self.current is None:
            self._next()
            if self.current is not None:
                self.current.step(self.t)
        self.arm.tick(self.t)
        if len(self.arm.clamped) > self._n_clamped:
            for tc, want, got in self.arm.clamped[self._n_clamped:]:
                self.log.append(Event(tc, "clamped", "middle line", {"target": want, "clamped_to": got}))
            self._n_clamped = len(self.arm.clamped)

    def run(self, seconds: float, robot: Callable[[float], None] | None = None) -> None:
        """Tick and step the world for `seconds`; `robot(t)` (a stand-in) is called each tick."""
        n = int(round(seconds / self.dt))
        t = self.world.time
        for _ in range(n):
            if robot is not None:
                robot(t)
            self.tick(t)
            for _ in range(self.physics_steps):
                self.world.step(1)
            t = self.world.time

    def appearance(self) -> PartnerView:
        """What an observer sees the person do: the behaviour under way and the hand's posture."""
        b = self.current
        return PartnerView(behaviour=b.name if b is not None else None, args=dict(b.args) if b is not None else {},
                           posture=self.arm.posture)

    def events(self, kind: str | None = None) -> list[Event]:
        return [e for e in self.log if kind is None or e.kind == kind]
