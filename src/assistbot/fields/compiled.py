"""A network spec laid out as flat arrays, so one step is a few vectorised operations.

All fields are concatenated into one vector of P positions; all items into one
vector of I items. Per step:

- f = sigmoid(u) per position (eq. 3, each field its own beta and u0);
- lateral interaction (eq. 2): the Gaussian part as a truncated convolution
  with the field's taps, the global inhibition as -w_inhib * dx^ndim * sum(f)
  of the field (exact: every position of a linear or periodic field sees all
  others with the same weight);
- coupling gates c_j = f(u(x_j)) at item centres; item drive d = K c +
  item stimuli, with K[m, j] = k a_mj over all couplings (eq. 4);
- coupling input rendered as Gaussians of the target field's input_sigma
  around each item centre, plus continuous stimuli S_ext;
- convolutions: every lateral kernel and continuous coupling is a *term*
  (a source, a projection, a weight) of a *group* (a target field, a
  boundary, a kernel shape); a group sums its terms' projected outputs and
  convolves the sum once, per axis in 2-D. Convolution is linear, so this is
  the sum of the separate convolutions, at the cost of one;
- Euler: u += dt/tau (-u + S + L + C + h) (+ noise/tau sqrt(dt) xi), C the
  continuous couplings' input.

Learning elements add two pieces of state beside u, both stepped by the same
explicit Euler step from the outputs f of that step:

- memory traces m (one per position, zero for fields without one): S gains
  amplitude * m (the trace before this step's update), then m moves toward f
  where f > threshold and toward 0 elsewhere, in fields active somewhere;
- learned tables w (one flat vector, coupling after coupling, each row-major
  target x source): their couplings are left out of K; their drive k w c_pre
  joins d, then w += dt g c_pre (rate c_post - decay w), clipped to bounds.

The Gaussian taps are truncated where exp(-d^2/2 sigma^2) < TRUNCATION (or
at a kernel's ``cutoff``), so both stepping paths compute the same sums; the
untruncated reference lives in the tests (scipy solve_ivp on the dense
equation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from assistbot.fields.spec import ContinuousCouplingSpec, FieldSpec, KernelSpec, NetworkSpec, gate_item

TRUNCATION = 1e-10

# how a term takes its source's output to the target's shape (the numba kernel switches on these)
DIRECT, SUM_OVER_Y, SUM_OVER_X, MAX_OVER_Y, MAX_OVER_X, EXPAND_ALONG_Y, EXPAND_ALONG_X = range(7)


def gaussian_half_width(sigma: float, dx: float) -> int:
    """Number of positions on each side where the Gaussian exceeds TRUNCATION."""
    return int(math.ceil(sigma * math.sqrt(-2.0 * math.log(TRUNCATION)) / dx))


def kernel_taps(kernel: KernelSpec, dx: float, n: int, circular: bool) -> np.ndarray:
    """The kernel's Gaussian along one axis of n positions, without A: ``2 r + 1`` taps, r clipped to the
    axis (to less than half of it when circular, so no position meets the kernel twice)."""
    if kernel.sigma == 0.0:
        return np.ones(1)
    r = gaussian_half_width(kernel.sigma, dx) if kernel.cutoff is None else int(math.ceil(kernel.cutoff * kernel.sigma / dx))
    r = min(r, (n - 1) // 2 if circular else n - 1)
    g = _gaussian(np.arange(-r, r + 1) * dx, kernel.sigma)
    g = g / g.sum() if kernel.normalize else g
    assert np.array_equal(g, g[::-1]), "the compiled convolution pairs mirrored taps"
    return g


def kernel_scale(kernel: KernelSpec, dx: float, ndim: int) -> float:
    """What multiplies the taps' product: A dx^ndim (the integral as a sum), or A for a normalised kernel or
    a position-to-position coupling."""
    return kernel.A if kernel.normalize or kernel.sigma == 0.0 else kernel.A * dx**ndim


def term_kind(c: ContinuousCouplingSpec) -> int:
    if c.project is not None:
        return {("sum", "y"): SUM_OVER_Y, ("sum", "x"): SUM_OVER_X,
                ("max", "y"): MAX_OVER_Y, ("max", "x"): MAX_OVER_X}[(c.project["op"], c.project["over"])]
    if c.expand is not None:
        return EXPAND_ALONG_Y if c.expand == "y" else EXPAND_ALONG_X
    return DIRECT


def project(kind: int, f_src: np.ndarray, src_grid: tuple[int, int]) -> np.ndarray:
    """A source output taken to its target's shape (flat), the numpy reference of the kernel's switch."""
    if kind == DIRECT:
        return f_src
    ny, nx = src_grid
    a = f_src.reshape(ny, nx)
    if kind == SUM_OVER_Y:
        return a.sum(axis=0)
    if kind == SUM_OVER_X:
        return a.sum(axis=1)
    if kind == MAX_OVER_Y:
        return a.max(axis=0)
    if kind == MAX_OVER_X:
        return a.max(axis=1)
    raise ValueError(f"project: kind {kind} needs the target's shape; use expand()")


def expand(kind: int, f_src: np.ndarray, tgt_grid: tuple[int, int]) -> np.ndarray:
    ny, nx = tgt_grid
    if kind == EXPAND_ALONG_Y:
        return np.broadcast_to(f_src[None, :], (ny, nx)).ravel()
    return np.broadcast_to(f_src[:, None], (ny, nx)).ravel()


def conv_operator(taps: np.ndarray, n: int, circular: bool) -> sp.csr_matrix:
    """(n, n) matrix of the convolution with ``taps`` along an axis of n positions."""
    r = (taps.size - 1) // 2
    i = np.arange(n)
    d = np.arange(-r, r + 1)
    j = i[:, None] + d[None, :]
    vals = np.broadcast_to(taps, j.shape)
    if circular:
        ok = np.ones_like(j, dtype=bool)
        j = j % n
    else:
        ok = (j >= 0) & (j < n)
    rows = np.broadcast_to(i[:, None], j.shape)[ok]
    return sp.csr_matrix((vals[ok], (rows, j[ok])), shape=(n, n))


@dataclass
class ConvTerm:
    """One lateral kernel or continuous coupling: ``weight * P(f(u_source))`` into a group's sum."""

    name: str
    source: int  # field index
    kind: int
    weight: float
    lateral: bool = False


