"""The human's behaviours: generators that drive the arm tick by tick and end in success or failure.

Each behaviour is a generator function ``fn(c, **args)`` over a controller-like context ``c``
(attributes ``world``, ``arm``, ``t``, ``profile``, ``view`` — the robot as the human last
perceived it — and a method ``note``).  It yields once per control tick and returns
``(ok, reason)``.  `Behaviour` wraps one with its status and times.  Every outcome is
decided by the physics: a grip exists only if the world's grip weld engaged, the stopper
comes off only if the fit gives, a drink counts only by particles reaching the mouth.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Generator

import numpy as np

from assistbot import catalogue
from assistbot.human.arm import grip_orientation, rot_y, rot_z
from assistbot.human.perception import RobotView
from assistbot.human.room import hand_room
from assistbot.interfaces import Status
from assistbot.task import DRINK_FRACTION
from assistbot.world import layout
from assistbot.world.state import standing_end

Gen = Generator[None, None, tuple[bool, str]]

#: where the human holds an object out / holds out the open palm (world, m): the hand-over zone
HOLD_OUT = np.array([-0.05, -0.05, 0.97])
#: lowest height (world z) of a held-out object's base: about 10 cm above the table
HOLD_OUT_BASE_Z = 0.88
#: the robot's open hand held out still this long (s) within MEET_MAX of what the person holds out,
#: without taking it, is taken as the robot reaching as far as it can: the person brings the object
#: into it, then MEET_STEP further up or aside toward the robot's shoulder each time, MEET_TRIES times
MEET_STILL = 1.5
MEET_MAX = 0.30
MEET_STEP = 0.06
MEET_TRIES = 3
#: s the person keeps holding an object out after the robot's hand was last near it
MEET_PATIENCE = 12.0
#: N: an object pressing back in the person's grip this hard has met something (the robot's hand)
FEEL_FORCE = 6.0
#: m: the robot's hand moving less than this is still, as the person sees it
STILL_TOLERANCE = 0.01
#: the robot's hand held out still this long (s) before the person reaches for what it offers; a grip that
#: gives way before the robot has let go is taken again, TAKE_TRIES in all
OFFER_STILL = 0.5
TAKE_TRIES = 2
#: how a reach for what the robot holds out that stopped short of it ends (the arm's limit reached before the
#: object, or the fingers closing on nothing there); the hand then waits BROUGHT_WAIT s for the robot to bring
#: the object to it, SHORT_TRIES times at most
SHORT_OF = ("could not reach the", "the grip on the")
#: m an object must have moved while the hand went to its approach pose for the hand to aim anew
REAIM = 0.01
BROUGHT_WAIT = 5.0
SHORT_TRIES = 3
#: the hand's height (world z) while it holds an object just taken from the robot, in toward the body
TAKEN_Z = 0.90
#: the farthest table x at which the person sets an object down under the robot's hand
UNDER_ROBOT_X_MAX = -0.045
#: m below the robot's hand, as the person sees it, that the top of what she sets down under it stays
UNDER_ROBOT_CLEARANCE = 0.08
#: a resting place of the hand near the body
REST = np.array([-0.34, -0.17, 0.86])
LIFT = 0.07                       # m lifted after a grasp
MOVE_TOL = 0.03                   # m: a reach has arrived when the hand is this near its goal
AT_GRASP_TOL = 0.02               # m: ... and the hand closing in on a grasp, this near the grasp
#: m that an object carried in the hand keeps from the other objects standing on the table (above, around)
CARRY_CLEARANCE = 0.03
#: an object held beyond this table x (toward the robot) is put down on the person's own side instead
OWN_SIDE_X = -0.15
#: where the person puts an object down on their own side (table x, y), and how far from the others
OWN_SIDE_SPOTS = ((-0.24, -0.20), (-0.24, -0.06), (-0.24, 0.08), (-0.24, 0.22))
OWN_SIDE_CLEAR = 0.12
#: grasp-site height above the object's base (m), per object and grip
GRASP_HEIGHT = {("bottle", "ag"): 0.17, ("bottle", "sg"): 0.085, ("glass", "ag"): 0.085, ("glass", "sg"): 0.055}
#: m: taking from the robot's hand, the gap the person's grip keeps from it, as the eyes judge it; and the steps
#: by which the side grip goes lower down the object to find that room
CLEAR_OF_HAND = 0.015
TAKE_HEIGHT_STEP = 0.01
#: m: a grasp comes in from this far above the object or back along the fingers; taking from the robot's
#: hand, from farther: the open fingers reach 10 cm beyond the grasp site and the hand turns into the grip
#: on the way, so the way in must start clear of the fingers round the object
APPROACH_BACK = 0.08
TAKE_APPROACH_BACK = 0.14
#: m/s: the most a hand closing in on another's hand moves (its joints keep to the straight way in)
CAREFUL_SPEED = 0.08
POINT_X_MAX = -0.10               # world x, the pointing hand stays behind this
POINT_TOLERANCE = 0.35            # rad, finger direction vs the direction to the object
TURN_LIFT = 0.04                  # m, the inverted glass is lifted this much before the half turn
TILT_MAX = 2.1                    # rad, glass tilt at the end of a drink
#: where the glass's pouring lip is held, relative to the mouth site (world, m)
LIP_OFFSET = np.array([0.015, 0.0, -0.015])
#: yaw (rad, about the vertical, to the left) of the side-grip hand while drinking
DRINK_YAW = 0.75
#: how far (rad) the person tilts the bottle to pour, its mouth this far above the glass's rim (m), and
#: how long they hold it there at most (s)
POUR_TILT = np.radians(125)
MOUTH_ABOVE_RIM = 0.03
POUR_TIMEOUT = 6.0
#: m (horizontally) that the bottle's mouth may be off its way over the glass once the person has tilted it
#: so far (the fraction of POUR_TILT) that the liquid reaches the mouth: further off, the stream misses the glass
MOUTH_TOLERANCE = 0.025
POURS_FROM = 0.6
#: the steps (fractions of POUR_TILT) in which the bottle is tilted, at this hand speed (m/s), each reached
#: within this distance (m)
TILT_STEPS = np.linspace(0.2, 1.0, 5)
POUR_SPEED = 0.08
POUR_TOL = 0.04
#: m between the glass and the bottle brought beside it to pour
POUR_GAP = 0.02


@dataclass
class Behaviour:
    """One running behaviour: name, arguments, `Status` (running, then succeeded or failed)."""

    name: str
    args: dict
    gen: Gen
    t_start: float
    status: Status = Status.RUNNING
    reason: str = ""
    t_end: float | None = None

    def step(self, t: float) -> Status:
        if self.status is not Status.RUNNING:
            return self.status
        try:
            next(self.gen)
        except StopIteration as stop:
            ok, why = stop.value if stop.value is not None else (True, "")
            self.status = Status.SUCCEEDED if ok else Status.FAILED
            self.reason = why
            self.t_end = t
        return self.status


# ---------------------------------------------------------------------------- helpers
def _pos(c, body: str) -> np.ndarray:
    return c.world.data.xpos[c.world.body_id[body]].copy()


def _axis(c, body: str) -> np.ndarray:
    return c.world.data.xmat[c.world.body_id[body]].reshape(3, 3)[:, 2].copy()


def _wait(c, seconds: float) -> Generator[None, None, None]:
    t_end = c.t + seconds
    while c.t < t_end - 1e-9:
        yield


def _wait_until(c, cond: Callable[[], bool], timeout: float) -> Generator[None, None, bool]:
    t_end = c.t + timeout
    while not cond():
        if c.t >= t_end:
            return False
        yield
    return True


def _move(c, p, R=None, speed: float | None = None, tol: float = MOVE_TOL,
          stop: Callable[[], bool] | None = None, lift: bool = True) -> Generator[None, None, bool]:
    """Reach to p (with rotation R); True when the hand got there (or `stop()` became true on the way:
    the hand then stays where it is).  An object in the hand is carried over, not through, the objects
    standing near the way (`_carry_height`): the hand first rises, crosses, then comes down. A reach the
    arm cannot make from where it is (a joint at its limit on the way, which a narrowed range of motion
    makes likely) goes back by the resting place first, as a person starts an awkward reach afresh, when
    the arm can make it from there (both known beforehand: `HumanArm.rehearse`)."""
    moves = [(over, R, speed, MOVE_TOL) for over in _carry_path(c, p)] + [(p, R, speed, tol)]
    if c.arm.rehearse(moves, c.t) < len(moves):
        afresh = [(c.arm.own_point(REST), c.arm.R_rest, speed, MOVE_TOL)] + moves
        if c.arm.rehearse(afresh, c.t) == len(afresh):
            moves = afresh
    for q, R_q, speed_q, tol_q in moves:
        if not (yield from _move_straight(c, q, R_q, speed_q, tol_q, stop, lift)):
            return False
    return True


def _carry_path(c, p) -> list[np.ndarray]:
    """The points the hand passes on its way to p, carrying what it holds over what stands in the way: up to
    the carry height where it is, across at that height; none when nothing is in the way."""
    high = _carry_height(c, p)
    if high is None:
        return []
    hand = c.arm.hand_pose()[0]
    path = []
    if hand[2] < high - 0.005:
        path.append(np.array([hand[0], hand[1], high]))
    if p[2] < high - 0.005:
        path.append(np.array([p[0], p[1], high]))
    return path


def _move_straight(c, p, R=None, speed: float | None = None, tol: float = MOVE_TOL,
                   stop: Callable[[], bool] | None = None, lift: bool = True,
                   hesitate: bool = True) -> Generator[None, None, bool]:
    if hesitate and c.profile.hesitation > 0:
        yield from _wait(c, c.profile.hesitation)
    dur = c.arm.move_to(p, R, t=c.t, speed=speed, lift=lift)
    t_end = c.t + dur + 1.5
    while not c.arm.arrived(c.t, tol):
        if stop is not None and stop():
            c.arm.move_to(c.arm.hand_pose()[0], c.arm.hand_pose()[1], t=c.t, duration=0.3)
            return True
        if c.t >= t_end:
            return False
        yield
    return True


def _carry_height(c, p) -> float | None:
    """The hand height (world z) at which the object in the hand passes CARRY_CLEARANCE above every other
    object standing within reach of the straight way to p; None when nothing is in the hand or in the way."""
    held = c.world.human_holding()
    if held not in catalogue.TASK_OBJECTS:
        return None
    hand = c.arm.hand_pose()[0]
    below = hand[2] - float(np.min([standing_end(c.world, held)[2], _pos(c, held)[2]]))  # hand above the held object's bottom
    a, b = hand[:2], np.asarray(p, float)[:2]
    need = None
    for other in catalogue.TASK_OBJECTS:
        if other == held or other == c.world.robot_holding():
            continue
        base = standing_end(c.world, other)
        if base[2] > layout.TABLE_Z + 0.03:     # not standing on the table
            continue
        ab = b - a
        s = float(np.clip((base[:2] - a) @ ab / max(float(ab @ ab), 1e-12), 0.0, 1.0))
        if np.linalg.norm(base[:2] - (a + s * ab)) < catalogue.radius(held) + catalogue.radius(other) + CARRY_CLEARANCE:
            top = base[2] + catalogue.top(other)
            need = max(need or 0.0, top + CARRY_CLEARANCE + below)
    return need


def _to_rest(c) -> Generator[None, None, bool]:
    """Bring the hand back to its resting place near the body, with a relaxed wrist."""
    return (yield from _move(c, c.arm.own_point(REST), c.arm.R_rest))


def _withdraw(c, rest: bool = True) -> Generator[None, None, bool]:
    """Take the open hand away from what is in another's hand the way it came in, back along its fingers
    (APPROACH_BACK) and carefully, before it goes to rest (``rest``) or on to another reach: going straight
    on, it would sweep past the other's fingers round the object."""
    hand, R = c.arm.hand_pose()
    ok = yield from _move(c, hand + APPROACH_BACK * R[:, 2], R, speed=min(c.arm.speed, CAREFUL_SPEED), lift=False)
    return (yield from _to_rest(c)) if rest else ok


