"""Networks of dynamic neural fields as plain data, validated on construction.

A network spec is what a user writes (a dict or a YAML file): fields with
their parameters, and couplings between named items of fields. Every bad
value raises `FieldError` naming the element and the parameter.

Units: a field has ``size`` positions spaced ``dx`` field units apart (a 2-D
field ``shape = [ny, nx]`` positions, ``dx`` apart along both axes); kernel
and input widths (``sigma``, ``input_sigma``) are in field units; ``tau`` and
``dt`` are in seconds of simulated time.

Two kinds of coupling: item couplings (eq. 4: input at the target's items from
the presence of peaks at the source's items, through a table) and continuous
couplings (the source's whole output, optionally projected to fewer or more
dimensions, convolved with a Gaussian kernel), as DFT toolkits couple fields.

Two learning elements, as the DFT toolkits have them: a field's ``memory``
(a trace built slowly where the field is active and fed back as a preshape)
and an item coupling's ``learn`` (its table changes by a gated Hebbian rule).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields as dc_fields
from typing import Any, Mapping

import numpy as np

from assistbot.fields.errors import FieldError


def _number(where: str, key: str, value: Any, *, positive: bool = False, nonneg: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise FieldError(where, key, f"must be a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise FieldError(where, key, f"must be finite, got {value!r}")
    if positive and v <= 0:
        raise FieldError(where, key, f"must be > 0, got {value!r}")
    if nonneg and v < 0:
        raise FieldError(where, key, f"must be >= 0, got {value!r}")
    return v


def _check_keys(where: str, given: Mapping[str, Any], allowed: list[str]) -> None:
    if not isinstance(given, Mapping):
        raise FieldError(where, "-", f"must be a mapping, got {type(given).__name__}")
    for key in given:
        if key not in allowed:
            raise FieldError(where, str(key), f"unknown parameter; allowed: {', '.join(allowed)}")


def _nested(cls, where: str, key: str, keys: list[str], d: Any):
    """A nested parameter block (``kernel``, ``memory``, ``learn``) from a mapping, its keys checked and named
    ``key.name`` in errors; an instance of ``cls`` passes as it is."""
    if isinstance(d, cls):
        return d
    if not isinstance(d, Mapping):
        raise FieldError(where, key, f"must be a mapping with {', '.join(keys)}")
    _check_keys(where, {f"{key}.{k}": v for k, v in d.items()}, [f"{key}.{k}" for k in keys])
    return cls(**d)


KERNEL_KEYS = ["A", "sigma", "w_inhib", "normalize", "cutoff"]


@dataclass
class KernelSpec:
    """Interaction kernel of eq. (2): w(d) = A exp(-d^2 / 2 sigma^2) - w_inhib.

    The Gaussian is sampled at the field's positions: ``A dx g(d)`` (the
    integral of eq. 1 as a sum), or with ``normalize`` ``A g(d) / sum g`` (the
    convention of COSIVINA and cedar, whose kernels sum to A). It is cut where
    it falls below 1e-10 of its peak, or with ``cutoff`` at ``ceil(cutoff
    sigma / dx)`` positions from the centre. In 2-D it is the product of one
    such Gaussian per axis, with A and dx^2 applied once.
    """

    A: float = 0.0
    sigma: float = 1.0
    w_inhib: float = 0.0
    normalize: bool = False
    cutoff: float | None = None

    def validate(self, where: str, *, lateral: bool = True) -> None:
        """A lateral kernel excites (A >= 0) around a peak of positive width; a coupling's kernel may
        inhibit (A < 0) and may have width 0 (position to position), but has no global term."""
        self.A = _number(where, "kernel.A", self.A, nonneg=lateral)
        self.sigma = _number(where, "kernel.sigma", self.sigma, nonneg=not lateral, positive=lateral)
        self.w_inhib = _number(where, "kernel.w_inhib", self.w_inhib, nonneg=True)
        if not lateral and self.w_inhib:
            raise FieldError(where, "kernel.w_inhib", "a coupling has no global term; give the target field's kernel w_inhib")
        if not isinstance(self.normalize, bool):
            raise FieldError(where, "kernel.normalize", f"must be true or false, got {self.normalize!r}")
        if self.cutoff is not None:
            self.cutoff = _number(where, "kernel.cutoff", self.cutoff, positive=True)

    @classmethod
    def from_dict(cls, where: str, d: Any) -> "KernelSpec":
        return _nested(cls, where, "kernel", KERNEL_KEYS, d)


MEMORY_KEYS = ["tau_build", "tau_decay", "amplitude", "threshold"]


@dataclass
class MemorySpec:
    """A memory trace of a field: a slowly built, slowly decaying preshape (COSIVINA's MemoryTrace).

    With f the field's output and m the trace (one value per position, 0 at the start), while the field
    holds activity somewhere (f > ``threshold`` at some position):

    - tau_build dm/dt = -m + f   where f > threshold (the trace builds toward the output);
    - tau_decay dm/dt = -m       everywhere else (it fades where the field is active elsewhere);

    and while the field is inactive everywhere the trace holds: no activity is no evidence to forget.
    The field receives ``amplitude * m`` as input (negative: a habituating trace).
    """

    tau_build: float = 1.0
    tau_decay: float = 10.0
    amplitude: float = 1.0
    threshold: float = 0.5

    def validate(self, where: str) -> None:
        self.tau_build = _number(where, "memory.tau_build", self.tau_build, positive=True)
        self.tau_decay = _number(where, "memory.tau_decay", self.tau_decay, positive=True)
        self.amplitude = _number(where, "memory.amplitude", self.amplitude)
        self.threshold = _number(where, "memory.threshold", self.threshold)
        if not 0.0 < self.threshold < 1.0:
            raise FieldError(where, "memory.threshold", f"compares with the output f in (0, 1); must lie between, got {self.threshold}")

    @classmethod
    def from_dict(cls, where: str, d: Any) -> "MemorySpec":
        return _nested(cls, where, "memory", MEMORY_KEYS, d)


@dataclass
class FieldSpec:
    """One 1-D field of eq. (1) with its sigmoid (3) and kernel (2).

    ``items`` name subpopulations placed at the centres of ``spacing``-wide
    bins, so ``size = len(items) * spacing``; a field without items gives its
    ``size`` directly. A 2-D field gives ``shape: [ny, nx]`` instead (rows
    along y, columns along x, stored row by row) and has no items; its kernel
    is the 2-D Gaussian and ``periodic`` wraps both axes.
    """

    name: str
    items: list[str] = field(default_factory=list)
    size: int = 0
    spacing: int = 10
    dx: float = 1.0
    tau: float = 0.1
    h: float = -3.0
    beta: float = 4.0
    u0: float = 0.0
    kernel: KernelSpec = field(default_factory=KernelSpec)
    input_sigma: float = 1.0
    noise: float = 0.0
    periodic: bool = False
    shape: list[int] | None = None
    memory: MemorySpec | None = None

    @property
    def where(self) -> str:
        return f"field '{self.name}'"

    @property
    def ndim(self) -> int:
        return 1 if self.shape is None else 2

    @property
    def grid(self) -> tuple[int, int]:
        """(rows, columns) of the field's positions: (1, size) for a 1-D field."""
        return (1, self.size) if self.shape is None else (self.shape[0], self.shape[1])

    def validate(self) -> None:
        w = self.where
        if self.shape is not None:
            if (not isinstance(self.shape, (list, tuple)) or len(self.shape) != 2
                    or not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1 for n in self.shape)):
                raise FieldError(w, "shape", f"must be two whole numbers >= 1 (rows along y, columns along x), got {self.shape!r}")
            if self.items:
                raise FieldError(w, "items", "a 2-D field has no items; couple it with continuous couplings")
            self.shape = [int(self.shape[0]), int(self.shape[1])]
            if self.size not in (0, self.shape[0] * self.shape[1]):
                raise FieldError(w, "size", f"{self.size} does not match shape {self.shape}; give one or the other")
            self.size = self.shape[0] * self.shape[1]
        if not isinstance(self.items, (list, tuple)) or not all(isinstance(i, str) and i for i in self.items):
            raise FieldError(w, "items", "must be a list of non-empty item names")
        self.items = list(self.items)
        dup = {i for i in self.items if self.items.count(i) > 1}
        if dup:
            raise FieldError(w, "items", f"names must be unique; repeated: {', '.join(sorted(dup))}")
        if isinstance(self.spacing, bool) or not isinstance(self.spacing, (int, np.integer)) or self.spacing < 1:
            raise FieldError(w, "spacing", f"must be a whole number of positions >= 1, got {self.spacing!r}")
        if self.items:
            expected = len(self.items) * int(self.spacing)
            if self.size not in (0, expected):
                raise FieldError(w, "size", f"{self.size} does not match {len(self.items)} items x spacing {self.spacing} = {expected}; "
                                             "give one or the other")
            self.size = expected
        if isinstance(self.size, bool) or not isinstance(self.size, (int, np.integer)) or self.size < 1:
            raise FieldError(w, "size", f"must be a whole number >= 1 (or give items), got {self.size!r}")
        self.dx = _number(w, "dx", self.dx, positive=True)
        self.tau = _number(w, "tau", self.tau, positive=True)
        self.h = _number(w, "h", self.h)
        if self.h >= 0:
            raise FieldError(w, "h", f"the resting level must be negative (h < 0), got {self.h}")
        self.beta = _number(w, "beta", self.beta, positive=True)
        self.u0 = _number(w, "u0", self.u0)
        self.input_sigma = _number(w, "input_sigma", self.input_sigma, positive=True)
        self.noise = _number(w, "noise", self.noise, nonneg=True)
        if not isinstance(self.periodic, bool):
            raise FieldError(w, "periodic", f"must be true or false, got {self.periodic!r}")
        if not isinstance(self.kernel, KernelSpec):
            raise FieldError(w, "kernel", f"must be a mapping with {', '.join(KERNEL_KEYS)}")
        self.kernel.validate(w)
        if self.memory is not None:
            if not isinstance(self.memory, MemorySpec):
                raise FieldError(w, "memory", f"must be a mapping with {', '.join(MEMORY_KEYS)}")
            self.memory.validate(w)

    def item_index(self, item: str) -> int:
        """Position index of an item's centre."""
        try:
            m = self.items.index(item)
        except ValueError:
            raise FieldError(self.where, str(item), f"unknown item; known: {', '.join(self.items) or '(none)'}") from None
        return m * self.spacing + self.spacing // 2

    @property
    def item_indices(self) -> np.ndarray:
        return np.arange(len(self.items)) * self.spacing + self.spacing // 2

    @property
    def positions(self) -> np.ndarray:
        """Field positions in field units."""
        return np.arange(self.size) * self.dx

    @classmethod
    def from_dict(cls, name: str, d: Mapping[str, Any]) -> "FieldSpec":
        allowed = [f.name for f in dc_fields(cls) if f.name != "name"]
        _check_keys(f"field '{name}'", d, allowed)
        d = dict(d)
        kernel = d.pop("kernel", {})
        if isinstance(kernel, Mapping):
            kernel = KernelSpec.from_dict(f"field '{name}'", kernel)
        if d.get("memory") is not None:
            d["memory"] = MemorySpec.from_dict(f"field '{name}'", d["memory"])
        spec = cls(name=name, kernel=kernel, **d)
        spec.validate()
        return spec


