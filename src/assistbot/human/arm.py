"""The human's right arm: minimum-jerk hand motions solved by damped least-squares IK.

Frames: targets are poses of the site ``human_r_grasp`` (the centre of a grip, in front of
the palm) in world coordinates (metres; x from the human toward the robot, z up from the
floor).  Orientations are rotation matrices whose columns are the hand's axes in the world:
the hand's -z points along the fingers, +y out of the palm.

Each control tick (`tick`, default 20 ms) the arm evaluates its current minimum-jerk
segment, takes one or two IK steps on a 7-joint model of the arm alone (`ikmodel`) from
the previously commanded joint angles, and writes those angles to the arm's position
servos in the scene.  Joint speeds are bounded (a person with a motor impairment), so the
servo targets never jump.

The middle line: a target whose x lies beyond `HANDOVER_X_MAX` is clamped there and the
attempt is logged in `clamped` (the hand never crosses the middle line beyond the hand-over
zone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from assistbot.human.dls import bounded, dls_step, pose_at
from assistbot.human.ikmodel import arm_model
from assistbot.human.tremor import Tremor
from assistbot.interfaces import CONTROL_DT
from assistbot.world import HAND_POSTURES, HUMAN_ARM_JOINTS, HUMAN_HAND_JOINTS, layout

#: the hand-over zone reaches this far across the middle line (world/table x, m)
HANDOVER_X_MAX = 0.05
#: how far the open, straight fingers reach beyond the grasp site (m; the distal finger capsules'
#: centres, measured 0.086 m): the site is clamped this far back from HANDOVER_X_MAX
FINGER_REACH = 0.10
#: lowest grasp-site height (world z, m): 2 cm above the table top
MIN_Z = 0.77
#: a reach that starts with the grasp site below this height (world z) first lifts the hand
LIFT_BELOW_Z = 0.84
MAX_JOINT_SPEED = 1.2       # rad/s, any arm joint
MIN_DURATION = 0.4          # s, shortest reach
ANGULAR_SPEED = 1.0         # rad/s mean hand rotation speed of a reach
SETTLED_STEP = 1e-6         # rad: an IK step below this at rest ends the IK until the next motion
#: s a rehearsed move goes on after its command has arrived, as a live one goes on while the measured hand
#: catches up and the next move is begun (what makes a rehearsal foretell the pours: docs/measurements.md)
SERVO_LAG = 0.25


def _rot(z_axis, y_axis) -> np.ndarray:
    z = np.asarray(z_axis, float)
    z = z / np.linalg.norm(z)
    y = np.asarray(y_axis, float)
    y = y - z * (y @ z)
    y = y / np.linalg.norm(y)
    return np.column_stack([np.cross(y, z), y, z])


def rot_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


#: hand orientations (columns: hand x, y, z in the world)
ORIENT = {
    # fingers forward (+x), palm facing down: grasping from above
    "ag": _rot([-1, 0, 0], [0, 0, -1]),
    # fingers forward, palm facing the midline (+y), thumb up: a side grip / handshake
    "sg": _rot([-1, 0, 0], [0, 1, 0]),
    # open palm up, fingers toward the robot: a request
    "request": _rot([-1, 0, 0], [0, 0, 1]),
    # index toward the robot, palm down (like ag)
    "point": _rot([-1, 0, 0], [0, 0, -1]),
}


def shoulder_and_reach(m: mujoco.MjModel) -> tuple[np.ndarray, float]:
    """The right shoulder (world, m) of an arm model and its reach: the grasp site's distance from the
    shoulder with the arm straight (its zero posture)."""
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    shoulder = d.xpos[m.body("human_r_upper_arm").id].copy()
    return shoulder, float(np.linalg.norm(d.site_xpos[m.site("human_r_grasp").id] - shoulder))


#: the default person's right shoulder and reach, read from the model: the points the behaviours name
#: (where things are held out, where the hand rests) are this person's, and move with another's body
DEFAULT_SHOULDER, DEFAULT_REACH = shoulder_and_reach(arm_model())
#: the default person's shoulder (table x, y)
SHOULDER_XY = DEFAULT_SHOULDER[:2].copy()
#: the direction (world) in which a tremor moves the hand: mostly up and down, partly sideways
TREMOR_DIRECTION = np.array([0.0, 0.6, 0.8])
#: s over which the tremor fades when the hand comes to rest on something stiff, and returns when it is free again
TREMOR_SUPPORT_TAU = 0.15
#: the hand trembles freely (and its tremor is measured, `tremor.Tremor.observe`) once it makes this much of it
TREMOR_FREE = 0.99


def own_point(p, shoulder: np.ndarray, reach: float) -> np.ndarray:
    """A point named for the default person (where it holds things out, rests its hand) as the person
    with this right ``shoulder`` (world) and ``reach`` has it: the same place relative to the shoulder,
    in proportion to the reach."""
    p = np.asarray(p, float)
    if reach == DEFAULT_REACH and np.array_equal(shoulder, DEFAULT_SHOULDER):
        return p       # the default person: exactly the point named
    return shoulder + (p - DEFAULT_SHOULDER) * (reach / DEFAULT_REACH)


def own_table_spot(xy, shoulder: np.ndarray, reach: float, radius: float) -> np.ndarray:
    """A table spot (x, y) named for the default person (where an object stands, where it is put down) as
    the person with this ``shoulder`` and ``reach`` has it (`own_point` at the table top), kept on the
    table and on the person's half for an object of ``radius``."""
    x, y = own_point([xy[0], xy[1], layout.TABLE_Z], shoulder, reach)[:2]
    xmax, ymax, inner = layout.standing_limits(radius)
    return np.array([min(max(x, -xmax), -inner), min(max(y, -ymax), ymax)])


