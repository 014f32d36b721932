"""A scenario's arrangement of the objects: zone, state and place of bottle and glass."""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any, Mapping

from assistbot.errors import UserError
from assistbot.world import layout

_STATES = {"bottle": layout.BOTTLE_STATES, "glass": layout.GLASS_STATES}


@dataclass(frozen=True)
class Placement:
    """One object's zone ("HWS"/"RWS"), state and optional table position (x, y) in metres."""

    zone: str
    state: str
    position: tuple[float, float] | None = None


@dataclass(frozen=True)
class Arrangement:
    """Where the bottle and the glass stand and in which state.

    bottle.state is "closed" or "open"; glass.state is "inverted", "empty" or "full" (full:
    the liquid starts in the glass, otherwise it is in the bottle).  Positions are table
    coordinates; None means the zone's default place (`layout.DEFAULT_POSITIONS`).
    """

    bottle: Placement
    glass: Placement

    def validate(self, where: str = "arrangement") -> "Arrangement":
        """Raise UserError naming the key of the first mistake; return self when fine."""
        for name in ("bottle", "glass"):
            p: Placement = getattr(self, name)
            key = f"objects.{name}"
            if p.zone not in layout.ZONES:
                raise UserError(where, f"{key}.zone", f"unknown zone {p.zone!r}; use one of {', '.join(layout.ZONES)}")
            if p.state not in _STATES[name]:
                raise UserError(where, f"{key}.state", f"unknown state {p.state!r}; use one of {', '.join(_STATES[name])}")
            if p.position is not None:
                _check_position(where, f"{key}.position", name, p.zone, p.position)
        places = {"bottle": self.position("bottle"), "glass": self.position("glass")}
        if self.bottle.state == "open":
            places["stopper"] = layout.STOPPER_PARK
        names = list(places)
        for a, b in itertools.combinations(names, 2):
            (xa, ya), (xb, yb) = places[a], places[b]
            gap = ((xa - xb) ** 2 + (ya - yb) ** 2) ** 0.5 - layout.OBJECT_RADIUS[a] - layout.OBJECT_RADIUS[b]
            if gap < 0.02:
                key = f"objects.{'glass' if 'glass' in (a, b) else 'bottle'}.position"
                what = "the removed stopper's place" if "stopper" in (a, b) else f"the {a}"
                raise UserError(where, key, f"{b if b != 'stopper' else a} overlaps {what} (need 2 cm between them)")
        return self

    def position(self, name: str) -> tuple[float, float]:
        """The table (x, y) of "bottle" or "glass": explicit or the zone's default."""
        p: Placement = getattr(self, name)
        return tuple(p.position) if p.position is not None else layout.DEFAULT_POSITIONS[(name, p.zone)]  # type: ignore[return-value]

    def label(self) -> str:
        return f"bottle-{self.bottle.zone}-{self.bottle.state}_glass-{self.glass.zone}-{self.glass.state}"

    @classmethod
    def from_mapping(cls, mapping: Any, where: str = "arrangement") -> "Arrangement":
        """Build from a scenario's ``objects:`` mapping (``{bottle: {zone, state, position?}, glass: {...}}``)."""
        if not isinstance(mapping, Mapping):
            raise UserError(where, "objects", "must be a mapping with the keys bottle and glass")
        unknown = sorted(set(mapping) - {"bottle", "glass"})
        if unknown:
            raise UserError(where, f"objects.{unknown[0]}", "unknown object; the scene has a bottle and a glass")
        parts = {}
        for name in ("bottle", "glass"):
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
    def from_options(cls, bottle: str, glass: str, where: str = "arguments") -> "Arrangement":
        """Build from command-line strings ``ZONE:STATE[@x,y]``, e.g. ``HWS:closed`` or ``RWS:empty@0.2,-0.1``."""
        parts = {}
        for name, text in (("bottle", bottle), ("glass", glass)):
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
    r = layout.OBJECT_RADIUS[name]
    xmax, ymax = layout.TABLE_HALF_X - r - layout.EDGE_MARGIN, layout.TABLE_HALF_Y - r - layout.EDGE_MARGIN
    if not (-xmax <= x <= xmax and -ymax <= y <= ymax):
        raise UserError(where, key, f"({x:g}, {y:g}) is off the table; x must be within ±{xmax:.3f} and y within ±{ymax:.3f} m")
    inner = r + layout.MIDLINE_MARGIN
    if zone == "HWS" and x > -inner:
        raise UserError(where, key, f"x = {x:g} is not in the HWS; the human's half needs x <= {-inner:.3f}")
    if zone == "RWS" and x < inner:
        raise UserError(where, key, f"x = {x:g} is not in the RWS; the robot's half needs x >= {inner:.3f}")


def all_arrangements() -> list[Arrangement]:
    """The 24 arrangements: bottle zone x state, glass zone x state, at default places."""
    return [
        Arrangement(Placement(bz, bs), Placement(gz, gs))
        for bz, bs, gz, gs in itertools.product(layout.ZONES, layout.BOTTLE_STATES, layout.ZONES, layout.GLASS_STATES)
    ]


#: The seed paper's arrangements (section IV): name -> arrangement.
PAPER_ARRANGEMENTS = {
    "fig3": Arrangement(Placement("HWS", "closed"), Placement("RWS", "inverted")),
    "fig4": Arrangement(Placement("RWS", "open"), Placement("RWS", "empty")),
    "fig5": Arrangement(Placement("RWS", "closed"), Placement("HWS", "empty")),
}
