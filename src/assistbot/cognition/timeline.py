"""Percept timelines: YAML files of time -> percept facts, played through the oracle.

Format::

    name: fig3
    description: free text
    duration: 20.0          # s of simulated time
    percept_rate: 10        # Hz, percepts per second (vision runs at about 10 Hz)
    config: {"readout.hold": 0.1}   # optional parameter overrides (cognition config paths)
    events:
      - t: 0.0
        bottle: {zone: HWS, state: closed}
        glass: {zone: RWS, state: inverted}
        hand: {posture: none}
      - t: 1.0
        hand: {posture: grasp_sg, object_in_hand: bottle, held_out: true}
      - t: 6.0
        robot: {status: succeeded}

Each event changes only the facts it names; facts hold until changed. A
robot status "succeeded"/"failed" is an event: it holds for one percept and
then returns to "idle". Mistakes raise `UserError` naming the file and key.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator

from assistbot import task
from assistbot.cognition.oracle import HAND_KEYS, OBJECT_KEYS, ROBOT_KEYS, oracle_percept
from assistbot.cognition.percept import ROBOT_STATUSES, Percept
from assistbot.errors import UserError, read_yaml
from assistbot.interfaces import Status

TOP_KEYS = ("name", "description", "duration", "percept_rate", "config", "events")
EVENT_KEYS = ("t", *task.OBJECTS, "hand", "robot")

_ALLOWED: dict[tuple[str, str], tuple] = {
    ("hand", "posture"): task.HAND_POSTURES,
    ("hand", "object_in_hand"): (None, *task.OBJECTS),
    ("hand", "directed_at"): (None, *task.OBJECTS),
    ("hand", "pointed_at"): (None, *task.OBJECTS),
    ("hand", "held_out"): (True, False),
    ("hand", "seen"): (True, False),
    **{(o, "lying"): (True, False) for o in task.OBJECTS},
    ("robot", "holding"): (None, *task.OBJECTS),
    ("robot", "status"): ROBOT_STATUSES,
    ("robot", "action"): (None, *task.AEL_ITEMS),
}


@dataclass
class Timeline:
    """A validated timeline: events sorted by time, played as percepts."""

    name: str
    duration: float
    percept_rate: float = 10.0
    description: str = ""
    config: dict[str, Any] = field(default_factory=dict)
    events: list[dict[str, Any]] = field(default_factory=list)
    source: str = "<timeline>"

    def percepts(self) -> Iterator[Percept]:
        """ORACLE percepts at ``percept_rate`` from t = 1/rate to ``duration``."""
        state: dict[str, dict[str, Any]] = {}
        pending = list(self.events)
        n = int(round(self.duration * self.percept_rate))
        for i in range(1, n + 1):
            t = i / self.percept_rate
            if state.get("robot", {}).get("status") in (Status.SUCCEEDED, Status.FAILED):
                state["robot"] = {**state["robot"], "status": "idle", "action": None}
            while pending and pending[0]["t"] <= t + 1e-9:
                ev = pending.pop(0)
                for part, facts in ev.items():
                    if part != "t":
                        state[part] = {**state.get(part, {}), **facts}
            yield oracle_percept(t, state)


def _fail(where: str, key: str, msg: str) -> UserError:
    return UserError(where, key, msg)


def timeline_from_dict(data: Any, source: str = "<timeline>") -> Timeline:
    if not isinstance(data, dict):
        raise _fail(source, "-", "a timeline is a mapping with name, duration, events")
    for k in data:
        if k not in TOP_KEYS:
            raise _fail(source, str(k), f"unknown key; allowed: {', '.join(TOP_KEYS)}")
    for k in ("duration", "events"):
        if k not in data:
            raise _fail(source, k, "is required")
    dur = data["duration"]
    if isinstance(dur, bool) or not isinstance(dur, (int, float)) or dur <= 0:
        raise _fail(source, "duration", f"must be a positive number of seconds, got {dur!r}")
    rate = data.get("percept_rate", 10.0)
    if isinstance(rate, bool) or not isinstance(rate, (int, float)) or rate <= 0:
        raise _fail(source, "percept_rate", f"must be a positive number (Hz), got {rate!r}")
    cfg = data.get("config") or {}
    if not isinstance(cfg, dict):
        raise _fail(source, "config", "must map parameter path -> value")
    evs = data["events"]
    if not isinstance(evs, list) or not evs:
        raise _fail(source, "events", "must be a non-empty list of {t: ..., <facts>}")
    events = []
    for i, ev in enumerate(evs):
        where_i = f"events[{i}]"
        if not isinstance(ev, dict):
            raise _fail(source, where_i, "must be a mapping with t and facts")
        for k in ev:
            if k not in EVENT_KEYS:
                raise _fail(source, f"{where_i}.{k}", f"unknown key; allowed: {', '.join(EVENT_KEYS)}")
        t = ev.get("t")
        if isinstance(t, bool) or not isinstance(t, (int, float)) or t < 0:
            raise _fail(source, f"{where_i}.t", f"must be a time in seconds >= 0, got {t!r}")
        clean: dict[str, Any] = {"t": float(t)}
        for part in EVENT_KEYS[1:]:
            if part not in ev:
                continue
            facts = ev[part]
            if not isinstance(facts, dict):
                raise _fail(source, f"{where_i}.{part}", "must be a mapping of facts")
            allowed_keys = OBJECT_KEYS if part in task.OBJECTS else HAND_KEYS if part == "hand" else ROBOT_KEYS
            for k, v in facts.items():
                key = f"{where_i}.{part}.{k}"
                if k not in allowed_keys:
                    raise _fail(source, key, f"unknown key; allowed: {', '.join(allowed_keys)}")
                if part in task.OBJECTS:
                    allowed = {"zone": task.ZONES, "state": task.OBJECT_STATES[part], "seen": (True, False)}.get(k)
                else:
                    allowed = _ALLOWED.get((part, k))
                if allowed is not None and v not in allowed:
                    shown = ", ".join("null" if a is None else str(a).lower() if isinstance(a, bool) else str(a) for a in allowed)
                    raise _fail(source, key, f"unknown value {v!r}; allowed: {shown}")
                if k == "position" and (not isinstance(v, list) or len(v) != 3):
                    raise _fail(source, key, "must be [x, y, z] in metres (table frame)")
                if k == "confidence" and (isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 <= v <= 1):
                    raise _fail(source, key, f"must be a number in [0, 1], got {v!r}")
            clean[part] = copy.deepcopy(facts)
        events.append(clean)
    events.sort(key=lambda e: e["t"])
    return Timeline(name=str(data.get("name", Path(source).stem)), duration=float(dur), percept_rate=float(rate),
                    description=str(data.get("description", "")), config=dict(cfg), events=events, source=source)


def load_timeline(path: str | Path) -> Timeline:
    """Read and validate a timeline file; every mistake is a `UserError` naming the file and key."""
    path = Path(path)
    data = read_yaml(path, "timeline")
    return timeline_from_dict(data, source=str(path))
