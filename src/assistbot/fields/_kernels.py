"""The compiled path of `assistbot.fields.stepping`: numba kernels over the flat network arrays.

Imported only when the numba path is used, so `assistbot.fields` itself needs numpy
and scipy alone. The kernels live at module level so numba's on-disk cache finds
them again in a new process (a closure would be compiled anew every time).
"""

from __future__ import annotations

import numba
import numpy as np

from assistbot.fields.compiled import DIRECT, EXPAND_ALONG_Y, MAX_OVER_X, MAX_OVER_Y, SUM_OVER_X, SUM_OVER_Y

# numpy's error model: a float division needs no zero check (numba's default raises ZeroDivisionError, and
# the check keeps the loop from vectorising); no division here can meet zero. "contract" lets a * b + c be
# one fused multiply-add, rounded once (so at least as exact); no other fast-math licence is given.
jit = numba.njit(cache=True, nogil=True, error_model="numpy", fastmath={"contract"})
inlined = numba.njit(cache=True, nogil=True, error_model="numpy", fastmath={"contract"}, inline="always")

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


@numba.njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def total(fv):
    """sum(fv), in the order a vector unit likes (reassociation allowed here only): an in-order sum waits
    on each add and cost more than the field's sigmoid."""
    acc = 0.0
    for i in range(fv.size):
        acc += fv[i]
    return acc


@jit
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


@inlined
def gather(q0, q1, offsets, grid, t_src, t_kind, t_w, f, bv, tny, tnx, proj):
    """bv = sum over the terms q0..q1 of weight * P(f(source)), P by the term's kind (see compiled)."""
    first = q0
    if t_kind[q0] == DIRECT:  # the common case sets bv rather than clearing it first
        w = t_w[q0]
        sv = f[offsets[t_src[q0]]:offsets[t_src[q0] + 1]]
        for i in range(bv.size):
            bv[i] = w * sv[i]
        first = q0 + 1
    else:
        for i in range(bv.size):
            bv[i] = 0.0
    for q in range(first, q1):
        s = t_src[q]
        so = offsets[s]
        sv = f[so:offsets[s + 1]]
        w = t_w[q]
        kind = t_kind[q]
        sny = grid[s, 0]
        snx = grid[s, 1]
        if kind == DIRECT:
            for i in range(bv.size):
                bv[i] += w * sv[i]
        elif kind == SUM_OVER_Y or kind == MAX_OVER_Y:  # one value per column
            pv = proj[:snx]
            for ix in range(snx):
                pv[ix] = sv[ix]
            for iy in range(1, sny):
                row = sv[iy * snx:(iy + 1) * snx]
                if kind == SUM_OVER_Y:
                    for ix in range(snx):
                        pv[ix] += row[ix]
                else:
                    for ix in range(snx):
                        pv[ix] = max(pv[ix], row[ix])
            for ix in range(snx):
                bv[ix] += w * pv[ix]
        elif kind == SUM_OVER_X or kind == MAX_OVER_X:  # one value per row
            for iy in range(sny):
                row = sv[iy * snx:(iy + 1) * snx]
                acc = row[0]
                if kind == SUM_OVER_X:
                    for ix in range(1, snx):
                        acc += row[ix]
                else:
                    for ix in range(1, snx):
                        acc = max(acc, row[ix])
                bv[iy] += w * acc
        else:  # EXPAND_ALONG_Y (the source runs along x), EXPAND_ALONG_X (the source runs along y)
            for iy in range(tny):
                row = bv[iy * tnx:(iy + 1) * tnx]
                if kind == EXPAND_ALONG_Y:
                    for ix in range(tnx):
                        row[ix] += w * sv[ix]
                else:
                    v = w * sv[iy]
                    for ix in range(tnx):
                        row[ix] += v


