"""Differential IK for the 7-DOF arm with mink, one solve per control tick.

Tasks: a `FrameTask` on the site ``robot_tcp`` (the target pose comes from
the motion primitive) and a `PostureTask` toward a natural arm posture.
Limits: joint ranges and the joint speeds of the MJCF (custom numeric
``robot_joint_max_speed``), and `CollisionAvoidanceLimit`s: the whole arm
keeps ``human_clearance`` (m) from the human's head and torso, the hand
keeps ``table_clearance`` and the forearm 3 cm from the table top (the hand
may go near it to grasp), and the forearm and hand keep ``body_clearance``
from the robot's own column and pedestal (an object close to the robot is
otherwise reached with the elbow folded into the column), and the arm keeps
``object_clearance`` from the objects standing where perception saw them
(`set_obstacles`: the cylinders of `ik_model.OBSTACLES`), so that reaching for
one it does not sweep the other over. A QP without a
solution (`mink.NoSolutionFound`) is reported in the `IKResult`, never
raised; the commanded configuration then stays put.
"""

from __future__ import annotations

import ctypes
import time
from dataclasses import dataclass

import daqp
import mink
import mujoco
import numpy as np

from assistbot.robot.ik_model import (
    ARM_GEOMS,
    ARM_JOINTS,
    BODY_GEOMS,
    HAND_GEOMS,
    HUMAN_BODY_GEOMS,
    OBSTACLE_AWAY_Z,
    OBSTACLES,
    TABLE_GEOMS,
    build_ik_model,
    obstacle_geom,
)
from assistbot.world.layout import TABLE_Z

#: a relaxed posture: elbow bent, forearm forward, hand above the table in front of the robot
READY_POSTURE = np.array([-0.77, -0.47, 0.44, 0.74, 0.35, -0.08, 0.29])  # TCP at (0.30, 0.05, 1.00), palm toward -x


@dataclass
class IKParams:
    position_cost: float = 1.0
    orientation_cost: float = 0.3
    posture_cost: float = 2e-3
    lm_damping: float = 1e-2
    damping: float = 1e-4
    human_clearance: float = 0.07   # m between arm geoms and human head/torso (tests require >= 0.05)
    table_clearance: float = 0.005  # m between the hand and the table top
    body_clearance: float = 0.02    # m between the forearm and hand and the robot's column and pedestal
    object_clearance: float = 0.015  # m between the arm and the objects standing in its way
    detection_distance: float = 0.15  # m: pairs closer than this enter the QP
    collision: bool = True
    speed_scale: float = 0.9        # fraction of the MJCF joint speeds the IK may use
    fast_qp: bool = True            # joint limits as QP bounds, daqp called directly (ArmIK._solve_qp)


@dataclass
class IKResult:
    q: np.ndarray            # commanded arm configuration (rad), 7
    ok: bool                 # False when the QP had no solution
    reason: str = ""
    position_error: float = 0.0  # m between the TCP of q and the target
    rotation_error: float = 0.0  # rad
    solve_us: float = 0.0


