"""The Euler step of a compiled network: a numpy path (the reference) and a numba path (the fast one).

Both compute exactly the sums described in `assistbot.fields.compiled`; the
tests check that they agree. The numba path is compiled on first use and
cached on disk; where numba is missing, "auto" falls back to numpy.
"""

from __future__ import annotations

import numpy as np
from scipy.special import expit

from assistbot.fields.compiled import Compiled


class NumpyStepper:
    """Vectorised numpy + scipy.sparse: a handful of whole-network operations per step."""

    name = "numpy"

    def __init__(self, c: Compiled) -> None:
        self.c = c
        self._starts = c.offsets[:-1]

    def run(self, n: int, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None) -> None:
        """``n`` Euler steps; ``xi`` is (n, P) standard normal noise or None."""
        for k in range(n):
            self._step(u, S, S_ext, stim_item, None if xi is None else xi[k])

    def _step(self, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None) -> None:
        c = self.c
        f = expit(c.beta * (u - c.u0))
        inhib = c.inhib * np.add.reduceat(f, self._starts)
        d = c.K @ f[c.item_pos] + stim_item
        np.add(S_ext, c.render @ d, out=S)
        rate = S + (c.lateral @ f) - inhib[c.field_of] + c.h - u
        u += c.dt_tau * rate
        if xi is not None:
            u += c.noise_scale * xi


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
        widest = int(np.max(np.diff(c.offsets) + 2 * c.radius))
        self._f = np.zeros(P)
        self._pad = np.zeros(widest)
        self._rate = np.zeros(P)
        self._d = np.zeros(I)
        self._no_xi = np.zeros((1, 1))
        K, R = c.K, c.render_items
        self._static = (
            c.dt_tau, c.h, c.beta, c.u0, c.noise_scale,
            c.offsets, c.radius, c.periodic, c.taps_off, c.taps, c.inhib,
            c.item_pos, K.indptr.astype(np.int64), K.indices.astype(np.int64), K.data,
            R.indptr.astype(np.int64), R.indices.astype(np.int64), R.data,
            self._f, self._pad, self._rate, self._d, np.zeros(P),
        )

    def run(self, n: int, u: np.ndarray, S: np.ndarray, S_ext: np.ndarray, stim_item: np.ndarray, xi: np.ndarray | None) -> None:
        """``n`` Euler steps in one call; ``xi`` is (n, P) standard normal noise or None."""
        if xi is None:
            self._kernel(n, u, S, S_ext, stim_item, self._no_xi, False, *self._static)
        else:
            self._kernel(n, u, S, S_ext, stim_item, xi, True, *self._static)


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
