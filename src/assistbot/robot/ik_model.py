"""The IK model: the scene reduced to what the arm's inverse kinematics needs.

mink solves over every degree of freedom of the model it is given. The full
scene has free joints for the objects and 40 liquid particles (~270 dofs), so
the IK runs on a reduced copy instead: the robot with only its 7 arm joints
(fingers, spread and head frozen at their zero pose), the table, and the
human's torso and head (made collidable here, in the copy only, so that
`CollisionAvoidanceLimit` can keep the arm away from them). The human's arm,
the objects and the liquid are left out. In their place stand OBSTACLES: one upright cylinder
per task object, of its size, which the arm's IK keeps clear of wherever perception puts the
object (`ArmIK.set_obstacles`); unused, they stand far below the floor.
"""

from __future__ import annotations

from pathlib import Path

import mujoco

from assistbot import catalogue
from assistbot.world import layout

ARM_JOINTS: tuple[str, ...] = tuple(f"robot_j{i}" for i in range(1, 8))
HUMAN_BODY_GEOMS: tuple[str, ...] = layout.PERSON_HEAD_AND_TORSO
TABLE_GEOMS: tuple[str, ...] = ("table_top",)
#: robot geoms that move with the arm (the pedestal and column do not)
ARM_GEOMS: tuple[str, ...] = (
    "robot_upper_arm", "robot_forearm_a", "robot_forearm_b", "robot_palm",
    "robot_f1_prox", "robot_f1_dist", "robot_f2_prox", "robot_f2_dist", "robot_f3_prox", "robot_f3_dist",
)
#: the gripper's geoms (the only ones allowed near the table)
HAND_GEOMS: tuple[str, ...] = ARM_GEOMS[3:]
#: the robot's own fixed body, which the forearm and hand must not fold into
BODY_GEOMS: tuple[str, ...] = ("robot_column", "robot_pedestal")

_DROP_BODIES = (*catalogue.NAMES, "human_r_upper_arm")
#: task object -> (radius, height) of the cylinder that stands for it as an obstacle (m): the bottle with its stopper
OBSTACLES: dict[str, tuple[float, float]] = {
    o: (catalogue.radius(o), catalogue.top(o))
    for o in catalogue.TASK_OBJECTS
}
#: where an obstacle that stands for nothing is kept (world z, m)
OBSTACLE_AWAY_Z = -10.0


def obstacle_geom(name: str) -> str:
    return f"obstacle_{name}"


def default_scene_xml() -> Path:
    """The scene `assistbot.world.build_world` loads (assets/mjcf/scene.xml)."""
    return layout.SCENE_XML


def build_ik_model(scene_xml: str | Path | None = None) -> mujoco.MjModel:
    """Compile the reduced IK model from the scene MJCF (default: the world's scene.xml)."""
    spec = mujoco.MjSpec.from_file(str(scene_xml or default_scene_xml()))
    for group in (spec.keys, spec.equalities, spec.actuators, spec.sensors, spec.excludes):
        for element in list(group):
            spec.delete(element)
    for body in list(spec.bodies):
        if body.name in _DROP_BODIES or body.name.startswith("particle"):
            spec.delete(body)
    for joint in list(spec.joints):
        if joint.name not in ARM_JOINTS:
            spec.delete(joint)
    for geom in spec.geoms:
        if geom.name in HUMAN_BODY_GEOMS:
            geom.contype, geom.conaffinity = 1, 1
    for name, (radius, height) in OBSTACLES.items():
        body = spec.worldbody.add_body(name=obstacle_geom(name), pos=[0.0, 0.0, OBSTACLE_AWAY_Z])
        body.add_geom(name=obstacle_geom(name), type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[radius, height / 2, 0],
                      contype=1, conaffinity=1)
    model = spec.compile()
    assert model.nq == len(ARM_JOINTS), model.nq
    return model