class ArmIK:
    """mink IK on the reduced model (see `ik_model`): `solve(q, target, dt) -> IKResult`."""

    def __init__(self, params: IKParams | None = None, model: mujoco.MjModel | None = None,
                 max_speed: np.ndarray | None = None) -> None:
        self.p = p = params or IKParams()
        self.model = model if model is not None else build_ik_model()
        self.configuration = mink.Configuration(self.model)
        self.tcp_task = mink.FrameTask("robot_tcp", "site", position_cost=p.position_cost,
                                       orientation_cost=p.orientation_cost, lm_damping=p.lm_damping)
        self.posture_task = mink.PostureTask(self.model, cost=p.posture_cost)
        self.posture_task.set_target(READY_POSTURE)
        if max_speed is None:
            max_speed = _max_speed(self.model)
        self.max_speed = np.asarray(max_speed, float)
        velocities = {j: float(v) * p.speed_scale for j, v in zip(ARM_JOINTS, self.max_speed)}
        self.base_limits = [mink.ConfigurationLimit(self.model), mink.VelocityLimit(self.model, velocities)]
        forearm = [g for g in ARM_GEOMS if g not in HAND_GEOMS]
        self.collision_limits = [
            mink.CollisionAvoidanceLimit(self.model, [(list(ARM_GEOMS), list(HUMAN_BODY_GEOMS))],
                                         minimum_distance_from_collisions=p.human_clearance,
                                         collision_detection_distance=p.human_clearance + p.detection_distance),
            mink.CollisionAvoidanceLimit(self.model, [(list(HAND_GEOMS), list(TABLE_GEOMS))],
                                         minimum_distance_from_collisions=p.table_clearance,
                                         collision_detection_distance=p.table_clearance + 0.05),
            mink.CollisionAvoidanceLimit(self.model, [(forearm, list(TABLE_GEOMS))],
                                         minimum_distance_from_collisions=0.03,
                                         collision_detection_distance=0.1),
            mink.CollisionAvoidanceLimit(self.model, [(list(ARM_GEOMS[1:]), list(BODY_GEOMS))],
                                         minimum_distance_from_collisions=p.body_clearance,
                                         collision_detection_distance=p.body_clearance + 0.1),
            mink.CollisionAvoidanceLimit(self.model, [(list(ARM_GEOMS), [obstacle_geom(o) for o in OBSTACLES])],
                                         minimum_distance_from_collisions=p.object_clearance,
                                         collision_detection_distance=p.object_clearance + 0.08),
        ]
        # cheap pre-check per collision limit: the arm's bounding spheres against the human's (a lower
        # bound on the distance), the hand's/forearm's lowest point against the table top (static), or
        # their horizontal distance from the column's axis
        m = self.model
        gid = lambda names: np.array([m.geom(g).id for g in names])  # noqa: E731
        d0 = self.configuration.data
        self._arm_ids, self._arm_r = gid(ARM_GEOMS), m.geom_rbound[gid(ARM_GEOMS)]
        self._human_ids = gid(HUMAN_BODY_GEOMS)
        self._human_r = m.geom_rbound[self._human_ids]
        self._hand_rows = np.isin(self._arm_ids, gid(HAND_GEOMS))
        t = gid(TABLE_GEOMS)[0]
        self._table_top = float(d0.geom_xpos[t][2] + np.abs(d0.geom_xmat[t].reshape(3, 3)[2]) @ m.geom_size[t])
        column = m.geom("robot_column").id
        self._column_xy = d0.geom_xpos[column][:2].copy()
        self._column_r = float(max(m.geom_size[column][0], m.geom_size[m.geom("robot_pedestal").id][0]))
        self._body_rows = self._arm_ids != m.geom(ARM_GEOMS[0]).id   # the upper arm starts at the column
        self._obstacle_body = {o: m.body(obstacle_geom(o)).id for o in OBSTACLES}
        self._obstacle_ids = gid([obstacle_geom(o) for o in OBSTACLES])
        self._obstacle_r = m.geom_rbound[self._obstacle_ids]
        self._reach = (p.human_clearance + p.detection_distance, p.table_clearance + 0.05, 0.1, p.body_clearance + 0.1,
                       p.object_clearance + 0.08)
        self._lo, self._hi = self.model.jnt_range[:, 0].copy(), self.model.jnt_range[:, 1].copy()
        self._vmax = self.max_speed * p.speed_scale
        self._gain = self.base_limits[0].gain
        self._damping_eye = p.damping * np.eye(self.model.nv)
        self.tcp_site = self.model.site("robot_tcp").id
        self.shoulder = self.configuration.data.xpos[self.model.body("robot_link1").id].copy()

    def _active_collision_limits(self) -> list:
        """The collision limits whose geoms are near enough to matter (the configuration is already updated).

        Each `CollisionAvoidanceLimit` only acts within its detection distance; skipping one whose
        geoms are certainly farther apart than that changes nothing but the cost of the QP."""
        xpos = self.configuration.data.geom_xpos
        pa = xpos[self._arm_ids]
        gap_h = np.linalg.norm(pa[:, None, :] - xpos[self._human_ids][None], axis=2) - self._arm_r[:, None] - self._human_r[None]
        low = pa[:, 2] - self._arm_r - self._table_top
        # the column and pedestal are vertical cylinders about one axis: the horizontal gap bounds the distance
        gap_b = np.linalg.norm(pa[self._body_rows, :2] - self._column_xy, axis=1) - self._arm_r[self._body_rows] - self._column_r
        gap_o = np.linalg.norm(pa[:, None, :] - xpos[self._obstacle_ids][None], axis=2) - self._arm_r[:, None] - self._obstacle_r[None]
        gaps = (float(gap_h.min()), float(low[self._hand_rows].min()), float(low[~self._hand_rows].min()), float(gap_b.min()),
                float(gap_o.min()))
        return [lim for lim, gap, reach in zip(self.collision_limits, gaps, self._reach) if gap < reach]

    def _solve_qp(self, q: np.ndarray, dt: float, collision_limits: list) -> np.ndarray:
        """The QP `mink.solve_ik` builds, with the joint position and speed limits as box bounds.

        Same tasks (mink's FrameTask and PostureTask objectives) and the same collision rows (mink's
        CollisionAvoidanceLimit); the ConfigurationLimit (gain 0.95) and VelocityLimit become the
        bounds lb <= dq <= ub handed to daqp directly, which skips qpsolvers' problem assembly and
        2 x 14 inequality rows. `tests/test_robot_ik.py` checks it gives mink's answer."""
        cfg = self.configuration
        H = self._damping_eye.copy()
        c = np.zeros(len(q))
        for task in (self.tcp_task, self.posture_task):
            Ht, ct = task.compute_qp_objective(cfg)
            H += Ht
            c += ct
        step = self._vmax * dt
        ub = np.minimum(step, self._gain * (self._hi - q))
        lb = np.maximum(-step, self._gain * (self._lo - q))
        rows = [lim.compute_qp_inequalities(cfg, dt) for lim in collision_limits]
        rows = [r for r in rows if r.G is not None]
        if rows:
            G = np.vstack([r.G for r in rows])
            h = np.concatenate([r.h for r in rows])
        else:
            G, h = np.zeros((0, len(q))), np.zeros(0)
        bupper = np.concatenate([ub, h])
        blower = np.concatenate([lb, np.full(len(h), -1e30)])
        x, _, exitflag, _ = daqp.solve(H, c, G, bupper, blower, np.zeros(len(bupper), dtype=ctypes.c_int))
        if exitflag <= 0:
            raise mink.NoSolutionFound("daqp")
        return x / dt

    def set_obstacles(self, standing: dict[str, tuple[float, float] | None]) -> None:
        """Where the objects stand (table x, y), for the arm to keep clear of; None or missing: nowhere."""
        for name, body in self._obstacle_body.items():
            xy = standing.get(name)
            z = TABLE_Z + OBSTACLES[name][1] / 2 if xy is not None else OBSTACLE_AWAY_Z
            self.model.body_pos[body] = (xy[0], xy[1], z) if xy is not None else (0.0, 0.0, z)

    def obstacles(self) -> dict[str, tuple[float, float] | None]:
        """The obstacles as last set (table x, y, or None)."""
        out = {}
        for name, body in self._obstacle_body.items():
            pos = self.model.body_pos[body]
            out[name] = None if pos[2] < 0 else (float(pos[0]), float(pos[1]))
        return out

    def set_posture(self, q: np.ndarray) -> None:
        self.posture_task.set_target(np.asarray(q, float))

    def tcp_pose(self, q: np.ndarray) -> mink.SE3:
        self.configuration.update(np.asarray(q, float))
        return self.configuration.get_transform_frame_to_world("robot_tcp", "site")

    def solve(self, q: np.ndarray, target: mink.SE3, dt: float, collision: bool | None = None) -> IKResult:
        """One differential IK step from arm configuration ``q`` toward ``target`` (TCP pose in world)."""
        use_collision = self.p.collision if collision is None else collision
        q = np.clip(np.asarray(q, float), self.model.jnt_range[:, 0], self.model.jnt_range[:, 1])
        self.configuration.update(q)
        self.tcp_task.set_target(target)
        limits = self.base_limits + (self._active_collision_limits() if use_collision else [])
        t0 = time.perf_counter()
        try:
            if self.p.fast_qp:
                v = self._solve_qp(q, dt, limits[len(self.base_limits):])
            else:
                v = mink.solve_ik(self.configuration, [self.tcp_task, self.posture_task], dt, "daqp",
                                  damping=self.p.damping, limits=limits)
        except mink.NoSolutionFound as exc:
            us = (time.perf_counter() - t0) * 1e6
            err = self.tcp_task.compute_error(self.configuration)
            return IKResult(q.copy(), False, f"IK: no solution ({exc})", float(np.linalg.norm(err[:3])),
                            float(np.linalg.norm(err[3:])), us)
        us = (time.perf_counter() - t0) * 1e6
        self.configuration.integrate_inplace(v, dt)
        q_new = self.configuration.q.copy()
        err = self.tcp_task.compute_error(self.configuration)
        return IKResult(q_new, True, "", float(np.linalg.norm(err[:3])), float(np.linalg.norm(err[3:])), us)


def _max_speed(model: mujoco.MjModel) -> np.ndarray:
    try:
        return np.array(model.numeric("robot_joint_max_speed").data, float)
    except KeyError:
        return np.array([1.0, 1.0, 1.2, 1.2, 1.5, 1.5, 2.0])