@dataclass
class ConvGroup:
    """Terms into one target field that share a kernel shape and boundary: convolved once, as their sum."""

    target: int
    circular: bool
    taps_y: np.ndarray  # (1,) for a 1-D target
    taps_x: np.ndarray
    terms: list[ConvTerm]


def _conv_groups(spec: NetworkSpec, names: list[str]) -> list[ConvGroup]:
    fs = [spec.fields[n] for n in names]
    groups: dict[tuple, ConvGroup] = {}

    def add(name: str, target: FieldSpec, source: str, kind: int, kernel: KernelSpec, circular: bool, lateral: bool) -> None:
        ny, nx = target.grid
        taps_x = kernel_taps(kernel, target.dx, nx, circular)
        taps_y = kernel_taps(kernel, target.dx, ny, circular) if target.ndim == 2 else np.ones(1)
        key = (target.name, circular, taps_y.tobytes(), taps_x.tobytes())
        g = groups.setdefault(key, ConvGroup(names.index(target.name), circular, taps_y, taps_x, []))
        g.terms.append(ConvTerm(name, names.index(source), kind, kernel_scale(kernel, target.dx, target.ndim),
                                lateral=lateral))

    for f in fs:
        if f.kernel.A != 0.0:
            add(f"{f.name} (lateral)", f, f.name, DIRECT, f.kernel, f.periodic, True)
    for c in spec.continuous:
        add(c.name, spec.fields[c.target], c.source, term_kind(c), c.kernel, c.circular, False)
    out = list(groups.values())
    for g in out:
        if len(g.terms) == 1:
            # a group of one term: its weight goes into the taps, one multiply per position fewer
            t = g.terms[0]
            if g.taps_y.size > 1:
                g.taps_y = t.weight * g.taps_y
            else:
                g.taps_x = t.weight * g.taps_x
            t.weight = 1.0
    return out


