"""A small MuJoCo model of the human's right arm alone, for inverse kinematics.

Built from assets/mjcf/human.xml (the same file the scene includes, a model that compiles on its
own) with the fingers, actuators and sensors removed: 7 joints, a handful of bodies, so that one
kinematics pass and one Jacobian cost a few microseconds instead of the whole scene's
(the scene has ~290 degrees of freedom, mostly liquid particles).  The human body sits at
an absolute position in the world, so site positions here equal world positions.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

import mujoco

from assistbot.resources import MJCF

if TYPE_CHECKING:
    from assistbot.human.population import Body

HUMAN_XML: Path = MJCF / "human.xml"


@lru_cache(maxsize=1)
def arm_model_xml() -> str:
    root = ET.fromstring(HUMAN_XML.read_text())
    for tag in ("actuator", "sensor", "contact"):
        for e in root.findall(tag):
            root.remove(e)
    hand = root.find(".//body[@name='human_r_hand']")
    if hand is None:
        raise RuntimeError(f"{HUMAN_XML}: no body human_r_hand")
    for b in hand.findall("body"):
        hand.remove(b)
    body = root.find(".//body[@name='human_body']")
    for g in list(body):
        if g.tag == "geom" or (g.tag == "site" and g.get("name") not in ("human_mouth", "human_eyes")):
            body.remove(g)
    root.set("model", "human_arm_ik")
    return ET.tostring(root, encoding="unicode")


def arm_model(body: "Body | None" = None) -> mujoco.MjModel:
    """A fresh MjModel of the arm (joints in HUMAN_ARM_JOINTS order): the default person's, or ``body``'s
    (`human.body.apply_body`, the same edit the scene gets)."""
    if body is None or body.is_default():
        return mujoco.MjModel.from_xml_string(arm_model_xml())
    from assistbot.human.body import apply_body

    return apply_body(mujoco.MjSpec.from_string(arm_model_xml()), body).compile()
