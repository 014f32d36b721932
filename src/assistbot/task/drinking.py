"""The drinking task as plain data: objects, sub-goals, actions, intentions, errors, utterances.

Everything the robot "knows" about the task is here, readable in one file and
free of logic (lookups only). `assistbot.cognition` turns these associations
into the connection tables a_mj of its fields; the human model reacts to the
``tag`` of each utterance; the robot module realises the `ROBOT_ACTIONS`; the
coverage test searches the `effects` below.

Names follow the seed paper (shared/seed, sections III-IV) where it gives them.
Item names never contain dots, so parameter paths like
``couplings.IL->AEL.table.Request-glass.Get-glass`` stay unambiguous.

Weights are relevance in [-1, 1]-ish units: 1 means "this fact is one full
piece of evidence for that item"; cognition scales them by coupling gains.
Negative weights are evidence against (inhibition).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from assistbot import catalogue

# ---------------------------------------------------------------------------------------------
# Objects, states, zones
# ---------------------------------------------------------------------------------------------

#: object type -> its possible states, the default first ("empty" and "full" glasses are upright): the catalogue's task objects
OBJECT_STATES: dict[str, tuple[str, ...]] = catalogue.STATES
OBJECTS: tuple[str, ...] = catalogue.TASK_OBJECTS
#: HWS: the human's workspace, RWS: the robot's. The human never reaches into RWS, the robot never into HWS.
ZONES: tuple[str, ...] = ("HWS", "RWS")
#: who can hold an object
HOLDERS: tuple[str, ...] = ("human", "robot")
#: the seed's short names of object states (CB closed bottle, OB open bottle, IG inverted glass, EG empty glass, FG full glass)
SHORT_NAMES: dict[tuple[str, str], str] = {
    ("bottle", "closed"): "CB",
    ("bottle", "open"): "OB",
    ("glass", "inverted"): "IG",
    ("glass", "empty"): "EG",
    ("glass", "full"): "FG",
}


def oml_item(obj: str, state: str, zone: str) -> str:
    """Name of the Object Memory Layer item for an object in a state and zone, e.g. ``bottle_closed_HWS``."""
    return f"{obj}_{state}_{zone}"


#: OML items: object x state x zone.
OML_ITEMS: tuple[str, ...] = tuple(oml_item(o, s, z) for o, states in OBJECT_STATES.items() for s in states for z in ZONES)

# ---------------------------------------------------------------------------------------------
# Sub-goals (CSGL): order and preconditions
# ---------------------------------------------------------------------------------------------

#: in task order (the order is also the priority when several are enabled)
SUBGOALS: tuple[str, ...] = ("Open-bottle", "Turn-glass", "Fill-glass", "Hand-over-full-glass")
#: sub-goal -> sub-goals that must be achieved before it is enabled
PRECONDITIONS: dict[str, tuple[str, ...]] = {
    "Open-bottle": (),
    "Turn-glass": (),
    "Fill-glass": ("Open-bottle", "Turn-glass"),
    "Hand-over-full-glass": ("Fill-glass",),
}
#: sub-goal -> the object facts (OML items) that show it is achieved. A later
#: sub-goal's evidence implies the earlier ones (a full glass was turned and filled).
ACHIEVED_BY: dict[str, tuple[str, ...]] = {
    "Open-bottle": ("bottle_open_HWS", "bottle_open_RWS", "glass_full_HWS", "glass_full_RWS"),
    "Turn-glass": ("glass_empty_HWS", "glass_empty_RWS", "glass_full_HWS", "glass_full_RWS"),
    "Fill-glass": ("glass_full_HWS", "glass_full_RWS"),
    "Hand-over-full-glass": ("glass_full_HWS",),
}
#: the final goal, done by the human only
FINAL_GOAL = "Drink"
#: the share of the glass's liquid that must reach the person's mouth for the drink to count: the
#: task's success, and so what the person drinks before she puts the glass down
DRINK_FRACTION = 0.75

# ---------------------------------------------------------------------------------------------
# Observation layer (OL): the human's motor primitives, with the object they are directed at
# ---------------------------------------------------------------------------------------------

#: hand postures the vision module classifies (static templates); see cognition.percept.HandPercept
HAND_POSTURES: tuple[str, ...] = (
    "none", "reach", "grasp_ag", "grasp_sg", "open_palm_request", "pointing", "remove_stopper", "pour", "drink",
)

#: OL items: primitive (+ object it is directed at). "hold_out" = the object in hand is held out toward the robot.
OL_ITEMS: tuple[str, ...] = (
    "reach_bottle", "grasp_ag_bottle", "grasp_sg_bottle", "hold_out_bottle", "point_bottle",
    "reach_glass", "grasp_ag_glass", "grasp_sg_glass", "hold_out_glass", "point_glass",
    "open_hand_request", "remove_stopper", "pour", "drink",
)

# ---------------------------------------------------------------------------------------------
# Grip-to-goal priors (seed IV, assumptions iii-v): weights, not a one-to-one map
# ---------------------------------------------------------------------------------------------

#: (grip, object) -> {goal: weight}. AG -> hand over; SG on bottle -> pour (or, held out, ask for help);
#: SG on glass -> turn or drink depending on its state.
GRIP_PRIORS: dict[tuple[str, str], dict[str, float]] = {
    ("grasp_ag", "bottle"): {"hand-over": 1.0, "pour": 0.3, "ask-help": 0.3},
    ("grasp_sg", "bottle"): {"pour": 1.0, "ask-help": 1.0, "hand-over": 0.3},
    ("grasp_ag", "glass"): {"hand-over": 1.0, "turn": 0.3, "drink": 0.2},
    ("grasp_sg", "glass"): {"turn": 1.0, "drink": 1.0, "hand-over": 0.3},
}


def grip_prior(grip: str, obj: str, goal: str) -> float:
    return GRIP_PRIORS.get((grip, obj), {}).get(goal, 0.0)


#: the OL items that are a grip on an object: what the grip-to-goal priors map, and what learning from the
#: user re-maps (`assistbot.cognition.learning`)
OL_GRIP_ITEMS: tuple[str, ...] = tuple(f"{grip}_{obj}" for grip, obj in GRIP_PRIORS)


# ---------------------------------------------------------------------------------------------
# Action simulation layer (ASL): the human's goal-directed action chains
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Chain:
    """A goal-directed action chain of the human, and the evidence for it.

    ``primitives``: OL item -> weight (the observed motor acts);
    ``objects``: OML item -> weight (context); ``subgoals``: CSGL-present item -> weight (task knowledge).
    """

    name: str
    primitives: dict[str, float]
    objects: dict[str, float] = field(default_factory=dict)
    subgoals: dict[str, float] = field(default_factory=dict)


def _both(obj_state: str, w: float) -> dict[str, float]:
    return {f"{obj_state}_HWS": w, f"{obj_state}_RWS": w}


#: a glass held out toward the robot reads as its hand-over on its own, whichever grip took it (the grip
#: foretells a hand-over; the hold-out is one), in any state. The bottle's hold-out weighs less: a closed bottle
#: held out from the side asks for help (the seed's Fig. 3), and weighed like this the open bottle's hand-over
#: would also take a closed bottle held out
HOLD_OUT_HANDS_OVER = 2.4
#: a held-out object is not being poured from, turned or drunk from
HOLD_OUT_NOT_IN_USE = -0.8


ASL_CHAINS: tuple[Chain, ...] = (
    Chain("Reach-grasp-SG-closed-bottle",
          {"reach_bottle": 0.4, "grasp_sg_bottle": grip_prior("grasp_sg", "bottle", "ask-help"), "hold_out_bottle": 0.6, "pour": -1.0},
          _both("bottle_closed", 1.0), {"Open-bottle": 0.5}),
    Chain("Reach-grasp-AG-closed-bottle-to-hand-over",
          {"reach_bottle": 0.4, "grasp_ag_bottle": grip_prior("grasp_ag", "bottle", "hand-over"), "hold_out_bottle": 0.6},
          _both("bottle_closed", 1.0), {"Open-bottle": 0.5}),
    Chain("Reach-grasp-SG-open-bottle-to-pour",
          {"reach_bottle": 0.4, "grasp_sg_bottle": grip_prior("grasp_sg", "bottle", "pour"), "pour": 2.4,
           "hold_out_bottle": HOLD_OUT_NOT_IN_USE},
          {**_both("bottle_open", 0.6), **_both("bottle_closed", 0.6)}, {"Fill-glass": 0.5}),
    Chain("Reach-grasp-AG-open-bottle-to-hand-over",
          {"reach_bottle": 0.4, "grasp_ag_bottle": grip_prior("grasp_ag", "bottle", "hand-over"), "hold_out_bottle": 0.6},
          _both("bottle_open", 1.0), {"Fill-glass": 0.5}),
    Chain("Reach-grasp-AG-glass-to-hand-over",
          {"reach_glass": 0.4, "grasp_ag_glass": grip_prior("grasp_ag", "glass", "hand-over"),
           "hold_out_glass": HOLD_OUT_HANDS_OVER},
          {**_both("glass_inverted", 0.6), **_both("glass_empty", 0.6), **_both("glass_full", 0.3)},
          {"Turn-glass": 0.3, "Fill-glass": 0.5}),
    Chain("Reach-grasp-SG-glass-to-turn",
          {"reach_glass": 0.4, "grasp_sg_glass": grip_prior("grasp_sg", "glass", "turn"), "drink": -1.0,
           "hold_out_glass": HOLD_OUT_NOT_IN_USE},
          _both("glass_inverted", 1.0), {"Turn-glass": 0.5}),
    Chain("Reach-grasp-SG-full-glass-to-drink",
          {"reach_glass": 0.4, "grasp_sg_glass": grip_prior("grasp_sg", "glass", "drink"), "drink": 2.4,
           "hold_out_glass": HOLD_OUT_NOT_IN_USE},
          {**_both("glass_full", 1.0), **_both("glass_empty", 0.6)}, {}),
    # a communicative gesture is one clear cue on its own
    Chain("Request-object-with-open-hand", {"open_hand_request": 3.8}, {}, {}),
    Chain("Point-to-bottle", {"point_bottle": 3.8}, {}, {}),
    Chain("Point-to-glass", {"point_glass": 3.8}, {}, {}),
)
ASL_ITEMS: tuple[str, ...] = tuple(c.name for c in ASL_CHAINS)
#: what a grip can mean: for each grip item, the chains a grip on the same object begins (a grip on the bottle
#: says nothing of the glass; the gestures are read from the gesture alone)
GRIP_CHAINS: dict[str, tuple[str, ...]] = {
    f"{grip}_{obj}": tuple(c.name for c in ASL_CHAINS if any(f"{g}_{o}" in c.primitives for g, o in GRIP_PRIORS if o == obj))
    for grip, obj in GRIP_PRIORS}

# ---------------------------------------------------------------------------------------------
# Intention layer (IL)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Intention:
    """An intention of the human: ``chains`` ASL -> weight, ``subgoals`` CSGL-present -> weight, ``objects`` OML -> weight;
    ``acts``: the OL acts in which the partner is seen doing what it predicts (a success of the reading)."""

    name: str
    chains: dict[str, float]
    subgoals: dict[str, float] = field(default_factory=dict)
    objects: dict[str, float] = field(default_factory=dict)
    acts: tuple[str, ...] = ()


INTENTIONS: tuple[Intention, ...] = (
    Intention("Remove-stopper",
              {"Reach-grasp-SG-closed-bottle": 1.5, "Reach-grasp-AG-closed-bottle-to-hand-over": 1.5},
              {"Open-bottle": 1.0}),
    Intention("Pour", {"Reach-grasp-SG-open-bottle-to-pour": 2.5}, {"Fill-glass": 0.5}, acts=("pour",)),
    Intention("Turn-glass", {"Reach-grasp-SG-glass-to-turn": 2.5}, {"Turn-glass": 0.5}),
    Intention("Drink", {"Reach-grasp-SG-full-glass-to-drink": 2.5}, {"Hand-over-full-glass": 0.3}, acts=("drink",)),
    Intention("Get-glass",
              {"Request-object-with-open-hand": 1.0, "Point-to-glass": 2.0},
              {"Turn-glass": 0.8, "Fill-glass": 0.3, "Hand-over-full-glass": 0.8},
              {"glass_inverted_RWS": 0.6, "glass_empty_RWS": 0.6, "glass_full_RWS": 0.6}),
    Intention("Get-bottle",
              {"Request-object-with-open-hand": 1.0, "Point-to-bottle": 2.0},
              {"Open-bottle": 0.3, "Fill-glass": 0.8},
              {"bottle_closed_RWS": 0.5, "bottle_open_RWS": 0.6}),
    Intention("Give-glass", {"Reach-grasp-AG-glass-to-hand-over": 2.5}, {"Turn-glass": 0.3, "Fill-glass": 0.5},
              acts=("hold_out_glass",)),
    # a closed bottle handed over is to be opened while opening it is the sub-goal; once it is not
    # (the glass already full, say), it is simply given
    Intention("Give-bottle", {"Reach-grasp-AG-open-bottle-to-hand-over": 2.5, "Reach-grasp-AG-closed-bottle-to-hand-over": 1.2},
              {"Fill-glass": 0.5, "Hand-over-full-glass": 0.5}, acts=("hold_out_bottle",)),
)
IL_ITEMS: tuple[str, ...] = tuple(i.name for i in INTENTIONS)
#: intention -> the partner's acts that carry it out (seen while it is inferred: the reading succeeded)
INTENTION_ACTS: dict[str, tuple[str, ...]] = {i.name: i.acts for i in INTENTIONS if i.acts}

# ---------------------------------------------------------------------------------------------
# Action monitoring layer (AML): mismatches between the intention and what is possible
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Error:
    """A mismatch: ``intentions`` IL -> weight, plus the fact that makes it impossible: ``chains`` ASL or ``objects`` OML."""

    name: str
    intentions: dict[str, float]
    chains: dict[str, float] = field(default_factory=dict)
    objects: dict[str, float] = field(default_factory=dict)


ERRORS: tuple[Error, ...] = (
    # held from the side, the bottle cannot be taken safely, and the robot's hand is too big for the stopper
    Error("Cannot-remove-stopper", {"Remove-stopper": 1.0}, {"Reach-grasp-SG-closed-bottle": 1.5}),
    Error("Pour-from-closed-bottle", {"Pour": 1.0}, {}, _both("bottle_closed", 1.2)),
    Error("Pour-into-inverted-glass", {"Pour": 1.0}, {}, _both("glass_inverted", 1.2)),
    Error("Drink-from-empty-glass", {"Drink": 1.0}, {}, _both("glass_empty", 1.2)),
)
#: Mismatches between what the robot did and what came of it: an action of the robot's that failed again
#: while the memory of its failure (the AFL layer) still stood. action -> the AML item it raises.
#: Failing to take what the person holds out is its own mismatch (it has an alternative: Take-from-table);
#: every other repeated failure is one mismatch, said as such, the action kept inhibited.
ACTION_FAILURES: tuple[str, ...] = ("Cannot-take-it-from-the-hand", "Keeps-failing")
#: An object seen lying on its side: neither partner can stand it up again here, so the task cannot go on.
#: object -> its AML item (driven by the percept, `Cognition.perceive`; it drives no action).
FALLS: dict[str, str] = {"bottle": "Bottle-fell-over", "glass": "Glass-fell-over"}
AML_ITEMS: tuple[str, ...] = tuple(e.name for e in ERRORS) + ACTION_FAILURES + tuple(FALLS.values())

# ---------------------------------------------------------------------------------------------
# Robot actions (AEL)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RobotAction:
    """A complementary action of the robot.

    ``target``: the object it acts on ("bottle", "glass"), "held_out" (whatever
    the human holds out) or None. ``motion``: what the robot module does for it: a
    motion (`assistbot.robot.actions.MOTIONS` names its primitive and the object that
    primitive acts on), or "speak" (speech only) or "none" (nothing); `moves` tells which.
    Evidence for selecting it (AEL inputs), weights: ``intentions`` (IL),
    ``objects`` (OML), ``present``/``past`` (CSGL), ``errors`` (AML),
    ``initiative`` (the robot's own initiative when the partner is passive), ``failures`` (AML
    mismatches of the robot's own repeated failures, `ACTION_FAILURES`).
    ``requires``/``effects``/``response``: the world model used by the coverage
    check (world-state variable -> allowed values / new value; the partner's
    response the action asks for, which a passive partner gives too).
    """

    name: str
    target: str | None
    motion: str
    intentions: dict[str, float] = field(default_factory=dict)
    objects: dict[str, float] = field(default_factory=dict)
    present: dict[str, float] = field(default_factory=dict)
    past: dict[str, float] = field(default_factory=dict)
    errors: dict[str, float] = field(default_factory=dict)
    failures: dict[str, float] = field(default_factory=dict)
    initiative: float = 0.0
    requires: dict[str, tuple] = field(default_factory=dict)
    effects: dict[str, object] = field(default_factory=dict)
    response: str | None = None

    @property
    def moves(self) -> bool:
        """The robot moves its arm for it (and so may fail physically): not speech or waiting alone."""
        return self.motion not in ("speak", "none")


_ALL_ERRORS = {e.name: 1.0 for e in ERRORS}

ROBOT_ACTIONS: tuple[RobotAction, ...] = (
    RobotAction("Communicate-Error", None, "speak", errors={k: 3.5 for k in _ALL_ERRORS}),
    RobotAction("Grasp-hold-bottle-to-remove-cup", "bottle", "grasp_hold_bottle",
                intentions={"Remove-stopper": 1.6, "Get-bottle": -1.0},
                objects={"bottle_closed_RWS": 1.2, "bottle_closed_HWS": 0.6},
                present={"Open-bottle": 1.0}, errors={"Cannot-remove-stopper": -3.0},
                failures={"Cannot-take-it-from-the-hand": -4.0}, initiative=1.0,
                requires={"bottle_state": ("closed",), "bottle_zone": ("RWS", "held_out")},
                effects={"bottle_state": "open", "bottle_zone": "RWS"}, response="remove_stopper"),
    RobotAction("Reach-and-turn-glass", "glass", "turn_glass",
                intentions={"Get-glass": 0.8, "Turn-glass": -1.0},
                objects={"glass_inverted_RWS": 0.8, "bottle_open_RWS": 0.6, "bottle_open_HWS": -0.3},
                present={"Turn-glass": 1.0}, initiative=1.0,
                requires={"glass_state": ("inverted",), "glass_zone": ("RWS",)}, effects={"glass_state": "empty"}),
    RobotAction("Reach-turn-and-hand-over-glass", "glass", "turn_and_hand_over_glass",
                intentions={"Get-glass": 1.5, "Turn-glass": -1.0},
                # the seed: an open bottle in RWS inhibits handing the glass over (the robot fills it first)
                objects={"glass_inverted_RWS": 0.8, "bottle_open_RWS": -1.5, "bottle_open_HWS": 0.4, "bottle_closed_HWS": 0.2},
                present={"Turn-glass": 1.0}, initiative=0.9,
                requires={"glass_state": ("inverted",), "glass_zone": ("RWS",)},
                effects={"glass_state": "empty", "glass_zone": "HWS"}, response="take_object"),
    RobotAction("Reach-grasp-open-bottle-fill-glass", "glass", "fill_glass",
                intentions={"Get-bottle": -1.0},
                objects={"bottle_open_RWS": 0.7, "glass_empty_RWS": 0.7, "glass_empty_HWS": -1.0},
                present={"Fill-glass": 1.0}, initiative=1.0,
                requires={"bottle_state": ("open",), "bottle_zone": ("RWS",), "glass_state": ("empty",), "glass_zone": ("RWS",)},
                effects={"glass_state": "full"}),
    RobotAction("Reach-full-glass-to-hand-over", "glass", "hand_over_glass",
                intentions={"Get-glass": 1.0},
                objects={"glass_full_RWS": 1.5}, present={"Hand-over-full-glass": 1.0}, initiative=1.0,
                requires={"glass_state": ("full",), "glass_zone": ("RWS",)},
                effects={"glass_zone": "HWS"}, response="take_object"),
    RobotAction("Request-glass", "glass", "request_glass",
                intentions={"Give-glass": -1.0},  # not asked for while it is being given
                objects={"glass_empty_HWS": 1.0, "glass_inverted_HWS": 0.8, "bottle_open_RWS": 0.4,
                         "glass_empty_RWS": -1.0, "glass_inverted_RWS": -1.0, "glass_full_RWS": -1.0},
                present={"Fill-glass": 1.0, "Turn-glass": 1.0}, initiative=1.0,
                requires={"glass_zone": ("HWS",), "glass_state": ("inverted", "empty")},
                effects={"glass_zone": "RWS"}, response="give_object"),
    RobotAction("Request-bottle", "bottle", "request_bottle",
                intentions={"Give-bottle": -1.0},  # not asked for while it is being given
                objects={"bottle_closed_HWS": 1.0, "bottle_open_HWS": 1.0, "glass_empty_RWS": 0.3},
                present={"Open-bottle": 1.0, "Fill-glass": 0.8}, initiative=1.0,
                requires={"bottle_zone": ("HWS",)}, effects={"bottle_zone": "RWS"}, response="give_object"),
    RobotAction("Hand-over-bottle", "bottle", "hand_over_bottle",
                intentions={"Get-bottle": 2.0},
                # as the seed's open bottle keeps the glass in RWS until filled: with the empty glass in
                # RWS the robot fills it rather than hand over a bottle the partner cannot pour from
                objects={"bottle_open_RWS": 0.8, "glass_empty_HWS": 0.6, "bottle_closed_RWS": 0.3, "glass_empty_RWS": -1.5},
                present={"Fill-glass": 0.6}, initiative=0.5,
                requires={"bottle_zone": ("RWS",)}, effects={"bottle_zone": "HWS"}, response="take_object"),
    RobotAction("Receive-object", "held_out", "receive_object",
                intentions={"Give-glass": 2.8, "Give-bottle": 2.8}, failures={"Cannot-take-it-from-the-hand": -4.0},
                objects={"bottle_open_HWS": 0.6, "bottle_closed_HWS": 0.6, "glass_inverted_HWS": 0.6, "glass_empty_HWS": 0.6,
                         "glass_full_HWS": 0.6},
                initiative=0.5, requires={"bottle_zone": ("held_out",)}, effects={"bottle_zone": "RWS"}),
    # the other way to get what the person cannot hand over: set down within reach, it is taken from the table
    RobotAction("Take-from-table", None, "take_from_table",
                failures={"Cannot-take-it-from-the-hand": 4.0}),
    RobotAction("Suggest-drink", "glass", "speak",
                intentions={"Drink": -2.0},
                objects={"glass_full_HWS": 1.5}, past={"Hand-over-full-glass": 1.0}, initiative=1.0,
                requires={"glass_state": ("full",), "glass_zone": ("HWS",)}, effects={"drunk": True}, response="drink"),
    RobotAction("Wait", None, "none",
                intentions={"Turn-glass": 2.5, "Pour": 2.5, "Drink": 2.5},
                objects={"glass_inverted_HWS": 0.6, "bottle_open_HWS": 0.6, "glass_full_HWS": 0.6}),
)
AEL_ITEMS: tuple[str, ...] = tuple(a.name for a in ROBOT_ACTIONS)

#: OML -> AEL weight of an object fact that rules an action out (`requires` not met)
AGAINST_REQUIREMENT = -1.0


def facts_against(action: RobotAction) -> tuple[str, ...]:
    """The OML items that rule ``action`` out: an object in a state or a zone its ``requires`` does not
    allow (the robot cannot turn a glass the person has, nor fill an inverted one). "held_out" stands
    for the person's workspace (the object is held out from there); an action on whatever is held out
    (Receive-object) has no object facts against it."""
    if action.target == "held_out":
        return ()
    out = []
    for obj, states in OBJECT_STATES.items():
        ok_states = action.requires.get(f"{obj}_state", states)
        ok_zones = tuple("HWS" if z == "held_out" else z for z in action.requires.get(f"{obj}_zone", ZONES))
        if f"{obj}_state" not in action.requires and f"{obj}_zone" not in action.requires:
            continue
        out += [oml_item(obj, st, z) for st in states for z in ZONES if st not in ok_states or z not in ok_zones]
    return tuple(out)


ROBOT_ACTION_BY_NAME: dict[str, RobotAction] = {a.name: a for a in ROBOT_ACTIONS}
#: the actions that move the robot and so can fail physically: the items of the action failure layer (AFL)
MOTION_ACTIONS: tuple[str, ...] = tuple(a.name for a in ROBOT_ACTIONS if a.moves)
#: motion action -> the AML mismatch (`ACTION_FAILURES`) its repeated failure raises
#: the actions that take an object from the person's hand (the bottle she holds out to be held for the
#: stopper, too): failing that twice has an alternative, the hand-over by the table (Take-from-table)
TAKES_FROM_THE_HAND: tuple[str, ...] = ("Receive-object", "Grasp-hold-bottle-to-remove-cup")
FAILURE_OF: dict[str, str] = {a: ("Cannot-take-it-from-the-hand" if a in TAKES_FROM_THE_HAND else "Keeps-failing")
                              for a in MOTION_ACTIONS}

#: what the human can do on his own initiative (an active partner only), for the coverage check.
#: The human acts in HWS only and cannot open the bottle alone.
HUMAN_INITIATIVES: tuple[dict, ...] = (
    {"name": "turn glass", "requires": {"glass_state": ("inverted",), "glass_zone": ("HWS",)}, "effects": {"glass_state": "empty"}},
    {"name": "pour", "requires": {"bottle_state": ("open",), "bottle_zone": ("HWS",), "glass_state": ("empty",), "glass_zone": ("HWS",)},
     "effects": {"glass_state": "full"}},
    {"name": "drink", "requires": {"glass_state": ("full",), "glass_zone": ("HWS",)}, "effects": {"drunk": True}},
    {"name": "hold out bottle (AG)", "requires": {"bottle_zone": ("HWS",)}, "effects": {"bottle_zone": "held_out"}},
    {"name": "hand over glass (AG) to robot", "requires": {"glass_zone": ("HWS",)}, "effects": {"glass_zone": "RWS"},
     "robot": "Receive-object"},
)
#: how a partner answers each request the robot makes (tag of the robot's utterance -> the response):
#: a passive partner gives them too; it only never starts anything.
PARTNER_RESPONSES: tuple[str, ...] = ("remove_stopper", "take_object", "give_object", "drink", "put_down_here")

# ---------------------------------------------------------------------------------------------
# Utterances: one per pool of ASL, IL, AML and AEL (the robot reasons aloud)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Utterance:
    """What the robot says when a pool's peak rises, and a semantic tag the human model reacts to.

    Tags are ``kind:what``; kinds: ``understood`` (ASL), ``infer`` (IL),
    ``error`` (AML, and Communicate-Error), ``request`` (give me X), ``offer``
    (take X), ``invite`` (do X now), ``inform`` (the robot does X), ``suggest``.
    """

    layer: str
    item: str
    text: str
    tag: str


UTTERANCES: dict[str, dict[str, Utterance]] = {
    "ASL": {u.item: u for u in (
        Utterance("ASL", "Reach-grasp-SG-closed-bottle", "You are holding the closed bottle out to me.",
                  "understood:hold_out_closed_bottle"),
        Utterance("ASL", "Reach-grasp-AG-closed-bottle-to-hand-over", "You are handing me the closed bottle.",
                  "understood:hand_over_closed_bottle"),
        Utterance("ASL", "Reach-grasp-SG-open-bottle-to-pour", "You are going to pour.", "understood:pour"),
        Utterance("ASL", "Reach-grasp-AG-open-bottle-to-hand-over", "You are handing me the open bottle.",
                  "understood:hand_over_open_bottle"),
        Utterance("ASL", "Reach-grasp-AG-glass-to-hand-over", "You are handing me the glass.", "understood:hand_over_glass"),
        Utterance("ASL", "Reach-grasp-SG-glass-to-turn", "You are turning the glass.", "understood:turn_glass"),
        Utterance("ASL", "Reach-grasp-SG-full-glass-to-drink", "You are going to drink.", "understood:drink"),
        Utterance("ASL", "Request-object-with-open-hand", "You are asking me for something.", "understood:request"),
        Utterance("ASL", "Point-to-bottle", "You are pointing at the bottle.", "understood:point_bottle"),
        Utterance("ASL", "Point-to-glass", "You are pointing at the glass.", "understood:point_glass"),
    )},
    "IL": {u.item: u for u in (
        Utterance("IL", "Remove-stopper", "You want the bottle opened.", "infer:open_bottle"),
        Utterance("IL", "Pour", "You want to fill the glass.", "infer:pour"),
        Utterance("IL", "Turn-glass", "You want to turn the glass upright.", "infer:turn_glass"),
        Utterance("IL", "Drink", "You want to drink.", "infer:drink"),
        Utterance("IL", "Get-glass", "You want the glass.", "infer:get_glass"),
        Utterance("IL", "Get-bottle", "You want the bottle.", "infer:get_bottle"),
        Utterance("IL", "Give-glass", "You want to give me the glass.", "infer:give_glass"),
        Utterance("IL", "Give-bottle", "You want to give me the bottle.", "infer:give_bottle"),
    )},
    "AML": {u.item: u for u in (
        Utterance("AML", "Cannot-remove-stopper", "I cannot remove the stopper: my hand is too big for it.", "error:cannot_remove_stopper"),
        Utterance("AML", "Pour-from-closed-bottle", "The bottle is still closed: nothing will pour.", "error:pour_closed_bottle"),
        Utterance("AML", "Pour-into-inverted-glass", "The glass is upside down: it cannot be filled.", "error:pour_inverted_glass"),
        Utterance("AML", "Drink-from-empty-glass", "The glass is empty.", "error:drink_empty_glass"),
        Utterance("AML", "Cannot-take-it-from-the-hand", "I cannot take it from your hand.", "error:cannot_take_it"),
        Utterance("AML", "Keeps-failing", "That did not work twice; I will try something else.", "error:keeps_failing"),
        Utterance("AML", "Bottle-fell-over", "The bottle has fallen over: I cannot go on.", "error:bottle_fell"),
        Utterance("AML", "Glass-fell-over", "The glass has fallen over: I cannot go on.", "error:glass_fell"),
    )},
    "AEL": {u.item: u for u in (
        # Communicate-Error speaks the message of the winning AML error; this text is its preface
        Utterance("AEL", "Communicate-Error", "I cannot do that.", "error:communicate"),
        Utterance("AEL", "Grasp-hold-bottle-to-remove-cup", "I will hold the bottle; please remove the stopper.", "invite:remove_stopper"),
        Utterance("AEL", "Reach-and-turn-glass", "I will turn the glass and fill it for you.", "inform:turn_glass"),
        Utterance("AEL", "Reach-turn-and-hand-over-glass", "I will turn the glass and give it to you.", "offer:glass"),
        Utterance("AEL", "Reach-grasp-open-bottle-fill-glass", "I will fill the glass.", "inform:fill_glass"),
        Utterance("AEL", "Reach-full-glass-to-hand-over", "Here is your full glass.", "offer:glass"),
        Utterance("AEL", "Request-glass", "Please give me the glass.", "request:glass"),
        Utterance("AEL", "Request-bottle", "Please give me the bottle.", "request:bottle"),
        Utterance("AEL", "Hand-over-bottle", "Here is the bottle.", "offer:bottle"),
        Utterance("AEL", "Receive-object", "I will take it.", "accept:object"),
        Utterance("AEL", "Take-from-table", "Please put it down on the table under my hand; I will take it from there.",
                  "request:put_down_here"),
        Utterance("AEL", "Suggest-drink", "Your glass is full: you can drink now.", "suggest:drink"),
        Utterance("AEL", "Wait", "I will wait.", "inform:wait"),
    )},
}

#: tag -> the partner response the human model gives (a passive partner too)
TAG_RESPONSES: dict[str, str] = {
    "invite:remove_stopper": "remove_stopper",
    "offer:glass": "take_object",
    "offer:bottle": "take_object",
    "request:glass": "give_object",
    "request:bottle": "give_object",
    "suggest:drink": "drink",
    "request:put_down_here": "put_down_here",
}
