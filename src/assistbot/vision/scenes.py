"""Labelled scenes for calibration, the template library, tests and the accuracy benchmark.

`SceneSampler(seed)` draws random `SceneSpec`s: an arrangement with random positions in the
zones, a head pan/tilt, and a hand posture of the human ("none" at rest, "reach" toward an
object, "grasp_ag"/"grasp_sg" on an object standing, lifted or held out toward the robot,
"open_palm_request", "pointing" at an object).  `pose(world, spec)` puts the scene in that
configuration kinematically (qpos + forward kinematics, no physics: a posture is a still
image) and returns its `Labels`, taken from WorldState and from the spec: labels are for
scoring and for building the library, never for inference.

Seed streams keep the sets apart: the template library and the calibration use
``purpose="library"``, tests and the benchmark ``purpose="test"``/``"bench"``, so that no
frame used to build templates is ever scored.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from functools import lru_cache

import mujoco
import numpy as np

from assistbot import catalogue
from assistbot.human.arm import ORIENT, grip_orientation, own_point, rot_y, rot_z, shoulder_and_reach
from assistbot.human.behaviours import GRASP_HEIGHT, HOLD_OUT, REST, TURN_LIFT, turn_roll
from assistbot.human.ikmodel import arm_model
from assistbot.task import HAND_POSTURES
from assistbot.world import HAND_POSTURES as FINGER_POSTURES, HUMAN_ARM_JOINTS, HUMAN_HAND_JOINTS, layout
from assistbot.world.arrangement import Arrangement, Placement
from assistbot.world.scripted import ik

_PURPOSE = {"library": 1, "test": 2, "bench": 3, "calibrate": 4}
#: finger posture (world.HAND_POSTURES) per perceived hand posture (task.HAND_POSTURES)
_FINGERS = {"none": "open", "reach": "open", "grasp_ag": "ag", "grasp_sg": "sg", "open_palm_request": "request", "pointing": "point",
            "remove_stopper": "ag", "pour": "sg", "drink": "sg"}
HAND_X_MAX = -0.03          # the human's grasp site never goes further toward the robot
#: a posed scene whose hand stayed further than this (m) from where its posture puts it (an object out of
#: this body's reach) is neither scored nor learnt from: its labels would describe a hand that is not there
POSE_TOLERANCE = 0.02


@dataclass
class SceneSpec:
    arrangement: Arrangement
    head: tuple[float, float]                 # pan, tilt (rad)
    posture: str = "none"
    target: str | None = None                 # object reached / grasped / pointed at
    variant: str = "table"                    # grasp: "table", "lifted", "held_out", "turning"; none: "rest", "home"
    jitter: tuple[float, float, float] = (0.0, 0.0, 0.0)
    reach_fraction: float = 0.6
    robot_holds: str | None = None            # object placed in the robot's gripper (tests)
    partner: int | None = None                # the person's population seed (None: the default person)


@dataclass
class Labels:
    """Ground truth of one posed scene (table frame, metres)."""

    objects: dict[str, dict] = field(default_factory=dict)   # name -> state, zone, position, held_by
    posture: str = "none"
    hand_position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    object_in_hand: str | None = None
    held_out: bool = False
    pointed_at: str | None = None
    directed_at: str | None = None
    pose_miss: float = 0.0             # how far (m) the posed hand stayed off where the posture puts it


def _random_position(rng, name: str, zone: str) -> tuple[float, float]:
    xmax, _, inner = layout.standing_limits(catalogue.radius(name))
    xmax, inner = xmax - 0.05, inner + 0.03
    x = rng.uniform(inner, xmax - 0.02)
    y = rng.uniform(-0.30, 0.30)
    return (-x if zone == "HWS" else x, y)


class SceneSampler:
    """Random labelled-scene specs from one seed stream (see module docstring)."""

    def __init__(self, seed: int = 0, purpose: str = "bench", partners: Sequence[int] | None = None,
                 default_share: float = 0.0) -> None:
        self.rng = np.random.default_rng([_PURPOSE[purpose], int(seed)])
        #: each scene's person is drawn from these population seeds (None: always the default person), but
        #: for a ``default_share`` of the scenes, which show the default person
        self.partners = None if partners is None else tuple(int(p) for p in partners)
        self.default_share = float(default_share)

    def arrangement(self) -> Arrangement:
        rng = self.rng
        for _ in range(200):
            zones = {o: str(rng.choice(layout.ZONES)) for o in catalogue.TASK_OBJECTS}
            arr = Arrangement(**{o: Placement(z, str(rng.choice(catalogue.STATES[o])), _random_position(rng, o, z))
                                 for o, z in zones.items()})
            try:
                arr.validate()
            except Exception:  # noqa: BLE001 - overlapping draw: draw again
                continue
            stopper = np.array(layout.STOPPER_PARK)
            if min(np.linalg.norm(np.array(arr.position(o)) - stopper) for o in catalogue.TASK_OBJECTS) < 0.12:
                continue  # keep the removed stopper's place clear of the objects
            return arr
        raise RuntimeError("could not draw a valid arrangement")

    def sample(self, posture: str | None = None) -> SceneSpec:
        """A scene with ``posture`` (else a random one), its person drawn from ``partners`` if given."""
        if self.partners is None:
            return self._sample(posture)
        partner = None if self.rng.random() < self.default_share else int(self.rng.choice(self.partners))
        spec = self._sample(posture)
        spec.partner = partner
        return spec

    def _sample(self, posture: str | None = None) -> SceneSpec:
        rng = self.rng
        posture = posture or str(rng.choice(HAND_POSTURES))
        if posture in ("remove_stopper", "pour", "drink"):
            return self._object_action(posture)
        arr = self.arrangement()
        head = (float(rng.uniform(-0.2, 0.2)), float(rng.uniform(0.65, 0.85)))
        hws = [o for o in catalogue.TASK_OBJECTS if arr.placement(o).zone == "HWS"]
        target, variant = None, "table"
        if posture in ("reach", "grasp_ag", "grasp_sg"):
            if not hws:   # the human reaches only into the HWS: move one object there
                o = str(rng.choice(catalogue.TASK_OBJECTS))
                return self._with_object_in_hws(arr, o, head, posture)
            target = str(rng.choice(hws))
        if posture in ("grasp_ag", "grasp_sg"):
            st = arr.placement(target).state
            variant = str(rng.choice(["table", "lifted", "held_out"])) if st != "inverted" else _inverted_grip(rng, posture)
        if posture == "pointing":
            target = str(rng.choice(catalogue.TASK_OBJECTS))
        if posture == "none":   # resting where the behaviours put the hand, or where a seated person starts
            variant = str(rng.choice(["rest", "home"]))
        jitter = tuple(float(v) for v in rng.uniform(-0.03, 0.03, 3))
        return SceneSpec(arr, head, posture, target, variant, jitter, float(rng.uniform(0.35, 0.75)))

    def _object_action(self, posture: str) -> SceneSpec:
        """remove_stopper: a closed bottle (standing in the HWS or held out); pour: an open bottle
        tilted over an upright glass in the HWS; drink: the glass at the mouth."""
        rng = self.rng
        need = {"remove_stopper": ("closed", None), "pour": ("open", "empty"), "drink": (None, "full")}[posture]
        for _ in range(200):
            arr = self.arrangement()
            b, g = arr.bottle, arr.glass
            bs = need[0] or b.state
            gs = need[1] if need[1] != "empty" else str(rng.choice(["empty", "full"]))
            gs = gs or g.state
            if posture == "drink":
                gs = str(rng.choice(["full", "empty"]))
            bz = "HWS" if posture in ("remove_stopper", "pour") else b.zone
            gz = "HWS" if posture in ("pour", "drink") else g.zone
            gp = g.position if gz == g.zone else _random_position(rng, "glass", gz)
            if posture == "pour":   # within the right hand's comfortable reach
                gp = (float(rng.uniform(-0.30, -0.12)), float(rng.uniform(-0.35, 0.0)))
            new = Arrangement(Placement(bz, bs, b.position if bz == b.zone else _random_position(rng, "bottle", bz)),
                              Placement(gz, gs, gp))
            try:
                new.validate()
            except Exception:  # noqa: BLE001
                continue
            break
        else:
            raise RuntimeError(f"could not draw an arrangement for {posture}")
        # drinking: the robot looks at its partner's face (the mouth is above the view at 0.65+)
        head = (float(rng.uniform(-0.2, 0.2)), float(rng.uniform(0.40, 0.60) if posture == "drink" else rng.uniform(0.65, 0.85)))
        target = {"remove_stopper": "bottle", "pour": "bottle", "drink": "glass"}[posture]
        variant = str(rng.choice(["table", "held_out"])) if posture == "remove_stopper" else "table"
        jitter = tuple(float(v) for v in rng.uniform(-0.03, 0.03, 3))
        return SceneSpec(new, head, posture, target, variant, jitter, float(rng.uniform(0.0, 1.0)))

    def _with_object_in_hws(self, arr: Arrangement, o: str, head, posture: str) -> SceneSpec:
        for _ in range(50):
            p = arr.placement(o)
            moved = Placement("HWS", p.state, _random_position(self.rng, o, "HWS"))
            new = Arrangement(**{n: moved if n == o else arr.placement(n) for n in catalogue.TASK_OBJECTS})
            try:
                new.validate()
                break
            except Exception:  # noqa: BLE001
                continue
        else:
            raise RuntimeError("could not place an object in the HWS")
        st = new.placement(o).state
        variant = "table"
        if posture.startswith("grasp"):
            variant = str(self.rng.choice(["table", "lifted", "held_out"])) if st != "inverted" else _inverted_grip(self.rng, posture)
        jitter = tuple(float(v) for v in self.rng.uniform(-0.03, 0.03, 3))
        return SceneSpec(new, head, posture, o, variant, jitter, float(self.rng.uniform(0.35, 0.75)))


def by_person(specs: Sequence[SceneSpec], seed: int = 0) -> Iterator[tuple[object, list[SceneSpec]]]:
    """The specs grouped by the person they show, each group with a world of that person (built in the
    physics, `human.population`): one world, and one renderer for it, per person rather than per scene."""
    from assistbot.human.population import sample_partner
    from assistbot.world import PAPER_ARRANGEMENTS, build_world

    for person in sorted({s.partner for s in specs}, key=lambda p: -1 if p is None else p):
        body = None if person is None else sample_partner(person).body
        yield build_world(PAPER_ARRANGEMENTS["fig3"], seed, body=body), [s for s in specs if s.partner == person]


# ---------------------------------------------------------------------------- posing
def _hold_out_habit(partner: int | None) -> np.ndarray:
    """Where this partner habitually holds things out, relative to HOLD_OUT (the default person: nowhere else)."""
    if partner is None:
        return np.zeros(3)
    from assistbot.human.population import sample_partner

    p = sample_partner(partner)
    return np.array([p.hold_out_dx, p.hold_out_dy, p.hold_out_dz])


@lru_cache(maxsize=256)
def _shoulder_and_reach(body) -> tuple[np.ndarray, float]:
    return shoulder_and_reach(arm_model(body))


class _Person:
    """The posed person's own points: the behaviours' named points (HOLD_OUT, REST) and grip bearings as
    this body has them (`human.arm.own_point`); the default person's exactly."""

    def __init__(self, world) -> None:
        self.shoulder, self.reach = _shoulder_and_reach(getattr(world, "human_body", None))
        self.shoulder_xy = self.shoulder[:2].copy()

    def point(self, p) -> np.ndarray:
        return own_point(p, self.shoulder, self.reach)

    def grip(self, kind: str, target) -> np.ndarray:
        return grip_orientation(kind, target, self.shoulder_xy)


