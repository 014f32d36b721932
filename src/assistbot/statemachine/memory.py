"""What the state machine remembers of the scene: each object's last seen state and zone, and when the
person's hand last did something.

Built only from the percepts it is given (the same `Percept` the field architecture gets): an object not
seen keeps its last facts; a state not seen (the stopper under the person's hand) keeps the last state.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from assistbot.cognition.architecture import ol_items_of
from assistbot.cognition.percept import Percept
from assistbot.task import OBJECTS

#: a cue beside the OL items: something held out that neither the cameras nor the table can name
HOLD_OUT_UNNAMED = "hold_out_something"
#: OL items that are the person acting on their own (not a cue addressed to the robot)
ACTING = ("reach", "grasp", "remove_stopper", "pour", "drink")


@dataclass
class ObjectFacts:
    state: str
    zone: str
    lying_since: float | None = None


@dataclass
class Memory:
    """The facts the rules read, in the vocabulary of the task's ``requires`` (``bottle_state``,
    ``glass_zone`` ...); an object held out by the person is in zone ``held_out``."""

    confirm: float = 0.0                                 # s a cue must show without a break to count
    objects: dict[str, ObjectFacts] = field(default_factory=dict)
    cues: list[str] = field(default_factory=list)        # the OL items seen without a break for ``confirm`` s
    showing_since: dict[str, float] = field(default_factory=dict)   # OL item -> since when it shows
    holding: str | None = None                           # the robot's hand (proprioception)
    hand_busy_at: float | None = None                    # the last time the person's hand did something

    def take_in(self, p: Percept) -> None:
        now = ol_items_of(p)
        h = p.hand
        if h.seen and h.held_out and h.object_in_hand is None and h.posture in ("grasp_ag", "grasp_sg"):
            # an object held out that the cameras cannot name: the one task object not seen on the table
            unseen = [o for o in OBJECTS if o in p.objects and not p.objects[o].seen]
            if len(unseen) == 1:
                now += [f"{h.posture}_{unseen[0]}", f"hold_out_{unseen[0]}"]
            else:
                now.append(HOLD_OUT_UNNAMED)
        self.showing_since = {c: self.showing_since.get(c, p.t) for c in now}
        # a percept comes every 100 ms: a cue seen in n percepts in a row has shown for (n - 1) x 100 ms
        self.cues = [c for c, t0 in self.showing_since.items() if p.t - t0 >= self.confirm - 1e-9]
        self.holding = p.robot.holding
        held_out = p.hand.object_in_hand if p.hand.seen and p.hand.held_out else None
        for name, o in p.objects.items():
            known = self.objects.get(name)
            if not o.seen and not o.lying:
                continue
            state = o.state if o.state_seen or known is None else known.state
            zone = "held_out" if name == held_out else o.zone
            lying = (known.lying_since if known and known.lying_since is not None else p.t) if o.lying else None
            self.objects[name] = ObjectFacts(state, zone, lying)
        if p.hand.seen and (p.hand.posture != "none" or p.hand.object_in_hand):
            self.hand_busy_at = p.t
        elif self.hand_busy_at is None:
            self.hand_busy_at = p.t

    def known(self) -> bool:
        """Every task object has been seen at least once."""
        return all(o in self.objects for o in OBJECTS)

    def facts(self) -> dict[str, str]:
        """``<object>_state`` and ``<object>_zone`` of every object seen so far."""
        out = {}
        for name, f in self.objects.items():
            out[f"{name}_state"], out[f"{name}_zone"] = f.state, f.zone
        return out

    def state(self, name: str) -> str | None:
        f = self.objects.get(name)
        return f.state if f else None

    def zone(self, name: str) -> str | None:
        f = self.objects.get(name)
        return f.zone if f else None

    def person_acting(self) -> bool:
        """The person's hand is doing something of their own (reaching, gripping, pouring, drinking)."""
        return any(c.startswith(ACTING) for c in self.cues)

    def idle_for(self, t: float) -> float:
        """Seconds since the person's hand last did anything."""
        return t - (self.hand_busy_at if self.hand_busy_at is not None else t)

    def fallen(self, t: float, after: float) -> str | None:
        """An object seen lying for ``after`` s or more."""
        for name, f in self.objects.items():
            if f.lying_since is not None and t - f.lying_since >= after:
                return name
        return None
