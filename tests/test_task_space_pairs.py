"""The six arrangement-profile pairs of the task space that failed when the task-space issue was filed (vision,
the default policies, seed 1 as in `make matrix`): each must drink, spilling under 10 %, with no robot geom more
than 1 cm into the person's (`TouchMonitor.DEEP`)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from assistbot.episode import run_scenario
from assistbot.episode.touch import TouchMonitor
from assistbot.scenario import parse_scenario

pytestmark = pytest.mark.slow
BASE = Path(__file__).resolve().parents[1] / "scenarios" / "sweeps" / "matrix-base.yaml"

PAIRS = [
    ("active", "HWS:closed", "HWS:inverted"),
    ("active", "HWS:open", "HWS:empty"),
    ("active", "HWS:closed", "RWS:full"),
    ("active", "HWS:open", "RWS:inverted"),
    ("passive", "HWS:closed", "HWS:inverted"),
    ("passive", "HWS:closed", "HWS:empty"),
]


def _episode(profile: str, bottle: str, glass: str):
    data = yaml.safe_load(BASE.read_text())
    for name, spec in (("bottle", bottle), ("glass", glass)):
        zone, state = spec.split(":")
        data["objects"][name] = {"zone": zone, "state": state}
    data["human"]["profile"] = profile
    return run_scenario(parse_scenario(data, BASE), perception="vision", video=False)


@pytest.mark.parametrize("profile, bottle, glass", PAIRS, ids=lambda v: v)
def test_the_pair_drinks(profile, bottle, glass):
    r = _episode(profile, bottle, glass)
    assert r.success and r.end_reason == "drink", (r.end_reason, [a for _, a in r.decisions])
    assert r.spilled_fraction < 0.1
    assert r.touched_person["depth"] <= TouchMonitor.DEEP, r.touched_person



def test_a_slow_person_pulls_the_stopper_from_the_bottle_the_robot_holds_with_the_hands_apart():
    """A slow person asks for the bottle; the robot says it will hold it for her to open, which cuts her request
    short. Her hand, still held out, is taken out of the robot's way before she waits for it (else the robot
    brings the bottle into it: 1.7 cm deep), then pulls the stopper while the robot holds the bottle."""
    r = _episode("slow", "RWS:closed", "RWS:empty")
    assert r.success and r.end_reason == "drink", (r.end_reason, [a for _, a in r.decisions])
    pulled = [e for e in r.world_events if e["event"] == "stopper_removed"]
    assert pulled and pulled[0]["robot_holds"] == "bottle" and pulled[0]["human_holds"] == "stopper", pulled
    assert r.touched_person["depth"] <= TouchMonitor.DEEP, r.touched_person