def _qadr(world, joint: str) -> int:
    return int(world.model.jnt_qposadr[world.model.joint(joint).id])


def _move_free(world, body: str, pos, R=None) -> None:
    """Move an upright free body to `pos` (rotated by R, 3x3, about its origin, if given), and with it
    rigidly the particles inside (a full glass, the bottle's liquid) and a bottle's stopper."""
    m, d = world.model, world.data
    qa = m.jnt_qposadr[m.body_jntadr[world.body_id[body]]]
    base = d.qpos[qa:qa + 3].copy()
    pos = np.asarray(pos, float)
    keep = R is None
    R = np.eye(3) if keep else np.asarray(R, float)

    def move(a: int) -> None:
        d.qpos[a:a + 3] = pos + R @ (d.qpos[a:a + 3] - base)

    if body in ("bottle", "glass"):
        pts = d.qpos[world.particle_qadr[:, None] + np.arange(3)]
        inside = np.hypot(pts[:, 0] - base[0], pts[:, 1] - base[1]) < 0.045
        inside &= (pts[:, 2] > base[2] - 0.01) & (pts[:, 2] < base[2] + 0.2)
        for i in np.flatnonzero(inside):
            move(world.particle_qadr[i])
    if body == "bottle" and d.eq_active[world.eq_stopper]:
        sa = m.jnt_qposadr[m.body_jntadr[world.body_id["stopper"]]]
        move(sa)
    d.qpos[qa:qa + 3] = pos
    if not keep:
        q = np.empty(4)
        mujoco.mju_mat2Quat(q, R.ravel())
        d.qpos[qa + 3:qa + 7] = q
        if body == "bottle" and d.eq_active[world.eq_stopper]:
            d.qpos[sa + 3:sa + 7] = q