@dataclass
class Compiled:
    spec: NetworkSpec
    names: list[str]
    offsets: np.ndarray  # (F+1,) start of each field in the flat vector
    # per position
    dt_tau: np.ndarray
    h: np.ndarray
    beta: np.ndarray
    u0: np.ndarray
    noise_scale: np.ndarray  # noise / tau * sqrt(dt)
    field_of: np.ndarray
    # lateral interaction
    inhib: np.ndarray  # (F,) w_inhib * dx^ndim
    # items and couplings
    item_pos: np.ndarray  # (I,) flat index of each item centre
    item_off: dict[str, int]  # first item of each field in the item vector
    K: sp.csr_matrix  # (I, I)
    render: sp.csr_matrix  # (P, I) Gaussians at item centres
    render_items: sp.csr_matrix  # (I, P) transpose, item-major for the compiled path
    lateral: sp.csr_matrix  # (P, P) Gaussian part of the 1-D fields' kernels, block diagonal
    has_noise: bool
    grid: np.ndarray  # (F, 2) rows and columns of each field: (1, size) in 1-D
    groups: list[ConvGroup]  # lateral kernels and continuous couplings, for the compiled path
    continuous_terms: list[tuple[ConvGroup, ConvTerm]]  # continuous couplings and 2-D lateral kernels, for numpy
    memory: "MemoryArrays"
    learning: "LearningArrays"

    @property
    def size(self) -> int:
        return int(self.offsets[-1])

    @property
    def n_items(self) -> int:
        return int(self.item_pos.size)


    def slice(self, name: str) -> slice:
        i = self.names.index(name)
        return slice(int(self.offsets[i]), int(self.offsets[i + 1]))


@dataclass
class MemoryArrays:
    """Memory traces per position: zero amplitude and rates where a field has none."""

    fields: np.ndarray     # (F,) whether the field has a trace
    amplitude: np.ndarray  # (P,)
    build: np.ndarray      # (P,) dt / tau_build
    decay: np.ndarray      # (P,) dt / tau_decay
    threshold: np.ndarray  # (P,)

    @property
    def any(self) -> bool:
        return bool(self.fields.any())


@dataclass
class LearningArrays:
    """The learning item couplings, one entry each, and their priors as one flat weight vector."""

    names: list[str]
    source: np.ndarray  # (L,) first item of the source field in the item vector
    n_source: np.ndarray
    target: np.ndarray  # (L,) first item of the target field
    n_target: np.ndarray
    gate: np.ndarray    # (L,) item index of the gate, -1 for none
    trace_pre: np.ndarray   # (L,) bool: c_j from the memory trace, not the output
    trace_post: np.ndarray  # (L,) bool: c_m from the memory trace, not the output
    pre_item: np.ndarray    # flat, n_source per coupling (from pre_ptr): the item whose c gives each source's c_j
    pre_ptr: np.ndarray     # (L+1,) start of each coupling's pre_item
    learns: np.ndarray  # flat like the weights: 1.0 where the weight learns, 0.0 where it keeps its prior
    post_threshold: np.ndarray  # (L,) weights onto a target item change only while its c_m exceeds this
    relative: np.ndarray    # (L,) bool: c_m over the largest c_m among each source item's learning targets
    k: np.ndarray
    rate: np.ndarray
    decay: np.ndarray
    floor: np.ndarray   # flat like the weights: the lowest each may fall to (lower bound + keep x (prior - bound))
    high: np.ndarray
    ptr: np.ndarray     # (L+1,) start of each table in the flat weights
    prior: np.ndarray   # flat weights as the spec gives them

    def table(self, w: np.ndarray, i: int) -> np.ndarray:
        """Coupling i's weights in ``w`` as a (target items, source items) view."""
        return w[self.ptr[i]:self.ptr[i + 1]].reshape(int(self.n_target[i]), int(self.n_source[i]))


