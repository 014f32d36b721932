"""What the human does next: responses to the robot (every profile) and the active default policy.

Responses follow `assistbot.task.drinking.TAG_RESPONSES` (the robot's utterance tag -> the
partner's answer).  The default policy of a human with initiative picks a move from what he
sees on the table (positions and states of the objects: a person's eyes) and from what he
already did; with a seeded chance it first grasps with the wrong grip.
"""

from __future__ import annotations

from assistbot import catalogue
from assistbot.task.drinking import TAG_RESPONSES
from assistbot.world.layout import HANDOVER_ZONE_X

#: behaviours that a robot's utterance does not interrupt (the hand is busy with an object)
UNINTERRUPTIBLE = ("pull_stopper", "drink", "put_down", "turn_glass", "pour", "take_from_robot", "hand_to_robot")
#: ... but for a request that goes on with what the hand holds: asked to set down what it holds out,
#: or told to drink (from the full glass it is handing over; anything else it puts down first)
CONTINUES = {"hand_to_robot": ("put_down_for_robot", "drink")}
#: behaviours that start with an empty hand: what the hand still holds (an object a hand-over did not take)
#: is put down on her side first, not let fall (take_from_robot's own answers put it down: `_put_down_first`)
NEEDS_FREE_HAND = ("pull_stopper", "request", "point")


def _put_down_first(holding: str | None, keep: str | None) -> list[tuple[str, dict]]:
    """A hand about to act on ``keep`` first puts down anything else it holds, on this side."""
    return [("put_down", {})] if holding is not None and holding != keep else []


def _scene(c) -> dict:
    w = c.world
    d = w.data
    out = {}
    for o in catalogue.TASK_OBJECTS:
        b = w.body_id[o]
        out[o + "_x"] = float(d.xpos[b][0])
        out[o + "_up"] = float(d.xmat[b][8])
    out["bottle_closed"] = bool(d.eq_active[w.eq_stopper])
    out["glass_full"] = w.state().glass_state == "full" if out["glass_up"] > 0.7 else False
    out["holding"] = w.human_holding()
    return out


def _left_for_robot(c) -> str | None:
    """What she has set down for the robot to take (`put_down_for_robot`) and it has not yet taken to its side."""
    left = c.policy_state.get("left_for_robot")
    if left is not None and _scene(c)[left + "_x"] > 0:
        del c.policy_state["left_for_robot"]
        left = None
    return left


def response_to_tag(c, tag: str) -> list[tuple[str, dict]]:
    kind = TAG_RESPONSES.get(tag)
    what = tag.split(":", 1)[1] if ":" in tag else ""
    holding = c.world.human_holding()
    if kind == "remove_stopper":
        out = []
        handing_over = c.current is not None and c.current.name == "hand_to_robot"
        held_out = holding == "bottle" and c.world.site_pos("human_r_grasp")[0] > HANDOVER_ZONE_X[0]
        if held_out and not handing_over:
            # the robot is coming for the bottle he holds out: he keeps it there until the robot has it (held by
            # another grip than his usual one for giving, he first sets it down and takes it again that way)
            out.append(("hand_to_robot", {"object": "bottle", "grip": c.profile.grip}))
        elif holding is not None and not handing_over:
            out.append(("put_down", {}))
        return out + [("pull_stopper", {"wait_for_robot": 30.0})]
    if kind == "take_object":
        # a hand that holds something first puts it down on this side (or holds the bottle out
        # for ever, while the robot waits to give the glass)
        return _put_down_first(holding, what) + [("take_from_robot", {"object": what})]
    if kind == "give_object":
        return _put_down_first(holding, what) + [("hand_to_robot", {"object": what, "grip": c.profile.grip})]
    if kind == "drink":
        return _put_down_first(holding, "glass") + [("drink", {})]
    if kind == "put_down_here" and holding in catalogue.TASK_OBJECTS:
        return [("put_down_for_robot", {})]
    if kind == "put_down_here" and holding is None:
        # "it" is what she was handing over: a hand-over that failed left it on her side, beyond the
        # robot's reach; she picks it up again and sets it down under the robot's hand
        offered = c.policy_state.get("offered")
        if offered in catalogue.TASK_OBJECTS and _scene(c)[offered + "_x"] < 0:
            return [("grasp", {"object": offered, "grip": c.profile.hand_over_grip(offered)}), ("put_down_for_robot", {})]
    if tag == "error:cannot_remove_stopper" and holding == "bottle" and c.profile.initiative:
        # the robot cannot take the bottle from a side grip: put it down, offer it from above
        return [("put_down", {"object": "bottle"}), ("hand_to_robot", {"object": "bottle", "grip": "ag"})]
    return []


