"""The compiled path of `assistbot.fields.stepping`: numba kernels over the flat network arrays.

Imported only when the numba path is used, so `assistbot.fields` itself needs numpy
and scipy alone. The kernels live at module level so numba's on-disk cache finds
them again in a new process (a closure would be compiled anew every time).
"""

from __future__ import annotations

import numba
import numpy as np

# exp(z) = 2^k e^r with k = round(z / ln 2), |r| <= ln(2)/2: a degree-12 Taylor
# polynomial of e^r is exact to double precision there (< 4e-16 relative, tested
# against math.exp), and unlike libm's exp it vectorises; 2^k is built from the
# exponent bits. Adding MAGIC (1.5 * 2^52) rounds to an integer kept in the low
# mantissa bits, which is how k reaches the bit pattern without a float->int cast.
LOG2E = 1.4426950408889634
LN2_HI = 6.93147180369123816490e-01
LN2_LO = 1.90821492927058770002e-10
MAGIC = 6755399441055744.0
MAGIC_BITS = int(np.array([MAGIC]).view(np.int64)[0])


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
