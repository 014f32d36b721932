"""When an episode ends and why: the failure kinds every summary names.

The judge watches the episode from outside, as an experimenter would (ground truth: the world's
state, the decisions and the robot's action records); nothing it knows reaches the robot or the
person. `end_reason` is one of END_REASONS, "object fell" naming the object:

  drink        the person drank from a full glass (the episode's goal)
  stalled      no decision and no robot motion for STALL_SECONDS
  repeating    the same action failed REPEAT_FAILURES times, or was decided REPEAT_DECISIONS times
               in a row (an action that cannot fail, such as Wait, repeated without end)
  object fell  the bottle or the glass lies on its side, or fell off the table, and stays there; the
               episode runs on until the robot says it cannot go on (it must see the fall itself), at
               most NOTICE_SECONDS, and ``robot_said`` records whether it did
  diverged     the physics produced NaN, MuJoCo found the state unusable (bad position, velocity or
               acceleration: it then resets the state), or something moves faster than MAX_SPEED;
               ``last_good`` in the detail is the state at the last tick before it, by name
  time limit   the scenario's time ran out
"""

from __future__ import annotations

import math
from collections import Counter

import mujoco
import numpy as np

from assistbot import catalogue, task
from assistbot.interfaces import Status
from assistbot.world import layout

END_REASONS = ("drink", "stalled", "repeating", "object fell", "diverged", "time limit")
STALL_SECONDS = 30.0
REPEAT_FAILURES = 3
REPEAT_DECISIONS = 5
#: an object whose axis is farther than this from vertical (up, or down for the glass) lies on its side
FALLEN_TILT = math.radians(60)
#: it must stay so, untouched by either partner, this long (s): a tipping object may right itself
FALLEN_SECONDS = 1.0
#: s after that for the robot to say that it cannot go on (vision sees the object lie, `task.FALLS`)
NOTICE_SECONDS = 5.0
#: the robot's utterance that an object fell -> the object
FALL_TAGS = {task.UTTERANCES["AML"][item].tag: obj for obj, item in task.FALLS.items()}
#: robot joint speed (rad/s) above which the robot counts as moving
MOVING_SPEED = 0.05
#: m/s or rad/s: no part of this scene moves this fast unless the physics has blown up (an exploding contact)
MAX_SPEED = 1000.0
#: MuJoCo's warnings that it found the state unusable (and reset it)
_BAD_STATE = {mujoco.mjtWarning.mjWARN_BADQPOS: "bad position", mujoco.mjtWarning.mjWARN_BADQVEL: "bad velocity",
              mujoco.mjtWarning.mjWARN_BADQACC: "bad acceleration"}