def _out_of_the_robots_way(c) -> Generator[None, None, None]:
    """A hand still held out asking (a request cut short by what the robot said) is where the robot brings
    what it holds: before waiting for it, the hand is taken out of its way (`_withdraw`)."""
    if c.arm.posture == "request":
        yield from _withdraw(c)


def _close(c, posture: str, obj: str) -> Generator[None, None, bool]:
    c.arm.set_posture(posture, squeeze=True)
    ok = yield from _wait_until(c, c.world.hand_closed, 3.0)
    ok = bool(ok and c.world.human_grasp(obj))
    c.arm.set_posture(posture)
    return ok


def _center_base(c, obj: str) -> np.ndarray:
    """The centre of the end the object stands on, whichever way up it is (a person's eyes)."""
    return standing_end(c.world, obj)


def grasp_point(c, obj: str, grip: str, height: float | None = None) -> np.ndarray:
    """Where the grasp site goes for ``grip`` on ``obj``: ``height`` (default GRASP_HEIGHT) above the end it stands on."""
    p, a = _pos(c, obj), _axis(c, obj)
    h = GRASP_HEIGHT[(obj, grip)] if height is None else height
    return p + h * a if a[2] >= 0 else p + (catalogue.height("glass") - h) * a


def grip_beside_the_robots_hand(c, obj: str) -> tuple[str, float]:
    """The grip and grasp-site height at which to take ``obj`` from the robot's hand, as the eyes judge the room
    it leaves (`room.HandRoom.clearance`) and the arm its own reach (`HumanArm.rehearse`): of her side grip at
    its usual height, lower down the object (TAKE_HEIGHT_STEP at a time, down to the end it stands on) and her
    grip from above, the first that keeps CLEAR_OF_HAND from the robot's hand, else the one that keeps farthest
    from it, that her arm can reach; none reachable, her usual side grip (she reaches as far as she goes)."""
    room, d = hand_room(c.world), c.world.data
    sg = GRASP_HEIGHT[(obj, "sg")]
    grips = [("sg", float(h)) for h in np.arange(sg, -1e-9, -TAKE_HEIGHT_STEP)] + [("ag", GRASP_HEIGHT[(obj, "ag")])]
    poses, gaps = [], []
    for grip, h in grips:
        target = grasp_point(c, obj, grip, h)
        R = grip_orientation(grip, target, c.arm.shoulder_xy)
        poses.append((target, R))
        gaps.append(room.clearance(d, grip, target, R))
    clear = [k for k, gap in enumerate(gaps) if gap >= CLEAR_OF_HAND]
    tight = sorted((k for k, gap in enumerate(gaps) if gap < CLEAR_OF_HAND), key=lambda k: -gaps[k])
    careful = min(c.arm.speed, CAREFUL_SPEED)
    for k in clear + tight:
        (target, R), grip = poses[k], grips[k][0]
        moves = [(_approach_point(target, R, grip, TAKE_APPROACH_BACK), R, None, MOVE_TOL), (target, R, careful, AT_GRASP_TOL)]
        if c.arm.rehearse(moves, c.t) == len(moves):
            return grips[k]
    return grips[0]


