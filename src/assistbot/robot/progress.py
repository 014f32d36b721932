"""How a running motion reports: the `Status` of a phase or a primitive, and a primitive's `Progress`."""

from __future__ import annotations

import enum
from dataclasses import dataclass


class Status(enum.Enum):
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"


@dataclass
class Progress:
    status: Status
    phase: str = ""
    reason: str = ""
    t: float = 0.0