def _turn(world, o: str, grip_at, R, fraction: float):
    """Mid-turn of an inverted glass, as the person's turn-glass behaviour does it: lifted `TURN_LIFT`
    in a side grip and rolled `fraction` of half a turn about the fingers' direction; the glass
    follows the hand rigidly.  Returns the hand's new grasp point and orientation."""
    d = world.data
    Rr = turn_roll(R, fraction)
    hand = grip_at + np.array([0, 0, TURN_LIFT])
    b = world.body_id[o]
    _move_free(world, o, hand + Rr @ (d.xpos[b] - grip_at), Rr @ d.xmat[b].reshape(3, 3))
    mujoco.mj_kinematics(world.model, d)
    return hand, Rr @ R


def _set_arm(world, target, R) -> float:
    """Pose the arm with its grasp site at ``target`` (orientation R), as near as the body allows; returns
    how far (m) the grasp site stayed off the target."""
    q = ik(world, "human_r_grasp", target, R, joints=HUMAN_ARM_JOINTS, iters=200)
    for j, v in q.items():
        world.data.qpos[_qadr(world, j)] = v
    mujoco.mj_kinematics(world.model, world.data)
    return float(np.linalg.norm(world.data.site_xpos[world.site_id["human_r_grasp"]] - np.asarray(target, float)))