def _approach_point(target: np.ndarray, R: np.ndarray, grip: str, back: float) -> np.ndarray:
    """Where a grasp comes in from: ``back`` above the grasp site (from above), or back along the fingers."""
    return target + (np.array([0.0, 0.0, back]) if grip == "ag" else back * R[:, 2])


# ---------------------------------------------------------------------------- behaviours
def grasp(c, object: str, grip: str = "ag", lift: bool = True, hold_out: bool = False,
          height: float | None = None, back: float = APPROACH_BACK, straight_in: bool = False) -> Gen:
    """Reach and grasp `object` with an above (ag) or side (sg) grip, its grasp site ``height`` above the end
    the object stands on (default GRASP_HEIGHT), coming in from ``back`` above it or back along the fingers
    (``straight_in``: slowly, CAREFUL_SPEED at most, along a straight line, even low over the table, as into
    another's hand), then lift it a little."""
    if c.world.human_holding() is not None:
        return False, f"the hand already holds the {c.world.human_holding()}"
    target = grasp_point(c, object, grip, height)
    R = grip_orientation(grip, target, c.arm.shoulder_xy)
    pre = _approach_point(target, R, grip, back)
    c.arm.set_posture("open")
    if not (yield from _move(c, pre, R)):
        return False, "could not reach the approach pose"
    if np.linalg.norm(grasp_point(c, object, grip, height) - target) > REAIM:
        # it has moved meanwhile (the robot holding it out brings it nearer): the eyes follow it
        target = grasp_point(c, object, grip, height)
    speed = min(c.arm.speed, CAREFUL_SPEED) if straight_in else None
    if not (yield from _move(c, target, R, speed=speed, tol=AT_GRASP_TOL, lift=not straight_in)):
        return False, f"could not reach the {object}"
    yield from _wait(c, 0.15)
    if not (yield from _close(c, grip, object)):
        c.arm.set_posture("open")
        return False, f"the grip on the {object} did not close"
    if lift:
        yield from _move(c, c.arm.p_goal + np.array([0, 0, LIFT]), R)
        if c.profile.drop_chance > 0.0 and c.rng.random() < c.profile.drop_chance:
            # a weak hand lets go of what it has just lifted: it falls in the physics
            c.world.human_release(object)
            c.arm.set_posture("open")
            c.note("dropped", {"object": object})
            return False, f"let go of the {object}"
    if hold_out and c.world.human_holding() == object:
        return (yield from globals()["hold_out"](c, object))
    return c.world.human_holding() == object, f"{object} in hand"


def hold_out_point(c) -> np.ndarray:
    """Where this person holds things (and the open hand) out: HOLD_OUT moved by the profile's habit, as this
    person's body has it (`HumanArm.own_point`)."""
    return c.arm.own_point(HOLD_OUT + np.asarray(c.profile.hold_out_offset, float))


def _middle(c, obj: str) -> np.ndarray:
    """The middle of an object held about upright or upside down (world): half its height above the end it stands on."""
    return standing_end(c.world, obj) + np.array([0.0, 0.0, 0.5 * catalogue.height(obj)])


