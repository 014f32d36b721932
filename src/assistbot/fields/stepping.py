"""The Euler step of a compiled network: a numpy path (the reference) and a numba path (the fast one).

Both compute exactly the sums described in `assistbot.fields.compiled`; the
tests check that they agree. The numba path is compiled on first use and
cached on disk; where numba is missing, "auto" falls back to numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.special import expit

from assistbot.fields.compiled import EXPAND_ALONG_X, EXPAND_ALONG_Y, Compiled, ConvTerm, conv_operator, expand, project


@dataclass
class _Operator:
    """One term with the slices it reads and writes and its convolution matrices (y is None in 1-D)."""

    term: ConvTerm
    source: slice
    source_grid: tuple[int, int]
    target: slice
    target_grid: tuple[int, int]
    op_y: sp.csr_matrix | None
    op_x: sp.csr_matrix

    def apply(self, f: np.ndarray) -> np.ndarray:
        ny, nx = self.target_grid
        t = self.term
        if t.kind in (EXPAND_ALONG_Y, EXPAND_ALONG_X):
            b = t.weight * expand(t.kind, f[self.source], self.target_grid)
        else:
            b = t.weight * project(t.kind, f[self.source], self.source_grid)
        if self.op_y is None:
            return self.op_x @ b
        return (self.op_y @ (self.op_x @ b.reshape(ny, nx).T).T).ravel()


class ContinuousInput:
    """The continuous couplings' and 2-D lateral kernels' input, one term at a time, each with its own
    convolution matrices: the reference the compiled path's grouped sums are tested against, and the
    read-out of each coupling's part."""

    def __init__(self, c: Compiled) -> None:
        self.terms: list[_Operator] = []
        for g, t in c.continuous_terms:
            ny, nx = (int(v) for v in c.grid[g.target])
            self.terms.append(_Operator(
                t, c.slice(c.names[t.source]), (int(c.grid[t.source][0]), int(c.grid[t.source][1])),
                c.slice(c.names[g.target]), (ny, nx),
                conv_operator(g.taps_y, ny, g.circular) if ny > 1 else None, conv_operator(g.taps_x, nx, g.circular)))

    def total(self, f: np.ndarray) -> np.ndarray:
        """Their input to every position of the network, from the outputs f."""
        out = np.zeros_like(f)
        for op in self.terms:
            out[op.target] += op.apply(f)
        return out

    def feeds(self, target: slice) -> bool:
        """Whether a continuous coupling (not a lateral kernel) feeds the target field."""
        return any(op.target == target and not op.term.lateral for op in self.terms)

    def parts(self, f: np.ndarray, target: slice) -> dict[str, np.ndarray]:
        """Each continuous coupling's input to the target field, by name (lateral kernels left out)."""
        return {op.term.name: op.apply(f) for op in self.terms if op.target == target and not op.term.lateral}


class NumpyStepper:
    """Vectorised numpy + scipy.sparse: a handful of whole-network operations per step."""

    name = "numpy"

    def __init__(self, c: Compiled) -> None:
        self.c = c
        self._starts = c.offsets[:-1]
        self.continuous = ContinuousInput(c)
        self._traced = [c.slice(c.names[i]) for i in np.flatnonzero(c.memory.fields)]

    def run(self, n: int, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None,
            m: np.ndarray, w: np.ndarray) -> None:
        """``n`` Euler steps; ``xi`` is (n, P) standard normal noise or None; ``m`` the memory traces and ``w``
        the learned weights, both updated in place."""
        for k in range(n):
            self._step(u, S, S_ext, stim_item, None if xi is None else xi[k], m, w)

    def _step(self, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None,
              m: np.ndarray, w: np.ndarray) -> None:
        c = self.c
        f = expit(c.beta * (u - c.u0))
        inhib = c.inhib * np.add.reduceat(f, self._starts)
        presence = f[c.item_pos]
        d = c.K @ presence + stim_item
        L = c.learning
        for i in range(len(L.names)):  # drive from the weights before this step's update
            s0, t0 = L.source[i], L.target[i]
            d[t0:t0 + L.n_target[i]] += L.k[i] * (L.table(w, i) @ presence[s0:s0 + L.n_source[i]])
        np.add(S_ext, c.render @ d, out=S)
        if self._traced:
            S += c.memory.amplitude * m
            self._build_traces(f, m)
        if len(L.names):
            self._learn(presence, m[c.item_pos], w)
        rate = S + (c.lateral @ f) - inhib[c.field_of] + c.h - u
        if self.continuous.terms:
            rate += self.continuous.total(f)
        u += c.dt_tau * rate
        if xi is not None:
            u += c.noise_scale * xi

    def _build_traces(self, f: np.ndarray, m: np.ndarray) -> None:
        mem = self.c.memory
        for sl in self._traced:
            active = f[sl] > mem.threshold[sl]
            if active.any():
                m[sl] += np.where(active, mem.build[sl] * (f[sl] - m[sl]), -mem.decay[sl] * m[sl])

    def _learn(self, presence: np.ndarray, traced: np.ndarray, w: np.ndarray) -> None:
        """``presence`` f and ``traced`` the memory traces (as built this step) at the item centres."""
        L, dt = self.c.learning, self.c.spec.dt
        for i in range(len(L.names)):
            W = L.table(w, i)
            g = 1.0 if L.gate[i] < 0 else presence[L.gate[i]]
            at = L.pre_item[L.pre_ptr[i]:L.pre_ptr[i + 1]]
            pre = np.where(at >= 0, (traced if L.trace_pre[i] else presence)[np.maximum(at, 0)], 0.0)
            post = (traced if L.trace_post[i] else presence)[L.target[i]:L.target[i] + L.n_target[i]]
            learns = L.table(L.learns, i) * (post > L.post_threshold[i])[:, None]
            c_m = np.broadcast_to(post[:, None], W.shape)
            if L.relative[i]:
                top = (learns * c_m).max(axis=0)
                c_m = c_m / np.where(top > 0, top, 1.0)[None, :]
            dW = dt * g * pre[None, :] * (L.rate[i] * c_m - L.decay[i] * W)
            W += learns * dW
            W[:] = np.where(learns > 0, np.clip(W, L.table(L.floor, i), L.high[i]), W)