def rot_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def grip_orientation(kind: str, target, shoulder_xy=SHOULDER_XY) -> np.ndarray:
    """ORIENT[kind] turned about the vertical so the fingers point along the shoulder->target bearing."""
    d = np.asarray(target, float)[:2] - np.asarray(shoulder_xy, float)[:2]
    return rot_z(float(np.arctan2(d[1], d[0]))) @ ORIENT[kind]


def _log_rot(R: np.ndarray) -> np.ndarray:
    """Rotation vector of R (axis * angle)."""
    c = min(1.0, max(-1.0, (R[0, 0] + R[1, 1] + R[2, 2] - 1.0) * 0.5))
    a = math.acos(c)
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if a < 1e-6:
        return 0.5 * w
    if a > np.pi - 1e-4:
        # near pi: axis from the symmetric part
        k = np.argmax(np.diag(R))
        v = R[:, k] + np.eye(3)[k]
        return a * v / np.linalg.norm(v)
    return (a / (2.0 * math.sin(a))) * w


def _skew(k: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])


def _exp_rot(w: np.ndarray) -> np.ndarray:
    a = float(np.linalg.norm(w))
    if a < 1e-9:
        return np.eye(3)
    K = _skew(w / a)
    return _I3 + math.sin(a) * K + (1.0 - math.cos(a)) * (K @ K)


_I3 = np.eye(3)


def min_jerk(s: float) -> float:
    """Minimum-jerk progress 10s^3 - 15s^4 + 6s^5 of a normalised time s in [0, 1]."""
    s = min(max(s, 0.0), 1.0)
    return s * s * s * (10.0 + s * (-15.0 + 6.0 * s))


@dataclass
class Segment:
    t0: float
    duration: float
    p0: np.ndarray
    p1: np.ndarray
    R0: np.ndarray
    dw: np.ndarray          # rotation vector from R0 to R1 (world frame)

    def __post_init__(self) -> None:
        self._dp = self.p1 - self.p0
        self._angle = float(np.linalg.norm(self.dw))
        K = _skew(self.dw / self._angle) if self._angle > 1e-9 else np.zeros((3, 3))
        self._K, self._K2 = K @ self.R0, (K @ K) @ self.R0

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        return pose_at(min_jerk((t - self.t0) / self.duration), self.p0, self._dp, self.R0, self._K, self._K2, self._angle)

    def done(self, t: float) -> bool:
        return t >= self.t0 + self.duration


