"""A network spec laid out as flat arrays, so one step is a few vectorised operations.

All fields are concatenated into one vector of P positions; all items into one
vector of I items. Per step:

- f = sigmoid(u) per position (eq. 3, each field its own beta and u0);
- lateral interaction (eq. 2): the Gaussian part as a truncated convolution
  with the field's taps, the global inhibition as -w_inhib * dx * sum(f) of
  the field (exact: every position of a linear or periodic field sees all
  others with the same weight);
- coupling gates c_j = f(u(x_j)) at item centres; item drive d = K c +
  item stimuli, with K[m, j] = k a_mj over all couplings (eq. 4);
- coupling input rendered as Gaussians of the target field's input_sigma
  around each item centre, plus continuous stimuli S_ext;
- Euler: u += dt/tau (-u + S + L + h) (+ noise/tau sqrt(dt) xi).

The Gaussian taps are truncated where exp(-d^2/2 sigma^2) < TRUNCATION, so
both stepping paths compute the same sums; the untruncated reference lives
in the tests (scipy solve_ivp on the dense equation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from assistbot.fields.spec import NetworkSpec

TRUNCATION = 1e-10


def gaussian_half_width(sigma: float, dx: float) -> int:
    """Number of positions on each side where the Gaussian exceeds TRUNCATION."""
    return int(math.ceil(sigma * math.sqrt(-2.0 * math.log(TRUNCATION)) / dx))


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
    radius: np.ndarray  # (F,) taps on each side
    periodic: np.ndarray  # (F,) bool
    taps_off: np.ndarray  # (F+1,) into taps
    taps: np.ndarray  # A * dx * gaussian, concatenated
    inhib: np.ndarray  # (F,) w_inhib * dx
    # items and couplings
    item_pos: np.ndarray  # (I,) flat index of each item centre
    item_off: dict[str, int]  # first item of each field in the item vector
    K: sp.csr_matrix  # (I, I)
    render: sp.csr_matrix  # (P, I) Gaussians at item centres
    render_items: sp.csr_matrix  # (I, P) transpose, item-major for the compiled path
    lateral: sp.csr_matrix  # (P, P) Gaussian part of the kernel, block diagonal
    has_noise: bool

    @property
    def size(self) -> int:
        return int(self.offsets[-1])

    @property
    def n_items(self) -> int:
        return int(self.item_pos.size)


    def slice(self, name: str) -> slice:
        i = self.names.index(name)
        return slice(int(self.offsets[i]), int(self.offsets[i + 1]))


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
    taps_list, radius, lat_rows, lat_cols, lat_vals = [], [], [], [], []
    for fi, f in enumerate(fs):
        r = gaussian_half_width(f.kernel.sigma, f.dx)
        r = min(r, (f.size - 1) // 2 if f.periodic else f.size - 1)
        d = np.arange(-r, r + 1)
        g = f.kernel.A * f.dx * _gaussian(d * f.dx, f.kernel.sigma)
        taps_list.append(g)
        radius.append(r)
        i = np.arange(f.size)
        j = i[:, None] + d[None, :]
        vals = np.broadcast_to(g, j.shape)
        if f.periodic:
            ok = np.ones_like(j, dtype=bool)
            j = j % f.size
        else:
            ok = (j >= 0) & (j < f.size)
        lat_rows.append((np.broadcast_to(i[:, None], j.shape)[ok]) + offsets[fi])
        lat_cols.append(j[ok] + offsets[fi])
        lat_vals.append(vals[ok])
    lateral = sp.csr_matrix(
        (np.concatenate(lat_vals), (np.concatenate(lat_rows), np.concatenate(lat_cols))), shape=(P, P)
    )
    taps_off = np.concatenate([[0], np.cumsum([t.size for t in taps_list])]).astype(np.int64)

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
        radius=np.asarray(radius, dtype=np.int64),
        periodic=np.array([f.periodic for f in fs], dtype=np.bool_),
        taps_off=taps_off,
        taps=np.concatenate(taps_list),
        inhib=np.array([f.kernel.w_inhib * f.dx for f in fs]),
        item_pos=np.asarray(item_pos, dtype=np.int64),
        item_off=item_off,
        K=K,
        render=render,
        render_items=render.T.tocsr(),
        lateral=lateral,
        has_noise=any(f.noise > 0 for f in fs),
    )
