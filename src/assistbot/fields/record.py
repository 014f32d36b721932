"""Recording of activity u and total input S over time for chosen fields."""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

import numpy as np

if TYPE_CHECKING:
    from assistbot.fields.network import Network


class Recorder:
    """Keeps u and S of some fields every ``every`` steps; arrays are built on access."""

    def __init__(self, net: "Network", fields: list[str], every: int = 1, couplings: Iterable[str] = ()) -> None:
        """``couplings``: fields of which also to keep, at each item centre, the part of S that each incoming
        coupling gives."""
        if int(every) < 1:
            from assistbot.fields.errors import FieldError

            raise FieldError("recorder", "every", f"must be a whole number >= 1, got {every!r}")
        self.net = net
        self.fields = list(fields)
        self.every = int(every)
        self._t: list[float] = []
        self._u: dict[str, list[np.ndarray]] = {f: [] for f in self.fields}
        self._s: dict[str, list[np.ndarray]] = {f: [] for f in self.fields}
        self.couplings = [f for f in couplings if f in self.fields]
        self._c: dict[str, dict[str, list[np.ndarray]]] = {f: {} for f in self.couplings}
        # learning elements are kept whenever the network has them: the trace of each recorded field that
        # has one, and every learning coupling's weights
        self._m: dict[str, list[np.ndarray]] = {f: [] for f in self.fields if net.spec.fields[f].memory is not None}
        self._w: dict[str, list[np.ndarray]] = {c.name: [] for c in net.spec.couplings if c.learn is not None}

    def maybe_record(self, force: bool = False) -> None:
        if not force and self.net.steps % self.every:
            return
        self._t.append(self.net.t)
        for f in self.fields:
            self._u[f].append(self.net.u(f).copy())
            self._s[f].append(self.net.input(f).copy())
        for f in self._m:
            self._m[f].append(self.net.memory(f).copy())
        for name in self._w:
            self._w[name].append(self.net.table(name))
        for f in self.couplings:
            at = self.net.spec.fields[f].item_indices
            for name, part in self.net.coupling_inputs(f).items():
                self._c[f].setdefault(name, []).append(part[at])

    @property
    def times(self) -> np.ndarray:
        return np.asarray(self._t)

    @property
    def u(self) -> dict[str, np.ndarray]:
        """Activity per field, shape (samples, positions)."""
        return {f: np.asarray(v) for f, v in self._u.items()}

    @property
    def s(self) -> dict[str, np.ndarray]:
        """Total input per field, shape (samples, positions)."""
        return {f: np.asarray(v) for f, v in self._s.items()}

    @property
    def memory(self) -> dict[str, np.ndarray]:
        """Memory trace per recorded field that has one, shape (samples, positions)."""
        return {f: np.asarray(v) for f, v in self._m.items()}

    @property
    def weights(self) -> dict[str, np.ndarray]:
        """Per learning coupling: its table over time, shape (samples, target items, source items)."""
        return {name: np.asarray(v) for name, v in self._w.items()}

    @property
    def coupling_items(self) -> dict[str, dict[str, np.ndarray]]:
        """Per field, per incoming coupling: its part of S at each item centre, shape (samples, items); empty
        for the fields not named in ``couplings``."""
        return {f: {name: np.asarray(v) for name, v in parts.items()} for f, parts in self._c.items()}

    def item_traces(self, field: str, which: str = "u") -> dict[str, np.ndarray]:
        """Time course at each item's centre: {item: (samples,)}."""
        spec = self.net.spec.fields[field]
        data = (self.u if which == "u" else self.s)[field]
        return {item: data[:, idx] for item, idx in zip(spec.items, spec.item_indices)}