@inlined
def conv_line(dst, pv, taps, n):
    """dst[i] += sum_t taps[t] pv[i + t] for i < n, taps symmetric (every kernel here is a Gaussian).

    Each pass takes four pairs of mirrored taps, adding the two inputs of a pair before one multiply:
    a quarter of the loads and stores of dst that one pass per tap costs, which is what bounds the loop.
    """
    T = taps.size
    r = (T - 1) // 2
    t = 0
    while t + 4 <= r:
        g0, g1, g2, g3 = taps[t], taps[t + 1], taps[t + 2], taps[t + 3]
        a0, b0 = pv[t:t + n], pv[T - 1 - t:T - 1 - t + n]
        a1, b1 = pv[t + 1:t + 1 + n], pv[T - 2 - t:T - 2 - t + n]
        a2, b2 = pv[t + 2:t + 2 + n], pv[T - 3 - t:T - 3 - t + n]
        a3, b3 = pv[t + 3:t + 3 + n], pv[T - 4 - t:T - 4 - t + n]
        for i in range(n):
            dst[i] += (g0 * (a0[i] + b0[i]) + g1 * (a1[i] + b1[i])) + (g2 * (a2[i] + b2[i]) + g3 * (a3[i] + b3[i]))
        t += 4
    while t < r:
        g = taps[t]
        a0, b0 = pv[t:t + n], pv[T - 1 - t:T - 1 - t + n]
        for i in range(n):
            dst[i] += g * (a0[i] + b0[i])
        t += 1
    g = taps[r]
    c = pv[r:r + n]
    for i in range(n):
        dst[i] += g * c[i]


@inlined
def conv_rows(dst, tmp, taps, ny, nx):
    """The same along y: row iy of dst (ny rows of nx) gains sum_t taps[t] times row iy + t of tmp."""
    T = taps.size
    r = (T - 1) // 2
    for iy in range(ny):
        d = dst[iy * nx:(iy + 1) * nx]
        t = 0
        while t + 4 <= r:
            g0, g1, g2, g3 = taps[t], taps[t + 1], taps[t + 2], taps[t + 3]
            a0, b0 = tmp[(iy + t) * nx:(iy + t + 1) * nx], tmp[(iy + T - 1 - t) * nx:(iy + T - t) * nx]
            a1, b1 = tmp[(iy + t + 1) * nx:(iy + t + 2) * nx], tmp[(iy + T - 2 - t) * nx:(iy + T - 1 - t) * nx]
            a2, b2 = tmp[(iy + t + 2) * nx:(iy + t + 3) * nx], tmp[(iy + T - 3 - t) * nx:(iy + T - 2 - t) * nx]
            a3, b3 = tmp[(iy + t + 3) * nx:(iy + t + 4) * nx], tmp[(iy + T - 4 - t) * nx:(iy + T - 3 - t) * nx]
            for i in range(nx):
                d[i] += (g0 * (a0[i] + b0[i]) + g1 * (a1[i] + b1[i])) + (g2 * (a2[i] + b2[i]) + g3 * (a3[i] + b3[i]))
            t += 4
        while t < r:
            g = taps[t]
            a0, b0 = tmp[(iy + t) * nx:(iy + t + 1) * nx], tmp[(iy + T - 1 - t) * nx:(iy + T - t) * nx]
            for i in range(nx):
                d[i] += g * (a0[i] + b0[i])
            t += 1
        g = taps[r]
        c = tmp[(iy + r) * nx:(iy + r + 1) * nx]
        for i in range(nx):
            d[i] += g * c[i]


@inlined
def pad_ends(pv, n, r, circular):
    """The r positions on each side of pv[r:r + n]: the other end's (circular) or zeros (linear)."""
    for i in range(r):
        pv[i] = pv[n + i] if circular else 0.0
        pv[n + r + i] = pv[r + i] if circular else 0.0