def _give_into_the_robots_hand(c, held: str, timeout: float) -> Gen:
    """Hold ``held`` out until the robot holds it (True) or ``timeout`` s pass (False). Meanwhile, when the
    robot's open, empty hand has been held out still for MEET_STILL s near the object without taking it
    (it cannot reach further), bring the object into it, as a person handing something over does; if it
    still does not take it, MEET_STEP more each time up or aside toward the robot's shoulder: the arm
    stops at the middle line, so what it cannot give in depth it gives in height and to the side. At
    most MEET_TRIES times."""
    t_end = c.t + timeout
    last, still_since, tries = None, None, 0
    while c.view.holds != held:
        if c.t >= t_end or c.world.human_holding() != held:
            return False
        v = c.view
        tcp = np.array(v.hand_pos, float)
        if not v.requests:
            last, still_since = None, None
        elif last is None or np.linalg.norm(tcp - last) > 0.01:   # moved on: still from here
            last, still_since = tcp, c.t
        middle = _middle(c, held)
        gap = tcp - middle
        if np.linalg.norm(gap) < MEET_MAX:
            t_end = max(t_end, c.t + MEET_PATIENCE)   # the robot is at it: keep holding it out
        if (still_since is not None and c.t - still_since >= MEET_STILL and np.linalg.norm(gap) < MEET_MAX
                and tries < MEET_TRIES):
            # first into the open hand; then, as it still cannot take it, on up or aside toward its shoulder
            toward = np.array(v.shoulder, float) - middle
            toward[0] = 0.0
            hand, R = c.arm.hand_pose()
            step = MEET_STEP * tries * toward / max(float(np.linalg.norm(toward)), 1e-9)
            # stopping where it meets the hand: felt as the object pressing back in the grip
            yield from _move_straight(c, hand + gap + step, R, speed=0.1,
                                      stop=lambda: c.view.holds == held or c.world.grip_force(held) > FEEL_FORCE)
            last, still_since, tries = None, None, tries + 1
            continue
        yield
    return True


def hold_out(c, object: str | None = None) -> Gen:
    """Hold the object in hand out toward the robot, in the hand-over zone."""
    held = c.world.human_holding()
    if held is None or (object is not None and held != object):
        return False, "nothing to hold out" if held is None else f"holds the {held}, not the {object}"
    # keep the grip, turned about the vertical so the fingers point along the shoulder's bearing to the point
    _, R = c.arm.hand_pose()
    target = hold_out_point(c)
    bearing = np.arctan2(*(target[:2] - c.arm.shoulder_xy)[::-1])
    R = rot_z(bearing - np.arctan2(-R[1, 2], -R[0, 2])) @ R
    lowest = HOLD_OUT_BASE_Z + c.profile.hold_out_dz
    target[2] = max(target[2], lowest + float(c.arm.hand_pose()[0][2] - _center_base(c, held)[2]))
    # the robot may take hold of it before the arm is fully out: the hand then stops there
    ok = yield from _move(c, target, R, stop=lambda: c.view.holds == held)
    return (ok and c.world.human_holding() == held), f"{held} held out"


def own_side_spot(c, held: str) -> np.ndarray:
    """A free place on the person's side, back from the hand-over zone, for putting ``held`` down: of
    OWN_SIDE_SPOTS (as this person has them: within their reach) the one farthest from the other objects
    standing there (a person's eyes)."""
    others = [standing_end(c.world, o)[:2] for o in catalogue.TASK_OBJECTS if o != held]
    spots = np.array([c.arm.own_table_spot(xy, catalogue.radius(held)) for xy in OWN_SIDE_SPOTS])
    clear = np.min([np.linalg.norm(spots - o, axis=1) for o in others], axis=0) if others else np.zeros(len(spots))
    hand = c.arm.hand_pose()[0][:2]
    # the farthest from the others, among those far enough the nearest to the hand
    ok = clear >= OWN_SIDE_CLEAR
    pick = np.flatnonzero(ok)[np.argmin(np.linalg.norm(spots[ok] - hand, axis=1))] if ok.any() else int(np.argmax(clear))
    return spots[pick].copy()


def _top(c, obj: str) -> float:
    """World z of the top of ``obj`` held about upright (the stopper on a closed bottle included)."""
    closed = obj == "bottle" and bool(c.world.data.eq_active[c.world.eq_stopper])
    return float(_center_base(c, obj)[2]) + catalogue.top(obj, fitted=closed)


def put_down(c, object: str | None = None, at: tuple[float, float] | None = None,
             under: float | None = None) -> Gen:
    """Put the object in hand down upright at table spot `at` (default: where it is, or, held out near the
    middle line, at a free place on this side: `own_side_spot`), let go, withdraw. An object held tilted
    (a pour given up half way, a grip closed at the edge of the arm's reach) is turned upright on the way,
    or upside down if it is held more so: set down on its edge it would fall over. ``under`` (world z):
    something held above the spot (the robot's hand showing it) that the object's top must pass below,
    so it is first lowered where it is, then brought in."""
    held = c.world.human_holding()
    if held is None or (object is not None and held != object):
        return False, "nothing in hand to put down"
    if under is not None and _top(c, held) > under:
        hand, R = c.arm.hand_pose()
        low = max(under - _top(c, held), layout.TABLE_Z + 0.01 - float(_center_base(c, held)[2]))
        yield from _move_straight(c, hand + np.array([0.0, 0.0, min(0.0, low)]), R)
    base = _center_base(c, held)
    hand, R = c.arm.hand_pose()
    a = _axis(c, held)
    upright = _turning(a, np.array([0.0, 0.0, 1.0 if a[2] >= 0.0 else -1.0]))
    if at is not None:
        spot = np.array(at, float)
    elif base[0] > OWN_SIDE_X and held in catalogue.TASK_OBJECTS:
        spot = own_side_spot(c, held)
    else:
        spot = base[:2]
    target_base = np.array([spot[0], spot[1], layout.TABLE_Z + 0.004])
    # straightened, the fingers turned about the vertical toward the spot's bearing from the shoulder (as the
    # arm reaches there; the object stays upright), if the arm can turn the hand so; else as held
    Ru = upright @ R
    bearing = np.arctan2(*(spot - c.arm.shoulder_xy)[::-1])
    straighten = rot_z(bearing - np.arctan2(-Ru[1, 2], -Ru[0, 2])) @ upright
    for turn in (straighten, np.eye(3)):
        offset = turn @ (hand - base)          # the hand relative to the object's base
        if (yield from _move(c, target_base + offset + np.array([0, 0, 0.04]), turn @ R)):
            break
    else:
        return False, "could not reach the spot"
    R = turn @ R
    yield from _move(c, target_base + offset, R, speed=0.05, tol=0.04)
    c.arm.set_posture("open")
    yield from _wait(c, 0.5)
    _, R_now = c.arm.hand_pose()
    back = -0.08 * R_now[:, 2] if held != "stopper" else np.zeros(3)
    yield from _move(c, c.arm.p_goal + np.array([0, 0, 0.07]) - back)
    yield from _to_rest(c)
    p = _center_base(c, held)
    ok = c.world.human_holding() is None and p[2] < layout.TABLE_Z + 0.03 and np.linalg.norm(p[:2] - spot) < 0.05
    return bool(ok), f"{held} put down at ({p[0]:.2f}, {p[1]:.2f})"