def _memory_arrays(spec: NetworkSpec, fs: list[FieldSpec], sizes: np.ndarray) -> MemoryArrays:
    def per_position(value) -> np.ndarray:
        return np.repeat(np.array([value(f.memory) if f.memory is not None else 0.0 for f in fs], dtype=float), sizes)

    return MemoryArrays(
        fields=np.array([f.memory is not None for f in fs], dtype=np.bool_),
        amplitude=per_position(lambda m: m.amplitude),
        build=per_position(lambda m: spec.dt / m.tau_build),
        decay=per_position(lambda m: spec.dt / m.tau_decay),
        threshold=per_position(lambda m: m.threshold),
    )


def _learning_arrays(spec: NetworkSpec, item_off: dict[str, int]) -> LearningArrays:
    learned = [c for c in spec.couplings if c.learn is not None]
    rules = [c.learn for c in learned if c.learn is not None]
    priors = [c.matrix(spec.fields).ravel() for c in learned]
    pre_items = []   # per coupling, per source item: where c_j is read (the source itself, or the `pre` field's item)
    for c, rule in zip(learned, rules):
        src = spec.fields[c.source].items
        if rule.pre is None:
            pre_items.append([item_off[c.source] + j for j in range(len(src))])
        else:
            held = spec.fields[rule.pre].items
            pre_items.append([item_off[rule.pre] + held.index(s) if s in held else -1 for s in src])
    learns = [np.array([float(rule.learns(s, t)) for t in spec.fields[c.target].items for s in spec.fields[c.source].items])
              for c, rule in zip(learned, rules)]
    gates = []
    for c, rule in zip(learned, rules):
        if rule.gate is None:
            gates.append(-1)
        else:
            field, item = gate_item(c.where, rule.gate, spec.fields)
            gates.append(item_off[field] + spec.fields[field].items.index(item))
    ints = lambda vals: np.array(vals, dtype=np.int64)  # noqa: E731
    floats = lambda vals: np.array(vals, dtype=float)  # noqa: E731
    return LearningArrays(
        names=[c.name for c in learned],
        source=ints([item_off[c.source] for c in learned]),
        n_source=ints([len(spec.fields[c.source].items) for c in learned]),
        target=ints([item_off[c.target] for c in learned]),
        n_target=ints([len(spec.fields[c.target].items) for c in learned]),
        gate=ints(gates),
        trace_pre=np.array([r.traces in ("pre", "both") for r in rules], dtype=np.bool_),
        trace_post=np.array([r.traces in ("post", "both") for r in rules], dtype=np.bool_),
        pre_item=ints([p for parts in pre_items for p in parts]),
        pre_ptr=ints(np.concatenate([[0], np.cumsum([len(parts) for parts in pre_items])])),
        learns=np.concatenate(learns) if learns else np.zeros(0),
        post_threshold=floats([r.post_threshold for r in rules]),
        relative=np.array([r.relative for r in rules], dtype=np.bool_),
        k=floats([c.k for c in learned]),
        rate=floats([r.rate for r in rules]),
        decay=floats([r.decay for r in rules]),
        floor=np.concatenate([r.bounds[0] + r.keep * (p - r.bounds[0]) for r, p in zip(rules, priors)]) if priors else np.zeros(0),
        high=floats([r.bounds[1] for r in rules]),
        ptr=ints(np.concatenate([[0], np.cumsum([p.size for p in priors])])),
        prior=np.concatenate(priors) if priors else np.zeros(0),
    )


