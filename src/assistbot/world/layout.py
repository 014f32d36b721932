"""Numbers of the scene that Python needs: table, zones, the containers' insides, default places.

All positions are in table coordinates (see `assistbot.world`): metres, origin at the
centre of the table top, x from the human toward the robot, y to the human's left, z up.
The world frame is the same with z measured from the floor: world z = table z + TABLE_Z.
They must agree with assets/mjcf/*.xml (tests check the important ones). The objects' outer
sizes and grasp heights are read from the model itself (`assistbot.catalogue`).
"""

from __future__ import annotations

from assistbot.resources import MJCF

SCENE_XML = MJCF / "scene.xml"

TABLE_Z = 0.75                 # height of the table top above the floor (m)
TABLE_HALF_X = 0.40            # the table spans x in [-0.40, 0.40]
TABLE_HALF_Y = 0.55            # and y in [-0.55, 0.55]
EDGE_MARGIN = 0.02             # an object must stand this far inside the table edge
MIDLINE_MARGIN = 0.01          # ... and this far from the middle line, entirely in its half

ZONES = ("HWS", "RWS")         # human's workspace x < 0, robot's workspace x > 0

BOTTLE_INNER_RADIUS = 0.029
BOTTLE_BASE_TOP = 0.006        # inner floor height in the bottle frame
BOTTLE_BODY_TOP = 0.128        # top of the full-width body, where the shoulder starts
GLASS_INNER_RADIUS = 0.035
GLASS_BASE_TOP = 0.008
STOPPER_PLUG_DEPTH = 0.020     # the plug reaches this far below the stopper's origin

PARTICLE_RADIUS = 0.006
N_PARTICLES = 40

#: the hand-over zone across the middle line (table x, m): the person's hand beyond its near end with
#: something in it (or open) holds it out to the robot; the robot's hand short of its far end is held
#: out to the person. The one definition for vision, the oracle and the person's eyes.
HANDOVER_ZONE_X = (-0.15, 0.08)

#: where a removed stopper stands (in the HWS, at the human's left hand)
STOPPER_PARK = (-0.30, 0.36)

#: the person's head and torso as the MJCF names their main geoms; their other parts (hair, face; shoulders,
#: neck) carry these names as prefixes. What the robot's arm must keep clear of, and what safety is measured to
PERSON_HEAD_AND_TORSO = ("human_head", "human_torso")


def standing_limits(radius: float) -> tuple[float, float, float]:
    """Where an object of ``radius`` may stand (table x, y): |x| <= xmax and |y| <= ymax keep it EDGE_MARGIN
    inside the table's edge, |x| >= inner keeps it MIDLINE_MARGIN clear of the middle line, in its half."""
    return TABLE_HALF_X - radius - EDGE_MARGIN, TABLE_HALF_Y - radius - EDGE_MARGIN, radius + MIDLINE_MARGIN


def zone_of(x: float) -> str:
    """The workspace a table x coordinate lies in."""
    return "HWS" if x < 0.0 else "RWS"