def _set_fingers(world, posture: str) -> None:
    for j, v in zip(HUMAN_HAND_JOINTS, FINGER_POSTURES[posture]):
        world.data.qpos[_qadr(world, j)] = v


def _inverted_grip(rng, posture: str) -> str:
    """An inverted glass is gripped where it stands, or (a side grip, half the time) mid-turn."""
    return "turning" if posture == "grasp_sg" and rng.random() < 0.5 else "table"


def pose(world, spec: SceneSpec) -> Labels:
    """Put `world` into `spec` (kinematically) and return the scene's labels."""
    m, d = world.model, world.data
    world.arrangement = spec.arrangement
    world.reset()
    person = _Person(world)
    misses = [0.0]
    hold_out = person.point(HOLD_OUT + _hold_out_habit(spec.partner))
    rest = person.point(REST)
    d.qpos[_qadr(world, "robot_head_pan")] = spec.head[0]
    d.qpos[_qadr(world, "robot_head_tilt")] = spec.head[1]
    jit = np.asarray(spec.jitter)
    held_out = False
    in_hand = None
    if spec.posture in ("grasp_ag", "grasp_sg"):
        grip = spec.posture[-2:]
        o = spec.target
        base = d.xpos[world.body_id[o]].copy()
        upright = not (o == "glass" and spec.arrangement.glass.state == "inverted")
        if spec.variant == "lifted":
            base = base + np.array([0, 0, 0.07]) + np.array([jit[0], jit[1], 0])
        elif spec.variant == "held_out":
            # where the person's hold-out behaviour puts an object's base (measured in episodes: ~1 cm past HOLD_OUT)
            base = np.array([hold_out[0] + 0.01 + jit[0], hold_out[1] + jit[1], 0.88 + (hold_out[2] - HOLD_OUT[2]) + 0.5 * jit[2]])
            held_out = True
        if spec.variant in ("lifted", "held_out"):
            _move_free(world, o, base)
            mujoco.mj_kinematics(m, d)
        h = GRASP_HEIGHT[(o, grip)]
        target = base + np.array([0, 0, h if upright else catalogue.height("glass") - h])
        R = person.grip(grip, target)
        if grip == "sg":
            target = target - 0.8 * catalogue.radius(o) * R[:, 2] * 0  # grasp site at the object's axis
        if spec.variant == "turning":
            target, R = _turn(world, o, target, R, spec.reach_fraction)
        misses.append(_set_arm(world, target, R))
        _set_fingers(world, grip)
        in_hand = o
    elif spec.posture == "reach":
        o = spec.target
        base = d.xpos[world.body_id[o]].copy()
        grip = "ag" if spec.reach_fraction > 0.55 else "sg"
        goal = base + np.array([0, 0, GRASP_HEIGHT[(o, grip)] + 0.06])
        p = rest + spec.reach_fraction * (goal - rest) + 0.5 * jit
        p[0] = min(p[0], HAND_X_MAX)
        misses.append(_set_arm(world, p, person.grip(grip, goal)))
        _set_fingers(world, "open")
    elif spec.posture == "open_palm_request":
        p = hold_out + jit
        misses.append(_set_arm(world, p, person.grip("request", p)))
        _set_fingers(world, "request")
        held_out = True
    elif spec.posture == "pointing":
        o = spec.target
        tgt = d.xpos[world.body_id[o]].copy() + np.array([0, 0, 0.10])
        hand0 = rest
        dvec = tgt - hand0
        dvec[2] = 0
        dist = 0.15 + 0.05 * (jit[0] / 0.03)
        p = tgt - dist * dvec / np.linalg.norm(dvec) + np.array([0, jit[1], 0.05 + jit[2]])
        p[0] = min(p[0], HAND_X_MAX)
        misses.append(_set_arm(world, p, person.grip("point", tgt)))
        _set_fingers(world, "point")
    elif spec.posture == "remove_stopper":
        o = "bottle"
        if spec.variant == "held_out":   # held out toward the robot (which would hold it steady)
            base = np.array([hold_out[0] - 0.04 + jit[0], hold_out[1] + jit[1], 0.85 + (hold_out[2] - HOLD_OUT[2]) + 0.5 * jit[2]])
            _move_free(world, o, base)
            mujoco.mj_kinematics(m, d)
        s_ = d.site_xpos[world.site_id["stopper_grasp"]].copy()
        p = s_ + np.array([0, 0, 0.04 * spec.reach_fraction])       # pulling: 0-4 cm above the stopper
        misses.append(_set_arm(world, p, person.grip("ag", p)))
        _set_fingers(world, "ag")
    elif spec.posture == "pour":
        misses.append(_pose_pour(world, spec, person))
        in_hand = "bottle"
    elif spec.posture == "drink":
        misses.append(_pose_drink(world, spec))
        in_hand = "glass"
    elif spec.variant == "home":  # none: the hand about where the world starts it (a passive user's hand)
        mujoco.mj_kinematics(m, d)
        p = d.site_xpos[world.site_id["human_r_grasp"]] + jit * np.array([1.0, 1.0, 0.5])
        misses.append(_set_arm(world, p, d.site_xmat[world.site_id["human_r_grasp"]].reshape(3, 3).copy()))
        _set_fingers(world, "open")
    else:  # none: hand near the resting place
        p = rest + jit * np.array([1.0, 1.0, 0.5])
        misses.append(_set_arm(world, p, person.grip("ag", p + np.array([0.2, 0, 0]))))
        _set_fingers(world, "open")
    if spec.robot_holds:
        _robot_hold(world, spec.robot_holds)
    mujoco.mj_forward(m, d)
    world.sync_liquid()
    lab = labels_of(world, spec, in_hand, held_out)
    lab.pose_miss = max(misses)
    return lab