class _Coupling:
    """What both kinds of coupling share: two named ends and a name (by default "source->target")."""

    source: str
    target: str
    name: str

    def __post_init__(self) -> None:
        if not self.name:
            self.name = f"{self.source}->{self.target}"

    @property
    def where(self) -> str:
        return f"coupling '{self.name}'"

    def _ends(self, fields_by_name: Mapping[str, FieldSpec]) -> tuple[FieldSpec, FieldSpec]:
        for key in ("source", "target"):
            ref = getattr(self, key)
            if ref not in fields_by_name:
                raise FieldError(self.where, key, f"unknown field {ref!r}; known: {', '.join(fields_by_name)}")
        return fields_by_name[self.source], fields_by_name[self.target]


LEARN_KEYS = ["rate", "decay", "gate", "bounds", "keep", "traces", "pre", "sources", "targets", "post_threshold",
              "relative"]
TRACE_SIDES = ("none", "pre", "post", "both")


@dataclass
class LearnSpec:
    """A gated Hebbian rule for an item coupling's table (the table given is the prior, the start):

        da_mj/dt = g(t) c_j(t) (rate c_m(t) - decay a_mj),   a_mj kept within ``bounds``

    c_j the presence of the source (pre-synaptic) item j, c_m that of the target (post-synaptic) item m,
    both f(u) at the item centres as in eq. (4); g the output f(u) at the ``gate`` item ("FIELD.ITEM"),
    1 without a gate. Only the weights of active source items change: while j is active and the gate
    open, its row of weights relaxes toward ``rate / decay`` times the target's pattern (with ``decay``
    0 it only grows, up to the upper bound). Rates are per second.

    For a gate that opens after the act (a success reported seconds later), when the fields have moved on:

    - ``traces``: ``post`` reads c_m from the target's memory trace (what it held last, kept while it rests),
      ``pre`` c_j from the pre-synaptic field's, ``both`` both (those fields need a ``memory``);
    - ``pre``: another field whose items named like the learning sources give c_j, e.g. a working memory
      that holds the source's last act through what follows it (the coupling still drives its target from
      its source);
    - ``sources``, ``targets``: the source and target items whose weights learn (default all); the others
      keep their prior, and only the learning weights are held to ``bounds``. ``targets`` may instead map
      each learning source item to its own targets (``{x: [p, q], y: [r]}``): only those pairs learn;
    - ``post_threshold``: only the weights onto target items whose c_m exceeds it change (default 0: with
      traces, a target never active keeps its weights; one that was active and lost to another relaxes
      toward what is left of its trace);
    - ``relative``: c_m divided by the largest c_m among the source item's learning targets above
      ``post_threshold`` (that one counts 1), so a row learns which of its targets won, not how far a trace
      has faded by the time the gate opens. A trace fades once another item of its field is up, and a gate
      that opens late would otherwise unlearn a target that was right but followed by a reading that is
      none of this source's targets (another object's chain, say).

    ``keep``: the share (0 to 1) of its prior, above the lower bound, that a weight keeps: it never falls
    below ``lowest + keep * (prior - lowest)`` (default 0: down to the bound), so one lost reading cannot
    unlearn an association outright.
    """

    rate: float = 0.0
    decay: float = 0.0
    gate: str | None = None
    bounds: list[float] = field(default_factory=lambda: [0.0, 1.0])
    traces: str = "none"
    pre: str | None = None
    sources: list[str] | None = None
    targets: list[str] | dict[str, list[str]] | None = None
    post_threshold: float = 0.0
    keep: float = 0.0
    relative: bool = False

    def validate(self, where: str, fields_by_name: Mapping[str, "FieldSpec"], source: "FieldSpec | None" = None,
                 target: "FieldSpec | None" = None) -> None:
        self.rate = _number(where, "learn.rate", self.rate, nonneg=True)
        self.decay = _number(where, "learn.decay", self.decay, nonneg=True)
        if (not isinstance(self.bounds, (list, tuple)) or len(self.bounds) != 2):
            raise FieldError(where, "learn.bounds", f"must be [lowest, highest] weight, got {self.bounds!r}")
        lo = _number(where, "learn.bounds", self.bounds[0])
        hi = _number(where, "learn.bounds", self.bounds[1])
        if lo > hi:
            raise FieldError(where, "learn.bounds", f"the lowest weight {lo:g} is above the highest {hi:g}")
        self.bounds = [lo, hi]
        if self.gate is not None:
            gate_item(where, self.gate, fields_by_name)
        self.post_threshold = _number(where, "learn.post_threshold", self.post_threshold, nonneg=True)
        self.keep = _number(where, "learn.keep", self.keep, nonneg=True)
        if not isinstance(self.relative, bool):
            raise FieldError(where, "learn.relative", f"must be true or false, got {self.relative!r}")
        if self.keep > 1.0:
            raise FieldError(where, "learn.keep", f"is a share of the prior, from 0 to 1; got {self.keep:g}")
        if self.sources is not None:
            self.sources = _item_list(where, "sources", self.sources, source)
        if isinstance(self.targets, Mapping):
            self.targets = {s: _item_list(where, f"targets.{s}", t, target) for s, t in self.targets.items()}
            _item_list(where, "targets", list(self.targets), source, kind="source")
        elif self.targets is not None:
            self.targets = _item_list(where, "targets", self.targets, target)
        pre = source
        if self.pre is not None:
            if not isinstance(self.pre, str) or self.pre not in fields_by_name:
                raise FieldError(where, "learn.pre", f"no field named {self.pre!r}; known: {', '.join(fields_by_name)}")
            pre = fields_by_name[self.pre]
            if source is not None:
                missing = [s for s in source.items if self.learns_from(s) and s not in pre.items]
                if missing:
                    raise FieldError(where, "learn.pre", f"field '{pre.name}' lacks the learning source items "
                                                         f"{', '.join(missing)}")
        if self.traces not in TRACE_SIDES:
            raise FieldError(where, "learn.traces", f"must be one of {', '.join(TRACE_SIDES)}, got {self.traces!r}")
        for side, end in (("pre", pre), ("post", target)):
            if self.traces in (side, "both") and end is not None and end.memory is None:
                raise FieldError(where, "learn.traces", f"reads the {side}-synaptic memory trace, and field '{end.name}' "
                                                        f"has no 'memory'")

    def learns_from(self, source_item: str) -> bool:
        """Whether weights from this source item learn (onto the learning targets)."""
        return ((self.sources is None or source_item in self.sources)
                and (not isinstance(self.targets, dict) or source_item in self.targets))

    def learns(self, source_item: str, target_item: str) -> bool:
        """Whether the weight from this source item onto this target item changes."""
        if not self.learns_from(source_item):
            return False
        if isinstance(self.targets, dict):
            return target_item in self.targets[source_item]
        return self.targets is None or target_item in self.targets

    @classmethod
    def from_dict(cls, where: str, d: Any) -> "LearnSpec":
        return _nested(cls, where, "learn", LEARN_KEYS, d)


