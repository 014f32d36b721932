"""A partner's body built in the physics: the human of an MJCF spec edited to a `population.Body`.

The same edit is applied to the scene's spec (`world.build_world`) and to the arm's own IK model
(`ikmodel.arm_model`), so the arm the person plans with is the arm the physics moves:

- the seat (the whole person with the chair) moves back from the table and aside;
- the shoulders rise or sink with the sitting shoulder height: every point of the upper body above the
  table (torso top, shoulders, neck, head, mouth and eyes, the right arm) moves by the same height,
  while the hips, the legs and the left forearm resting on the table stay;
- the right upper arm and forearm are scaled in length (their capsules and the next joint's place);
- a reduced range of motion narrows the joints that carry the hand out (`ROM_JOINTS`: shoulder flexion
  and abduction, elbow; and their servos) toward the resting posture: each end of a range comes that
  fraction of its distance nearer the resting angle.

The person's workspace is theirs too (`own_places`): an object at its default place in the HWS stands
where this person has that place, within their reach, as the experimenter would set it for them.
"""

from __future__ import annotations

from functools import lru_cache

import mujoco
import numpy as np

from assistbot import catalogue
from assistbot.human.population import Body
from assistbot.resources import MJCF
from assistbot.world import HUMAN_ARM_JOINTS, Arrangement, Placement, layout

#: points of the upper body above this height (world z, m) move with the shoulders: above the table
#: top and the left forearm resting on it, below the shoulder
UPPER_BODY_FROM_Z = 0.85
SEAT_GEOM = "human_chair_seat"
SHOULDER_BODY = "human_r_upper_arm"
FOREARM_BODY = "human_r_forearm"
HAND_BODY = "human_r_hand"
#: the joints a reduced range of motion narrows: those that carry the hand out (shoulder flexion and
#: abduction, elbow), which limit the reach; the rotations of the upper arm and forearm and the wrist,
#: which orient the hand for a grip, keep their range (the person's grips have no other way to be made)
ROM_JOINTS = ("human_r_shoulder_flex", "human_r_shoulder_abd", "human_r_elbow")


@lru_cache(maxsize=1)
def resting_arm() -> tuple[float, ...]:
    """The arm's joint angles in the scene's home keyframe (the resting posture), in HUMAN_ARM_JOINTS order."""
    m = mujoco.MjModel.from_xml_path(str(layout.SCENE_XML))
    key = m.key("home").id
    return tuple(float(m.key_qpos[key][m.jnt_qposadr[m.joint(j).id]]) for j in HUMAN_ARM_JOINTS)


@lru_cache(maxsize=1)
def seat_top() -> float:
    """The chair seat's top in the person's frame (m): the shoulder height is measured from it."""
    seat = mujoco.MjSpec.from_file(str(MJCF / "human.xml")).geom(SEAT_GEOM)
    return float(seat.pos[2] + seat.size[2])


def _shift_upper(vec: np.ndarray, dz: float, z0: float) -> np.ndarray:
    """A point (x, y, z) of the person's body frame moved up by dz when it lies above UPPER_BODY_FROM_Z."""
    v = np.array(vec, float)
    if v[2] + z0 > UPPER_BODY_FROM_Z:
        v[2] += dz
    return v


def _move_geom(g, f) -> None:
    """Apply ``f`` (a point -> a point) to a geom's placement: both ends of a ``fromto``, else its ``pos``."""
    if not np.isnan(g.fromto[0]):
        g.fromto = np.concatenate([f(g.fromto[:3]), f(g.fromto[3:])])
    else:
        g.pos = f(g.pos)


def apply_body(spec: mujoco.MjSpec, body: Body) -> mujoco.MjSpec:
    """Edit the human in ``spec`` (a scene, or the arm alone) to ``body``; returns the spec."""
    if body.is_default():
        return spec
    person = spec.body("human_body")
    z0 = float(person.pos[2])
    person.pos = person.pos + np.array([-body.seat_back, body.seat_side, 0.0])
    if body.shoulder_height != 1.0:
        dz = (body.shoulder_height - 1.0) * (float(spec.body(SHOULDER_BODY).pos[2]) - seat_top())
        for g in person.geoms:
            _move_geom(g, lambda v: _shift_upper(v, dz, z0))
        for s in person.sites:
            s.pos = _shift_upper(s.pos, dz, z0)
        for b in person.bodies:
            b.pos = _shift_upper(b.pos, dz, z0)
    for name, child, scale in ((SHOULDER_BODY, FOREARM_BODY, body.upper_arm), (FOREARM_BODY, HAND_BODY, body.forearm)):
        if scale == 1.0:
            continue
        for g in spec.body(name).geoms:
            _move_geom(g, lambda v: v * scale)
        nxt = spec.body(child)
        nxt.pos = nxt.pos * scale
    if body.rom > 0.0:
        for name, rest in zip(HUMAN_ARM_JOINTS, resting_arm()):
            if name not in ROM_JOINTS:
                continue
            j = spec.joint(name)
            lo, hi = (float(v) for v in j.range)
            rng = np.array([rest + (1.0 - body.rom) * (lo - rest), rest + (1.0 - body.rom) * (hi - rest)])
            j.range = rng
            act = spec.actuator(name)
            if act is not None:
                act.ctrlrange = rng
    return spec


def own_places(arrangement: Arrangement, body: Body) -> Arrangement:
    """The arrangement as this person finds it: an object at its zone's default place in the HWS (the
    person's workspace) stands where this person has that place (`arm.own_table_spot`: the same place
    relative to their shoulder, in proportion to their reach). Explicit positions and the robot's
    workspace stay as given; for the default person nothing changes."""
    if body.is_default():
        return arrangement
    from assistbot.human.arm import own_table_spot, shoulder_and_reach
    from assistbot.human.ikmodel import arm_model

    shoulder, reach = shoulder_and_reach(arm_model(body))
    placed = {}
    for name, p in zip(catalogue.TASK_OBJECTS, arrangement.placements):
        if p.zone == "HWS" and p.position is None:
            xy = own_table_spot(catalogue.BY_NAME[name].places["HWS"], shoulder, reach, catalogue.radius(name))
            p = Placement(p.zone, p.state, (float(xy[0]), float(xy[1])))
        placed[name] = p
    return Arrangement(**placed).validate(f"the arrangement for {body}")
