"""An MJCF change the robot needs, applied in memory until assets/mjcf/robot.xml has it.

Requested from the scene's owner (see the issue 6 report): the finger bases
``robot_f3_prox`` / ``robot_f1_base`` / ``robot_f2_base`` at y = +-0.046 leave 74 mm
between the open fingers (their capsules are 9 mm thick, and the distal joints' lower
limit 0 keeps the fingers from splaying), less than the glass (80 mm). The glass is then
pinched by the open hand: it is dragged when the hand backs off after a release, and a
glass taken from the human's hand stays stuck in the open hand. At y = +-0.056 the
opening is 94 mm.

`apply(spec)` sets the value on a `mujoco.MjSpec` (a no-op once robot.xml has it);
`build_world(arrangement, seed)` is `assistbot.world.build_world` on the patched scene
(World accepts a compiled model), for the robot's tests and `assistbot act`.
"""

from __future__ import annotations

import mujoco

FINGER_Y = 0.056


def apply(spec: mujoco.MjSpec) -> mujoco.MjSpec:
    for name, sign in (("robot_f3_prox", 1), ("robot_f1_base", -1), ("robot_f2_base", -1)):
        b = spec.body(name)
        b.pos = [b.pos[0], sign * FINGER_Y, b.pos[2]]
    return spec


def needed() -> bool:
    """True while the scene's robot.xml still has the narrow finger spacing."""
    from assistbot.world import layout

    spec = mujoco.MjSpec.from_file(str(layout.SCENE_XML))
    return abs(abs(spec.body("robot_f3_prox").pos[1]) - FINGER_Y) > 1e-9


def build_world(arrangement, seed: int = 0):
    """`assistbot.world.build_world` with the finger spacing applied to the scene."""
    from assistbot.world import World, layout

    arrangement.validate()
    model = apply(mujoco.MjSpec.from_file(str(layout.SCENE_XML))).compile()
    return World(model, arrangement, seed)
