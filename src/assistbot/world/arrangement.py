"""A scenario's arrangement of the objects: zone, state and place of each task object."""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any, Mapping

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.world import layout


@dataclass(frozen=True)
class Placement:
    """One object's zone ("HWS"/"RWS"), state and optional table position (x, y) in metres."""

    zone: str
    state: str
    position: tuple[float, float] | None = None


@dataclass(frozen=True, init=False)
class Arrangement:
    """Where each task object (`catalogue.TASK_OBJECTS`) stands and in which state.

    Build it with one placement per task object, by position in catalogue order or by name
    (``Arrangement(bottle=..., glass=...)``). The states are the catalogue's (a full glass: the
    liquid starts in the glass, otherwise it is in the bottle).  Positions are table
    coordinates; None means the zone's default place (the catalogue entry's `places`).
    """

    placements: tuple[Placement, ...]   # one per task object, in catalogue order

    def __init__(self, *placements: Placement, **by_name: Placement) -> None:
        names = catalogue.TASK_OBJECTS
        given = {**dict(zip(names, placements)), **by_name}
        if len(placements) > len(names) or sorted(given) != sorted(names):
            raise TypeError(f"an arrangement places {', '.join(names)}, one each; got {', '.join(given) or 'nothing'}")
        object.__setattr__(self, "placements", tuple(given[n] for n in names))

    def placement(self, name: str) -> Placement:
        return self.placements[catalogue.TASK_OBJECTS.index(name)]

    @property
    def bottle(self) -> Placement:
        return self.placement("bottle")

    @property
    def glass(self) -> Placement:
        return self.placement("glass")

    def validate(self, where: str = "arrangement") -> "Arrangement":
        """Raise UserError naming the key of the first mistake; return self when fine."""
        for name in catalogue.TASK_OBJECTS:
            p = self.placement(name)
            key = f"objects.{name}"
            states = catalogue.STATES[name]
            if p.zone not in layout.ZONES:
                raise UserError(where, f"{key}.zone", f"unknown zone {p.zone!r}; use one of {', '.join(layout.ZONES)}")
            if p.state not in states:
                raise UserError(where, f"{key}.state", f"unknown state {p.state!r}; use one of {', '.join(states)}")
            if p.position is not None:
                _check_position(where, f"{key}.position", name, p.zone, p.position)
        places = {name: self.position(name) for name in catalogue.TASK_OBJECTS}
        if self.bottle.state == "open":
            places["stopper"] = layout.STOPPER_PARK
        names = list(places)
        for a, b in itertools.combinations(names, 2):
            (xa, ya), (xb, yb) = places[a], places[b]
            gap = ((xa - xb) ** 2 + (ya - yb) ** 2) ** 0.5 - catalogue.radius(a) - catalogue.radius(b)
            if gap < 0.02:
                blamed = [n for n in (a, b) if n in catalogue.TASK_OBJECTS][-1]   # the later task object of the pair
                what = "the removed stopper's place" if "stopper" in (a, b) else f"the {a}"
                who = b if b != "stopper" else a
                raise UserError(where, f"objects.{blamed}.position", f"{who} overlaps {what} (need 2 cm between them)")
        return self

    def position(self, name: str) -> tuple[float, float]:
        """The table (x, y) of a task object: explicit or the zone's default."""
        p = self.placement(name)
        return tuple(p.position) if p.position is not None else catalogue.BY_NAME[name].places[p.zone]  # type: ignore[return-value]

    def label(self) -> str:
        return "_".join(f"{n}-{p.zone}-{p.state}" for n, p in zip(catalogue.TASK_OBJECTS, self.placements))

    @classmethod
    def from_mapping(cls, mapping: Any, where: str = "arrangement") -> "Arrangement":
        """Build from a scenario's ``objects:`` mapping (``{bottle: {zone, state, position?}, glass: {...}}``)."""
        names = catalogue.TASK_OBJECTS
        if not isinstance(mapping, Mapping):
            raise UserError(where, "objects", f"must be a mapping with the keys {' and '.join(names)}")
        unknown = sorted(set(mapping) - set(names))
        if unknown:
            raise UserError(where, f"objects.{unknown[0]}", f"unknown object; the scene has {' and '.join(f'a {n}' for n in names)}")
        parts = {}
        for name in names:
            key = f"objects.{name}"
            entry = mapping.get(name)
            if not isinstance(entry, Mapping):
                raise UserError(where, key, "missing or not a mapping; give zone and state (and optionally position: [x, y])")
            extra = sorted(set(entry) - {"zone", "state", "position"})
            if extra:
                raise UserError(where, f"{key}.{extra[0]}", "unknown key; allowed: zone, state, position")
            for k in ("zone", "state"):
                if k not in entry:
                    raise UserError(where, f"{key}.{k}", "missing")
            pos = entry.get("position")
            if pos is not None:
                pos = _parse_position(where, f"{key}.position", pos)
            parts[name] = Placement(str(entry["zone"]).upper(), str(entry["state"]).lower(), pos)
        return cls(**parts).validate(where)

    @classmethod
    def from_options(cls, *texts: str, where: str = "arguments") -> "Arrangement":
        """Build from command-line strings ``ZONE:STATE[@x,y]``, one per task object in catalogue order,
        e.g. ``HWS:closed`` or ``RWS:empty@0.2,-0.1``."""
        parts = {}
        for name, text in zip(catalogue.TASK_OBJECTS, texts, strict=True):
            spec, _, at = str(text).partition("@")
            zone, sep, state = spec.partition(":")
            if not sep:
                raise UserError(where, f"--{name}", f"expected ZONE:STATE[@x,y], got {text!r}")
            pos = _parse_position(where, f"--{name}", at.split(",")) if at else None
            parts[name] = Placement(zone.strip().upper(), state.strip().lower(), pos)
        arr = cls(**parts)
        try:
            return arr.validate(where)
        except UserError as exc:  # name the option rather than the YAML key
            raise UserError(where, f"--{exc.key.split('.')[1]}", exc.message) from None


