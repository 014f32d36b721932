"""What cognition sees (`Percept`) and what it decides (`Decision`).

Contract for producers of a `Percept` (the vision module, or the labelled
oracle in `assistbot.cognition.oracle`):

- ``t``: simulated time in seconds at which the percept was taken.
- ``objects``: one `ObjectPercept` per object type the task knows
  ("bottle", "glass"); an object not found in the images has ``seen=False``
  (its other fields are then ignored: cognition keeps its memory of it).
  ``zone`` is "HWS" or "RWS" (which side of the table line the object is on;
  an object in the robot's gripper is in "RWS", one in the human's hand is in
  "HWS", or "RWS" only if held out across the line). ``state``: bottle
  "closed"/"open"; glass "inverted"/"empty"/"full" (empty and full are
  upright). ``position``: (x, y, z) in metres in the table frame (origin at
  the table centre on its surface, x toward the robot, z up); ``confidence``
  in [0, 1] scales the evidence. ``state_seen=False``: the object is seen
  but its state is not (the stopper under the person's hand): ``state`` is
  a guess, and cognition places the state it remembers where the object is.
- ``hand``: the human's working hand as the cameras see it. ``posture`` is
  one of `assistbot.task.HAND_POSTURES`: "none" (at rest / nothing
  object-directed), "reach" (moving toward ``directed_at``), "grasp_ag" /
  "grasp_sg" (above / side grip on ``object_in_hand``), "open_palm_request"
  (an open empty palm held out: a request), "pointing" (at ``pointed_at``),
  and three postures classified from the hand with an object: "remove_stopper"
  (fingers at the bottle's stopper), "pour" (bottle tilted over the glass),
  "drink" (glass at the mouth). ``held_out``: the hand (with
  ``object_in_hand``) is extended toward the robot. ``seen=False``: the hand
  was not found (no evidence either way). ``position`` is where the posture
  read holds things (its grip point); ``end`` is where the hand's end is seen,
  whatever posture it is read as, so a hand kept still stays still in ``end``
  while a posture that flickers between classes moves ``position``.
  ``end_hidden``: the hand's skin ends on the robot's own arm in a camera, so
  its end seen falls short and its outline (the posture read) is partly the
  robot's.
- ``robot``: proprioception. ``holding``: the object in the gripper or None;
  ``action``: the AEL action being executed or just ended (or None);
  ``status``: an `assistbot.interfaces.Status` ("idle" | "running" |
  "succeeded" | "failed"). A percept with status "succeeded" or "failed" is
  an event: it releases the current decision (if ``action`` is given it must
  name that decision).

Nothing here reads the simulator: a Percept is what cameras and joint
sensors can tell.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from assistbot.interfaces import Status
from assistbot.task import HAND_POSTURES, OBJECT_STATES, OBJECTS, ZONES

ROBOT_STATUSES = tuple(s.value for s in Status)
#: m above the table: an object seen with its base lower than this stands on the table; higher, it is
#: lifted (in a hand)
STANDING_Z = 0.03
#: m: the object the robot holds is placed at its hand, unless it is seen farther than this from the hand
#: (horizontally): then where it is seen (the grasp closed on something else, or the object stayed behind)
NOT_IN_HAND_XY = 0.10


def away_from_hand(position, tcp) -> bool:
    """An object seen at ``position`` is not in the robot's hand at ``tcp`` (both table x, y first)."""
    return math.hypot(position[0] - tcp[0], position[1] - tcp[1]) > NOT_IN_HAND_XY


@dataclass
class ObjectPercept:
    """One object as seen: type, zone, state, position (m, table frame), confidence, seen, lying.

    ``state_seen`` False: the object is seen but its state is not (the bottle's stopper under the
    person's hand); ``state`` is then only a guess, and cognition keeps the state it remembers."""

    type: str
    zone: str = "HWS"
    state: str = ""
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    confidence: float = 1.0
    seen: bool = True
    state_seen: bool = True
    lying: bool = False      # seen on its side (fallen over): then not ``seen`` as standing, ``position`` roughly

    def validate(self) -> None:
        if self.type not in OBJECTS:
            raise ValueError(f"object type {self.type!r}; known: {', '.join(OBJECTS)}")
        if self.zone not in ZONES:
            raise ValueError(f"zone {self.zone!r} of {self.type}; known: {', '.join(ZONES)}")
        if self.state not in OBJECT_STATES[self.type]:
            raise ValueError(f"state {self.state!r} of {self.type}; known: {', '.join(OBJECT_STATES[self.type])}")


@dataclass
class HandPercept:
    """The human hand: posture, position (m, table frame), object in hand, held out, reach/point targets."""

    posture: str = "none"
    position: tuple[float, float, float] = (0.0, -0.4, 0.1)
    object_in_hand: str | None = None
    held_out: bool = False
    directed_at: str | None = None
    pointed_at: str | None = None
    confidence: float = 1.0
    seen: bool = True
    end: tuple[float, float, float] | None = None   # None: the same as ``position``
    end_hidden: bool = False

    def __post_init__(self) -> None:
        if self.end is None:
            self.end = self.position

    def validate(self) -> None:
        if self.posture not in HAND_POSTURES:
            raise ValueError(f"hand posture {self.posture!r}; known: {', '.join(HAND_POSTURES)}")
        for name in ("object_in_hand", "directed_at", "pointed_at"):
            v = getattr(self, name)
            if v is not None and v not in OBJECTS:
                raise ValueError(f"hand {name} {v!r}; known: {', '.join(OBJECTS)} or none")


@dataclass
class RobotPercept:
    """Proprioception: what the gripper holds, the current action and its status."""

    holding: str | None = None
    action: str | None = None
    status: Status = Status.IDLE

    def validate(self) -> None:
        if self.holding is not None and self.holding not in OBJECTS:
            raise ValueError(f"robot holding {self.holding!r}; known: {', '.join(OBJECTS)} or none")
        if self.status not in ROBOT_STATUSES:
            raise ValueError(f"robot status {self.status!r}; known: {', '.join(ROBOT_STATUSES)}")
        self.status = Status(self.status)


@dataclass
class Percept:
    """Everything cognition sees at time ``t`` (see the module docstring for the contract)."""

    t: float
    objects: dict[str, ObjectPercept] = field(default_factory=dict)
    hand: HandPercept = field(default_factory=HandPercept)
    robot: RobotPercept = field(default_factory=RobotPercept)

    def validate(self) -> "Percept":
        for name, o in self.objects.items():
            if name != o.type:
                raise ValueError(f"object key {name!r} differs from its type {o.type!r}")
            o.validate()
        self.hand.validate()
        self.robot.validate()
        return self


@dataclass(frozen=True)
class Said:
    """One utterance spoken at time ``t``: the pool (layer, item), its text and semantic tag."""

    t: float
    layer: str
    item: str
    text: str
    tag: str


@dataclass
class Decision:
    """Cognition's output after a percept.

    ``action``: the AEL winner once its peak is self-sustained (None while no
    decision stands); ``target``: the object it acts on ("bottle", "glass",
    or None); ``new``: the decision was taken at this update; ``released``:
    the previous decision was released at this update (finished / failed);
    ``error``: the winning AML error when ``action`` is Communicate-Error;
    ``utterances``: what the robot says now, one per peak that just rose in
    ASL, IL, AML, AEL; ``peaks``: the items above threshold per layer (for logs).
    """

    t: float
    action: str | None = None
    target: str | None = None
    new: bool = False
    released: str | None = None
    error: str | None = None
    utterances: list[Said] = field(default_factory=list)
    peaks: dict[str, list[str]] = field(default_factory=dict)