def _item_list(where: str, key: str, listed: Any, end: "FieldSpec | None", kind: str = "") -> list[str]:
    """A learning rule's list of items, each an item of ``end`` (the source or target field)."""
    kind = kind or key.split(".")[0][:-1]
    if isinstance(listed, str) or not isinstance(listed, (list, tuple)):
        also = ", or a mapping of source items to lists of target items" if key == "targets" else ""
        raise FieldError(where, f"learn.{key}", f"must be a list of {kind} items{also}, got {listed!r}")
    if end is not None:
        for item in listed:
            if item not in end.items:
                raise FieldError(where, f"learn.{key}", f"unknown item {item!r} of {kind} field '{end.name}'; "
                                                        f"known: {', '.join(end.items)}")
    return list(listed)


def gate_item(where: str, ref: Any, fields_by_name: Mapping[str, "FieldSpec"]) -> tuple[str, str]:
    """(field, item) of a "FIELD.ITEM" reference; the field is the longest known name before a dot."""
    if not isinstance(ref, str) or "." not in ref:
        raise FieldError(where, "learn.gate", f"must be FIELD.ITEM, got {ref!r}")
    for name in sorted(fields_by_name, key=len, reverse=True):
        if ref.startswith(name + "."):
            item = ref[len(name) + 1:]
            if item not in fields_by_name[name].items:
                raise FieldError(where, "learn.gate", f"unknown item {item!r} of field '{name}'; "
                                                      f"known: {', '.join(fields_by_name[name].items) or '(none)'}")
            return name, item
    raise FieldError(where, "learn.gate", f"no field named in {ref!r}; known: {', '.join(fields_by_name)}")


