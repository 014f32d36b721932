"""The scene's objects, one entry each: the one place that lists them.

Every part that loops over objects (the world, the arrangement, the task's data, vision, the
person, the episode, the sweep) loops over `OBJECTS` or `TASK_OBJECTS` here. An entry gives
an object's name, its states (the first is the default), its MJCF body and sites, its parts
(the bottle's stopper), the colour class vision segments it by, and whether it is a task
object: placed by a scenario's arrangement, perceived, reasoned about, taken and handed over.

The geometry (`radius`, `height`, `top`, `grasp_height`) is read from the MJCF model that holds it
(assets/mjcf/objects.xml compiles on its own), once, on first use: importing this module
costs nothing. A new object needs its entry here and its bodies, sites and welds in the MJCF.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cache


@dataclass(frozen=True)
class CatalogueObject:
    """One object of the scene and where the MJCF model and vision find it."""

    name: str
    states: tuple[str, ...]    # the first is the default (no percept yet, nothing said)
    radius_geom: str           # the MJCF geom whose radius is the object's outer radius
    grasp_site: str            # the MJCF site where a gripper takes it (its height above the base)
    top_site: str | None       # the MJCF site at its top (the bottle's mouth, the glass's rim), None if flat
    parts: tuple[str, ...]     # other catalogue objects that start fitted on it
    colour: str                # the vision colour class (assistbot.vision.segment.PARTS)
    task: bool                 # a task object (see the module docstring)
    #: a task object's default place (table x, y, m) per zone, where an arrangement without a position puts it
    places: dict[str, tuple[float, float]] = field(default_factory=dict, compare=False)

    @property
    def body(self) -> str:
        """The MJCF body (free joint ``<name>_free``; the person's grip weld ``human_hold_<name>``)."""
        return self.name


OBJECTS: tuple[CatalogueObject, ...] = (
    CatalogueObject("bottle", states=("closed", "open"), radius_geom="bottle_visual_body", grasp_site="bottle_grasp",
                    top_site="bottle_mouth", parts=("stopper",), colour="bottle", task=True,
                    places={"HWS": (-0.22, -0.12), "RWS": (0.20, 0.12)}),
    CatalogueObject("glass", states=("inverted", "empty", "full"), radius_geom="glass_base", grasp_site="glass_grasp",
                    top_site="glass_rim", parts=(), colour="glass", task=True,
                    places={"HWS": (-0.22, 0.12), "RWS": (0.20, -0.12)}),
    CatalogueObject("stopper", states=(), radius_geom="stopper_cap", grasp_site="stopper_grasp",
                    top_site=None, parts=(), colour="stopper", task=False),
)
BY_NAME: dict[str, CatalogueObject] = {o.name: o for o in OBJECTS}
#: every object's name, in catalogue order
NAMES: tuple[str, ...] = tuple(BY_NAME)
#: the task objects' names (see the module docstring)
TASK_OBJECTS: tuple[str, ...] = tuple(o.name for o in OBJECTS if o.task)
#: task object -> its states, the default first
STATES: dict[str, tuple[str, ...]] = {o.name: o.states for o in OBJECTS if o.task}


@cache
def _model():
    import mujoco

    from assistbot.resources import MJCF

    return mujoco.MjModel.from_xml_path(str(MJCF / "objects.xml"))


@cache
def radius(name: str) -> float:
    """The object's outer radius (m)."""
    return float(_model().geom(BY_NAME[name].radius_geom).size[0])


@cache
def height(name: str) -> float:
    """Base to top (m): the bottle's mouth (without the stopper), the glass's rim."""
    site = BY_NAME[name].top_site
    if site is None:
        raise ValueError(f"the {name} has no top site")
    return float(_model().site(site).pos[2])


@cache
def top(name: str, fitted: bool = True) -> float:
    """Base to the top of the object as it stands (m): with ``fitted``, the parts fitted on it included (the
    closed bottle's stopper cap: its highest geom's top above the part's origin, which sits at the mouth)."""
    if not fitted or not BY_NAME[name].parts:
        return height(name)
    m = _model()
    return height(name) + max(_part_top(m, part) for part in BY_NAME[name].parts)


def _part_top(m, part: str) -> float:
    """How far (m) the part's upright cylinders and boxes reach above its body's origin."""
    import mujoco

    body = m.body(BY_NAME[part].body).id
    half = {int(mujoco.mjtGeom.mjGEOM_CYLINDER): 1, int(mujoco.mjtGeom.mjGEOM_BOX): 2}   # the size's half height
    return max(float(m.geom_pos[g][2] + m.geom_size[g][half[int(m.geom_type[g])]])
               for g in range(m.ngeom) if m.geom_bodyid[g] == body and int(m.geom_type[g]) in half)


@cache
def grasp_height(name: str) -> float:
    """Height (m) above the object's base where a gripper takes it upright."""
    return float(_model().site(BY_NAME[name].grasp_site).pos[2])
