"""Room for the person's hand beside the robot's on an object both hold: what the eyes judge before a grip.

A person taking a glass from someone's hand does not put their fingers where the other hand is: they see
where it holds the glass and take it where there is room. `clearance` places the person's hand, its fingers
in a grip's closed posture, in a candidate pose (its grasp site at a point, the hand turned as the grip
has it) and measures the gap to the robot's hand as it is now (`mujoco.mj_geomDistance` between every
pair of their geoms; negative: they would overlap by that much). Nothing moves: the hand's geoms are placed
in a scratch copy of the data.
"""

from __future__ import annotations

import weakref

import mujoco
import numpy as np

from assistbot.world import HAND_POSTURES, HUMAN_HAND_JOINTS

#: the person's hand body and grasp site, and the robot's hand body (each with the bodies below it)
PERSON_HAND = "human_r_hand"
PERSON_GRASP_SITE = "human_r_grasp"
ROBOT_HAND = "robot_gripper"
#: m: gaps beyond this count as this (mj_geomDistance's search bound)
FAR = 0.1


def subtree_geoms(m: mujoco.MjModel, body: str) -> np.ndarray:
    """The geoms of ``body`` and of every body below it."""
    inside = {m.body(body).id}
    for b in range(m.nbody):      # MuJoCo numbers a body after its parent
        if m.body_parentid[b] in inside:
            inside.add(b)
    return np.array([g for g in range(m.ngeom) if m.geom_bodyid[g] in inside], int)


class HandRoom:
    """The clearance between the person's hand in a grip and the robot's hand, in one world."""

    def __init__(self, model: mujoco.MjModel) -> None:
        self.model = model
        self.scratch = mujoco.MjData(model)
        self.mine = subtree_geoms(model, PERSON_HAND)
        self.robots = subtree_geoms(model, ROBOT_HAND)
        self._shape: dict[str, tuple[np.ndarray, np.ndarray]] = {}

    def hand_in(self, posture: str) -> tuple[np.ndarray, np.ndarray]:
        """The person's hand geoms relative to the grasp site (positions, orientations in the hand's frame),
        the fingers in ``posture``: the MJCF's hand, bent as the posture bends it."""
        if posture not in self._shape:
            m, d = self.model, mujoco.MjData(self.model)
            for j, q in zip(HUMAN_HAND_JOINTS, HAND_POSTURES[posture]):
                d.qpos[m.joint(j).qposadr[0]] = q
            mujoco.mj_kinematics(m, d)
            hb = m.body(PERSON_HAND).id
            R = d.xmat[hb].reshape(3, 3)
            site = d.site_xpos[m.site(PERSON_GRASP_SITE).id]
            pos = (d.geom_xpos[self.mine] - site) @ R
            rot = np.einsum("ji,njk->nik", R, d.geom_xmat[self.mine].reshape(-1, 3, 3))
            self._shape[posture] = (pos, rot)
        return self._shape[posture]

    def clearance(self, data: mujoco.MjData, posture: str, site: np.ndarray, R: np.ndarray) -> float:
        """The least gap (m) between the person's hand, fingers in ``posture``, its grasp site at ``site`` and
        the hand turned ``R`` (world), and the robot's hand where ``data`` has it; FAR at most."""
        s, m = self.scratch, self.model
        s.geom_xpos[self.robots] = data.geom_xpos[self.robots]
        s.geom_xmat[self.robots] = data.geom_xmat[self.robots]
        pos, rot = self.hand_in(posture)
        s.geom_xpos[self.mine] = np.asarray(site, float) + pos @ R.T
        s.geom_xmat[self.mine] = np.einsum("ij,njk->nik", R, rot).reshape(-1, 9)
        gap = FAR
        for g in self.mine:
            for r in self.robots:
                gap = min(gap, mujoco.mj_geomDistance(m, s, int(g), int(r), FAR, None))
        return float(gap)


_ROOM: "weakref.WeakKeyDictionary[object, HandRoom]" = weakref.WeakKeyDictionary()


def hand_room(world) -> HandRoom:
    """The `HandRoom` of a world, built once."""
    got = _ROOM.get(world)
    if got is None:
        got = _ROOM[world] = HandRoom(world.model)
    return got
