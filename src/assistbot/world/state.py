"""Ground truth of the scene (`WorldState`): for scoring, tests and the oracle perception only.

Cognition must never read it; it sees the world through vision's Percept.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from assistbot import catalogue
from assistbot.world import layout

FULL_FRACTION = 0.6   # a glass holding at least this share of the liquid is "full"


@dataclass(frozen=True)
class ObjectState:
    """Pose and situation of one object.  pos is in world coordinates (table x, y; z from the floor)."""

    name: str
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]
    zone: str                 # "HWS" or "RWS", by the object's x
    upright: bool             # object axis within 45 deg of vertical
    inverted: bool            # object axis within 45 deg of pointing down
    held_by: str | None       # "robot" (by gripper contact), "human" (grip weld) or None


@dataclass(frozen=True)
class LiquidState:
    total: int
    in_bottle: int
    in_glass: int
    drunk: int
    spilled: int              # everything else: on the table, the floor, or in flight
    near_mouth: int


@dataclass(frozen=True)
class WorldState:
    time: float
    objects: dict[str, ObjectState]
    bottle_open: bool         # the stopper is no longer fitted on the bottle
    stopper_attached: bool
    glass_state: str          # "inverted", "full" or "empty" (same words as the arrangement)
    bottle_state: str         # "open" or "closed"
    liquid: LiquidState
    robot_holds: str | None
    human_holds: str | None

    def state_of(self, name: str) -> str:
        """A task object's state, in the catalogue's (and the arrangement's) words."""
        return {"bottle": self.bottle_state, "glass": self.glass_state}[name]

    def summary(self) -> str:
        o = self.objects
        return (f"t={self.time:.2f}s bottle {o['bottle'].zone} {self.bottle_state}, glass {o['glass'].zone} {self.glass_state}, "
                f"liquid bottle/glass/spilled/drunk "
                f"{self.liquid.in_bottle}/{self.liquid.in_glass}/{self.liquid.spilled}/{self.liquid.drunk}, "
                f"robot holds {self.robot_holds}, human holds {self.human_holds}")


def in_cylinder(points: np.ndarray, pos: np.ndarray, R: np.ndarray, radius: float, z0: float, z1: float) -> np.ndarray:
    local = (points - pos) @ R  # R columns are the body axes
    return (np.hypot(local[:, 0], local[:, 1]) < radius) & (local[:, 2] > z0) & (local[:, 2] < z1)


def in_glass_region(world, pts: np.ndarray) -> np.ndarray:
    """Which of the points (world frame) lie inside the glass (its inner cylinder, rim included)."""
    d, gb = world.data, world.body_id["glass"]
    return in_cylinder(pts, d.xpos[gb], d.xmat[gb].reshape(3, 3), layout.GLASS_INNER_RADIUS + 0.002, 0.0, catalogue.height("glass") + 0.005)


def standing_end(world, name: str) -> np.ndarray:
    """World position of the centre of the end ``name`` stands on: its base, or the rim of an inverted glass
    (the body's origin is its base centre, and its axis then points down)."""
    d, b = world.data, world.body_id[name]
    pos, axis = d.xpos[b], d.xmat[b].reshape(3, 3)[:, 2]
    return pos + catalogue.height(name) * axis if (name in catalogue.TASK_OBJECTS and axis[2] < -0.707) else pos.copy()


def world_state(world) -> WorldState:
    d = world.data
    robot = world.robot_holding()
    human = world.human_holding()
    objects = {}
    for name in catalogue.NAMES:
        b = world.body_id[name]
        pos = d.xpos[b].copy()
        axis_z = d.xmat[b].reshape(3, 3)[2, 2]
        held = "robot" if robot == name else "human" if human == name else None
        objects[name] = ObjectState(name, tuple(pos), tuple(d.xquat[b]), layout.zone_of(pos[0]), axis_z > 0.707, axis_z < -0.707, held)
    pts = d.xpos[world.particle_bodies]
    alive = ~world.drunk
    bb = world.body_id["bottle"]
    in_bottle = in_cylinder(pts, d.xpos[bb], d.xmat[bb].reshape(3, 3), layout.BOTTLE_INNER_RADIUS + 0.002, 0.0,
                            catalogue.height("bottle") + 0.005) & alive
    in_glass = in_glass_region(world, pts) & alive & ~in_bottle
    mouth = d.site_xpos[world.site_id["human_mouth"]]
    near_mouth = int(np.sum((np.linalg.norm(pts - mouth, axis=1) < 0.08) & alive))
    total = len(pts)
    liquid = LiquidState(total, int(in_bottle.sum()), int(in_glass.sum()), int(world.drunk.sum()),
                         int(total - in_bottle.sum() - in_glass.sum() - world.drunk.sum()), near_mouth)
    attached = bool(d.eq_active[world.eq_stopper])
    g = objects["glass"]
    glass_state = "inverted" if g.inverted else ("full" if liquid.in_glass >= FULL_FRACTION * total else "empty")
    return WorldState(float(d.time), objects, not attached, attached, glass_state, "closed" if attached else "open",
                      liquid, robot, human)
