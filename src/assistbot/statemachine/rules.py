"""The state machine's rules: what to do on a cue of the person, and what to do next on its own.

Written from the task data (`assistbot.task`) as an engineer would write them: a cue of the person
(an object held out, a wrong move, a request) is answered first; without one, the robot works through the
task's sub-goals in their order -- open the bottle, turn the glass, fill it, hand it over -- choosing the
action whose requirements (`RobotAction.requires`) the remembered facts meet. Every rule names the action;
`feasible` checks it against the task's own requirements, so a rule can never ask for what the task rules out.
"""

from __future__ import annotations

from assistbot.statemachine.memory import Memory
from assistbot.task import ROBOT_ACTION_BY_NAME

#: a person's wrong move (OL item) -> the mismatch (AML item) it is, when the object is in this state
WRONG_MOVES: tuple[tuple[str, str, str, str], ...] = (
    # cue,               object,   state,      mismatch
    ("grasp_sg_bottle", "bottle", "closed", "Cannot-remove-stopper"),   # only when it is held out (see cue_response)
    ("pour", "bottle", "closed", "Pour-from-closed-bottle"),
    ("pour", "glass", "inverted", "Pour-into-inverted-glass"),
    ("drink", "glass", "empty", "Drink-from-empty-glass"),
)


def feasible(action: str, m: Memory) -> bool:
    """The remembered facts meet the action's requirements in the task data."""
    facts = m.facts()
    return all(facts.get(key) in allowed for key, allowed in ROBOT_ACTION_BY_NAME[action].requires.items())


def mismatch(m: Memory) -> str | None:
    """The mismatch the person's current move is (an AML item), or None."""
    for cue, obj, state, error in WRONG_MOVES:
        if cue in m.cues and m.state(obj) == state:
            if error == "Cannot-remove-stopper" and "hold_out_bottle" not in m.cues:
                continue
            return error
    return None


def give(m: Memory, wanted: str | None) -> str | None:
    """The action that gives the person what they ask for (``wanted``, or whatever moves the task on)."""
    glass, bottle = m.state("glass"), m.state("bottle")
    if wanted in (None, "glass") and m.zone("glass") == "RWS":
        if glass == "full":
            return "Reach-full-glass-to-hand-over"
        if glass == "inverted":
            # with the open bottle on its side the robot fills the glass itself before handing it over
            return "Reach-and-turn-glass" if (bottle, m.zone("bottle")) == ("open", "RWS") else "Reach-turn-and-hand-over-glass"
        if glass == "empty" and (bottle, m.zone("bottle")) == ("open", "RWS"):
            return "Reach-grasp-open-bottle-fill-glass"
    if wanted in (None, "bottle") and m.zone("bottle") == "RWS":
        return "Hand-over-bottle"
    return None


def cue_response(m: Memory) -> tuple[str, str | None] | None:
    """(action, mismatch) answering the person's cue now, or None. Communicate-Error carries its mismatch."""
    error = mismatch(m)
    if error is not None:
        return "Communicate-Error", error
    held_out = next((c[len("hold_out_"):] for c in m.cues if c.startswith("hold_out_")), None)   # or "something"
    if held_out is not None:
        if held_out == "bottle" and m.state("bottle") == "closed":
            return "Grasp-hold-bottle-to-remove-cup", None
        return "Receive-object", None
    if "open_hand_request" in m.cues:
        action = give(m, None)
        return (action, None) if action else None
    pointed = next((c[len("point_"):] for c in m.cues if c.startswith("point_")), None)
    if pointed is not None:
        action = give(m, pointed)
        return (action, None) if action else None
    pours_or_drinks = m.state("glass") in ("empty", "full") and bool({"pour", "drink"} & set(m.cues))
    turns = "grasp_sg_glass" in m.cues and m.state("glass") == "inverted"
    if pours_or_drinks or turns:
        return "Wait", None    # the person pours, drinks or turns the glass: let them
    return None


def next_step(m: Memory) -> str | None:
    """The robot's own next step toward the drink, from the facts alone (the sub-goals in order)."""
    glass, bottle = m.state("glass"), m.state("bottle")
    gz, bz = m.zone("glass"), m.zone("bottle")
    if glass == "full":
        return "Reach-full-glass-to-hand-over" if gz == "RWS" else "Suggest-drink"
    if bottle == "closed":                                                  # Open-bottle
        return "Grasp-hold-bottle-to-remove-cup" if bz == "RWS" else "Request-bottle"
    if glass == "inverted":                                                 # Turn-glass
        if gz == "RWS":
            return "Reach-and-turn-glass" if bz == "RWS" else "Reach-turn-and-hand-over-glass"
        return "Request-glass"
    if gz == "RWS" and bz == "RWS":                                         # Fill-glass
        return "Reach-grasp-open-bottle-fill-glass"
    if gz == "RWS":
        return "Request-bottle"
    return "Request-glass"     # the glass on the person's side: the robot fills it on its own side
