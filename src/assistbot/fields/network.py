"""A network of coupled 1-D and 2-D fields, stepped as one batch, addressable by field, item and parameter path."""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path
from typing import Any, Iterable, Mapping, cast

import numpy as np

from assistbot.fields.compiled import Compiled, compile_spec, gaussian_half_width
from assistbot.fields.errors import FieldError
from assistbot.fields.record import Recorder
from assistbot.fields.spec import MEMORY_KEYS, FieldSpec, KernelSpec, NetworkSpec
from assistbot.fields.stepping import ContinuousInput, make_stepper

BACKENDS = ("auto", "numpy", "numba")


class Network:
    """Fields and couplings of a `NetworkSpec`, with their state u and inputs.

    Stimuli at items (``set_stimulus``) and at arbitrary positions
    (``set_stimulus_at``) are held until changed, as vision input is. Time
    advances in steps of ``spec.dt`` seconds.
    """

    t: float              # s since the start (or the last reset)
    steps: int            # Euler steps since then
    state_u: np.ndarray   # every field's activation, concatenated
    state_m: np.ndarray   # every field's memory trace, concatenated (zero where a field has none)
    state_w: np.ndarray   # the learning couplings' weights, one table after another, row-major

    def __init__(self, spec: NetworkSpec, backend: str = "auto", seed: int | None = 0) -> None:
        if backend not in BACKENDS:
            raise FieldError("network", "backend", f"unknown backend {backend!r}; allowed: {', '.join(BACKENDS)}")
        spec.validate()
        self.spec = spec
        self.backend_request = backend
        self.rng = np.random.default_rng(seed)
        self._recorders: list[Recorder] = []
        self._point_stimuli: dict[tuple[str, str], tuple[tuple[float, ...], float, float]] = {}
        self._patterns: dict[tuple[str, str], np.ndarray] = {}
        self._compile(fresh=True)

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_dict(cls, d: Mapping[str, Any], backend: str = "auto", seed: int | None = 0) -> "Network":
        return cls(NetworkSpec.from_dict(d), backend=backend, seed=seed)

    @classmethod
    def from_yaml(cls, path: str | Path, backend: str = "auto", seed: int | None = 0) -> "Network":
        import yaml

        path = Path(path)
        try:
            data = yaml.safe_load(path.read_text())
        except OSError as exc:
            raise FieldError(str(path), "-", f"cannot read the file: {exc.strerror}") from None
        except yaml.YAMLError as exc:
            raise FieldError(str(path), "-", f"not valid YAML: {exc}") from None
        try:
            return cls.from_dict(data or {}, backend=backend, seed=seed)
        except FieldError as exc:
            raise FieldError(f"{path}: {exc.where}", exc.key, exc.message) from None

    def _compile(self, fresh: bool) -> None:
        old = None if fresh else (self._c, self.state_u, self.state_m, self.state_w)
        self._c: Compiled = compile_spec(self.spec)
        self._stepper = make_stepper(self._c, self.backend_request)
        self._continuous_input: ContinuousInput | None = None
        c = self._c
        # per field: its slice of the state vector and its item centres (read-outs use them every tick)
        self._slices = {name: c.slice(name) for name in c.names}
        self._items_at = {name: self.spec.fields[name].item_indices for name in c.names}
        self.state_u = c.h.copy()
        self.state_m = np.zeros(c.size)
        self.state_w = c.learning.prior.copy()
        self._S = np.zeros(c.size)
        self._S_ext = np.zeros(c.size)
        self._stim_item = np.zeros(c.n_items)
        self._tables: dict[str, np.ndarray] = {}   # a_mj per coupling, for coupling_inputs
        if fresh:
            self.t = 0.0
            self.steps = 0
        else:
            assert old is not None
            old_c, old_u, old_m, old_w = old
            for name in c.names:
                if name in old_c.names and old_c.slice(name) == c.slice(name):
                    self.state_u[c.slice(name)] = old_u[old_c.slice(name)]
                    if c.memory.fields[c.names.index(name)]:
                        self.state_m[c.slice(name)] = old_m[old_c.slice(name)]
            # what was learnt survives a parameter change (kept within the bounds now in force)
            L, old_L = c.learning, old_c.learning
            for i, name in enumerate(L.names):
                if name in old_L.names:
                    j = old_L.names.index(name)
                    before = old_L.table(old_w, j)
                    if before.shape == L.table(self.state_w, i).shape:
                        learns = L.table(L.learns, i) > 0    # a weight kept at its prior need not lie within the bounds
                        L.table(self.state_w, i)[:] = np.where(learns, np.clip(before, L.table(L.floor, i), L.high[i]), before)
            for key, amp in getattr(self, "_item_stimuli", {}).items():
                self._stim_item[self._item(*key)] = amp
        if fresh:
            self._item_stimuli: dict[tuple[str, str], float] = {}
        self._render_stimuli()

    @property
    def backend(self) -> str:
        """The stepping path in use: "numpy" or "numba"."""
        return self._stepper.name

    @property
    def dt(self) -> float:
        return self.spec.dt

    @property
    def field_names(self) -> list[str]:
        return list(self._c.names)

    def field(self, name: str) -> FieldSpec:
        return self.spec.field(name)

    # -- inputs -------------------------------------------------------------------------
    def _item(self, field: str, item: str) -> int:
        f = self.spec.field(field)
        if item not in f.items:
            raise FieldError(f.where, str(item), f"unknown item; known: {', '.join(f.items) or '(none)'}")
        return self._c.item_off[field] + f.items.index(item)

    def set_stimulus(self, field: str, item: str, amplitude: float) -> None:
        """Gaussian input of eq. (4) at the item's centre, width input_sigma, held until changed."""
        idx = self._item(field, item)
        self._stim_item[idx] = float(amplitude)
        self._item_stimuli[(field, item)] = float(amplitude)

    def clear_stimulus(self, field: str, item: str) -> None:
        self.set_stimulus(field, item, 0.0)
        del self._item_stimuli[(field, item)]

    def clear_stimuli(self, field: str | None = None) -> None:
        for key in [k for k in self._item_stimuli if field is None or k[0] == field]:
            self.clear_stimulus(*key)
        for key in [k for k in self._point_stimuli if field is None or k[0] == field]:
            del self._point_stimuli[key]
        for key in [k for k in self._patterns if field is None or k[0] == field]:
            del self._patterns[key]
        self._render_stimuli()

    def set_stimulus_at(self, field: str, name: str, position: float | tuple[float, float], amplitude: float,
                        sigma: float | None = None) -> None:
        """A named Gaussian input at any position (field units; (x, y) in a 2-D field), held until changed or
        cleared."""
        f = self.spec.field(field)
        sigma = f.input_sigma if sigma is None else float(sigma)
        if not sigma > 0:
            raise FieldError(f.where, "sigma", f"stimulus width must be > 0, got {sigma}")
        pos = np.atleast_1d(np.asarray(position, dtype=float))
        if pos.shape != (f.ndim,) or not np.all(np.isfinite(pos)):
            raise FieldError(f.where, "position", f"must be {'one number' if f.ndim == 1 else '(x, y)'}, got {position!r}")
        self._point_stimuli[(field, name)] = (tuple(pos.tolist()), float(amplitude), sigma)
        self._render_stimuli()

    def clear_stimulus_at(self, field: str, name: str) -> None:
        """Remove a named input set with ``set_stimulus_at`` or ``set_stimulus_pattern``."""
        self._point_stimuli.pop((field, name), None)
        self._patterns.pop((field, name), None)
        self._render_stimuli()

    def set_stimulus_pattern(self, field: str, name: str, values: np.ndarray) -> None:
        """A named input of any form: one value per position (shape (ny, nx) in 2-D), held until changed."""
        f = self.spec.field(field)
        arr = np.array(values, dtype=float)
        if arr.shape != ((f.size,) if f.shape is None else tuple(f.shape)) or not np.all(np.isfinite(arr)):
            raise FieldError(f.where, "values", f"pattern {name!r} needs {f.shape or f.size} finite values, got shape {arr.shape}")
        self._patterns[(field, name)] = arr.ravel()
        self._render_stimuli()

    def _render_stimuli(self) -> None:
        self._S_ext[:] = 0.0
        for (field, _), (pos, amp, sigma) in self._point_stimuli.items():
            f = self.spec.fields[field]
            ny, nx = f.grid
            # one Gaussian per axis (x first); their outer product in 2-D
            gs = []
            for p, n in zip(pos, (nx, ny)):
                d = np.arange(n) * f.dx - p
                if f.periodic:
                    L = n * f.dx
                    d = (d + L / 2) % L - L / 2
                gs.append(np.exp(-(d**2) / (2 * sigma**2)))
            g = gs[0] if f.ndim == 1 else np.outer(gs[1], gs[0]).ravel()
            self._S_ext[self._c.slice(field)] += amp * g
        for (field, _), values in self._patterns.items():
            self._S_ext[self._c.slice(field)] += values

    # -- dynamics -----------------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        """Advance ``n`` Euler steps; runs of steps between recordings go to the stepper in one call."""
        c = self._c
        remaining = int(n)
        while remaining > 0:
            chunk = remaining
            for r in self._recorders:
                chunk = min(chunk, r.every - self.steps % r.every)
            xi = self.rng.standard_normal((chunk, c.size)) if c.has_noise else None
            self._stepper.run(chunk, self.state_u, self._S, self._S_ext, self._stim_item, xi, self.state_m, self.state_w)
            remaining -= chunk
            self.steps += chunk
            self.t = self.steps * self.spec.dt
            for r in self._recorders:
                r.maybe_record()

    def run(self, seconds: float) -> None:
        self.step(int(round(seconds / self.spec.dt)))

    def reset(self) -> None:
        """Back to the resting level h everywhere, time 0, stimuli kept; memory traces and learned weights
        are kept too (what a network learnt outlives a trial: `forget` clears it)."""
        self.state_u[:] = self._c.h
        self._S[:] = 0.0
        self.t = 0.0
        self.steps = 0

    def forget(self) -> None:
        """Memory traces back to zero and learned tables back to their priors (the spec's tables)."""
        self.state_m[:] = 0.0
        self.state_w[:] = self._c.learning.prior

    def reset_field(self, field: str) -> None:
        """Put one field back to rest, e.g. to release a decision once it was carried out."""
        self.state_u[self._c.slice(self.spec.field(field).name)] = self.spec.fields[field].h

    # -- read-out -----------------------------------------------------------------------
    def _slice(self, field: str) -> slice:
        try:
            return self._slices[field]
        except KeyError:
            self.spec.field(field)  # raises the FieldError naming the known fields
            raise

    @property
    def _continuous(self) -> ContinuousInput:
        """The continuous couplings one by one, for read-outs (built when first read: stepping needs it not)."""
        if self._continuous_input is None:
            self._continuous_input = ContinuousInput(self._c)
        return self._continuous_input

    def _shaped(self, field: str, flat: np.ndarray) -> np.ndarray:
        shape = self.spec.fields[field].shape
        return flat if shape is None else flat.reshape(shape)

    def u(self, field: str) -> np.ndarray:
        """Activity of a field (a view: copy it to keep it); (ny, nx) for a 2-D field."""
        return self._shaped(field, self.state_u[self._slice(field)])

    def input(self, field: str) -> np.ndarray:
        """Total input S(x): stimuli and item couplings of the last step, plus the continuous couplings'
        input from the outputs now (the compiled path sums those with the lateral kernels, so it does not
        keep them apart)."""
        sl = self._slice(field)
        s = self._S[sl]
        if self._continuous.feeds(sl):
            s = s + sum(self._continuous.parts(self._outputs(), sl).values())
        return self._shaped(field, s)

    def memory(self, field: str) -> np.ndarray:
        """A field's memory trace (a view; (ny, nx) in 2-D); the field must have one."""
        f = self.spec.field(field)
        if f.memory is None:
            raise FieldError(f.where, "memory", "this field has no memory trace; give it memory: {tau_build, tau_decay, ...}")
        return self._shaped(field, self.state_m[self._slice(field)])

    def _learning_index(self, coupling: str) -> int:
        L = self._c.learning
        if coupling not in L.names:
            self.spec.coupling(coupling)  # raises the FieldError naming the known couplings
            raise FieldError(f"coupling '{coupling}'", "learn", f"does not learn; learning couplings: {', '.join(L.names) or '(none)'}")
        return L.names.index(coupling)

    def table(self, coupling: str) -> np.ndarray:
        """An item coupling's a_mj now (target items x source items, a copy): a learning coupling's current
        weights, any other's table."""
        c = self.spec.coupling(coupling)
        if c.learn is not None:
            return self._c.learning.table(self.state_w, self._learning_index(coupling)).copy()
        return self._table(c).copy()

    def set_table(self, coupling: str, table: Mapping[str, Mapping[str, float]] | np.ndarray) -> None:
        """Put weights into a learning coupling (e.g. read back from a file): a matrix (target x source items)
        or {target item: {source item: weight}} (learning weights left out are 0, the others their prior, which
        they must keep); the learning weights must lie within its bounds.
        Checked as a table in the spec is (`CouplingSpec.validate`), without changing the spec's prior."""
        i = self._learning_index(coupling)
        # validate turns a matrix into the mapping, as it does for a spec's table
        spec = self.spec.coupling(coupling)
        weights = dataclasses.replace(spec, table=cast(Any, table))
        weights.validate(self.spec.fields)
        new, prior = weights.matrix(self.spec.fields), spec.matrix(self.spec.fields)
        learn = spec.learn
        assert learn is not None
        src, tgt = self.spec.fields[spec.source].items, self.spec.fields[spec.target].items
        for j, s in enumerate(src):
            for m, t in enumerate(tgt):   # a weight that does not learn stays at its prior (left out: the prior)
                if learn.learns(s, t):
                    continue
                given = weights.table.get(t, {}).get(s)
                if given is not None and given != prior[m, j]:
                    raise FieldError(spec.where, f"table.{t}.{s}", f"does not learn (not in learn.sources/targets); "
                                                                   f"it stays at its prior {prior[m, j]:g}, got {given:g}")
                new[m, j] = prior[m, j]
        for j, s in enumerate(src):
            for m, t in enumerate(tgt):
                if not learn.learns(s, t):
                    continue
                floor = learn.bounds[0] + learn.keep * (prior[m, j] - learn.bounds[0])
                if new[m, j] < floor:
                    raise FieldError(spec.where, f"table.{t}.{s}", f"the weight {new[m, j]:g} is below {floor:g}: it "
                                                                   f"keeps learn.keep={learn.keep:g} of its prior")
        self._c.learning.table(self.state_w, i)[:] = new

    def learned_tables(self) -> dict[str, dict[str, dict[str, float]]]:
        """Every learning coupling's learning weights now (those from its ``learn.sources`` onto its ``targets``),
        {coupling: {target item: {source item: weight}}}: plain data for a JSON file, read back with `set_table`."""
        out = {}
        for name in self._c.learning.names:
            c = self.spec.coupling(name)
            assert c.learn is not None
            a = self.table(name)
            src, tgt = self.spec.fields[c.source].items, self.spec.fields[c.target].items
            rows = {t: {s_item: float(a[i, j]) for j, s_item in enumerate(src) if c.learn.learns(s_item, t)}
                    for i, t in enumerate(tgt)}
            out[name] = {t: row for t, row in rows.items() if row}
        return out

    def _outputs(self) -> np.ndarray:
        c = self._c
        return 1.0 / (1.0 + np.exp(-np.clip(c.beta * (self.state_u - c.u0), -500, 500)))

    def coupling_inputs(self, field: str) -> dict[str, np.ndarray]:
        """The part of ``field``'s input S(x) that each incoming coupling gives, by coupling name, from the
        outputs now (eq. 4: k times the table times the source items' outputs, spread like S; a continuous
        coupling's kernel over its projected source; a learning coupling's current weights), and a memory
        trace's part as "NAME (memory)"; what S holds beyond their sum is the stimuli."""
        c, sl = self._c, self._slice(field)
        out = {}
        if self._continuous.feeds(sl):
            out = {name: self._shaped(field, part) for name, part in self._continuous.parts(self._outputs(), sl).items()}
        f_items = 1.0 / (1.0 + np.exp(-np.clip(c.beta[c.item_pos] * (self.state_u[c.item_pos] - c.u0[c.item_pos]), -500, 500)))
        for cp in self.spec.couplings:
            if cp.target != field:
                continue
            src, tgt = self.spec.fields[cp.source], self.spec.fields[cp.target]
            s0, t0 = c.item_off[cp.source], c.item_off[cp.target]
            d = np.zeros(c.n_items)
            a = self.table(cp.name) if cp.learn is not None else self._table(cp)
            d[t0:t0 + len(tgt.items)] = cp.k * (a @ f_items[s0:s0 + len(src.items)])
            out[cp.name] = (c.render @ d)[sl]
        trace = self.spec.fields[field].memory
        if trace is not None:
            out[f"{field} (memory)"] = self._shaped(field, trace.amplitude * self.state_m[sl])
        return out

    def _table(self, coupling) -> np.ndarray:
        if coupling.name not in self._tables:
            self._tables[coupling.name] = coupling.matrix(self.spec.fields)
        return self._tables[coupling.name]

    def output(self, field: str) -> np.ndarray:
        f = self.spec.field(field)
        return 1.0 / (1.0 + np.exp(-np.clip(f.beta * (self.u(field) - f.u0), -500, 500)))

    def peak_xy(self, field: str, threshold: float = 0.0) -> tuple[float, float, float] | None:
        """(x, y, u) of a 2-D field's strongest position (field units) if above ``threshold``, refined below
        one position by the centroid of f(u) within 4 sigma of it; None without a peak."""
        f = self.spec.field(field)
        if f.ndim != 2:
            raise FieldError(f.where, "shape", "peak_xy reads 2-D fields; use peaks or peak_positions in 1-D")
        u = self.u(field)
        iy, ix = (int(i) for i in np.unravel_index(int(np.argmax(u)), u.shape))
        top = float(u[iy, ix])
        if top <= threshold:
            return None
        out = self.output(field)
        r = max(1, int(round(4 * f.kernel.sigma / f.dx)))
        y0, y1 = max(0, iy - r), min(u.shape[0], iy + r + 1)
        x0, x1 = max(0, ix - r), min(u.shape[1], ix + r + 1)
        w = out[y0:y1, x0:x1]
        total = w.sum()
        x = float((w.sum(axis=0) * np.arange(x0, x1)).sum() / total) * f.dx
        y = float((w.sum(axis=1) * np.arange(y0, y1)).sum() / total) * f.dx
        return x, y, top

    def activity(self, field: str, item: str) -> float:
        f = self.spec.field(field)
        return float(self.u(field)[f.item_index(item)])

    def activities(self, field: str) -> dict[str, float]:
        vals = self.u(field)[self._items_at[field]]
        return dict(zip(self.spec.fields[field].items, vals.tolist()))

    def item_state_indices(self, field: str) -> np.ndarray:
        """Indices of the field's item centres in ``state_u``, the one vector holding every field's activity.

        For read-outs that gather items of several fields in one numpy operation.
        """
        return self._slice(field).start + self._items_at[field]

    def presence(self, field: str) -> np.ndarray:
        """c_j of eq. (4): the sigmoid of the activity at each item's centre."""
        return self.output(field)[self._items_at[field]]

    def peaks(self, field: str, threshold: float = 0.0) -> list[str]:
        """Items whose centre activity is above ``threshold``, strongest first."""
        vals = self.u(field)[self._items_at[field]]
        above = np.flatnonzero(vals > threshold)
        if above.size == 0:
            return []
        items = self.spec.fields[field].items
        return [items[i] for i in above[np.argsort(-vals[above], kind="stable")]]

    def peak_positions(self, field: str, threshold: float = 0.0) -> list[float]:
        """Positions (field units) of local maxima above ``threshold``, for fields without items."""
        f = self.spec.field(field)
        if f.ndim != 1:
            raise FieldError(f.where, "shape", "peak_positions reads 1-D fields; use peak_xy in 2-D")
        u = self.u(field)
        left = np.concatenate([[-np.inf], u[:-1]])
        right = np.concatenate([u[1:], [-np.inf]])
        idx = np.nonzero((u > threshold) & (u >= left) & (u > right))[0]
        return (idx * f.dx).tolist()

    # -- recording ----------------------------------------------------------------------
    def record(self, fields: Iterable[str] | None = None, every: int = 1, couplings: Iterable[str] = ()) -> Recorder:
        """Keep u and S of ``fields`` (default all) every ``every`` steps, and for the fields in ``couplings`` the
        part of S each incoming coupling gives at the items."""
        names = list(fields) if fields is not None else self.field_names
        for n in names:
            self.spec.field(n)
        rec = Recorder(self, names, every, couplings=couplings)
        self._recorders.append(rec)
        rec.maybe_record(force=True)
        return rec

    def stop_recording(self, rec: Recorder) -> None:
        self._recorders.remove(rec)

    # -- parameters by path -------------------------------------------------------------
    def parameter_paths(self) -> list[str]:
        paths = ["dt"]
        for f in self.spec.fields.values():
            for key in ("tau", "h", "beta", "u0", "input_sigma", "noise", "dx", "periodic"):
                paths.append(f"fields.{f.name}.{key}")
            for key in ("A", "sigma", "w_inhib"):
                paths.append(f"fields.{f.name}.kernel.{key}")
            if f.memory is not None:
                paths += [f"fields.{f.name}.memory.{key}" for key in MEMORY_KEYS]
        for c in self.spec.couplings:
            paths.append(f"couplings.{c.name}.k")
            if c.learn is not None:
                paths += [f"couplings.{c.name}.learn.{key}" for key in ("rate", "decay")]
            for t, row in c.table.items():
                for s in row:
                    paths.append(f"couplings.{c.name}.table.{t}.{s}")
        for cc in self.spec.continuous:
            for key in ("A", "sigma"):
                paths.append(f"couplings.{cc.name}.kernel.{key}")
        return paths

    def _resolve(self, path: str) -> tuple[Any, str]:
        parts = path.split(".")
        if parts == ["dt"]:
            return self.spec, "dt"
        if len(parts) >= 3 and parts[0] == "fields":
            f = self.spec.field(parts[1])
            if len(parts) == 3 and parts[2] in ("tau", "h", "beta", "u0", "input_sigma", "noise", "dx", "periodic"):
                return f, parts[2]
            if len(parts) == 4 and parts[2] == "kernel" and parts[3] in ("A", "sigma", "w_inhib"):
                return f.kernel, parts[3]
            if len(parts) == 4 and parts[2] == "memory" and parts[3] in MEMORY_KEYS and f.memory is not None:
                return f.memory, parts[3]
        if len(parts) >= 3 and parts[0] == "couplings":
            # coupling names may contain dots only if the user chose so; match the longest known name
            for c in self.spec.couplings:
                cn = c.name.split(".")
                if parts[1 : 1 + len(cn)] == cn:
                    rest = parts[1 + len(cn) :]
                    if rest == ["k"]:
                        return c, "k"
                    if len(rest) == 2 and rest[0] == "learn" and rest[1] in ("rate", "decay") and c.learn is not None:
                        return c.learn, rest[1]
                    if len(rest) == 3 and rest[0] == "table":
                        row = c.table.setdefault(rest[1], {})
                        return row, rest[2]
            for cc in self.spec.continuous:
                cn = cc.name.split(".")
                if parts[1 : 1 + len(cn)] == cn and parts[1 + len(cn):] in (["kernel", "A"], ["kernel", "sigma"]):
                    return cc.kernel, parts[-1]
        raise FieldError("network", path, "unknown parameter path; see Network.parameter_paths()")

    def get(self, path: str) -> Any:
        obj, key = self._resolve(path)
        return obj[key] if isinstance(obj, dict) else getattr(obj, key)

    def set(self, path: str, value: Any) -> None:
        """Change a parameter while the network runs; activity of every field is kept."""
        before = copy.deepcopy(self.spec)
        obj, key = self._resolve(path)
        if isinstance(obj, dict):
            obj[key] = value
        else:
            setattr(obj, key, value)
        try:
            self.spec.validate()
        except FieldError:
            self.spec = before
            raise
        self._compile(fresh=False)

    def describe_table(self, coupling: str) -> str:
        """The connection table a_mj of a coupling as readable text."""
        c = self.spec.coupling(coupling)
        title = f"{c.name} (k={c.k:g}{', learnt' if c.learn is not None else ''})"
        return format_table(self.table(coupling), self.spec.fields[c.target].items, self.spec.fields[c.source].items, title)

    def __repr__(self) -> str:
        sizes = ", ".join(f"{n}[{'x'.join(map(str, self.spec.fields[n].shape or [self.spec.fields[n].size]))}]"
                          for n in self._c.names)
        n_couplings = len(self.spec.couplings) + len(self.spec.continuous)
        return f"Network({sizes}; {n_couplings} couplings; dt={self.spec.dt}; backend={self.backend})"


def format_table(a: np.ndarray, rows: list[str], cols: list[str], title: str = "") -> str:
    """Rows = target items, columns = source items; zeros shown as '.'."""
    width = max([len(c) for c in cols] + [5])
    rw = max([len(r) for r in rows] + [6])
    lines = [title] if title else []
    lines.append(" " * rw + " | " + " ".join(c.rjust(width) for c in cols))
    lines.append("-" * (rw + 3 + (width + 1) * len(cols)))
    for i, r in enumerate(rows):
        cells = [(f"{a[i, j]:g}" if a[i, j] != 0 else ".").rjust(width) for j in range(len(cols))]
        lines.append(r.rjust(rw) + " | " + " ".join(cells))
    return "\n".join(lines)


__all__ = ["Network", "NetworkSpec", "FieldSpec", "KernelSpec", "format_table", "gaussian_half_width"]
