"""The MuJoCo scene: a robot and a human at a table with a bottle (stopper, liquid) and a glass.

Frames.  World: origin on the floor under the table centre, z up, x pointing from the
human toward the robot, y to the human's left (the robot's right).  Table coordinates
(used by arrangements and scenario files): the same x and y in metres, origin at the
centre of the table top (world z = 0.75).  The middle line is x = 0; x < 0 is the human's
workspace (HWS), x > 0 the robot's (RWS).  The table spans |x| <= 0.40, |y| <= 0.55.

Why `mujoco.MjSpec` (and not dm_control's mjcf): the scene is one hand-written MJCF file
(assets/mjcf/scene.xml including robot.xml, human.xml, table.xml, objects.xml with liquid.xml)
that opens in `python -m mujoco.viewer` as is; an arrangement only changes initial poses,
so the native loader is enough and keeps the model a plain MjModel that mink and
mujoco.Renderer use directly, with no second naming layer and no dm_control/mujoco version
coupling.  MjSpec is the place to edit the model programmatically should that be needed.

Names other parts build on (see the MJCF files for the full parts lists):
  robot joints/actuators  robot_j1 .. robot_j7; robot_finger1..3 (proximal, distal coupled),
                          robot_spread; robot_head_pan, robot_head_tilt
  robot sites             robot_tcp (centre of a grasped 70 mm cylinder), robot_palm_face
  cameras                 head_cam_left, head_cam_right (0.12 m apart on the tilt body),
                          scene_cam (side view for videos), top_cam
  human                   human_r_* arm joints/actuators (HUMAN_ARM_JOINTS), hand joints
                          (HUMAN_HAND_JOINTS), site human_r_grasp, site human_mouth
  objects                 bodies bottle, stopper, glass, particle0..39; sites bottle_mouth,
                          bottle_grasp, glass_rim, glass_grasp, stopper_grasp
  equalities              stopper_fit, human_hold_bottle/glass/stopper

Usage::

    from assistbot.world import Arrangement, build_world
    world = build_world(Arrangement.from_options("HWS:closed", "RWS:inverted"), seed=0)
    world.step(500)                 # 1 s
    print(world.state().summary())
"""

from assistbot.world.arrangement import PAPER_ARRANGEMENTS, Arrangement, Placement, all_arrangements
from assistbot.world.layout import TABLE_Z, zone_of
from assistbot.world.state import LiquidState, ObjectState, WorldState
from assistbot.world.world import (
    CAMERAS,
    GRIPPER_CLOSED,
    GRIPPER_OPEN,
    HAND_POSTURES,
    HUMAN_ARM_JOINTS,
    HUMAN_HAND_JOINTS,
    ROBOT_ARM_ACTUATORS,
    ROBOT_ARM_JOINTS,
    ROBOT_FINGER_ACTUATORS,
    ROBOT_HEAD_JOINTS,
    STOPPER_RELEASE_FORCE,
    World,
    build_world,
)

__all__ = [
    "Arrangement", "Placement", "PAPER_ARRANGEMENTS", "all_arrangements", "build_world", "World",
    "WorldState", "ObjectState", "LiquidState", "TABLE_Z", "zone_of", "CAMERAS", "HAND_POSTURES",
    "HUMAN_ARM_JOINTS", "HUMAN_HAND_JOINTS", "ROBOT_ARM_JOINTS", "ROBOT_ARM_ACTUATORS",
    "ROBOT_FINGER_ACTUATORS", "ROBOT_HEAD_JOINTS", "GRIPPER_OPEN", "GRIPPER_CLOSED", "STOPPER_RELEASE_FORCE",
]
