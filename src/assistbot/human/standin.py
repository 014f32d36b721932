"""A stand-in for the robot's hand, for tests and behaviour videos of the human alone.

The scene plus one mocap body ``standin`` (a grey block the size of a gripper, no
collisions) and two welds ``standin_hold_bottle`` / ``standin_hold_glass`` between it and
the objects, added with `mujoco.MjSpec` (the scene's MJCF files stay untouched).  The
stand-in moves along minimum-jerk paths; it holds an object only through its weld, engaged
where the block is, so physics carries the consequences (a held bottle does not lift when
the stopper is pulled; an object the human lets go of stays in the stand-in's "hand").

`StandIn.view` is what the human sees of it (a `perception.RobotView`): what it holds, where
its hand is, whether the hand is held out and open.  The stand-in has no cognition: tests
script it (`hold`, `move`, `release`, `open_hand`) or give it a small reactive rule
(`take_when_offered`, `release_when_taken`), as a simple robot would act.
"""

from __future__ import annotations

import mujoco
import numpy as np

from assistbot import catalogue
from assistbot.human.arm import min_jerk
from assistbot.human.perception import RobotView, held_out_x
from assistbot.world import Arrangement, World, layout

#: what the stand-in holds: what the robot hands over, the task objects
HOLDABLE = catalogue.TASK_OBJECTS
#: m between an object's wall and the block's centre when the block holds it
HOLD_BESIDE = 0.025
#: the block's offset from an object's body origin when it takes hold (world, m): beside the
#: object on the robot's side, at the height a gripper takes it (its grasp site)
HOLD_OFFSET = {o: np.array([catalogue.radius(o) + HOLD_BESIDE, 0.0, catalogue.grasp_height(o)]) for o in HOLDABLE}
#: s an object held out must stay still before the stand-in reaches for it
STILL_FOR = 0.3
#: where the stand-in waits, far in the robot's workspace
PARK = np.array([0.35, -0.30, 1.10])


def build_world_with_standin(arrangement: Arrangement, seed: int = 0) -> World:
    """The scene for `arrangement` plus the stand-in's mocap body and welds."""
    spec = mujoco.MjSpec.from_file(str(layout.SCENE_XML))
    body = spec.worldbody.add_body(name="standin", mocap=True, pos=list(PARK))
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.03, 0.045, 0.02], contype=0, conaffinity=0,
                  rgba=[0.55, 0.55, 0.6, 1.0], group=1)
    for o in HOLDABLE:
        spec.add_equality(name=f"standin_hold_{o}", type=mujoco.mjtEq.mjEQ_WELD, name1="standin", name2=o,
                          objtype=mujoco.mjtObj.mjOBJ_BODY, active=False)
    return World(spec.compile(), arrangement.validate(), seed)