def put_down_for_robot(c) -> Gen:
    """Asked to set what the hand holds down under the robot's hand: put it down on the table below the
    robot's hand as seen, as close to it as the arm goes. With the hand empty, "it" is what she was handing
    over: asked while she was putting it down on her side after a hand-over that failed, she picks it up
    again first (asked with the hand already empty, the policy has her grasp it before this)."""
    held = c.world.human_holding()
    offered = c.policy_state.get("offered")
    if held is None and offered in catalogue.TASK_OBJECTS and _pos(c, offered)[0] < 0:
        ok, why = yield from grasp(c, offered, c.profile.hand_over_grip(offered))
        if not ok:
            return False, why
        held = c.world.human_holding()
    if held not in catalogue.TASK_OBJECTS:
        return False, "nothing in hand to set down"
    # the robot's open hand comes to show the place: wait until it is held out there, still
    tcp = yield from _robot_hand_still(c, lambda v: v.requests, MEET_STILL, 15.0)
    if tcp is None:
        return False, "the robot showed no place"
    ok, why = yield from put_down(c, held, at=(min(float(tcp[0]), UNDER_ROBOT_X_MAX), float(tcp[1])),
                                  under=float(tcp[2]) - UNDER_ROBOT_CLEARANCE)
    if ok:
        c.policy_state["left_for_robot"] = held     # hers no more, until the robot has taken it
    return ok, why


def hand_to_robot(c, object: str, grip: str | None = None, timeout: float = 40.0) -> Gen:
    """Grasp `object` (if not in hand, or held by another grip than ``grip``: then set down first), hold it out,
    and let go once the robot holds it."""
    c.policy_state["offered"] = object      # what "it" means if the robot then asks her to set it down
    if c.world.human_holding() == object and grip is not None and c.arm.posture != grip:
        # held by another grip than the one asked for (a side grip round its middle, taken to hold it out):
        # the taker's hand would close where her fingers wrap it, so she sets it down and takes it again
        ok, why = yield from put_down(c, object)
        if not ok:
            return False, why
    if c.world.human_holding() != object:
        ok, why = yield from grasp(c, object, grip or c.profile.grip)
        if not ok:
            return False, why
    ok, why = yield from hold_out(c, object)
    if not ok:
        return False, why
    if not (yield from _give_into_the_robots_hand(c, object, timeout)):
        return False, f"the robot did not take the {object}"
    yield from _wait(c, c.profile.reaction_delay)
    yield from _let_go(c, object)
    ok = c.world.human_holding() is None and c.view.holds == object
    return ok, f"{object} handed over"


def _let_go(c, held: str) -> Generator[None, None, bool]:
    """Let go of what the robot's hand now holds, the way the grip came in. A grip from above loosens, and the
    hand rises off the object (APPROACH_BACK, slowly) before it opens: its fingers hang down the object's side
    toward the robot, and opened there they would sweep out into the robot's hand beside them. A grip from the
    side opens where it is, then withdraws back along its fingers (`_withdraw`). Loosening and rising are one
    motion: no hesitation between them (the robot, feeling the object's weight, takes it away)."""
    if c.arm.posture == "ag":
        c.world.human_release(held)
        hand, R = c.arm.hand_pose()
        yield from _move_straight(c, _approach_point(hand, R, "ag", APPROACH_BACK), R, speed=min(c.arm.speed, CAREFUL_SPEED),
                                  lift=False, hesitate=False)
    c.arm.set_posture("open")
    yield from _wait(c, 0.5)
    return (yield from _withdraw(c))


def _robot_hand_still(c, showing: Callable[[RobotView], bool], seconds: float,
                      timeout: float) -> Generator[None, None, np.ndarray | None]:
    """Wait until the robot's hand, ``showing(view)`` all along, has kept still (within STILL_TOLERANCE)
    for ``seconds``: where it is then, or None after ``timeout`` s."""
    t_end = c.t + timeout
    last, since = None, None
    while True:
        v = c.view
        tcp = np.array(v.hand_pos, float)
        if not showing(v) or last is None or np.linalg.norm(tcp - last) > STILL_TOLERANCE:
            last, since = (tcp if showing(v) else None), c.t
        elif c.t - since >= seconds:
            return tcp
        if c.t >= t_end:
            return None
        yield


def _offered_still(c, object: str | None, timeout: float) -> Generator[None, None, bool]:
    """Wait until the robot holds ``object`` (any, when None) out and its hand has kept still for
    OFFER_STILL s: a person reaches for a thing handed to them once it has arrived, not while it moves."""
    offered = lambda v: v.offers is not None and (object is None or v.offers == object)  # noqa: E731
    return (yield from _robot_hand_still(c, offered, OFFER_STILL, timeout)) is not None


def _brought_nearer(c, object: str, offered_at: np.ndarray) -> Generator[None, None, bool]:
    """The hand stopped short of what the robot holds out (as far as this arm goes): it stays there, open, up
    to BROUGHT_WAIT s for the robot to bring the object to it (its hand seen moving from ``offered_at``, where
    it was when this reach began, then still again)."""
    c.arm.set_posture("open")
    moved = yield from _wait_until(c, lambda: float(np.linalg.norm(np.array(c.view.hand_pos, float) - offered_at)) > STILL_TOLERANCE,
                                   BROUGHT_WAIT)
    return bool(moved) and (yield from _offered_still(c, object, BROUGHT_WAIT))


