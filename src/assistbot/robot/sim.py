"""Running one primitive in an `assistbot.world.World` (tests, `assistbot act`, the benchmark).

The scene, the arrangement and the physical rules are the world's (`build_world`); this
module only steps it with the robot's 50 Hz control ticks and measures the safety figures
the tests check: the arm's clearance to the human's head and torso, how far into the HWS
it reaches, and whether every arm joint stays in its range.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import mujoco
import numpy as np

from assistbot.interfaces import CONTROL_DT
from assistbot.robot.ik_model import ARM_GEOMS, ARM_JOINTS, HUMAN_BODY_GEOMS
from assistbot.robot.primitives import Primitive, Progress, Status


@dataclass
class Safety:
    """Worst values over a run: clearance (m) to the human's head/torso, smallest x (m) reached by any
    arm or gripper geom (exact for its capsule, cylinder or box), and whether every arm joint stayed in
    its range."""

    human: float = 1e9
    min_x: float = 1e9
    limits: bool = True
    worst_joint: str = ""
    _ids: tuple = field(default=(), repr=False)

    def update(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        if not self._ids:
            arm = [model.geom(g).id for g in ARM_GEOMS]
            human = [model.geom(g).id for g in HUMAN_BODY_GEOMS]
            joints = [model.joint(j).id for j in ARM_JOINTS]
            self._ids = (arm, human, joints)
        arm, human, joints = self._ids
        x = min_x(model, data, arm)
        self.min_x = min(self.min_x, x)
        if x < 0.3:  # the only place the human's body can be near
            for a in arm:
                for h in human:
                    self.human = min(self.human, mujoco.mj_geomDistance(model, data, a, h, 0.3, None))
        for j in joints:
            q = data.qpos[model.jnt_qposadr[j]]
            lo, hi = model.jnt_range[j]
            if q < lo - 1e-3 or q > hi + 1e-3:
                self.limits = False
                self.worst_joint = model.joint(j).name


def min_x(model: mujoco.MjModel, data: mujoco.MjData, geoms) -> float:
    """The smallest world x of the given geoms (capsule, cylinder, box, sphere: exact; others: bounding sphere)."""
    best = 1e9
    for g in geoms:
        c = data.geom_xpos[g]
        R = data.geom_xmat[g].reshape(3, 3)
        size = model.geom_size[g]
        t = model.geom_type[g]
        if t == mujoco.mjtGeom.mjGEOM_CAPSULE:
            x = c[0] - abs(R[0, 2]) * size[1] - size[0]
        elif t == mujoco.mjtGeom.mjGEOM_CYLINDER:
            x = c[0] - abs(R[0, 2]) * size[1] - size[0] * np.sqrt(max(0.0, 1.0 - R[0, 2] ** 2))
        elif t == mujoco.mjtGeom.mjGEOM_BOX:
            x = c[0] - float(np.abs(R[0]) @ size)
        elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
            x = c[0] - size[0]
        else:
            x = c[0] - model.geom_rbound[g]
        best = min(best, float(x))
    return best


def run(world, prim: Primitive, target: Callable[[], tuple[float, float] | None] = lambda: None,
        seconds: float = 30.0, each_tick: Callable[[float], None] | None = None,
        start: bool = True) -> tuple[Progress, Safety]:
    """Start ``prim`` and tick it with ``target()`` until it ends or ``seconds`` of simulated time pass.

    ``each_tick(t)`` runs before each control tick's physics steps (a human controller, a stand-in
    force). Returns the last progress and the safety figures."""
    safety = Safety()
    n_sub = max(1, int(round(CONTROL_DT / world.model.opt.timestep)))
    if start:
        prim.start(target())
    pr = prim.progress
    for _ in range(int(round(seconds / CONTROL_DT))):
        pr = prim.tick(CONTROL_DT, target())
        if each_tick is not None:
            each_tick(world.time)
        world.step(n_sub)
        safety.update(world.model, world.data)
        if pr.status is not Status.RUNNING:
            break
    return pr, safety


def body_xy(world, name: str) -> Callable[[], tuple[float, float]]:
    """Ground-truth table x, y of a body (a stand-in for perception in tests)."""
    b = world.body_id[name] if name in world.body_id else world.model.body(name).id
    return lambda: (float(world.data.xpos[b][0]), float(world.data.xpos[b][1]))


def body_lift(world, name: str) -> Callable[[], float]:
    """Ground-truth height (m) of a body's origin above the table top (a stand-in for perception)."""
    from assistbot.world.layout import TABLE_Z

    b = world.body_id[name] if name in world.body_id else world.model.body(name).id
    return lambda: float(world.data.xpos[b][2]) - TABLE_Z