def _gaussian(d: np.ndarray, sigma: float) -> np.ndarray:
    return np.exp(-(d**2) / (2.0 * sigma**2))


def compile_spec(spec: NetworkSpec) -> Compiled:
    names = list(spec.fields)
    fs = [spec.fields[n] for n in names]
    sizes = np.array([f.size for f in fs])
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    P = int(offsets[-1])
    rep = lambda vals: np.repeat(np.asarray(vals, dtype=float), sizes)  # noqa: E731

    dt = spec.dt
    blocks = []
    for f in fs:
        if f.ndim == 2:
            blocks.append(sp.csr_matrix((f.size, f.size)))  # the numpy path convolves 2-D kernels per axis
            continue
        taps = kernel_taps(f.kernel, f.dx, f.size, f.periodic)
        blocks.append(conv_operator(kernel_scale(f.kernel, f.dx, 1) * taps, f.size, f.periodic))
    lateral = sp.block_diag(blocks, format="csr")

    item_pos, item_off, r_rows, r_cols, r_vals = [], {}, [], [], []
    n = 0
    for fi, f in enumerate(fs):
        item_off[f.name] = n
        if not f.items:
            continue
        r = gaussian_half_width(f.input_sigma, f.dx)
        for c in f.item_indices:
            d = np.arange(-r, r + 1)
            j = c + d
            if f.periodic:
                # several images of a wide Gaussian can land on one position: sum them
                j = j % f.size
            ok = (j >= 0) & (j < f.size)
            r_rows.append(j[ok] + offsets[fi])
            r_cols.append(np.full(int(ok.sum()), n))
            r_vals.append(_gaussian(d[ok] * f.dx, f.input_sigma))
            item_pos.append(c + offsets[fi])
            n += 1
    I = n
    if I:
        render = sp.csr_matrix((np.concatenate(r_vals), (np.concatenate(r_rows), np.concatenate(r_cols))), shape=(P, I))
    else:
        render = sp.csr_matrix((P, 0))
    render.sum_duplicates()

    k_rows, k_cols, k_vals = [], [], []
    for c in spec.couplings:
        if c.learn is not None:
            continue  # its weights change as it runs: stepped apart from K
        a = c.matrix(spec.fields)
        m, j = np.nonzero(a)
        k_rows.append(m + item_off[c.target])
        k_cols.append(j + item_off[c.source])
        k_vals.append(c.k * a[m, j])
    if k_rows:
        K = sp.csr_matrix((np.concatenate(k_vals), (np.concatenate(k_rows), np.concatenate(k_cols))), shape=(I, I))
    else:
        K = sp.csr_matrix((I, I))
    K.sum_duplicates()

    groups = _conv_groups(spec, names)
    continuous_terms = [(g, t) for g in groups for t in g.terms if not t.lateral or fs[g.target].ndim == 2]

    return Compiled(
        spec=spec,
        names=names,
        offsets=offsets,
        dt_tau=rep([dt / f.tau for f in fs]),
        h=rep([f.h for f in fs]),
        beta=rep([f.beta for f in fs]),
        u0=rep([f.u0 for f in fs]),
        noise_scale=rep([f.noise / f.tau * math.sqrt(dt) for f in fs]),
        field_of=np.repeat(np.arange(len(fs)), sizes),
        inhib=np.array([f.kernel.w_inhib * f.dx**f.ndim for f in fs]),
        item_pos=np.asarray(item_pos, dtype=np.int64),
        item_off=item_off,
        K=K,
        render=render,
        render_items=render.T.tocsr(),
        lateral=lateral,
        has_noise=any(f.noise > 0 for f in fs),
        grid=np.array([f.grid for f in fs], dtype=np.int64).reshape(-1, 2),
        groups=groups,
        continuous_terms=continuous_terms,
        memory=_memory_arrays(spec, fs, sizes),
        learning=_learning_arrays(spec, item_off),
    )