@dataclass
class CouplingSpec(_Coupling):
    """Input from items of ``source`` to items of ``target``, eq. (4), scaled by ``k``.

    ``table`` maps target item -> {source item: a_mj}; a matrix of shape
    (target items, source items) is accepted too. With ``learn`` the table is
    the prior of a gated Hebbian rule (`LearnSpec`).
    """

    source: str
    target: str
    k: float = 1.0
    table: dict[str, dict[str, float]] = field(default_factory=dict)
    name: str = ""
    learn: LearnSpec | None = None


    def validate(self, fields_by_name: Mapping[str, FieldSpec]) -> None:
        w = self.where
        src, tgt = self._ends(fields_by_name)
        if not src.items or not tgt.items:
            raise FieldError(w, "source" if not src.items else "target", "couplings connect named items; that field has none")
        self.k = _number(w, "k", self.k)
        if isinstance(self.table, (list, tuple, np.ndarray)):
            arr = np.asarray(self.table, dtype=float)
            if arr.shape != (len(tgt.items), len(src.items)):
                raise FieldError(w, "table", f"matrix shape {arr.shape} does not match (target items, source items) = "
                                              f"({len(tgt.items)}, {len(src.items)})")
            self.table = {t: {s: float(arr[i, j]) for j, s in enumerate(src.items) if arr[i, j] != 0.0} for i, t in enumerate(tgt.items)}
        if not isinstance(self.table, Mapping):
            raise FieldError(w, "table", "must map target item -> {source item: weight}")
        clean: dict[str, dict[str, float]] = {}
        for t, row in self.table.items():
            if t not in tgt.items:
                raise FieldError(w, f"table.{t}", f"unknown item of target field '{tgt.name}'; known: {', '.join(tgt.items)}")
            if not isinstance(row, Mapping):
                raise FieldError(w, f"table.{t}", "must map source item -> weight")
            clean[t] = {}
            for s, a in row.items():
                if s not in src.items:
                    raise FieldError(w, f"table.{t}.{s}", f"unknown item of source field '{src.name}'; known: {', '.join(src.items)}")
                clean[t][s] = _number(w, f"table.{t}.{s}", a)
        self.table = clean
        if self.learn is not None:
            if not isinstance(self.learn, LearnSpec):
                raise FieldError(w, "learn", f"must be a mapping with {', '.join(LEARN_KEYS)}")
            self.learn.validate(w, fields_by_name, src, tgt)
            lo, hi = self.learn.bounds
            for t in tgt.items:            # every learning weight, those left out (0) too
                for s in src.items:
                    if not self.learn.learns(s, t):
                        continue
                    a = clean.get(t, {}).get(s, 0.0)
                    if not lo <= a <= hi:
                        raise FieldError(w, f"table.{t}.{s}", f"the weight {a:g}{'' if a else ' (left out)'} lies outside "
                                                             f"learn.bounds [{lo:g}, {hi:g}]")

    def matrix(self, fields_by_name: Mapping[str, FieldSpec]) -> np.ndarray:
        """a_mj as an array (target items x source items)."""
        src, tgt = fields_by_name[self.source], fields_by_name[self.target]
        a = np.zeros((len(tgt.items), len(src.items)))
        for t, row in self.table.items():
            for s, v in row.items():
                a[tgt.items.index(t), src.items.index(s)] = v
        return a

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], index: int) -> "CouplingSpec":
        where = f"coupling #{index}"
        _check_keys(where, d, ["source", "target", "k", "table", "name", "learn"])
        for key in ("source", "target"):
            if key not in d:
                raise FieldError(where, key, "is required")
        d = dict(d)
        if d.get("learn") is not None:
            d["learn"] = LearnSpec.from_dict(where if not d.get("name") else f"coupling '{d['name']}'", d["learn"])
        return cls(**d)


