"""A 2-D field (eq. 1 over a plane), e.g. over the table, whose peak holds a motion target.

Positions are in the units of ``origin``/``dx`` (metres for the table plane).
The kernel is eq. (2) with a 2-D Gaussian, applied as two 1-D passes (it is
separable), plus global inhibition over the whole field.
"""

from __future__ import annotations

import math

import numpy as np

from assistbot.fields.errors import FieldError
from assistbot.fields.spec import _number


class Field2D:
    def __init__(self, name: str, shape: tuple[int, int], origin: tuple[float, float] = (0.0, 0.0), dx: float = 1.0,
                 tau: float = 0.1, h: float = -3.0, beta: float = 4.0, u0: float = 0.0,
                 A: float = 0.0, sigma: float = 1.0, w_inhib: float = 0.0, noise: float = 0.0, seed: int | None = 0) -> None:
        where = f"field '{name}'"
        if len(shape) != 2 or any(int(n) < 1 for n in shape):
            raise FieldError(where, "shape", f"must be two whole numbers >= 1 (rows along y, columns along x), got {shape!r}")
        self.name = name
        self.shape = (int(shape[0]), int(shape[1]))
        self.origin = (float(origin[0]), float(origin[1]))
        self.dx = _number(where, "dx", dx, positive=True)
        self.tau = _number(where, "tau", tau, positive=True)
        self.h = _number(where, "h", h)
        if self.h >= 0:
            raise FieldError(where, "h", f"the resting level must be negative (h < 0), got {h}")
        self.beta = _number(where, "beta", beta, positive=True)
        self.u0 = _number(where, "u0", u0)
        self.A = _number(where, "kernel.A", A, nonneg=True)
        self.sigma = _number(where, "kernel.sigma", sigma, positive=True)
        self.w_inhib = _number(where, "kernel.w_inhib", w_inhib, nonneg=True)
        self.noise = _number(where, "noise", noise, nonneg=True)
        self.rng = np.random.default_rng(seed)
        ny, nx = self.shape
        self.xs = self.origin[0] + np.arange(nx) * self.dx
        self.ys = self.origin[1] + np.arange(ny) * self.dx
        # 1-D Gaussian passes; A and dx^2 (the area element) folded into one of them
        gy = np.exp(-((self.ys[:, None] - self.ys[None, :]) ** 2) / (2 * self.sigma**2))
        gx = np.exp(-((self.xs[:, None] - self.xs[None, :]) ** 2) / (2 * self.sigma**2))
        self._gy = self.A * self.dx * self.dx * gy
        self._gxT = gx.T.copy()
        self.u = np.full(self.shape, self.h)
        self.S = np.zeros(self.shape)

    def check_dt(self, dt: float) -> None:
        if dt <= 0 or dt > self.tau / 2:
            raise FieldError(f"field '{self.name}'", "tau",
                             f"dt={dt} s is not a stable Euler step with tau={self.tau} s; need 0 < dt <= tau/2")

    def clear_input(self) -> None:
        self.S[:] = 0.0

    def add_gaussian(self, center: tuple[float, float], amplitude: float, sigma: float) -> None:
        """Add a Gaussian input centred at (x, y) in plane units."""
        gx = np.exp(-((self.xs - center[0]) ** 2) / (2 * sigma**2))
        gy = np.exp(-((self.ys - center[1]) ** 2) / (2 * sigma**2))
        self.S += amplitude * np.outer(gy, gx)

    def output(self) -> np.ndarray:
        return 1.0 / (1.0 + np.exp(-np.clip(self.beta * (self.u - self.u0), -500, 500)))

    def step(self, dt: float, n: int = 1) -> None:
        self.check_dt(dt)
        for _ in range(int(n)):
            f = self.output()
            lateral = self._gy @ f @ self._gxT - self.w_inhib * self.dx * self.dx * f.sum()
            self.u += dt / self.tau * (-self.u + self.S + lateral + self.h)
            if self.noise:
                self.u += self.noise / self.tau * math.sqrt(dt) * self.rng.standard_normal(self.shape)

    def reset(self) -> None:
        self.u[:] = self.h

    def peak(self, threshold: float = 0.0) -> tuple[float, float, float] | None:
        """(x, y, u) of the strongest position if above ``threshold``, refined to sub-cell by the centroid of f."""
        i = int(np.argmax(self.u))
        iy, ix = divmod(i, self.shape[1])
        top = float(self.u[iy, ix])
        if top <= threshold:
            return None
        f = self.output()
        # centroid over the supra-threshold blob around the maximum gives a sub-cell estimate
        r = max(1, int(round(4 * self.sigma / self.dx)))
        y0, y1 = max(0, iy - r), min(self.shape[0], iy + r + 1)
        x0, x1 = max(0, ix - r), min(self.shape[1], ix + r + 1)
        w = f[y0:y1, x0:x1]
        total = w.sum()
        x = float((w.sum(axis=0) * self.xs[x0:x1]).sum() / total)
        y = float((w.sum(axis=1) * self.ys[y0:y1]).sum() / total)
        return x, y, top