@inlined
def convolve_plane(rv, bv, ny, nx, ty, tx, circular, pad, tmp):
    """rv += (ty x tx) * bv over a (ny, nx) grid, zero-padded or wrapped, one axis at a time."""
    rx = (tx.size - 1) // 2
    ry = (ty.size - 1) // 2
    pv = pad[:nx + 2 * rx]
    for iy in range(ny):
        row = bv[iy * nx:(iy + 1) * nx]
        for i in range(nx):
            pv[rx + i] = row[i]
        pad_ends(pv, nx, rx, circular)
        out = tmp[(iy + ry) * nx:(iy + ry + 1) * nx]
        for i in range(nx):
            out[i] = 0.0
        conv_line(out, pv, tx, nx)
    for k in range(ry):
        lo = tmp[k * nx:(k + 1) * nx]
        hi = tmp[(ny + ry + k) * nx:(ny + ry + k + 1) * nx]
        for i in range(nx):
            lo[i] = tmp[(ny + k) * nx + i] if circular else 0.0
            hi[i] = tmp[(ry + k) * nx + i] if circular else 0.0
    conv_rows(rv, tmp, ty, ny, nx)


@inlined
def learned_drive(f, item_pos, d, w, l_src, l_ns, l_tgt, l_nt, l_k, l_ptr):
    """d (target items) += k W c (source items) for each learning coupling, W its weights now."""
    for L in range(l_src.size):
        s0, ns, t0, p0 = l_src[L], l_ns[L], l_tgt[L], l_ptr[L]
        for mi in range(l_nt[L]):
            acc = 0.0
            for j in range(ns):
                acc += w[p0 + mi * ns + j] * f[item_pos[s0 + j]]
            d[t0 + mi] += l_k[L] * acc


@inlined
def build_traces(f, m, offsets, mem_fields, mem_build, mem_decay, mem_thr):
    """Each traced field active somewhere: m toward f where f > threshold, toward 0 elsewhere."""
    for fi in range(offsets.size - 1):
        if not mem_fields[fi]:
            continue
        o, e = offsets[fi], offsets[fi + 1]
        active = False
        for i in range(o, e):
            if f[i] > mem_thr[i]:
                active = True
                break
        if active:
            for i in range(o, e):
                if f[i] > mem_thr[i]:
                    m[i] += mem_build[i] * (f[i] - m[i])
                else:
                    m[i] += -mem_decay[i] * m[i]


@inlined
def learn(f, m, item_pos, w, dt, l_src, l_ns, l_tgt, l_nt, l_gate, l_tpre, l_tpost, l_pre_item, l_pre_ptr, l_learns,
          l_post_thr, l_rel, l_rate, l_decay, l_floor, l_hi, l_ptr):
    """w += dt g c_pre (rate c_post - decay w) where the weight learns and c_post exceeds the post threshold,
    clipped to [its floor, the upper bound] (see compiled); each c the output f, or the memory trace m on a traced side, c_pre
    read at each source's pre item; with l_rel, c_post over the largest among the source's learning targets."""
    for L in range(l_src.size):
        ns, t0, p0, q0 = l_ns[L], l_tgt[L], l_ptr[L], l_pre_ptr[L]
        g = 1.0 if l_gate[L] < 0 else f[item_pos[l_gate[L]]]
        cpre = m if l_tpre[L] else f
        cpost = m if l_tpost[L] else f
        for j in range(ns):
            at = l_pre_item[q0 + j]
            if at < 0:
                continue
            top = 1.0
            if l_rel[L]:
                top = 0.0
                for mi in range(l_nt[L]):
                    post = cpost[item_pos[t0 + mi]]
                    if l_learns[p0 + mi * ns + j] != 0.0 and post > l_post_thr[L] and post > top:
                        top = post
                if top <= 0.0:
                    continue
            for mi in range(l_nt[L]):
                post = cpost[item_pos[t0 + mi]]
                q = p0 + mi * ns + j
                if post <= l_post_thr[L] or l_learns[q] == 0.0:
                    continue
                v = w[q] + dt * g * cpre[item_pos[at]] * (l_rate[L] * post / top - l_decay[L] * w[q])
                w[q] = l_floor[q] if v < l_floor[q] else (l_hi[L] if v > l_hi[L] else v)