AXES = ("x", "y")
PROJECTION_OPS = ("sum", "max")
BOUNDARIES = ("linear", "circular")


@dataclass
class ContinuousCouplingSpec(_Coupling):
    """Input ``kernel * P(f(u_source))`` over the whole target field, as DFT toolkits couple fields.

    P is the identity when source and target have the same shape; ``project:
    {op: sum|max, over: x|y}`` turns a 2-D source into a 1-D target along the
    axis left (sum or max over the other); ``expand: x|y`` spreads a 1-D
    source along that axis of a 2-D target (the source runs along the other
    axis). The kernel (`KernelSpec` without w_inhib; ``A`` may be negative,
    ``sigma: 0`` couples position to position) is then convolved over the
    target's shape with a ``linear`` (zero-padded) or ``circular`` boundary,
    by default the target field's own (``periodic``).
    """

    source: str
    target: str
    kernel: KernelSpec = field(default_factory=KernelSpec)
    boundary: str | None = None
    project: dict[str, str] | None = None
    expand: str | None = None
    name: str = ""


    @property
    def circular(self) -> bool:
        return self.boundary == "circular"

    def validate(self, fields_by_name: Mapping[str, FieldSpec]) -> None:
        w = self.where
        src, tgt = self._ends(fields_by_name)
        self.kernel = KernelSpec.from_dict(w, self.kernel)
        self.kernel.validate(w, lateral=False)
        if self.boundary is None:
            self.boundary = "circular" if tgt.periodic else "linear"
        if self.boundary not in BOUNDARIES:
            raise FieldError(w, "boundary", f"must be one of {', '.join(BOUNDARIES)}, got {self.boundary!r}")
        if src.dx != tgt.dx:
            raise FieldError(w, "target", f"source dx {src.dx:g} and target dx {tgt.dx:g} differ; the kernel needs one grid")
        if self.project is not None and self.expand is not None:
            raise FieldError(w, "project", "give project (2-D to 1-D) or expand (1-D to 2-D), not both")
        if self.project is not None:
            if not isinstance(self.project, Mapping) or set(self.project) != {"op", "over"}:
                raise FieldError(w, "project", "must be a mapping {op: sum|max, over: x|y}")
            if self.project["op"] not in PROJECTION_OPS:
                raise FieldError(w, "project.op", f"must be one of {', '.join(PROJECTION_OPS)}, got {self.project['op']!r}")
            if self.project["over"] not in AXES:
                raise FieldError(w, "project.over", f"must be x or y, got {self.project['over']!r}")
            if src.ndim != 2 or tgt.ndim != 1:
                raise FieldError(w, "project", "projects a 2-D source onto a 1-D target")
            ny, nx = src.grid
            left = nx if self.project["over"] == "y" else ny
            if tgt.size != left:
                raise FieldError(w, "target", f"has {tgt.size} positions; the projection over {self.project['over']} leaves {left}")
        elif self.expand is not None:
            if self.expand not in AXES:
                raise FieldError(w, "expand", f"must be x or y, got {self.expand!r}")
            if src.ndim != 1 or tgt.ndim != 2:
                raise FieldError(w, "expand", "expands a 1-D source into a 2-D target")
            ny, nx = tgt.grid
            along_other = nx if self.expand == "y" else ny
            if src.size != along_other:
                raise FieldError(w, "source", f"has {src.size} positions; expanding along {self.expand} needs {along_other}")
        elif src.grid != tgt.grid:
            raise FieldError(w, "target", f"shape {list(tgt.grid)} differs from the source's {list(src.grid)}; "
                                          "give project or expand to change dimensions")

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], index: int) -> "ContinuousCouplingSpec":
        where = f"coupling #{index}"
        if "learn" in d:
            raise FieldError(where, "learn", "learning changes an item coupling's table; a coupling with a kernel has none")
        _check_keys(where, d, ["source", "target", "kernel", "boundary", "project", "expand", "name"])
        for key in ("source", "target", "kernel"):
            if key not in d:
                raise FieldError(where, key, "is required")
        d = dict(d)
        d["kernel"] = KernelSpec.from_dict(where if not d.get("name") else f"coupling '{d['name']}'", d["kernel"])
        return cls(**d)