def take_from_robot(c, object: str | None = None, timeout: float = 20.0) -> Gen:
    """Take the object the robot holds out once it has arrived: reach it where the robot's hand leaves room
    for the grip (`grip_beside_the_robots_hand`), close, wait for the robot to let go. A grip that gives way
    before the robot has let go (it pulled or moved on) is taken again while the robot still holds it out."""
    yield from _out_of_the_robots_way(c)
    if not (yield from _offered_still(c, object, timeout)):
        return False, "the robot offers nothing"
    obj = c.view.offers
    short = 0
    for _ in range(TAKE_TRIES):
        offered_at = np.array(c.view.hand_pos, float)
        grip, height = grip_beside_the_robots_hand(c, obj)
        ok, why = yield from grasp(c, obj, grip, lift=False, height=height, back=TAKE_APPROACH_BACK, straight_in=True)
        while not ok and why.startswith(SHORT_OF) and short < SHORT_TRIES and (yield from _brought_nearer(c, obj, offered_at)):
            short += 1
            offered_at = np.array(c.view.hand_pos, float)
            grip, height = grip_beside_the_robots_hand(c, obj)
            ok, why = yield from grasp(c, obj, grip, lift=False, height=height, back=TAKE_APPROACH_BACK,
                                       straight_in=True)
        if not ok:
            return False, why
        # the robot lets go, or the grip gives way (felt: the hand holds nothing any more)
        if not (yield from _wait_until(c, lambda: c.view.holds != obj or c.world.human_holding() != obj, timeout)):
            c.arm.set_posture("open")
            return False, f"the robot did not let go of the {obj}"
        if c.world.human_holding() == obj:
            break
        c.arm.set_posture("open")
        if not (yield from _offered_still(c, obj, timeout)):
            return False, f"the {obj} slipped from the grip and the robot no longer offers it"
    else:
        return False, f"the grip on the {obj} gave way {TAKE_TRIES} times"
    # brought in toward the body, above a free place on this side (not over what stands there)
    spot = own_side_spot(c, obj)
    yield from _move(c, np.array([spot[0], spot[1], TAKEN_Z]), None)
    return c.world.human_holding() == obj, f"took the {obj}"


def request(c, hold: float = 3.0) -> Gen:
    """Hold out an open, empty palm toward the robot (a request) for `hold` s, then lower the hand.

    A request is a gesture, not a posture to keep: left out, it would go on asking."""
    if c.world.human_holding() is not None:
        return False, "the hand is not empty"
    c.arm.set_posture("request")
    at = hold_out_point(c)
    R = grip_orientation("request", at, c.arm.shoulder_xy)
    ok = yield from _move(c, at, R)
    yield from _wait(c, hold)
    c.arm.set_posture("open")
    yield from _to_rest(c)
    return ok, "open hand held out"


def point(c, object: str, hold: float = 1.5) -> Gen:
    """Point at `object` with the index finger (the hand stays in the HWS), hold, lower the hand.

    Succeeds when the measured finger direction was within POINT_TOLERANCE of the object."""
    target = _pos(c, object) + np.array([0, 0, 0.10])
    c.arm.set_posture("point")
    d = np.array([*(target[:2] - c.arm.shoulder_xy), 0.0])       # the bearing from the shoulder
    d /= max(float(np.linalg.norm(d)), 1e-6)
    p = target - 0.15 * d
    if p[0] > POINT_X_MAX:  # an object in the RWS: point from this side of the line, along the same bearing
        p = p - d * (p[0] - POINT_X_MAX) / max(d[0], 1e-6)
    ok = yield from _move(c, p, grip_orientation("point", target, c.arm.shoulder_xy))
    hand, R = c.arm.hand_pose()
    v = target - hand
    err = float(np.arccos(np.clip((-R[:, 2]) @ v / max(float(np.linalg.norm(v)), 1e-6), -1.0, 1.0)))
    yield from _wait(c, hold)
    c.arm.set_posture("open")
    yield from _to_rest(c)
    return bool(ok and err < POINT_TOLERANCE), f"pointed at the {object} ({np.degrees(err):.0f} deg off)"


def pull_stopper(c, timeout: float = 3.0, wait_for_robot: float = 0.0) -> Gen:
    """Grip the stopper from above and pull it up; works only if something holds the bottle down.

    ``wait_for_robot`` > 0: first wait up to that many seconds until the robot is seen holding
    the bottle (a person invited to pull the stopper waits for the robot to hold it out).
    """
    w = c.world
    yield from _out_of_the_robots_way(c)
    if wait_for_robot > 0:
        # held out toward the person, and still for a moment: then reach for the stopper
        if not (yield from _wait_until(c, lambda: c.view.offers == "bottle", wait_for_robot)):
            return False, "the robot did not hold the bottle out"
        yield from _wait(c, 1.0)
    if not w.data.eq_active[w.eq_stopper]:
        return False, "the bottle is already open"
    if w.human_holding() is not None:
        return False, "the hand is not empty"
    s = w.data.site_xpos[w.site_id["stopper_grasp"]].copy()
    R = grip_orientation("ag", s, c.arm.shoulder_xy)
    c.arm.set_posture("open")
    if not (yield from _move(c, s + np.array([0, 0, 0.07]), R)):
        return False, "could not reach above the stopper"
    s = w.data.site_xpos[w.site_id["stopper_grasp"]].copy()
    if not (yield from _move(c, s, R, tol=0.02)):
        return False, "could not reach the stopper"
    if not (yield from _close(c, "ag", "stopper")):
        c.arm.set_posture("open")
        return False, "the grip on the stopper did not close"
    b0 = _pos(c, "bottle")[2]
    c.arm.move_to(s + np.array([0, 0, 0.12]), R, t=c.t, speed=0.15)
    t_end = c.t + timeout
    while c.t < t_end:
        yield
        if not w.data.eq_active[w.eq_stopper]:
            break
        if _pos(c, "bottle")[2] > b0 + 0.02:
            # the whole bottle comes up with the stopper: nothing holds it; put it back, let go
            yield from _move(c, s, R)
            c.arm.set_posture("open")
            yield from _wait(c, 0.4)
            yield from _to_rest(c)
            return False, "the bottle lifts with the stopper (nobody holds it)"
    if w.data.eq_active[w.eq_stopper]:
        c.arm.set_posture("open")
        return False, "the stopper did not come off"
    # put the stopper aside in the HWS
    ok, _ = yield from put_down(c, "stopper", at=(-0.32, -0.32))
    return True, "stopper removed"


def turn_roll(R: np.ndarray, fraction: float) -> np.ndarray:
    """The rotation that rolls a side grip of hand orientation R by ``fraction`` of the glass's half
    turn, about the fingers' direction (Rodrigues' formula): what turn_glass does to the hand."""
    axis = -R[:, 2]
    a = axis / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    ang = -np.pi * fraction
    return np.eye(3) + np.sin(ang) * K + (1 - np.cos(ang)) * K @ K


def turn_glass(c) -> Gen:
    """Turn an inverted glass upright in the HWS: side grip, lift, roll half a turn, put down."""
    if _axis(c, "glass")[2] > 0:
        return False, "the glass is already upright"
    base0 = _center_base(c, "glass")
    ok, why = yield from grasp(c, "glass", "sg", lift=False)
    if not ok:
        return False, why
    hand, R = c.arm.hand_pose()
    yield from _move(c, hand + np.array([0, 0, TURN_LIFT]), R)
    for frac in (0.5, 1.0):
        yield from _move(c, hand + np.array([0, 0, TURN_LIFT]), turn_roll(R, frac) @ R, speed=0.1)
    ok, why = yield from put_down(c, "glass", at=tuple(base0[:2]))
    up = _axis(c, "glass")[2] > 0.9
    return bool(ok and up), "glass upright" if up else "the glass is not upright"