def _hold_in_hand(world, o: str, R0: np.ndarray, grasp: float) -> None:
    """Put object o in the human's hand as a grip with hand orientation R0 (object upright) would
    hold it, at the hand's actual pose (grasp: grasp-site height above the object's base)."""
    mujoco.mj_kinematics(world.model, world.data)
    site = world.site_id["human_r_grasp"]
    p = world.data.site_xpos[site].copy()
    Ra = world.data.site_xmat[site].reshape(3, 3)
    Ro = Ra @ R0.T
    _move_free(world, o, p - Ro @ np.array([0, 0, grasp]), Ro)


def _pose_pour(world, spec: SceneSpec, person: _Person) -> float:
    """The open bottle in a side grip, rolled about the fingers' axis (100-130 deg) so that its
    mouth is over the glass (the glass beside the hand, toward the palm)."""
    d = world.data
    jit = np.asarray(spec.jitter)
    g = d.xpos[world.body_id["glass"]].copy()
    b = g[:2] - person.shoulder_xy
    b = np.append(b / np.linalg.norm(b), 0.0)                     # fingers' bearing
    a = np.array([-b[1], b[0], 0.0])                              # toward the palm (the midline side)
    theta = np.radians(100 + 30 * spec.reach_fraction)
    k = np.cross([0, 0, 1.0], a)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    Rt = np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K
    mouth = g + np.array([0, 0, catalogue.height("glass") + 0.03]) + 0.5 * jit
    base = mouth - Rt @ np.array([0, 0, catalogue.height("bottle")])
    h = GRASP_HEIGHT[("bottle", "sg")]
    R0 = rot_z(float(np.arctan2(b[1], b[0]))) @ ORIENT["sg"]
    miss = _set_arm(world, base + Rt @ np.array([0, 0, h]), Rt @ R0)
    _set_fingers(world, "sg")
    _hold_in_hand(world, "bottle", R0, h)
    return miss