@dataclass
class NetworkSpec:
    """Fields and couplings of one network, stepped with ``dt`` seconds.

    In a dict or YAML file both kinds of coupling sit in one ``couplings``
    list; one with a ``kernel`` is continuous and lands in ``continuous``.
    """

    dt: float = 0.005
    fields: dict[str, FieldSpec] = field(default_factory=dict)
    couplings: list[CouplingSpec] = field(default_factory=list)
    continuous: list[ContinuousCouplingSpec] = field(default_factory=list)

    def validate(self) -> None:
        self.dt = _number("network", "dt", self.dt, positive=True)
        if not self.fields:
            raise FieldError("network", "fields", "a network needs at least one field")
        for f in self.fields.values():
            f.validate()
            # Explicit Euler on tau du/dt = -u + ...: dt >= 2 tau diverges and
            # dt >= tau overshoots; half of tau is the coarsest step we accept.
            if self.dt > f.tau / 2:
                raise FieldError(f.where, "tau",
                                 f"dt={self.dt} s is too large for a stable Euler step with tau={f.tau} s; need dt <= tau/2")
            if f.memory is not None:
                for key in ("tau_build", "tau_decay"):
                    if self.dt > getattr(f.memory, key):
                        raise FieldError(f.where, f"memory.{key}",
                                         f"dt={self.dt} s is larger than {key}={getattr(f.memory, key)} s; the trace would overshoot")
        names = set()
        every: list[CouplingSpec | ContinuousCouplingSpec] = [*self.couplings, *self.continuous]
        for c in every:
            c.validate(self.fields)
            if c.name in names:
                raise FieldError(c.where, "name", "two couplings share this name; give one a distinct 'name'")
            names.add(c.name)
        for c in self.couplings:
            if c.learn is not None and c.learn.decay * self.dt > 1.0:
                raise FieldError(c.where, "learn.decay", f"{c.learn.decay:g}/s with dt={self.dt} s overshoots; need decay <= 1/dt")

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "NetworkSpec":
        _check_keys("network", d, ["dt", "fields", "couplings"])
        fields_d = d.get("fields", {})
        if not isinstance(fields_d, Mapping):
            raise FieldError("network", "fields", "must map field name -> parameters")
        couplings_d = d.get("couplings", []) or []
        if not isinstance(couplings_d, (list, tuple)):
            raise FieldError("network", "couplings", "must be a list of couplings")
        for i, c in enumerate(couplings_d):
            if not isinstance(c, Mapping):
                raise FieldError(f"coupling #{i}", "-", f"must be a mapping, got {type(c).__name__}")
        spec = cls(
            dt=d.get("dt", 0.005),
            fields={str(n): FieldSpec.from_dict(str(n), p or {}) for n, p in fields_d.items()},
            couplings=[CouplingSpec.from_dict(c, i) for i, c in enumerate(couplings_d) if "kernel" not in c],
            continuous=[ContinuousCouplingSpec.from_dict(c, i) for i, c in enumerate(couplings_d) if "kernel" in c],
        )
        spec.validate()
        return spec

    def coupling(self, name: str) -> CouplingSpec:
        """An item coupling by name."""
        for c in self.couplings:
            if c.name == name:
                return c
        raise FieldError("network", name, f"unknown item coupling; known: {', '.join(c.name for c in self.couplings) or '(none)'}")

    def field(self, name: str) -> FieldSpec:
        try:
            return self.fields[name]
        except KeyError:
            raise FieldError("network", name, f"unknown field; known: {', '.join(self.fields)}") from None
