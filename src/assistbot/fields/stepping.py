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


# exp(z) = 2^k e^r with k = round(z / ln 2), |r| <= ln(2)/2: a degree-12 Taylor
# polynomial of e^r is exact to double precision there (< 4e-16 relative, tested
# against math.exp), and unlike libm's exp it vectorises; 2^k is built from the
# exponent bits. Adding MAGIC (1.5 * 2^52) rounds to an integer kept in the low
# mantissa bits, which is how k reaches the bit pattern without a float->int cast.
_LOG2E = 1.4426950408889634
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_MAGIC = 6755399441055744.0
_MAGIC_BITS = int(np.array([_MAGIC]).view(np.int64)[0])


def _build_numba_kernel():
    import numba

    LOG2E, LN2_HI, LN2_LO, MAGIC, MAGIC_BITS = _LOG2E, _LN2_HI, _LN2_LO, _MAGIC, _MAGIC_BITS

    @numba.njit(cache=True, nogil=True)
    def sigmoid(u, beta, u0, f, tbuf):
        """f = 1 / (1 + exp(-beta (u - u0))), vectorised (see the note above)."""
        n = u.size
        for i in range(n):
            z = -beta[i] * (u[i] - u0[i])
            z = 700.0 if z > 700.0 else z
            z = -700.0 if z < -700.0 else z
            t = z * LOG2E + MAGIC
            k = t - MAGIC
            r = z - k * LN2_HI - k * LN2_LO
            f[i] = 1.0 + r * (1.0 + r * (1 / 2 + r * (1 / 6 + r * (1 / 24 + r * (1 / 120 + r * (1 / 720 + r * (
                1 / 5040 + r * (1 / 40320 + r * (1 / 362880 + r * (1 / 3628800 + r * (1 / 39916800 + r * (
                    1 / 479001600))))))))))))
            tbuf[i] = t
        bits = tbuf.view(np.int64)
        for i in range(n):
            bits[i] = (bits[i] - MAGIC_BITS + 1023) << 52
        for i in range(n):
            f[i] = 1.0 / (1.0 + f[i] * tbuf[i])

    @numba.njit(cache=True, nogil=True)
    def run(n_steps, u, S, S_ext, stim_item, xi, use_noise,
            dt_tau, h, beta, u0, noise_scale,
            offsets, radius, periodic, taps_off, taps, inhib,
            item_pos, K_indptr, K_indices, K_data,
            R_indptr, R_indices, R_data,
            f, pad, rate, d, tbuf):
        P = u.size
        for step in range(n_steps):
            sigmoid(u, beta, u0, f, tbuf)
            for fi in range(offsets.size - 1):
                o = offsets[fi]
                n = offsets[fi + 1] - o
                r = radius[fi]
                # contiguous views keep the tap loop free of offset arithmetic, so it vectorises
                fv = f[o:o + n]
                rv = rate[o:o + n]
                hv = h[o:o + n]
                uv = u[o:o + n]
                pv = pad[:n + 2 * r]
                total = 0.0
                for i in range(n):
                    total += fv[i]
                wrap = periodic[fi]
                for i in range(r):
                    pv[i] = fv[n - r + i] if wrap else 0.0
                    pv[n + r + i] = fv[i] if wrap else 0.0
                for i in range(n):
                    pv[r + i] = fv[i]
                base = -inhib[fi] * total
                for i in range(n):
                    rv[i] = base + hv[i] - uv[i]
                tv = taps[taps_off[fi]:taps_off[fi + 1]]
                for t in range(2 * r + 1):
                    g = tv[t]
                    for i in range(n):
                        rv[i] += g * pv[i + t]
            for m in range(d.size):
                acc = stim_item[m]
                for q in range(K_indptr[m], K_indptr[m + 1]):
                    acc += K_data[q] * f[item_pos[K_indices[q]]]
                d[m] = acc
            for p in range(P):
                S[p] = S_ext[p]
            for m in range(d.size):
                dm = d[m]
                if dm != 0.0:
                    for q in range(R_indptr[m], R_indptr[m + 1]):
                        S[R_indices[q]] += dm * R_data[q]
            if use_noise:
                for p in range(P):
                    u[p] += dt_tau[p] * (rate[p] + S[p]) + noise_scale[p] * xi[step, p]
            else:
                for p in range(P):
                    u[p] += dt_tau[p] * (rate[p] + S[p])

    return run, sigmoid


_NUMBA_KERNEL = None


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
        global _NUMBA_KERNEL
        if _NUMBA_KERNEL is None:
            _NUMBA_KERNEL = _build_numba_kernel()
        self._kernel = _NUMBA_KERNEL[0]
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
    global _NUMBA_KERNEL
    if _NUMBA_KERNEL is None:
        _NUMBA_KERNEL = _build_numba_kernel()
    u = np.ascontiguousarray(u, dtype=float)
    f = np.empty_like(u)
    _NUMBA_KERNEL[1](u, np.broadcast_to(beta, u.shape).copy(), np.broadcast_to(u0, u.shape).copy(), f, np.empty_like(u))
    return f


def make_stepper(c: Compiled, backend: str):
    if backend == "numba" or (backend == "auto" and numba_available()):
        return NumbaStepper(c)
    return NumpyStepper(c)