class Judge:
    """Feed it the episode's events (`decided`, `action_ended`) and call `verdict(t)` every control tick."""

    def __init__(self, world, time_limit: float) -> None:
        self.world = world
        self.time_limit = float(time_limit)
        m = world.model
        # the arm and the fingers: the head follows what it looks at, which is not progress
        joints = [j for j in range(m.njnt) if m.joint(j).name.startswith("robot_") and "head" not in m.joint(j).name]
        self._robot_dofs = np.array([m.jnt_dofadr[j] for j in joints])
        self._last_activity = 0.0
        self._failures: Counter[str] = Counter()
        self._run: list[str] = []           # the decisions since the last different one
        self._lying_since: dict[str, float] = {}
        self._said_fell: set[str] = set()   # the objects the robot has said fell over
        self.reason: str | None = None
        self.detail: dict = {}
        self._good_t, self._good_qpos = world.time, world.data.qpos.copy()

    # -- events ------------------------------------------------------------------------------
    def decided(self, t: float, action: str) -> None:
        self._last_activity = t
        self._run = (self._run if self._run and self._run[-1] == action else []) + [action]
        if len(self._run) >= REPEAT_DECISIONS:
            self._end("repeating", action=action, decided_in_a_row=len(self._run))

    def said(self, t: float, tag: str) -> None:
        """The robot said something (its utterance's tag)."""
        if tag in FALL_TAGS:
            self._said_fell.add(FALL_TAGS[tag])

    def action_ended(self, t: float, action: str, status: str, reason: str = "") -> None:
        self._last_activity = t
        if status == Status.FAILED:
            self._failures[action] += 1
            if self._failures[action] >= REPEAT_FAILURES:
                self._end("repeating", action=action, failures=self._failures[action], last_reason=reason)

    def _end(self, reason: str, **detail) -> None:
        if self.reason is None:
            self.reason, self.detail = reason, detail

    # -- the world -----------------------------------------------------------------------------
    def fallen(self) -> list[str]:
        """The task objects lying on their side or below the table top, held by no one."""
        w, d = self.world, self.world.data
        held = {w.human_holding(), w.robot_holding()}
        out = []
        for name in catalogue.TASK_OBJECTS:    # the stopper, once off, is set aside and not needed
            b = w.body_id[name]
            if name in held:
                continue
            axis_z = float(d.xmat[b][8])
            upright = axis_z > math.cos(FALLEN_TILT) or ("inverted" in catalogue.BY_NAME[name].states and axis_z < -math.cos(FALLEN_TILT))
            off_table = float(d.xpos[b][2]) < layout.TABLE_Z - 0.05
            if not upright or off_table:
                out.append(name)
        return out

    def verdict(self, t: float, drank: bool = False) -> str | None:
        """The end reason if the episode ends now, else None."""
        d = self.world.data
        if drank:
            self._end("drink")
        if self.reason is None:
            cause = self._divergence()
            if cause is None:
                self._good_t = t
                np.copyto(self._good_qpos, d.qpos)
            else:
                self._end("diverged", cause=cause, at=round(self._good_t, 3), last_good=self._named_state(self._good_qpos))
        if self.reason is None:
            lying = set(self.fallen())
            self._lying_since = {o: self._lying_since.get(o, t) for o in lying}
            for o, t0 in self._lying_since.items():
                said = o in self._said_fell
                if t - t0 >= FALLEN_SECONDS and (said or t - t0 >= FALLEN_SECONDS + NOTICE_SECONDS):
                    self._end("object fell", object=o, robot_said=said)
        if self.reason is None:
            if np.abs(d.qvel[self._robot_dofs]).max() > MOVING_SPEED:
                self._last_activity = t
            if t - self._last_activity >= STALL_SECONDS:
                self._end("stalled", since=round(self._last_activity, 3))
        if self.reason is None and t >= self.time_limit:
            self._end("time limit")
        return self.reason

    def _divergence(self) -> str | None:
        """Why the physics cannot be trusted any more, or None."""
        d = self.world.data
        for warning, what in _BAD_STATE.items():
            if d.warning[warning].number:
                return f"MuJoCo: {what} (state reset)"
        if not (np.isfinite(d.qpos).all() and np.isfinite(d.qvel).all()):
            return "NaN in the state"
        fastest = int(np.argmax(np.abs(d.qvel)))
        if abs(d.qvel[fastest]) > MAX_SPEED:
            m = self.world.model
            return f"{m.body(m.dof_bodyid[fastest]).name} moves at {abs(d.qvel[fastest]):.3g} (> {MAX_SPEED:g})"
        return None

    def _named_state(self, qpos: np.ndarray) -> dict:
        """A state by name: hinge and slide joints' positions, free bodies' positions (the liquid left out)."""
        m, out = self.world.model, {}
        for j in range(m.njnt):
            a, kind = m.jnt_qposadr[j], int(m.jnt_type[j])
            if kind == mujoco.mjtJoint.mjJNT_FREE:
                body = m.body(m.jnt_bodyid[j]).name
                if body in catalogue.BY_NAME:
                    out[body] = [round(float(v), 4) for v in qpos[a:a + 3]]
            elif kind in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
                out[m.joint(j).name] = round(float(qpos[a]), 4)
        return out

    def end_reason(self) -> str:
        """The end reason as summaries print it: 'object fell: bottle' names the object."""
        if self.reason == "object fell":
            return f"object fell: {self.detail['object']}"
        return self.reason or "time limit"
