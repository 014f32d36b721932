"""Validation of the scenario's human block: good scripts parse, mistakes name file, key and fix."""

import pytest

from assistbot.errors import UserError
from assistbot.human.script import HumanConfig, parse_human


def test_parses_the_documented_script():
    cfg = parse_human({
        "profile": "passive", "reaction_delay": 1.2, "grip": "side",
        "script": [
            {"do": "grasp", "object": "bottle", "grip": "side", "hold_out": True},
            {"do": "put_down", "object": "bottle", "at": [-0.25, -0.15]},
            {"do": "request", "gesture": "open_hand"},
            {"do": "wait", "seconds": 2},
            {"do": "pull_stopper", "after": {"robot_said": "invite:remove_stopper"}},
            {"do": "take", "object": "glass", "after": {"robot_holds": "glass"}},
            {"do": "drink", "after": "glass_full"},
        ],
    }, "s.yaml")
    assert isinstance(cfg, HumanConfig) and cfg.profile == "passive"
    assert cfg.overrides == {"reaction_delay": 1.2, "grip": "sg"}
    assert [s.do for s in cfg.script] == ["grasp", "put_down", "request", "wait", "pull_stopper", "take", "drink"]
    assert cfg.script[0].args["grip"] == "sg" and cfg.script[1].args["at"] == (-0.25, -0.15)
    assert cfg.script[4].after == ("robot_said", "invite:remove_stopper")
    assert cfg.script[6].after == ("glass_full", None)
    assert cfg.profile_params().reaction_delay == 1.2


@pytest.mark.parametrize("human,key,words", [
    ({"script": [{"do": "juggle"}]}, "human.script[0].do", "unknown step"),
    ({"script": [{"do": "put_down", "at": [0.2, 0.1]}]}, "human.script[0].at", "RWS"),
    ({"script": [{"do": "grasp", "object": "teapot"}]}, "human.script[0].object", "unknown object"),
    ({"script": [{"do": "drink", "after": "glass_sparkles"}]}, "human.script[0].after", "unknown event"),
    ({"script": [{"do": "drink", "after": {"robot_sings": 1}}]}, "human.script[0].after", "unknown event"),
    ({"script": [{"do": "drink", "after": {"robot_said": "hello"}}]}, "human.script[0].after.robot_said", "unknown utterance tag"),
    ({"script": [{"do": "take", "after": {"robot_holds": "cup"}}]}, "human.script[0].after.robot_holds", "unknown object"),
    ({"script": [{"do": "wait"}]}, "human.script[0].seconds", "missing"),
    ({"script": [{"do": "grasp", "object": "glass", "grip": "claw"}]}, "human.script[0].grip", "unknown grip"),
    ({"profile": "sleepy"}, "human.profile", "unknown profile"),
    ({"wrong_grip": 2}, "human.wrong_grip", "between 0 and 1"),
    ({"mood": "happy"}, "human.mood", "unknown key"),
])
def test_mistakes_name_the_key(human, key, words):
    with pytest.raises(UserError) as exc:
        parse_human(human, "scen.yaml")
    assert exc.value.where == "scen.yaml" and exc.value.key == key and words in exc.value.message
    assert exc.value.line().startswith("error: scen.yaml: ")