def response_to_sight(c, key: str) -> list[tuple[str, dict]]:
    # an active person takes what the robot holds out without being told (putting down what the hand holds)
    if key.startswith("robot_offers:") and c.profile.initiative:
        what = key.split(":", 1)[1]
        holding = c.world.human_holding()
        if holding == what or what == _left_for_robot(c):
            return []       # (lifted from where she set it down for the robot: taken, not offered)
        return _put_down_first(holding, what) + [("take_from_robot", {"object": what})]
    return []


def follow_up(c, done) -> list[tuple[str, dict]]:
    """What every partner does next after a behaviour of his succeeded (passive ones too).

    Holding a full glass he was handed, he drinks from it; handed an empty one, he sets it down on his
    side (to pour into it, or for the robot to fill), rather than hold it for ever. Handed the bottle
    while the glass is out of his reach (in the robot's workspace), he cannot pour: he puts the bottle
    down on his side, where the robot can take it again."""
    if done.name == "take_from_robot" and c.world.human_holding() == "glass":
        return [("drink", {})] if c.world.state().glass_state == "full" else [("put_down", {"object": "glass"})]
    if done.name == "take_from_robot" and c.world.human_holding() == "bottle" and _scene(c)["glass_x"] > 0:
        return [("put_down", {"object": "bottle"})]
    return []


def still_relevant(c, name: str, args: dict) -> bool:
    """A response that waited while the hand was busy: does what it answers still hold?"""
    if name == "take_from_robot":
        # the hand is free to take it; the robot may still be fetching the object it announced
        # (take_from_robot itself waits for the offer), but not be holding out something else
        offered = c.view.offers
        return c.world.human_holding() is None and (offered is None or args.get("object") in (None, offered))
    if name == "put_down":
        return c.world.human_holding() is not None
    if name == "hand_to_robot":
        # asked twice for what she was handing over: once the robot has it, there is nothing left to hand
        return args.get("object") is None or c.view.holds != args["object"]
    if name == "pull_stopper":
        return bool(c.world.data.eq_active[c.world.eq_stopper])
    return True


def next_move(c) -> tuple[str, dict] | None:
    """The active default policy: the next move toward drinking, or None."""
    s = _scene(c)
    st = c.policy_state
    if s["holding"] is not None:
        return None
    # what the robot holds, or what she has set down for it to take, is the robot's to act on
    left = _left_for_robot(c)
    mine = {o: s[o + "_x"] < 0 and o not in (left, c.view.holds) for o in catalogue.TASK_OBJECTS}
    if mine["glass"] and s["glass_full"] and not st.get("drink"):
        st["drink"] = True
        return ("drink", {})
    if mine["glass"] and s["glass_up"] < -0.7 and not st.get("turn"):
        st["turn"] = True
        return ("turn_glass", {})
    if (mine["bottle"] and not s["bottle_closed"] and mine["glass"] and s["glass_up"] > 0.9 and not s["glass_full"]
            and not st.get("pour")):
        st["pour"] = True
        return ("pour", {"grip": c.profile.pour_grip})
    if mine["bottle"] and s["bottle_closed"] and not st.get("bottle"):
        st["bottle"] = True
        grip = c.profile.grip
        if c.rng.random() < c.profile.wrong_grip:
            grip = "sg" if grip == "ag" else "ag"
            c.note("wrong_grip", {"grip": grip})
        return ("grasp", {"object": "bottle", "grip": grip, "hold_out": True})
    if s["glass_x"] > 0 and not st.get("request"):
        st["request"] = True
        return ("request", {"hold": 3.0})
    return None