def _pose_drink(world, spec: SceneSpec) -> float:
    """The glass in a side grip at the mouth, tilted toward the face (0.3-1.4 rad)."""
    jit = np.asarray(spec.jitter)
    mouth = world.site_pos("human_mouth")
    tilt = 0.3 + 1.1 * spec.reach_fraction
    Rc = rot_z(0.75) @ ORIENT["sg"]
    Rg = rot_y(-tilt)
    h = GRASP_HEIGHT[("glass", "sg")]
    lip = np.array([0, 0, catalogue.height("glass") - h]) + np.array([-layout.GLASS_INNER_RADIUS, 0, 0])
    away = 0.04 * (1 + jit[0] / 0.03)
    p = mouth + np.array([0.015 + away, jit[1], -0.015 - 0.5 * away]) - Rg @ lip
    miss = _set_arm(world, p, Rg @ Rc)
    _set_fingers(world, "sg")
    _hold_in_hand(world, "glass", Rc, h)
    return miss


def _robot_hold(world, o: str) -> None:
    """Put the robot's TCP at a point in the RWS and the object in its closed gripper."""
    m, d = world.model, world.data
    target = np.array([0.28, -0.02, layout.TABLE_Z + 0.22])
    joints = tuple(f"robot_j{i}" for i in range(1, 8))
    q = ik(world, "robot_tcp", target, None, joints=joints, iters=300)
    for j, v in q.items():
        d.qpos[_qadr(world, j)] = v
    for f in (1, 2, 3):
        for part in ("prox", "dist"):
            name = f"robot_f{f}_{part}"
            try:
                d.qpos[_qadr(world, name)] = 0.9 if part == "prox" else 0.5
            except KeyError:
                pass
    mujoco.mj_kinematics(m, d)
    tcp = d.site_xpos[world.site_id["robot_tcp"]].copy()
    mid = 0.09 if o == "bottle" else 0.05
    _move_free(world, o, tcp - np.array([0, 0, mid]))


def labels_of(world, spec: SceneSpec, in_hand: str | None, held_out: bool) -> Labels:
    st = world.state()
    lab = Labels(posture=spec.posture, object_in_hand=in_hand, held_out=held_out)
    for o in catalogue.TASK_OBJECTS:
        os_ = st.objects[o]
        p = np.array(os_.pos)
        p[2] -= layout.TABLE_Z
        if os_.inverted:     # the base it stands on is the rim side: the glass's height below the body origin
            p[2] -= catalogue.height("glass")
        # WorldState's words: a glass rolled past 45 deg from upside down (mid-turn) is no longer "inverted"
        state = st.state_of(o)
        held = "human" if in_hand == o else ("robot" if spec.robot_holds == o else None)
        zone = "RWS" if held == "robot" else ("HWS" if held == "human" and not held_out else layout.zone_of(p[0]))
        lab.objects[o] = {"state": state, "zone": zone, "position": tuple(float(v) for v in p), "held_by": held}
    hp = world.site_pos("human_r_grasp")
    hp[2] -= layout.TABLE_Z
    lab.hand_position = tuple(float(v) for v in hp)
    if spec.posture == "pointing":
        lab.pointed_at = spec.target
    if spec.posture in ("reach", "grasp_ag", "grasp_sg", "remove_stopper", "pour", "drink"):
        lab.directed_at = spec.target
    return lab