@jit
def run(n_steps, u, S, S_ext, stim_item, xi, use_noise,
        dt_tau, h, beta, u0, noise_scale,
        offsets, grid, inhib,
        g_field, g_circular, g_ty_off, g_tx_off, taps_y, taps_x, g_term_ptr, t_src, t_kind, t_w,
        item_pos, K_indptr, K_indices, K_data,
        R_indptr, R_indices, R_data,
        f, buf, proj, pad, tmp, rate, d, tbuf,
        m, w, use_mem, mem_fields, mem_amp, mem_build, mem_decay, mem_thr,
        dt, l_src, l_ns, l_tgt, l_nt, l_gate, l_tpre, l_tpost, l_pre_item, l_pre_ptr, l_learns, l_post_thr, l_rel, l_k, l_rate,
        l_decay, l_floor, l_hi, l_ptr):
    P = u.size
    for step in range(n_steps):
        sigmoid(u, beta, u0, f, tbuf)
        for fi in range(offsets.size - 1):
            o = offsets[fi]
            n = offsets[fi + 1] - o
            # contiguous views keep the loops free of offset arithmetic, so they vectorise
            fv = f[o:o + n]
            rv = rate[o:o + n]
            hv = h[o:o + n]
            uv = u[o:o + n]
            base = -inhib[fi] * total(fv)
            for i in range(n):
                rv[i] = base + hv[i] - uv[i]
        for g in range(g_field.size):
            fi = g_field[g]
            o = offsets[fi]
            n = offsets[fi + 1] - o
            ny, nx = grid[fi, 0], grid[fi, 1]
            tx = taps_x[g_tx_off[g]:g_tx_off[g + 1]]
            if ny == 1:
                # the terms are summed straight into the middle of the padded line
                r = (tx.size - 1) // 2
                pv = pad[:n + 2 * r]
                gather(g_term_ptr[g], g_term_ptr[g + 1], offsets, grid, t_src, t_kind, t_w, f, pv[r:r + n], ny, nx, proj)
                pad_ends(pv, n, r, g_circular[g])
                conv_line(rate[o:o + n], pv, tx, n)
            else:
                bv = buf[:n]
                gather(g_term_ptr[g], g_term_ptr[g + 1], offsets, grid, t_src, t_kind, t_w, f, bv, ny, nx, proj)
                convolve_plane(rate[o:o + n], bv, ny, nx, taps_y[g_ty_off[g]:g_ty_off[g + 1]], tx, g_circular[g],
                               pad, tmp)
        for m_ in range(d.size):
            acc = stim_item[m_]
            for q in range(K_indptr[m_], K_indptr[m_ + 1]):
                acc += K_data[q] * f[item_pos[K_indices[q]]]
            d[m_] = acc
        learned_drive(f, item_pos, d, w, l_src, l_ns, l_tgt, l_nt, l_k, l_ptr)
        if use_mem:
            for p in range(P):
                S[p] = S_ext[p] + mem_amp[p] * m[p]
            build_traces(f, m, offsets, mem_fields, mem_build, mem_decay, mem_thr)
        else:
            for p in range(P):
                S[p] = S_ext[p]
        for m_ in range(d.size):
            dm = d[m_]
            if dm != 0.0:
                for q in range(R_indptr[m_], R_indptr[m_ + 1]):
                    S[R_indices[q]] += dm * R_data[q]
        learn(f, m, item_pos, w, dt, l_src, l_ns, l_tgt, l_nt, l_gate, l_tpre, l_tpost, l_pre_item, l_pre_ptr, l_learns,
              l_post_thr, l_rel, l_rate, l_decay, l_floor, l_hi, l_ptr)
        if use_noise:
            for p in range(P):
                u[p] += dt_tau[p] * (rate[p] + S[p]) + noise_scale[p] * xi[step, p]
        else:
            for p in range(P):
                u[p] += dt_tau[p] * (rate[p] + S[p])
