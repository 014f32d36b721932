"""How a running primitive reports: its `Progress` (a `Status` of `assistbot.interfaces`, the phase, why it failed)."""

from __future__ import annotations

from dataclasses import dataclass

from assistbot.interfaces import Status


@dataclass
class Progress:
    status: Status
    phase: str = ""
    reason: str = ""
    t: float = 0.0


__all__ = ["Progress"]