def _kernels():
    from assistbot.fields import _kernels

    return _kernels




def numba_available() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


class NumbaStepper:
    """One compiled function per step over the flat arrays; no Python loop on the hot path."""

    name = "numba"

    def __init__(self, c: Compiled) -> None:
        self._kernel = _kernels().run
        self.c = c
        P, I = c.size, c.n_items
        self._f = np.zeros(P)
        self._rate = np.zeros(P)
        self._d = np.zeros(I)
        self._no_xi = np.zeros((1, 1))
        K, R = c.K, c.render_items
        G = c.groups
        terms = [t for g in G for t in g.terms]
        cat = lambda arrays: np.concatenate(arrays) if arrays else np.zeros(0)  # noqa: E731
        ptr = lambda sizes: np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)  # noqa: E731
        grids = [tuple(int(v) for v in c.grid[g.target]) for g in G]
        self._static = (
            c.dt_tau, c.h, c.beta, c.u0, c.noise_scale,
            c.offsets, c.grid, c.inhib,
            np.array([g.target for g in G], dtype=np.int64), np.array([g.circular for g in G], dtype=np.bool_),
            ptr([g.taps_y.size for g in G]), ptr([g.taps_x.size for g in G]),
            cat([g.taps_y for g in G]), cat([g.taps_x for g in G]), ptr([len(g.terms) for g in G]),
            np.array([t.source for t in terms], dtype=np.int64), np.array([t.kind for t in terms], dtype=np.int64),
            np.array([t.weight for t in terms], dtype=float),
            c.item_pos, K.indptr.astype(np.int64), K.indices.astype(np.int64), K.data,
            R.indptr.astype(np.int64), R.indices.astype(np.int64), R.data,
            self._f, np.zeros(P),
            np.zeros(int(np.max(c.grid))),
            np.zeros(max([nx + g.taps_x.size for g, (_, nx) in zip(G, grids)], default=1)),
            np.zeros(max([(ny + g.taps_y.size) * nx for g, (ny, nx) in zip(G, grids)], default=1)),
            self._rate, self._d, np.zeros(P),
        )
        mem, L = c.memory, c.learning
        self._learning = (
            mem.any, mem.fields, mem.amplitude, mem.build, mem.decay, mem.threshold,
            c.spec.dt, L.source, L.n_source, L.target, L.n_target, L.gate, L.trace_pre, L.trace_post, L.pre_item,
            L.pre_ptr, L.learns, L.post_threshold, L.relative, L.k, L.rate, L.decay, L.floor, L.high, L.ptr,
        )

    def run(self, n: int, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None,
            m: np.ndarray, w: np.ndarray) -> None:
        """``n`` Euler steps in one call; ``xi`` is (n, P) standard normal noise or None; ``m`` the memory
        traces and ``w`` the learned weights, both updated in place."""
        if xi is None:
            self._kernel(n, u, S, S_ext, stim_item, self._no_xi, False, *self._static, m, w, *self._learning)
        else:
            self._kernel(n, u, S, S_ext, stim_item, xi, True, *self._static, m, w, *self._learning)


def numba_sigmoid(u: np.ndarray, beta: np.ndarray, u0: np.ndarray) -> np.ndarray:
    """The compiled path's sigmoid on its own (for tests against the numpy one)."""
    u = np.ascontiguousarray(u, dtype=float)
    f = np.empty_like(u)
    _kernels().sigmoid(u, np.broadcast_to(beta, u.shape).copy(), np.broadcast_to(u0, u.shape).copy(), f, np.empty_like(u))
    return f


def make_stepper(c: Compiled, backend: str):
    if backend == "numba" or (backend == "auto" and numba_available()):
        return NumbaStepper(c)
    return NumpyStepper(c)
