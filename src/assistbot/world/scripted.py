"""Scripted joint-space motion for tests, snapshots and demos: a small IK and target ramps.

This is not the robot's controller (that is `assistbot.robot`, with mink); it only turns a
wanted site pose into joint targets (damped least squares on a scratch MjData) and ramps
servo targets over time, so that the scene's physical facts can be shown without cognition.
"""

from __future__ import annotations

from typing import Callable, Sequence

import mujoco
import numpy as np


def ik(world, site: str, pos, mat=None, joints: Sequence[str] = (), q_start: dict | None = None,
       iters: int = 300, damping: float = 1e-3) -> dict[str, float]:
    """Joint angles that put `site` at world `pos` (and orientation `mat`, 3x3, if given)."""
    m = world.model
    d = mujoco.MjData(m)
    d.qpos[:] = world.data.qpos
    jid = [m.joint(j).id for j in joints]
    qadr = np.array([m.jnt_qposadr[j] for j in jid])
    vadr = np.array([m.jnt_dofadr[j] for j in jid])
    lo, hi = m.jnt_range[jid, 0], m.jnt_range[jid, 1]
    if q_start:
        for j, v in q_start.items():
            d.qpos[m.jnt_qposadr[m.joint(j).id]] = v
    sid = m.site(site).id
    target = np.asarray(pos, float)
    jp, jr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
    for _ in range(iters):
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        err = [target - d.site_xpos[sid]]
        mujoco.mj_jacSite(m, d, jp, jr, sid)
        J = [jp[:, vadr]]
        if mat is not None:
            R = d.site_xmat[sid].reshape(3, 3)
            e = 0.5 * (np.cross(R[:, 0], mat[:, 0]) + np.cross(R[:, 1], mat[:, 1]) + np.cross(R[:, 2], mat[:, 2]))
            err.append(e * 0.5)
            J.append(jr[:, vadr] * 0.5)
        e = np.concatenate(err)
        if np.linalg.norm(e) < 1e-5:
            break
        Jm = np.vstack(J)
        dq = Jm.T @ np.linalg.solve(Jm @ Jm.T + damping * np.eye(len(e)), e)
        d.qpos[qadr] = np.clip(d.qpos[qadr] + dq, lo, hi)
    return {j: float(d.qpos[a]) for j, a in zip(joints, qadr)}


def ramp(world, targets: dict[str, float], duration: float, hold: float = 0.0,
         each_step: Callable[[], None] | None = None) -> None:
    """Move position-servo targets (by actuator name) linearly to `targets` over `duration` s, then hold."""
    m = world.model
    ids = np.array([m.actuator(n).id for n in targets])
    start = world.data.ctrl[ids].copy()
    goal = np.array(list(targets.values()))
    n = max(1, int(round(duration / m.opt.timestep)))
    for k in range(1, n + 1):
        world.data.ctrl[ids] = start + (goal - start) * (k / n)
        world.step(1)
        if each_step:
            each_step()
    if hold > 0:
        for _ in range(int(round(hold / m.opt.timestep))):
            world.step(1)
            if each_step:
                each_step()