def drink(c, timeout: float = 6.0, put_back: bool = True) -> Gen:
    """Bring the glass (grasped if needed) to the mouth and tilt it; counts when the glass was full
    (WorldState) and >= 75% of its liquid reached the mouth.  Then (put_back) the glass goes back upright where it was taken from, if that
    was in the HWS, else near the body."""
    w = c.world
    base_xy = _center_base(c, "glass")[:2].copy()
    if base_xy[0] > -0.12:
        base_xy = c.arm.own_table_spot((-0.24, 0.05), catalogue.radius("glass"))
    if w.human_holding() != "glass":
        ok, why = yield from grasp(c, "glass", "sg")
        if not ok:
            return False, why
    st = w.state()
    n0 = st.liquid.in_glass
    full = st.glass_state == "full"          # WorldState: at least FULL_FRACTION of the liquid in the glass
    drunk0 = int(w.drunk.sum())
    mouth = w.data.site_xpos[w.site_id["human_mouth"]].copy()
    # The pouring lip: the point of the rim on the side toward the face.  The glass tilts
    # about the world y axis (toward the face, -x); the lip is held just in front of and
    # below the mouth, so the liquid that flows over it passes the lips.
    # The glass is round: any hand yaw about the vertical holds it the same.  The drinking hand
    # orientation is the grip's, turned about the vertical so the fingers point DRINK_YAW to the
    # left of straight ahead, whatever the yaw of the grasp was.
    hand, R0 = c.arm.hand_pose()
    gpos, Rg0 = _pos(c, "glass"), w.data.xmat[w.body_id["glass"]].reshape(3, 3).copy()
    fingers = -R0[:, 2]
    Rc = rot_z(DRINK_YAW - np.arctan2(fingers[1], fingers[0])) @ R0   # yawed only: the glass stays as upright as it is
    g_in_hand, Rg_in_hand = R0.T @ (gpos - hand), R0.T @ Rg0
    axis0 = Rc @ Rg_in_hand[:, 2]
    toward_face = np.array([-1.0, 0.0, 0.0]) - axis0 * -axis0[0]
    toward_face /= max(float(np.linalg.norm(toward_face)), 1e-9)
    lip_in_hand = Rc.T @ (Rc @ g_in_hand + catalogue.height("glass") * axis0 + layout.GLASS_INNER_RADIUS * toward_face)
    lip_at = mouth + LIP_OFFSET

    def pose(tilt: float, away: float = 0.0):
        Rt = rot_y(-tilt) @ Rc
        return lip_at + np.array([away, 0.0, -0.5 * away]) - Rt @ lip_in_hand, Rt

    p, R = pose(0.3, away=0.08)
    if not (yield from _move(c, p, R)):
        return False, "could not bring the glass up"
    p, R = pose(0.5)
    yield from _move(c, p, R, tol=0.04)
    emptied = lambda: int(w.drunk.sum()) - drunk0 >= n0  # noqa: E731
    for tilt in np.linspace(0.9, TILT_MAX, 4):
        if emptied():
            break
        p, R = pose(tilt)
        yield from _move(c, p, R, speed=0.05, tol=0.05)
    enough = max(1, int(np.ceil(DRINK_FRACTION * max(n0, 1))))
    got = yield from _wait_until(c, lambda: int(w.drunk.sum()) - drunk0 >= enough and n0 > 0, timeout)
    drunk = int(w.drunk.sum()) - drunk0
    p, R = pose(0.0, away=0.10)
    yield from _move(c, p, R)
    c.note("drink", {"in_glass": n0, "drunk": drunk})
    if put_back:
        yield from put_down(c, "glass", at=tuple(base_xy))
    if n0 == 0:
        return False, "the glass was empty: nothing to drink"
    if not full:
        return False, f"the glass was not full: drank {drunk} of {n0} particles"
    return bool(got), f"drank {drunk} of {n0} particles"


