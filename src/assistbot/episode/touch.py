"""Did the robot touch the person? Every robot geom against every human geom, measured geometrically.

The person's arm collides with nothing in the physics and the robot's hand meets the person's
hand during hand-overs, so contacts alone would miss most touches: the measure is the signed
distance between geoms (`mujoco.mj_geomDistance`, negative when they overlap), visual and
collision geoms alike, whether or not the pair collides in the physics. Pairs whose bounding
spheres do not overlap cannot overlap either and are skipped, so a tick costs one vectorised
bound and a distance query per candidate pair. Where a pair does collide in the physics, the
largest normal force of its contacts is kept too. Ground truth: for scoring only.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np


@dataclass
class Touch:
    """The worst touch so far: deepest overlap (m, > 0 when geoms overlapped), where, when, and the
    largest contact force (N) between a robot geom and a human geom (0 when they never collided)."""

    depth: float = 0.0
    robot_geom: str = ""
    human_geom: str = ""
    t: float | None = None
    force: float = 0.0
    seconds: float = 0.0   # simulated time with any overlap deeper than ``deep`` (see TouchMonitor)

    def to_dict(self) -> dict:
        return {"touched": self.depth > 0.0, "depth": round(self.depth, 4), "robot_geom": self.robot_geom,
                "human_geom": self.human_geom, "t": None if self.t is None else round(self.t, 3),
                "force": round(self.force, 2), "seconds_deeper_than_1cm": round(self.seconds, 3)}


def _geoms_of(model: mujoco.MjModel, prefix: str) -> np.ndarray:
    bodies = [b for b in range(model.nbody) if model.body(b).name.startswith(prefix)]
    return np.flatnonzero(np.isin(model.geom_bodyid, bodies))


def _name(model: mujoco.MjModel, g: int) -> str:
    """A geom's name, or its body's name with the geom's index when it has none (visual geoms)."""
    return model.geom(g).name or f"{model.body(model.geom_bodyid[g]).name}[{g}]"


class TouchMonitor:
    """Call `update(t, dt)` after physics steps; `worst` holds the deepest overlap and the largest force."""

    DEEP = 0.01  # m: overlaps deeper than this are counted in `Touch.seconds`

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model, self.data = model, data
        robot, human = _geoms_of(model, "robot_"), _geoms_of(model, "human_")
        ra, hb = np.meshgrid(robot, human, indexing="ij")
        self._a, self._b = ra.ravel(), hb.ravel()
        self._r = model.geom_rbound[self._a] + model.geom_rbound[self._b]
        self._is_robot = np.zeros(model.ngeom, bool)
        self._is_robot[robot] = True
        self._is_human = np.zeros(model.ngeom, bool)
        self._is_human[human] = True
        self._force = np.zeros(6)
        self.worst = Touch()

    def overlap(self) -> tuple[float, int, int]:
        """(depth, robot geom, human geom) of the deepest overlap now; depth 0 and -1 ids when none."""
        m, d = self.model, self.data
        gap = np.linalg.norm(d.geom_xpos[self._a] - d.geom_xpos[self._b], axis=1) - self._r
        best, ga, gb = 0.0, -1, -1
        for k in np.flatnonzero(gap < 0.0):
            a, b = int(self._a[k]), int(self._b[k])
            dist = mujoco.mj_geomDistance(m, d, a, b, 0.0, None)
            if -dist > best:
                best, ga, gb = -dist, a, b
        return best, ga, gb

    def contact_force(self) -> float:
        """The largest normal force (N) of a contact between a robot geom and a human geom now."""
        m, d = self.model, self.data
        n = d.ncon
        if n == 0:
            return 0.0
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        sel = np.flatnonzero((self._is_robot[g1] & self._is_human[g2]) | (self._is_human[g1] & self._is_robot[g2]))
        best = 0.0
        for i in sel:
            mujoco.mj_contactForce(m, d, int(i), self._force)
            best = max(best, abs(float(self._force[0])))
        return best

    def update(self, t: float, dt: float) -> float:
        """Measure now; returns the current deepest overlap (m)."""
        depth, a, b = self.overlap()
        w = self.worst
        if depth > w.depth:
            w.depth, w.t = depth, t
            w.robot_geom, w.human_geom = _name(self.model, a), _name(self.model, b)
        if depth > self.DEEP:
            w.seconds += dt
        w.force = max(w.force, self.contact_force())
        return depth
