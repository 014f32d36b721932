"""A minimal physics bench for the robot: the scene MJCF with the objects placed by hand.

Stand-in for `assistbot.world` while that is being built, and the harness of
the robot tests and `assistbot act`: it places the bottle, the glass and the
liquid at given table positions and steps the physics with the robot's control
ticks (2 ms physics, 50 Hz control). Object placement happens once, before the
first step; after that only actuators move things.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np

from assistbot.robot import mjcf_patch
from assistbot.robot.ik_model import default_scene_xml

TABLE_Z = 0.75
CONTROL_DT = 0.02


@dataclass
class Placement:
    bottle: tuple[float, float] = (0.20, 0.12)
    glass: tuple[float, float] = (0.20, -0.12)
    glass_inverted: bool = False
    liquid_in: str = "bottle"     # "bottle", "glass"
    bottle_open: bool = False
    park: dict[str, tuple[float, float, float]] = field(default_factory=dict)


def _set_free(model: mujoco.MjModel, data: mujoco.MjData, body: str, pos, quat=(1, 0, 0, 0)) -> None:
    j = model.body(body).jntadr[0]
    a = model.jnt_qposadr[j]
    data.qpos[a:a + 3] = pos
    data.qpos[a + 3:a + 7] = quat
    data.qvel[model.jnt_dofadr[j]:model.jnt_dofadr[j] + 6] = 0


class Bench:
    """Scene + placement; `step(n)` steps the physics; `particles_in(body)` counts liquid."""

    def __init__(self, placement: Placement | None = None, scene_xml=None, patch: bool = True) -> None:
        self.placement = p = placement or Placement()
        xml = str(scene_xml or default_scene_xml())
        self.model = mjcf_patch.load_model(xml) if patch else mujoco.MjModel.from_xml_path(xml)
        self.data = mujoco.MjData(self.model)
        m, d = self.model, self.data
        bx, by = p.bottle
        gx, gy = p.glass
        _set_free(m, d, "bottle", (bx, by, TABLE_Z))
        if p.glass_inverted:
            _set_free(m, d, "glass", (gx, gy, TABLE_Z + 0.100), (0, 1, 0, 0))
        else:
            _set_free(m, d, "glass", (gx, gy, TABLE_Z))
        self._stopper_eq = m.equality("stopper_fit").id
        if p.bottle_open:
            d.eq_active[self._stopper_eq] = 0
            _set_free(m, d, "stopper", (-0.30, 0.36, TABLE_Z + 0.020))
        else:
            _set_free(m, d, "stopper", (bx, by, TABLE_Z + 0.194))
        self.particles = [m.body(i).name for i in range(m.nbody) if m.body(i).name.startswith("particle")]
        if p.liquid_in == "glass":
            cx, cy, z0, r = gx, gy, TABLE_Z + 0.008 + 0.007, 0.022
        else:
            cx, cy, z0, r = bx, by, TABLE_Z + 0.006 + 0.007, 0.018
        for k, name in enumerate(self.particles):
            ring = k % 2
            a = k * 2 * math.pi / len(self.particles) * 2
            rr = r * (0.5 + 0.5 * ring)
            _set_free(m, d, name, (cx + rr * math.cos(a), cy + rr * math.sin(a), z0 + 0.013 * (k // 10)))
        mujoco.mj_forward(m, d)
        self.n_sub = int(round(CONTROL_DT / m.opt.timestep))

    def step(self, n: int | None = None) -> None:
        mujoco.mj_step(self.model, self.data, nstep=n or self.n_sub)

    def body_pos(self, name: str) -> np.ndarray:
        return self.data.xpos[self.model.body(name).id].copy()

    def body_up(self, name: str) -> np.ndarray:
        """The body's z axis in world (upright containers: +z)."""
        return self.data.xmat[self.model.body(name).id].reshape(3, 3)[:, 2].copy()

    def particles_in(self, container: str, radius: float, height: float) -> int:
        """Particles inside an upright cylinder around the container's origin."""
        c = self.body_pos(container)
        n = 0
        for name in self.particles:
            q = self.body_pos(name)
            if math.hypot(q[0] - c[0], q[1] - c[1]) < radius and c[2] - 0.01 < q[2] < c[2] + height:
                n += 1
        return n

    # --- safety measures used by the tests --------------------------------
    def _robot_arm_geoms(self) -> list[int]:
        if not hasattr(self, "_arm_geoms"):
            from assistbot.robot.ik_model import ARM_GEOMS
            self._arm_geoms = [self.model.geom(g).id for g in ARM_GEOMS]
            self._human_geoms = [self.model.geom(g).id for g in ("human_head", "human_torso")]
        return self._arm_geoms

    def min_human_distance(self) -> float:
        """Smallest distance (m) between an arm/gripper geom and the human's head or torso."""
        arm = self._robot_arm_geoms()
        best = 1e9
        for a in arm:
            for h in self._human_geoms:
                best = min(best, mujoco.mj_geomDistance(self.model, self.data, a, h, 1.0, None))
        return best

    def robot_min_x(self) -> float:
        """The smallest world x reached by any arm/gripper geom (its bounding sphere)."""
        ids = self._robot_arm_geoms()
        return float(np.min(self.data.geom_xpos[ids, 0] - self.model.geom_rbound[ids]))

    def arm_within_limits(self, tol: float = 1e-3) -> bool:
        from assistbot.robot.ik_model import ARM_JOINTS
        for j in ARM_JOINTS:
            jid = self.model.joint(j).id
            q = self.data.qpos[self.model.jnt_qposadr[jid]]
            lo, hi = self.model.jnt_range[jid]
            if q < lo - tol or q > hi + tol:
                return False
        return True