class StandIn:
    """Drives the stand-in of a world made by `build_world_with_standin` (see module docstring).

    Call `tick(t)` once per control tick (it fits `HumanController.run(robot=...)`)."""

    def __init__(self, world: World) -> None:
        m = world.model
        self.world = world
        self.body = m.body("standin").id
        self.mocap = int(m.body_mocapid[self.body])
        self.eq = {o: m.equality(f"standin_hold_{o}").id for o in HOLDABLE}
        self.open = True
        self.take_when_offered: str | None = None    # object to take when the human holds it out
        self.release_when_taken = False               # let go once the human's grip holds the object
        self._path: tuple[float, float, np.ndarray, np.ndarray] | None = None
        self._t = 0.0
        self._last_obj: np.ndarray | None = None
        self._withdraw_when_free: str | None = None
        self._still_since: float | None = None

    # ------------------------------------------------------------------ state
    @property
    def pos(self) -> np.ndarray:
        return self.world.data.mocap_pos[self.mocap].copy()

    def holds(self) -> str | None:
        d = self.world.data
        for o, e in self.eq.items():
            if d.eq_active[e]:
                return o
        return None

    def view(self, world=None) -> RobotView:
        """What the human sees of the stand-in (signature of `perception.see_robot`)."""
        p = self.pos
        held = self.holds()
        return RobotView(held, (float(p[0]), float(p[1]), float(p[2])), held_out_x(p[0]),
                         bool(held is None and self.open))

    # ------------------------------------------------------------------ commands
    def place(self, p) -> None:
        """Put the block at p at once (before a run)."""
        self.world.data.mocap_pos[self.mocap] = np.asarray(p, float)
        self._path = None
        mujoco.mj_forward(self.world.model, self.world.data)

    def move(self, p, duration: float | None = None, speed: float = 0.25) -> float:
        """Start a minimum-jerk move of the block to p; returns its duration (s)."""
        p0, p1 = self.pos, np.asarray(p, float)
        dur = duration if duration is not None else max(0.4, float(np.linalg.norm(p1 - p0)) / speed)
        self._path = (self._t, dur, p0, p1)
        return dur

    def carry_to(self, p, speed: float = 0.25) -> float:
        """Move so that the held object's body origin arrives at p (world, m); returns the duration."""
        held = self.holds()
        if held is None:
            raise ValueError("the stand-in holds nothing to carry")
        return self.move(np.asarray(p, float) + self.pos - self.world.data.xpos[self.world.body_id[held]], speed=speed)

    def moving(self) -> bool:
        return self._path is not None

    def hold(self, obj: str) -> None:
        """Take hold of `obj` where the block and the object are now (the weld keeps their relative pose)."""
        if obj not in HOLDABLE:
            raise ValueError(f"the stand-in holds {' or '.join(HOLDABLE)}, not {obj!r}")
        m, d = self.world.model, self.world.data
        o = self.world.body_id[obj]
        e = self.eq[obj]
        qb_inv = np.zeros(4)
        mujoco.mju_negQuat(qb_inv, d.xquat[self.body])
        relq = np.zeros(4)
        mujoco.mju_mulQuat(relq, qb_inv, d.xquat[o])
        Rb = d.xmat[self.body].reshape(3, 3)
        m.eq_data[e, 0:3] = 0.0
        m.eq_data[e, 3:6] = Rb.T @ (d.xpos[o] - d.xpos[self.body])
        m.eq_data[e, 6:10] = relq
        m.eq_data[e, 10] = 1.0
        d.eq_active[e] = 1
        self.open = False

    def grasp_at(self, obj: str) -> None:
        """Put the block beside `obj` (HOLD_OFFSET) and take hold of it at once."""
        self.place(self.world.data.xpos[self.world.body_id[obj]] + HOLD_OFFSET[obj])
        self.hold(obj)

    def release(self) -> None:
        for e in self.eq.values():
            self.world.data.eq_active[e] = 0
        self.open = True

    # ------------------------------------------------------------------ tick
    def tick(self, t: float) -> None:
        self._t = float(t)
        w = self.world
        if self.take_when_offered is not None and self.holds() is None and w.human_holding() == self.take_when_offered:
            obj = self.take_when_offered
            o = w.data.xpos[w.body_id[obj]].copy()
            moved = self._last_obj is None or float(np.linalg.norm(o - self._last_obj)) > 0.0005
            self._still_since = t if moved or self._still_since is None else self._still_since
            still = t - self._still_since >= STILL_FOR
            self._last_obj = o
            # the object is held out when it is near the middle line and has come to rest
            if o[0] > -0.20 and still and not self.moving():
                if np.linalg.norm(self.pos - (o + HOLD_OFFSET[obj])) < 0.01:
                    self.hold(obj)
                    self.take_when_offered = None
                    self._withdraw_when_free = obj
                else:
                    self.move(o + HOLD_OFFSET[obj], speed=0.3)
        if self._withdraw_when_free is not None and w.human_holding() != self._withdraw_when_free and not self.moving():
            # the human let go: bring the object back into the robot's workspace
            self._withdraw_when_free = None
            self.move(np.array([0.28, self.pos[1], self.pos[2]]), speed=0.2)
        if self.release_when_taken and self.holds() is not None and w.human_holding() == self.holds():
            self.release()
            self.release_when_taken = False
            self.move(PARK, speed=0.2)
        if self._path is not None:
            t0, dur, p0, p1 = self._path
            s = min_jerk((t - t0) / dur)
            w.data.mocap_pos[self.mocap] = p0 + s * (p1 - p0)
            if t >= t0 + dur:
                self._path = None