class HumanArm:
    """Drives the human's right arm and hand in a `World` (see module docstring).

    speed: mean hand speed (m/s) of a reach; a reach of distance d lasts
    max(MIN_DURATION, d / speed, rotation / ANGULAR_SPEED) seconds. The arm is the world's person's
    (``world.human_body``). A tremor (amplitude m, frequency Hz) moves the hand along TREMOR_DIRECTION all
    the time, at rest too, by that amplitude as the measured hand makes it (`tremor.Tremor`), but while the
    hand is braced on something stiff (`World.hand_braced`: what it holds rests on the table or in the robot's
    hand), where it stops.
    """

    def __init__(self, world, speed: float = 0.2, dt: float = CONTROL_DT, tremor_amplitude: float = 0.0,
                 tremor_frequency: float = 6.0) -> None:
        if speed <= 0:
            raise ValueError(f"speed must be > 0 m/s, got {speed}")
        self.world = world
        self.speed = float(speed)
        self.dt = float(dt)
        self.m = arm_model(getattr(world, "human_body", None))
        self.shoulder, self.reach = shoulder_and_reach(self.m)
        self.shoulder_xy = self.shoulder[:2].copy()
        self.tremor_amplitude = float(tremor_amplitude)
        self.tremor_frequency = float(tremor_frequency)
        self._tremor = Tremor(self.tremor_amplitude, self.tremor_frequency, TREMOR_DIRECTION, self.dt)
        self._tremor_free = 1.0      # how much of the tremor the hand makes: none while it is braced (`World.hand_braced`)
        self.d = mujoco.MjData(self.m)
        wm = world.model
        self._act = np.array([wm.actuator(j).id for j in HUMAN_ARM_JOINTS])
        self._hand_act = np.array([wm.actuator(j).id for j in HUMAN_HAND_JOINTS])
        self._wq = np.array([wm.jnt_qposadr[wm.joint(j).id] for j in HUMAN_ARM_JOINTS])
        self._site = self.m.site("human_r_grasp").id
        self._wsite = wm.site("human_r_grasp").id
        self._lo = self.m.jnt_range[:, 0].copy()
        self._hi = self.m.jnt_range[:, 1].copy()
        self._jacp = np.zeros((3, self.m.nv))
        self._jacr = np.zeros((3, self.m.nv))
        self.clamped: list[tuple[float, tuple[float, float, float], tuple[float, float, float]]] = []
        self.posture = "open"
        self.reset()

    # ------------------------------------------------------------------ state
    def reset(self) -> None:
        """Start from the arm's present joint angles (in the world) at rest."""
        self.q = self.world.data.qpos[self._wq].copy()
        self.q_rest = self.q.copy()
        self.segment: Segment | None = None
        self.segments: list[Segment] = []
        self._settled = False
        p, R = self.fk(self.q)
        self.p_goal, self.R_goal = p, R
        self.R_rest = R          # the hand's orientation at rest (a relaxed wrist)

    def fk(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pose (position, rotation) of the grasp site for arm angles q."""
        self.d.qpos[:] = q
        mujoco.mj_kinematics(self.m, self.d)
        return self.d.site_xpos[self._site].copy(), self.d.site_xmat[self._site].reshape(3, 3).copy()

    def hand_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """The measured grasp-site pose in the scene."""
        d, sid = self.world.data, self._wsite
        return d.site_xpos[sid].copy(), d.site_xmat[sid].reshape(3, 3).copy()

    def own_point(self, p) -> np.ndarray:
        """A point named for the default person as this person has it (`own_point`)."""
        return own_point(p, self.shoulder, self.reach)

    def own_table_spot(self, xy, radius: float) -> np.ndarray:
        """A table spot named for the default person as this person has it (`own_table_spot`)."""
        return own_table_spot(xy, self.shoulder, self.reach, radius)

    def tremor(self, t: float) -> np.ndarray:
        """The tremor's commanded displacement of the hand at time t (world, m)."""
        return self._tremor.offset(t)

    # ------------------------------------------------------------------ commands
    def clamp_target(self, p, t: float = 0.0) -> np.ndarray:
        """Apply the body's limits to a hand target; log an attempt beyond the middle line."""
        p = np.array(p, dtype=float)
        q = p.copy()
        if q[0] > HANDOVER_X_MAX - FINGER_REACH:
            q[0] = HANDOVER_X_MAX - FINGER_REACH
            self.clamped.append((float(t), tuple(p), tuple(q)))
        q[2] = max(q[2], MIN_Z)
        return q

    def move_to(self, p, R=None, t: float = 0.0, duration: float | None = None, speed: float | None = None,
                lift: bool = True) -> float:
        """Start a minimum-jerk motion of the grasp site to position p (and rotation R).

        Starts from the present commanded pose (smooth re-targeting); a hand near the table first comes up
        (unless not ``lift``: it goes straight).  Returns the duration (s)."""
        p1 = self.clamp_target(p, t)
        p0, R0 = self.fk(self.q)
        R1 = R0 if R is None else np.asarray(R, float)
        v = self.speed if speed is None else speed
        segs = []
        t0 = float(t)
        if lift and p0[2] < LIFT_BELOW_Z and float(np.linalg.norm(p1[:2] - p0[:2])) > 0.05:
            # a hand resting near the table first comes up, so fingers do not drag on the table
            up = p0 + np.array([0.0, 0.0, LIFT_BELOW_Z + 0.03 - p0[2]])
            d_up = max(0.3, float(up[2] - p0[2]) / v)
            segs.append(Segment(t0, d_up, p0, up, R0, np.zeros(3)))
            t0, p0 = t0 + d_up, up
        dw = _log_rot(R1 @ R0.T)
        if duration is None:
            duration = max(MIN_DURATION, float(np.linalg.norm(p1 - p0)) / v, float(np.linalg.norm(dw)) / ANGULAR_SPEED * self.speed / v)
        segs.append(Segment(t0, float(duration), p0, p1, R0, dw))
        self.segments = segs
        self.segment = segs[-1]
        self._settled = False
        self.p_goal, self.R_goal = p1, R1
        return float(t0 + duration - t)

    def rehearse(self, moves, t: float = 0.0) -> int:
        """How many of ``moves`` ((p, R, speed, tol) one after the other, as `move_to` takes them) the arm would
        complete from its present posture: the same segments and IK tracking as the control ticks, with
        nothing commanded (a person's sense of their own arm). A move is complete when the commanded hand is
        within tol (m) of its goal at most 1.5 s after the segment's time is up."""
        saved = (self.q.copy(), self.segment, self.segments, self._settled, self.p_goal, self.R_goal, len(self.clamped))
        try:
            for n, (p, R, speed, tol) in enumerate(moves):
                t_end = t + self.move_to(p, R, t=t, speed=speed) + 1.5
                arrived = None       # when the command got there: the hand follows it within SERVO_LAG
                while arrived is None or t < arrived + SERVO_LAG:
                    if t >= t_end:
                        return n
                    self.q = self._follow(t)[0]
                    t += self.dt
                    if arrived is None and self.segment.done(t) and float(np.linalg.norm(self.fk(self.q)[0] - self.p_goal)) < tol:
                        arrived = t
            return len(moves)
        finally:
            self.q, self.segment, self.segments, self._settled, self.p_goal, self.R_goal, n_clamped = saved
            del self.clamped[n_clamped:]

    def arrived(self, t: float, tol: float = 0.03) -> bool:
        """The motion's time is up and the measured hand is within tol (m) of the goal."""
        if self.segment is not None and not self.segment.done(t):
            return False
        return float(np.linalg.norm(self.hand_pose()[0] - self.p_goal)) < tol

    def set_posture(self, posture: str, squeeze: bool = False) -> None:
        """Command a hand posture (world.HAND_POSTURES).  squeeze=True drives the closing fingers
        toward their limit (the finger servos are slow and heavily damped); call again
        without it once the grip holds."""
        if posture not in HAND_POSTURES:
            raise ValueError(f"unknown hand posture {posture!r}; use one of {', '.join(HAND_POSTURES)}")
        self.posture = posture
        target = np.asarray(HAND_POSTURES[posture], float)
        if squeeze:
            hi = self.world.model.actuator_ctrlrange[self._hand_act, 1]
            target = np.where(target > 0.3, hi, target)
        self.world.data.ctrl[self._hand_act] = target

    # ------------------------------------------------------------------ control tick
    def tick(self, t: float, iterations: int = 1) -> None:
        """One control tick at time t: follow the segment with IK and command the servos."""
        moving = self.segment is not None and not self.segment.done(t)
        if not moving and self._settled and self.tremor_amplitude == 0.0:
            return  # holding still at the goal: the servo targets stand
        if self.tremor_amplitude > 0.0:
            # a hand braced on something stiff (what it holds resting on the table or in the robot's hand, or an
            # object standing there that it is about to close on) trembles against it, which stops it: the tremor
            # is the muscles' oscillating force, and a position command that went on trembling would press the
            # object into the table or the robot's fingers with a force no hand makes (and tear the grip open)
            free = 0.0 if self.world.hand_braced() else 1.0
            self._tremor_free += min(1.0, self.dt / TREMOR_SUPPORT_TAU) * (free - self._tremor_free)
            if self._tremor_free > TREMOR_FREE:
                # the tremor is measured while the hand rests on nothing (the table under what it holds stops it),
                # with what it holds too: the load lowers the arm's resonance toward the tremor band, and
                # unregulated the held object swayed twice the drawn amplitude. Its deviation from the planned path
                # is the tremor and slow lags, which the lock-in ignores
                self._tremor.observe(t, self.hand_pose()[0] - self._planned(t)[0])
            else:
                self._tremor.pause()
        q, biggest = self._follow(t, iterations)
        self.q = q
        self._settled = not moving and biggest < SETTLED_STEP
        self.world.data.ctrl[self._act] = self.q

    def _planned(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """The hand's pose at time t on the present motion (the tremor aside)."""
        if self.segment is not None:
            seg = next((g for g in self.segments if not g.done(t)), self.segment)
            return seg.at(t)
        return self.p_goal, self.R_goal

    def _follow(self, t: float, iterations: int = 1) -> tuple[np.ndarray, float]:
        """The commanded angles of the next tick: IK toward the segment's pose at t + dt from the present
        command, each joint moved at most its top speed; and the largest step taken."""
        p_t, R_t = self._planned(t + self.dt)
        if self.tremor_amplitude > 0.0:
            p_t = p_t + self._tremor_free * self.tremor(t + self.dt)
        q = self.q
        m, d = self.m, self.d
        for _ in range(iterations):
            d.qpos[:] = q
            mujoco.mj_kinematics(m, d)
            mujoco.mj_comPos(m, d)
            mujoco.mj_jacSite(m, d, self._jacp, self._jacr, self._site)
            # damped least squares with a weak pull toward the rest posture in the null space (dls.py)
            q = dls_step(p_t, R_t, d.site_xpos[self._site], d.site_xmat[self._site].reshape(3, 3),
                         self._jacp, self._jacr, q, self.q_rest, self._lo, self._hi)
        return bounded(q, self.q, self._lo, self._hi, MAX_JOINT_SPEED * self.dt)