def _rodrigues(axis: np.ndarray, angle: float) -> np.ndarray:
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _turning(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The smallest rotation that turns unit vector ``a`` onto unit vector ``b`` (not opposite)."""
    axis = np.cross(a, b)
    s = float(np.linalg.norm(axis))
    if s < 1e-9:
        return np.eye(3)
    return _rodrigues(axis, float(np.arctan2(s, float(np.dot(a, b)))))


class _PourWay:
    """A way to pour into the glass whose rim centre is ``rim``: the bottle, held with its mouth at
    ``mouth_in_hand`` (hand frame), stands upright beside the glass on the side away from ``toward`` (the
    horizontal direction its top tips to), then tips toward the glass by up to POUR_TILT about
    z x toward, its mouth coming down over the rim."""

    def __init__(self, rim: np.ndarray, mouth_in_hand: np.ndarray, gap: float) -> None:
        self.rim, self.mouth_in_hand = rim, mouth_in_hand
        self.beside = catalogue.radius("glass") + catalogue.radius("bottle") + gap

    def aim(self, toward, R_hand: np.ndarray, rise: float | None = None) -> None:
        """Tip toward ``toward`` from the hand orientation R_hand; the mouth starts ``rise`` above its pouring
        height (default: the bottle's height, its base above the rim)."""
        t = np.array([toward[0], toward[1], 0.0])
        self.toward = t / max(float(np.linalg.norm(t)), 1e-9)
        self.tip = np.cross([0.0, 0.0, 1.0], self.toward)   # tilting about this turns the bottle's top toward `toward`
        self.R_hand = R_hand
        self.rise = catalogue.height("bottle") if rise is None else rise

    def mouth_at(self, f: float) -> np.ndarray:
        return (self.rim - self.toward * self.beside * (1.0 - f)
                + np.array([0.0, 0.0, MOUTH_ABOVE_RIM + (1.0 - f) * self.rise]))

    def pose(self, f: float) -> tuple[np.ndarray, np.ndarray]:
        """Fraction f of the pour: 0 upright beside the glass, 1 fully tilted."""
        Rh = _rodrigues(self.tip, f * POUR_TILT) @ self.R_hand
        return self.mouth_at(f) - Rh @ self.mouth_in_hand, Rh

    def station(self) -> np.ndarray:
        """Where the bottle's base stands (x, y) before it tips."""
        return (self.rim - self.toward * self.beside)[:2]


#: the ways around the glass a person holding the bottle from above considers (directions, evenly spaced)
WAYS_FROM_ABOVE = 12


def _way_from_above(c, way: _PourWay, base_xy: np.ndarray) -> None:
    """Aims ``way`` for a bottle held from above. Such a hand cannot roll the bottle far every way (the forearm
    turns about 85 degrees each way, the wrist less, and how far depends on where the arm is): the person tries
    the ways around the glass with a sense of their own arm (`HumanArm.rehearse`) and takes the one that tips the
    bottle furthest, the nearest to where it stood among equals. The bottle need only clear the table before it
    tips (its base rises as it turns), which keeps the hand low enough to hold it from above."""
    xmax, ymax, inner = layout.standing_limits(catalogue.radius("bottle"))
    rise = catalogue.height("bottle") - catalogue.height("glass") + CARRY_CLEARANCE
    best = None
    for a in np.linspace(0.0, 2.0 * np.pi, WAYS_FROM_ABOVE, endpoint=False):
        toward = (np.cos(a), np.sin(a))
        way.aim(toward, np.eye(3), rise)
        x, y = way.station()
        if not (-xmax <= x <= -inner and abs(y) <= ymax):
            continue
        R = grip_orientation("ag", [x, y, way.rim[2]], c.arm.shoulder_xy)
        way.aim(toward, R, rise)
        start, R_start = way.pose(0.0)
        carry = [(over, R_start, None, MOVE_TOL) for over in _carry_path(c, start)] + [(start, R_start, None, MOVE_TOL)]
        tilts = [(*way.pose(float(f)), POUR_SPEED, POUR_TOL) for f in TILT_STEPS]
        key = (c.arm.rehearse(carry + tilts) - len(carry), -float(np.linalg.norm(way.station() - base_xy)))
        if best is None or key > best[0]:
            best = (key, toward, R)
    if best is None:   # no place beside the glass on this side of the table: tip it toward the person
        best = (None, (-1.0, 0.0), grip_orientation("ag", way.rim, c.arm.shoulder_xy))
    way.aim(best[1], best[2], rise)


def pour(c, timeout: float = POUR_TIMEOUT, grip: str = "sg") -> Gen:
    """Fill the upright glass on this side from the open bottle: a grip on the bottle (side or above), the bottle
    lifted beside the glass, then tilted toward it while its mouth comes over the rim, held until the glass looks
    full (a person's eyes: WorldState), tilted back and put back where it stood. From the side the bottle tips
    toward the palm; from above, the way around the glass that the arm can tip it furthest (`_way_from_above`)."""
    w = c.world
    if w.data.eq_active[w.eq_stopper]:
        return False, "the bottle is closed"
    if _axis(c, "glass")[2] < 0.9:
        return False, "the glass is not upright"
    base0 = _center_base(c, "bottle")[:2].copy()
    if w.human_holding() != "bottle":
        ok, why = yield from grasp(c, "bottle", grip)
        if not ok:
            return False, why

    def mouth_now() -> np.ndarray:
        """Where the bottle's mouth is (world), as the person sees it."""
        Rb = w.data.xmat[w.body_id["bottle"]].reshape(3, 3)
        return _pos(c, "bottle") + Rb @ np.array([0.0, 0.0, catalogue.height("bottle")])

    hand, R0 = c.arm.hand_pose()
    mouth_in_hand = R0.T @ (mouth_now() - hand)
    rim = _center_base(c, "glass") + np.array([0.0, 0.0, catalogue.height("glass")])
    if grip == "sg":
        # lifted with its base above the rim, the bottle tips toward the palm
        way = _PourWay(rim, mouth_in_hand, POUR_GAP)
        way.aim(R0[:, 1], R0)
    else:
        # from above, brought beside the glass lower (its base below the rim), so further off
        way = _PourWay(rim, mouth_in_hand, 2 * POUR_GAP)
        _way_from_above(c, way, base0)
    return (yield from _tip_into_glass(c, way, mouth_now, base0, timeout))


def _tip_into_glass(c, way: _PourWay, mouth_now: Callable[[], np.ndarray], base0: np.ndarray, timeout: float) -> Gen:
    """The bottle in hand brought beside the glass, tipped over it in TILT_STEPS, held until the glass looks
    full, tipped back and put down at ``base0``."""
    w = c.world

    def mouth_off(f: float) -> float:
        """How far (m, horizontally) the bottle's mouth is from where it should be at fraction f."""
        return float(np.linalg.norm((mouth_now() - way.mouth_at(f))[:2]))

    p, R = way.pose(0.0)
    if not (yield from _move(c, p, R)):
        return False, "could not bring the bottle to the glass"
    tilted = 0.0
    # tipping and tipping back are straight moves over the glass, as the way was planned: not carried over it
    for f in TILT_STEPS:
        p, R = way.pose(float(f))
        reached = yield from _move_straight(c, p, R, speed=POUR_SPEED, tol=POUR_TOL)
        if not reached or (f >= POURS_FROM and mouth_off(float(f)) > MOUTH_TOLERANCE):
            break       # the arm cannot bring the mouth over the rim: tilting on would pour beside the glass
        tilted = float(f)
    full = tilted == 1.0 and (yield from _wait_until(c, lambda: w.state().glass_state == "full", timeout))
    for f in np.linspace(0.75 * tilted, 0.0, 4):
        p, R = way.pose(float(f))
        yield from _move_straight(c, p, R, speed=POUR_SPEED, tol=POUR_TOL)
    yield from put_down(c, "bottle", at=tuple(base0))
    if tilted < 1.0:
        return False, "could not hold the bottle over the glass"
    return bool(full), "glass filled" if full else "the glass did not fill"


def wait(c, seconds: float) -> Gen:
    """Do nothing for `seconds`."""
    yield from _wait(c, seconds)
    return True, f"waited {seconds:g} s"


BEHAVIOURS: dict[str, Callable[..., Gen]] = {
    "grasp": grasp, "hold_out": hold_out, "put_down": put_down, "hand_to_robot": hand_to_robot,
    "take_from_robot": take_from_robot, "request": request, "point": point, "pull_stopper": pull_stopper,
    "turn_glass": turn_glass, "drink": drink, "pour": pour, "wait": wait, "put_down_for_robot": put_down_for_robot,
}
