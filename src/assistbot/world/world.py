"""Building the scene for an arrangement, stepping it, and the physical rules that live in Python.

Two pieces of the scene's physics need a line of Python each step, and both are decided by
measured quantities, never by who is doing what:

* the stopper's friction fit: the weld ``stopper_fit`` is deactivated when its measured
  pull-out force (the weld's constraint force along the bottle axis, low-pass filtered over
  ~20 ms) exceeds STOPPER_RELEASE_FORCE.  A bottle standing free is lifted by a pull long
  before that (it weighs ~3.4 N); held down by the robot's gripper, the pull grows until the
  fit gives.
* the human's grip: an equality weld that `World.human_grasp` turns on only when the hand's
  grasp site is at the object and the hand posture is closed, and that `step` turns off as
  soon as the hand opens, or when the force it transmits (low-pass filtered like the stopper's
  pull) exceeds HUMAN_GRIP_YIELD_FORCE: a person's fingers give way under a pull no grip
  withstands, so a tug of war with the robot ends with one holder. The yield lies above the
  stopper's fit (the stopper comes off before the fingers slip off it) and below what the
  robot's friction grip holds.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import mujoco
import numpy as np

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.world import layout
from assistbot.world.arrangement import Arrangement
from assistbot.world.state import in_cylinder, in_glass_region

if TYPE_CHECKING:
    from assistbot.human.population import Body

STOPPER_RELEASE_FORCE = 12.0   # N, pull-out force of the stopper's friction fit
STOPPER_FORCE_TAU = 0.02       # s, low-pass time constant of the measured pull
#: the rendered liquid's height in the glass (m) with every particle inside it
LIQUID_LEVEL_FULL = 0.07
CHECK_EVERY = 5                # physics steps between checks of the stopper fit, the grip and the mouth
GRASP_REACH = 0.03             # m, how far outside an object's surface the grasp site may be
HUMAN_GRIP_YIELD_FORCE = 20.0  # N, force on the human's grip weld at which the fingers give way
HUMAN_GRIP_FORCE_TAU = 0.05    # s, low-pass time constant of that force
MOUTH_RADIUS = 0.04            # m, a particle this close to the mouth site is drunk

ROBOT_ARM_JOINTS = tuple(f"robot_j{i}" for i in range(1, 8))
ROBOT_ARM_ACTUATORS = ROBOT_ARM_JOINTS
ROBOT_FINGER_ACTUATORS = ("robot_finger1", "robot_finger2", "robot_finger3")
ROBOT_HEAD_JOINTS = ("robot_head_pan", "robot_head_tilt")
HUMAN_ARM_JOINTS = (
    "human_r_shoulder_flex", "human_r_shoulder_abd", "human_r_shoulder_rot",
    "human_r_elbow", "human_r_forearm_rot", "human_r_wrist_flex", "human_r_wrist_dev",
)
HUMAN_HAND_JOINTS = (
    "human_r_index_prox", "human_r_index_dist", "human_r_fingers_prox",
    "human_r_fingers_dist", "human_r_thumb_opp", "human_r_thumb_flex",
)
CAMERAS = ("scene_cam", "top_cam", "head_cam_left", "head_cam_right")
#: the objects of the scene; the person's hand can hold each (its weld ``human_hold_<name>``)
OBJECTS = catalogue.NAMES

#: Finger targets (rad) of the human's hand postures, in HUMAN_HAND_JOINTS order.
HAND_POSTURES: dict[str, tuple[float, ...]] = {
    "open": (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    "request": (0.05, 0.05, 0.05, 0.05, -0.2, 0.0),   # open empty palm held out
    "point": (0.0, 0.0, 1.5, 1.5, 0.8, 0.8),
    "ag": (0.9, 0.7, 0.9, 0.7, 1.0, 0.4),              # above grip (from the top)
    "sg": (1.2, 0.9, 1.2, 0.9, 0.9, 0.3),              # side grip
}
_CLOSED_MIN = {"human_r_index_prox": 0.6, "human_r_fingers_prox": 0.6, "human_r_thumb_opp": 0.5}

#: Robot finger targets: open, and "closed" (beyond any object: the servos then squeeze).
GRIPPER_OPEN = -0.3
GRIPPER_CLOSED = 1.6


def build_world(arrangement: Arrangement, seed: int = 0, body: "Body | None" = None) -> "World":
    """Load the scene and place bottle, stopper, glass and liquid as `arrangement` says; the person has
    ``body`` (`assistbot.human.population.Body`; None: the default person's), and the objects at their
    default places in the HWS stand where this person has those places (`human.body.own_places`).

    The seed only jitters the liquid's starting layout (deterministically)."""
    from assistbot.human.body import apply_body, own_places
    from assistbot.human.population import Body

    arrangement.validate()
    body = body or Body()
    arrangement = own_places(arrangement, body)
    spec = apply_body(mujoco.MjSpec.from_file(str(layout.SCENE_XML)), body)
    model = spec.compile()
    world = World(model, arrangement, seed)
    world.human_body = body
    return world


def _quat_x180() -> np.ndarray:
    return np.array([0.0, 1.0, 0.0, 0.0])


class World:
    """The MuJoCo model and data of one scene, with named lookups and ground truth.

    `model`/`data` are plain mujoco.MjModel/MjData (mink works on them directly).  Drive the
    robot and the human through `data.ctrl` (see `actuator`, `set_ctrl`) and advance with
    `step`, which also runs the stopper fit and the human's grip.
    """

    def __init__(self, model: mujoco.MjModel, arrangement: Arrangement, seed: int = 0) -> None:
        self.model = model
        self.data = mujoco.MjData(model)
        self.arrangement = arrangement
        self.seed = int(seed)
        #: the person's body as built in this model (`build_world` sets it; the default person's otherwise)
        self.human_body: Body | None = None
        m = model
        self.body_id = {n: m.body(n).id for n in (*OBJECTS, "human_r_hand", "robot_gripper")}
        self.eq_stopper = m.equality("stopper_fit").id
        self.eq_hold = {o: m.equality(f"human_hold_{o}").id for o in OBJECTS}
        self._eq_hold_ids = np.array(list(self.eq_hold.values()))
        self.site_id = {n: m.site(n).id for n in ("human_r_grasp", "human_mouth", "robot_tcp", "bottle_mouth", "stopper_grasp")}
        self.particle_bodies = np.array([i for i in range(m.nbody) if m.body(i).name.startswith("particle")])
        self.particle_geoms = np.array([m.body_geomadr[b] for b in self.particle_bodies])
        self.particle_qadr = np.array([m.jnt_qposadr[m.body_jntadr[b]] for b in self.particle_bodies])
        self.particle_vadr = np.array([m.jnt_dofadr[m.body_jntadr[b]] for b in self.particle_bodies])
        # geom -> object (its index in OBJECTS, -1 other); geom -> gripper part (1..3 fingers, 4 palm, 0 none)
        gb = m.geom_bodyid
        self.geom_object = np.full(m.ngeom, -1)
        for k, o in enumerate(OBJECTS):
            self.geom_object[gb == self.body_id[o]] = k
        self.geom_gripper = np.zeros(m.ngeom, dtype=int)
        for i in range(m.nbody):
            name = m.body(i).name
            for f in (1, 2, 3):
                if name.startswith(f"robot_f{f}_"):
                    self.geom_gripper[gb == i] = f
        self.geom_gripper[gb == self.body_id["robot_gripper"]] = 4
        self.geom_table = gb == m.body("table").id
        # what a trembling hand's object rests against and stops on: the table and the robot
        self.geom_stiff = self.geom_table | np.array([m.body(b).name.startswith("robot") for b in gb])
        self._hand_qadr = np.array([m.jnt_qposadr[m.joint(j).id] for j in _CLOSED_MIN])
        self._hand_min = np.array(list(_CLOSED_MIN.values()))
        self._liquid_geom = m.geom("glass_visual_liquid").id
        self._particle_alpha = m.geom_rgba[self.particle_geoms, 3].copy()
        self.reset()

    # ---------------------------------------------------------------- setup
    def reset(self) -> None:
        """Put everything at its arrangement's starting pose (time 0, home posture)."""
        m, d = self.model, self.data
        mujoco.mj_resetDataKeyframe(m, d, m.key("home").id)  # robot and human at the scene's home posture, servos holding it
        d.eq_active[:] = m.eq_active0
        for o in OBJECTS:
            d.eq_active[self.eq_hold[o]] = 0
        arr = self.arrangement
        z = layout.TABLE_Z
        for o in catalogue.TASK_OBJECTS:   # upright on the table, or upside down standing on its rim
            x, y = arr.position(o)
            if arr.placement(o).state == "inverted":
                self._set_free(o, (x, y, z + catalogue.height(o)), _quat_x180())
            else:
                self._set_free(o, (x, y, z), (1, 0, 0, 0))
        bx, by = arr.position("bottle")
        if arr.bottle.state == "closed":
            self._set_free("stopper", (bx, by, z + catalogue.height("bottle")), (1, 0, 0, 0))
            d.eq_active[self.eq_stopper] = 1
        else:
            sx, sy = layout.STOPPER_PARK
            self._set_free("stopper", (sx, sy, z + layout.STOPPER_PLUG_DEPTH), (1, 0, 0, 0))
            d.eq_active[self.eq_stopper] = 0
        gx, gy = arr.position("glass")
        # liquid: one layer on the inner floor of its container (particles do not touch each other)
        rng = np.random.default_rng(self.seed)
        n = len(self.particle_bodies)
        if arr.glass.state == "full":
            cx, cy, floor, rin = gx, gy, z + layout.GLASS_BASE_TOP, layout.GLASS_INNER_RADIUS
        else:
            cx, cy, floor, rin = bx, by, z + layout.BOTTLE_BASE_TOP, layout.BOTTLE_INNER_RADIUS
        k = np.arange(n) + 0.5
        rr = (rin - layout.PARTICLE_RADIUS - 0.002) * np.sqrt(k / n)
        th = k * np.pi * (3 - np.sqrt(5)) + rng.uniform(0, 2 * np.pi)
        for i, qa in enumerate(self.particle_qadr):
            d.qpos[qa:qa + 3] = (cx + rr[i] * np.cos(th[i]), cy + rr[i] * np.sin(th[i]), floor + layout.PARTICLE_RADIUS - 0.0002)
            d.qpos[qa + 3:qa + 7] = (1, 0, 0, 0)
        self.drunk = np.zeros(n, dtype=bool)
        m.geom_contype[self.particle_geoms] = 2
        m.geom_conaffinity[self.particle_geoms] = 0
        m.body_gravcomp[self.particle_bodies] = 0.0
        self._stopper_pull = 0.0
        self._grip_load = 0.0
        self.grip_yields: list[tuple[float, str]] = []   # (time, object) where the human's grip gave way
        self._since_check = 0
        mujoco.mj_forward(m, d)
        self.sync_liquid()

    def _set_free(self, body: str, pos, quat) -> None:
        m = self.model
        qa = m.jnt_qposadr[m.body_jntadr[self.body_id[body]]]
        self.data.qpos[qa:qa + 3] = pos
        self.data.qpos[qa + 3:qa + 7] = quat

    # ---------------------------------------------------------------- lookups
    @property
    def time(self) -> float:
        return float(self.data.time)

    def actuator(self, name: str) -> int:
        return self.model.actuator(name).id

    def set_ctrl(self, targets: dict[str, float]) -> None:
        """Set position-servo targets by actuator name (radians)."""
        for name, value in targets.items():
            self.data.ctrl[self.model.actuator(name).id] = value

    def qpos(self, joint: str) -> float:
        return float(self.data.qpos[self.model.jnt_qposadr[self.model.joint(joint).id]])

    def site_pos(self, site: str) -> np.ndarray:
        return self.data.site(site).xpos.copy()

    def set_hand_posture(self, posture: str) -> None:
        """Command one of HAND_POSTURES to the human's finger servos."""
        if posture not in HAND_POSTURES:
            raise UserError("human", "posture", f"unknown hand posture {posture!r}; use one of {', '.join(HAND_POSTURES)}")
        self.set_ctrl(dict(zip(HUMAN_HAND_JOINTS, HAND_POSTURES[posture])))

    def set_gripper(self, closure: float) -> None:
        """Command the robot's three finger servos (0 open .. GRIPPER_CLOSED squeeze)."""
        self.set_ctrl({a: closure for a in ROBOT_FINGER_ACTUATORS})

    def warnings(self) -> dict[str, int]:
        """MuJoCo warnings raised so far (name -> count), empty when none."""
        return {mujoco.mjtWarning(i).name: int(w.number) for i, w in enumerate(self.data.warning) if w.number}

    # ---------------------------------------------------------------- stepping
    def step(self, n: int = 1) -> None:
        """Advance n physics steps (model.opt.timestep each), with the stopper fit, the human grip and the mouth.

        Those three are checked every CHECK_EVERY steps (10 ms) rather than every step: the
        stopper's pull is low-passed over 20 ms anyway, and per-step Python checks cost as much
        as the physics itself. Between checks MuJoCo runs the steps in one call.
        """
        m, d = self.model, self.data
        while n > 0:
            k = min(n, CHECK_EVERY - self._since_check)
            mujoco.mj_step(m, d, nstep=k)
            n -= k
            self._since_check += k
            if self._since_check >= CHECK_EVERY:
                self._since_check = 0
                self._check()

    def sync_liquid(self) -> None:
        """Set the rendered liquid level in the glass from the particles inside it (see objects.xml).

        Particles no camera can see (drunk, wholly inside the opaque body of the bottle, or
        wholly under the rendered liquid surface) are left out of the rendered scene: a renderer
        on the CPU pays for every sphere's vertices, hidden or not; the images are the same
        pixel for pixel.  For rendering only, so stepping does not call it (it would cost as much
        as a fifth of the physics): call it before rendering a world that has been stepped."""
        m, d = self.model, self.data
        pts = d.xpos[self.particle_bodies]
        inside = in_glass_region(self, pts) & ~self.drunk
        h = LIQUID_LEVEL_FULL * float(inside.sum()) / max(1, len(pts))
        g = self._liquid_geom
        m.geom_size[g, 1] = max(0.5 * h, 5e-4)
        m.geom_pos[g, 2] = layout.GLASS_BASE_TOP + 0.5 * h
        shown = h > 0.002
        m.geom_rgba[g, 3] = 1.0 if shown else 0.0
        r = layout.PARTICLE_RADIUS
        bb, gb = self.body_id["bottle"], self.body_id["glass"]
        hidden = self.drunk | in_cylinder(pts, d.xpos[bb], d.xmat[bb].reshape(3, 3), catalogue.radius("bottle") - r, r,
                                          layout.BOTTLE_BODY_TOP - r)
        if shown:
            # resting particles sink a fraction of a millimetre into the glass's base
            hidden |= in_cylinder(pts, d.xpos[gb], d.xmat[gb].reshape(3, 3), m.geom_size[g, 0] - r,
                                  layout.GLASS_BASE_TOP + r - 0.001, layout.GLASS_BASE_TOP + h - r)
        m.geom_rgba[self.particle_geoms, 3] = np.where(hidden, 0.0, self._particle_alpha)

    def _check(self) -> None:
        d = self.data
        if d.eq_active[self.eq_stopper]:
            dt = CHECK_EVERY * self.model.opt.timestep
            self._stopper_pull += dt / (STOPPER_FORCE_TAU + dt) * (self.stopper_pull_force() - self._stopper_pull)
            if self._stopper_pull > STOPPER_RELEASE_FORCE:
                d.eq_active[self.eq_stopper] = 0
        held = self.human_holding()
        if held is not None and not self.hand_closed():
            self.human_release()
        elif held is not None:
            dt = CHECK_EVERY * self.model.opt.timestep
            self._grip_load += dt / (HUMAN_GRIP_FORCE_TAU + dt) * (self.grip_force(held) - self._grip_load)
            if self._grip_load > HUMAN_GRIP_YIELD_FORCE:
                self.human_release()
                self.grip_yields.append((self.time, held))
        if held is None or not d.eq_active[self.eq_hold[held]]:
            self._grip_load = 0.0
        self._drink()

    def stopper_pull_force(self) -> float:
        """The stopper fit's constraint force along the bottle's axis, pulling the stopper out (N)."""
        d = self.data
        # searching only the equality rows keeps this check cheap while contacts fill the rest
        rows = self._eq_rows(self.eq_stopper)
        if rows.size < 3:
            return 0.0
        f = d.efc_force[rows[:3]]
        axis = d.xmat[self.body_id["bottle"]].reshape(3, 3)[:, 2]
        return float(f @ axis)

    def _eq_rows(self, eq: int) -> np.ndarray:
        """The constraint rows of equality ``eq`` (MuJoCo puts the d.ne equality rows first)."""
        d = self.data
        return np.flatnonzero(d.efc_id[:d.ne] == eq)

    def grip_force(self, obj: str) -> float:
        """The force (N) the human's grip weld on ``obj`` transmits now: its translational rows' norm."""
        rows = self._eq_rows(self.eq_hold[obj])
        if rows.size < 3:
            return 0.0
        return float(np.linalg.norm(self.data.efc_force[rows[:3]]))

    # ---------------------------------------------------------------- the human's grip
    def hand_closed(self) -> bool:
        return bool(np.all(self.data.qpos[self._hand_qadr] >= self._hand_min))

    def grasp_distance(self, obj: str) -> float:
        """Distance (m) from the human's grasp site to the surface of `obj` (negative inside)."""
        return self.surface_distance(obj, self.data.site_xpos[self.site_id["human_r_grasp"]])

    def surface_distance(self, obj: str, p: np.ndarray) -> float:
        """Distance (m) from the point ``p`` (world) to the surface of `obj` where it stands now (negative inside)."""
        d = self.data
        b = self.body_id[obj]
        pos, R = d.xpos[b], d.xmat[b].reshape(3, 3)
        local = R.T @ (p - pos)
        if obj == "stopper":
            return float(np.linalg.norm(p - d.site_xpos[self.site_id["stopper_grasp"]]) - catalogue.radius("stopper"))
        height, radius = catalogue.height(obj), catalogue.radius(obj)
        if obj == "bottle" and local[2] > layout.BOTTLE_BODY_TOP:
            radius = 0.0165  # shoulder and neck
        radial = np.hypot(local[0], local[1]) - radius
        axial = max(-local[2], local[2] - height, 0.0)
        return float(max(radial, axial) if radial > 0 or axial > 0 else radial)

    def human_grasp(self, obj: str) -> bool:
        """Close the human's grip on `obj` if the grasp site is at it and the hand is closed.

        Returns whether the grip holds.  The weld keeps the current relative pose, so
        nothing jumps.  A grip needs the site above the table top (never through the table)."""
        if obj not in OBJECTS:
            raise UserError("human", "object", f"unknown object {obj!r}; use one of {', '.join(OBJECTS)}")
        m, d = self.model, self.data
        if not self.hand_closed():
            return False
        if d.site_xpos[self.site_id["human_r_grasp"]][2] < layout.TABLE_Z:
            return False
        if self.grasp_distance(obj) > GRASP_REACH:
            return False
        eq = self.eq_hold[obj]
        h, o = self.body_id["human_r_hand"], self.body_id[obj]
        # relpose = pose of the object in the hand frame
        Rh = d.xmat[h].reshape(3, 3)
        relpos = Rh.T @ (d.xpos[o] - d.xpos[h])
        qh_inv = np.zeros(4)
        mujoco.mju_negQuat(qh_inv, d.xquat[h])
        relq = np.zeros(4)
        mujoco.mju_mulQuat(relq, qh_inv, d.xquat[o])
        m.eq_data[eq, 0:3] = 0.0
        m.eq_data[eq, 3:6] = relpos
        m.eq_data[eq, 6:10] = relq
        m.eq_data[eq, 10] = 1.0
        d.eq_active[eq] = 1
        return True

    def human_release(self, obj: str | None = None) -> None:
        for o in (OBJECTS if obj is None else (obj,)):
            self.data.eq_active[self.eq_hold[o]] = 0

    def hand_braced(self) -> bool:
        """The person's hand rests on something stiff: what it holds touches the table or the robot (its hand
        closing on it, or holding it too), or the hand is at an object standing on the table (within GRASP_REACH
        of its surface, where the fingers close on it)."""
        d = self.data
        n = d.ncon
        if n == 0:
            return False
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        o1, o2 = self.geom_object[g1], self.geom_object[g2]
        held = self.human_holding()
        if held is not None:
            k = OBJECTS.index(held)
            return bool(((o1 == k) & self.geom_stiff[g2]).any() or ((o2 == k) & self.geom_stiff[g1]).any())
        on_table = set(o1[self.geom_table[g2] & (o1 >= 0)].tolist()) | set(o2[self.geom_table[g1] & (o2 >= 0)].tolist())
        return any(OBJECTS[k] in catalogue.TASK_OBJECTS and self.grasp_distance(OBJECTS[k]) < GRASP_REACH for k in on_table)

    def human_holding(self) -> str | None:
        for o in OBJECTS:
            if self.data.eq_active[self.eq_hold[o]]:
                return o
        return None

    # ---------------------------------------------------------------- contacts
    def robot_holding(self) -> str | None:
        """The object the robot's gripper holds by contact: touched by finger 3 and by finger 1 or 2."""
        d = self.data
        n = d.ncon
        if n == 0:
            return None
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        for k, o in enumerate(OBJECTS):
            if o not in catalogue.TASK_OBJECTS:
                continue
            parts = set()
            for a, b in ((g1, g2), (g2, g1)):
                sel = self.geom_object[a] == k
                parts.update(self.geom_gripper[b[sel]].tolist())
            if 3 in parts and (1 in parts or 2 in parts):
                return o
        return None

    def _drink(self) -> None:
        """Particles that reach the mouth are drunk: counted, and parked out of the way."""
        d, m = self.data, self.model
        mouth = d.site_xpos[self.site_id["human_mouth"]]
        pos = d.xpos[self.particle_bodies]
        near = (np.linalg.norm(pos - mouth, axis=1) < MOUTH_RADIUS) & ~self.drunk
        for i in np.flatnonzero(near):
            self.drunk[i] = True
            g, b = self.particle_geoms[i], self.particle_bodies[i]
            m.geom_contype[g] = 0
            m.geom_conaffinity[g] = 0
            m.body_gravcomp[b] = 1.0
            qa, va = self.particle_qadr[i], self.particle_vadr[i]
            d.qpos[qa:qa + 3] = (-0.55, 0.0, 0.80)  # inside the human's torso
            d.qvel[va:va + 6] = 0.0

    def state(self):
        """Ground truth (`WorldState`) for scoring, tests and the oracle perception only."""
        from assistbot.world.state import world_state

        return world_state(self)
