"""Learning from the user, across episodes: the grip-to-chain weights in a file.

The seed assumes which grip means which goal (above grip: hand over; side grip: pour or turn) and
proposes to learn it from the user. Here the OL -> ASL weights from each grip item onto the chains a grip
on the same object begins (`task.GRIP_CHAINS`) learn by the field library's gated Hebbian rule
(`CognitionConfig`'s ``learning`` block): while SUCCESS is up (an action of the robot's finished as it
should, a sub-goal was reached, or the partner was seen doing what the inferred intention predicts), the grip
in hand (GRIP, a memory of the grip seen as an object was taken) moves its
weight toward the chain ASL read last (ASL's memory trace) and away from a chain read before and given
up, keeping half its prior; a chain that took no part keeps its weight.

A weights file carries what was learnt from one episode to the next::

    {"format": "assistbot learned weights", "episodes": 3,
     "couplings": {"OL->ASL": {"<chain>": {"<grip item>": 0.8, ...}, ...}}}

`assistbot run SCENARIO --learn FILE` reads it (the priors if it does not exist yet), learns, and
writes it back; a run without ``--learn`` never changes the priors.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Mapping

from assistbot.errors import UserError

#: the learning rate `--learn` switches on (per s). Above ``learning.decay`` (1/s): a grip's weight onto a chain
#: read to the end (its trace above 2/3) relaxes to the priors' strength (``learning.highest``), most of the way
#: within one success; onto a chain read and then given up, toward what is left of its trace times 1.5 (not below
#: the share ``learning.keep`` of its prior)
LEARNING_RATE = 1.5
FORMAT = "assistbot learned weights"
KEY = "--learn"


def learning_overrides(overrides: Mapping[str, Any], prefix: str = "cognition.") -> dict[str, Any]:
    """``overrides`` with learning switched on (`LEARNING_RATE`) unless they set a rate of their own; ``prefix``
    "cognition." for a scenario's or `--set`'s paths, "" for the architecture's own."""
    out = dict(overrides)
    path = f"{prefix}learning.rate"
    if float(out.get(path, 0.0)) <= 0:
        out[path] = LEARNING_RATE
    return out


def check_learner(agent: str) -> None:
    """Only the field architecture learns: ``--learn`` with another agent is a `UserError`."""
    if agent != "dnf":
        raise UserError(KEY, agent, "only the field architecture (agent dnf) learns from the user")


def read_weights(path: Path) -> tuple[dict[str, Any], int]:
    """(the couplings' tables, the episodes they were learnt over) from a weights file; ({}, 0) if it does not
    exist yet. A file that is not one is a `UserError` naming it and the key."""
    path = Path(path)
    if not path.exists():
        return {}, 0
    if path.is_dir():
        raise UserError(str(path), KEY, "is a folder; name a weights file (.json)")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise UserError(str(path), KEY, f"cannot read the weights file: {exc}") from None
    except json.JSONDecodeError as exc:
        raise UserError(str(path), f"line {exc.lineno}", f"not JSON: {exc.msg}") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise UserError(str(path), "format", f"not a weights file (expected \"format\": \"{FORMAT}\")")
    episodes = data.get("episodes", 0)
    if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 0:
        raise UserError(str(path), "episodes", f"must be a whole number >= 0, got {episodes!r}")
    couplings = data.get("couplings")
    if not isinstance(couplings, dict):
        raise UserError(str(path), "couplings", "must map a coupling's name to {target item: {source item: weight}}")
    return couplings, episodes


def load_into(agent: Any, path: Path) -> int:
    """Put a weights file's tables into ``agent`` (a learning `Cognition`); the episodes they were learnt over.
    Unknown couplings, items or weights outside the bounds are a `UserError` naming the file and the key."""
    from assistbot.fields.errors import FieldError

    couplings, episodes = read_weights(path)
    learning = agent.learned_weights()
    for name, table in couplings.items():
        if name not in learning:
            raise UserError(str(path), f"couplings.{name}", f"does not learn; the learning couplings: {', '.join(learning)}")
        try:
            agent.load_weights({name: table})
        except FieldError as exc:
            entry = exc.key[len("table."):] if exc.key.startswith("table.") else ""
            raise UserError(str(path), f"couplings.{name}" + (f".{entry}" if entry else ""), exc.message) from None
    return episodes


def write_weights(path: Path, tables: Mapping[str, Any], episodes: int) -> None:
    """Write the learnt tables (atomically: an interrupted write leaves the old file whole)."""
    from assistbot.episode.outputs import replace_text

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    replace_text(path, json.dumps({"format": FORMAT, "episodes": int(episodes), "couplings": tables}, indent=1) + "\n")


def distance_from_priors(tables: Mapping[str, Mapping[str, Mapping[str, float]]],
                         priors: Mapping[str, Mapping[str, Mapping[str, float]]]) -> float:
    """The learnt weights' Euclidean distance from the priors, over every weight of every learning coupling."""
    total = 0.0
    for name, table in tables.items():
        prior = priors.get(name, {})
        for t in set(table) | set(prior):
            for s in set(table.get(t, {})) | set(prior.get(t, {})):
                total += (table.get(t, {}).get(s, 0.0) - prior.get(t, {}).get(s, 0.0)) ** 2
    return math.sqrt(total)
