"""Scenario files: the schema, the loader, and errors that name the file and the key.

```yaml
name: paper-fig3-4
description: ...
seed: 0
time_limit: 240            # simulated seconds
objects:                   # validated by assistbot.world (zones, states, positions)
  bottle: {zone: HWS, state: closed}
  glass:  {zone: RWS, state: inverted}
human:                     # validated by assistbot.human (profile, parameters, script)
  profile: active
overrides: {}              # dotted parameter paths -> values
agent: dnf                 # the robot's mind: dnf (the default), or package.module:factory
```

Sections that belong to another package are validated by that package, so
each rule is written once; this module owns the top level.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from assistbot.errors import UserError, read_yaml
from assistbot.resources import SCENARIOS

TOP_KEYS = ("name", "description", "seed", "time_limit", "objects", "human", "overrides", "agent")


@dataclass
class Scenario:
    name: str
    path: Path | None
    description: str = ""
    seed: int = 0
    time_limit: float = 240.0
    objects: Any = None  # assistbot.world.Arrangement
    human: Any = None  # assistbot.human.script.HumanConfig
    overrides: dict[str, Any] = field(default_factory=dict)
    agent: str = "dnf"   # assistbot.agents.AGENTS, or package.module:factory
    raw: dict[str, Any] = field(default_factory=dict)


#: the vision overrides a scenario, `assistbot run --set` or a sweep may give: dotted path -> VisionPerception keyword
VISION_PARAMS = {"vision.dropout": "dropout", "vision.pipelined": "pipelined"}


def check_vision_value(path: str, value: Any, where: str) -> Any:
    """A vision override's value, checked (dropout: a probability in [0, 1); pipelined: true or false)."""
    if path == "vision.dropout":
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value < 1:
            raise UserError(where, path, f"a probability in [0, 1), got {value!r}")
    elif not isinstance(value, bool):
        raise UserError(where, path, f"true or false, got {value!r}")
    return value


def _where(path: Path | str | None) -> str:
    return str(path) if path is not None else "scenario"


def parse_scenario(data: Any, path: Path | str | None = None) -> Scenario:
    where = _where(path)
    if not isinstance(data, dict):
        raise UserError(where, "-", "a scenario is a YAML mapping with keys " + ", ".join(TOP_KEYS))
    for key in data:
        if key not in TOP_KEYS:
            raise UserError(where, str(key), f"unknown key; allowed: {', '.join(TOP_KEYS)}")
    for key in ("name", "objects", "human"):
        if key not in data:
            raise UserError(where, key, "is required")
    name = data["name"]
    if not isinstance(name, str) or not name or any(c in name for c in "/\\ "):
        raise UserError(where, "name", f"must be a non-empty word without spaces or slashes (it names the output folder), got {name!r}")
    seed = data.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise UserError(where, "seed", f"must be a whole number >= 0, got {seed!r}")
    limit = data.get("time_limit", 240)
    if isinstance(limit, bool) or not isinstance(limit, (int, float)) or not 0 < limit <= 3600:
        raise UserError(where, "time_limit", f"must be simulated seconds in (0, 3600], got {limit!r}")
    desc = data.get("description", "")
    if not isinstance(desc, str):
        raise UserError(where, "description", "must be text")
    overrides = data.get("overrides") or {}
    if not isinstance(overrides, dict) or not all(isinstance(k, str) for k in overrides):
        raise UserError(where, "overrides", "must map dotted parameter paths to values, e.g. {cognition.k: 0.8}")
    agent = data.get("agent", "dnf")
    if not isinstance(agent, str):
        raise UserError(where, "agent", f"must be an agent's name or package.module:factory, got {agent!r}")
    from assistbot.agents import agent_factory
    from assistbot.human.script import parse_human
    from assistbot.world import Arrangement

    agent_factory(agent, where)   # an unknown agent is named now, not when the episode starts

    # both name their keys in full ("objects.glass.zone", "human.script[2].do")
    objects = Arrangement.from_mapping(data["objects"], where)
    human = parse_human(data["human"], where)
    return Scenario(name=name, path=Path(path) if path else None, description=desc, seed=seed, time_limit=float(limit),
                    objects=objects, human=human, overrides=dict(overrides), agent=agent, raw=dict(data))


def resolve_path(spec: str | Path) -> Path:
    """A scenario file path, or the name of a shipped scenario."""
    p = Path(spec)
    if p.suffix in (".yaml", ".yml") or p.exists():
        return p
    shipped = SCENARIOS / f"{spec}.yaml"
    if shipped.exists():
        return shipped
    known = ", ".join(s.stem for s in shipped_scenarios())
    raise UserError(str(spec), "scenario", f"no such file or shipped scenario; shipped: {known or '(none)'}")


def load_scenario(spec: str | Path) -> Scenario:
    path = resolve_path(spec)
    return parse_scenario(read_yaml(path), path)


def shipped_scenarios() -> list[Path]:
    return sorted(SCENARIOS.glob("*.yaml"))