def _parse_position(where: str, key: str, value: Any) -> tuple[float, float]:
    try:
        x, y = (float(v) for v in value)
    except (TypeError, ValueError):
        raise UserError(where, key, f"expected two numbers [x, y] in metres, got {value!r}") from None
    return (x, y)


def _check_position(where: str, key: str, name: str, zone: str, pos: tuple[float, float]) -> None:
    x, y = pos
    xmax, ymax, inner = layout.standing_limits(catalogue.radius(name))
    if not (-xmax <= x <= xmax and -ymax <= y <= ymax):
        raise UserError(where, key, f"({x:g}, {y:g}) is off the table; x must be within ±{xmax:.3f} and y within ±{ymax:.3f} m")
    if zone == "HWS" and x > -inner:
        raise UserError(where, key, f"x = {x:g} is not in the HWS; the human's half needs x <= {-inner:.3f}")
    if zone == "RWS" and x < inner:
        raise UserError(where, key, f"x = {x:g} is not in the RWS; the robot's half needs x >= {inner:.3f}")


def all_arrangements() -> list[Arrangement]:
    """Every arrangement at default places: each task object's zone x state (24 for bottle and glass)."""
    each = [[Placement(z, s) for z in layout.ZONES for s in catalogue.STATES[o]] for o in catalogue.TASK_OBJECTS]
    return [Arrangement(*ps) for ps in itertools.product(*each)]


#: The seed paper's arrangements (section IV): name -> arrangement.
PAPER_ARRANGEMENTS = {
    "fig3": Arrangement(Placement("HWS", "closed"), Placement("RWS", "inverted")),
    "fig4": Arrangement(Placement("RWS", "open"), Placement("RWS", "empty")),
    "fig5": Arrangement(Placement("RWS", "closed"), Placement("HWS", "empty")),
}
