"""Where the hand should go: a 2-D dynamic field over the table plane whose peak is the IK target.

Perception of the current action's target (an object, the human's hand)
arrives as a Gaussian input at its table position. The field's
self-sustained peak is the estimate the arm moves to: it stays in place
through gaps in perception (a missed camera frame, an occluded object) and
is dragged along by a moving input, smoothly, at the field's time scale.

Coordinates are the table frame in metres (x, y on the surface). The field
is the one 2-D member of a `assistbot.fields.Network`, whose positions run
from 0; this class moves them to the table frame.
"""

from __future__ import annotations

from dataclasses import dataclass

from assistbot.fields import Network


@dataclass
class TargetFieldParams:
    # the robot's side of the table and, across the middle line, the whole region where a person may hold
    # something out, with a kernel's width to spare: a peak cut by the field's edge sits off its input
    x_range: tuple[float, float] = (-0.45, 0.8)
    y_range: tuple[float, float] = (-0.55, 0.55)
    # m per field position: well below the kernel's width, so that a peak between two positions is as
    # strong as one on a position (on a grid as coarse as the kernel, such a peak dies within a second
    # without input, and a grid-centred one is pinned where it is)
    resolution: float = 0.0125
    tau: float = 0.03  # s
    h: float = -3.0
    beta: float = 4.0
    # per m^2: sustains a peak without input, anywhere. Global inhibition keeps it one narrow peak that a
    # moving input drags along, and lets an input far from it win within a fraction of a second
    A: float = 2500.0
    sigma: float = 0.03  # m
    w_inhib: float = 200.0
    input_amplitude: float = 10.0
    input_sigma: float = 0.03  # m
    dt: float = 0.01  # s per Euler step: two per 50 Hz control tick


FIELD = "target"
PERCEPT = "percept"  # the name of the one input the field has


class TargetField:
    def __init__(self, params: TargetFieldParams | None = None) -> None:
        self.p = p = params or TargetFieldParams()
        nx = int(round((p.x_range[1] - p.x_range[0]) / p.resolution)) + 1
        ny = int(round((p.y_range[1] - p.y_range[0]) / p.resolution)) + 1
        self.origin = (p.x_range[0], p.y_range[0])
        self.net = Network.from_dict({"dt": p.dt, "fields": {FIELD: {
            "shape": [ny, nx], "dx": p.resolution, "tau": p.tau, "h": p.h, "beta": p.beta,
            "kernel": {"A": p.A, "sigma": p.sigma, "w_inhib": p.w_inhib}, "input_sigma": p.input_sigma}}})
        self._t_pending = 0.0

    def observe(self, xy: tuple[float, float] | None, confidence: float = 1.0) -> None:
        """The target as perceived now; None when it is not seen (the peak then holds)."""
        if xy is None:
            self.net.clear_stimulus_at(FIELD, PERCEPT)
            return
        at = (float(xy[0]) - self.origin[0], float(xy[1]) - self.origin[1])
        self.net.set_stimulus_at(FIELD, PERCEPT, at, self.p.input_amplitude * float(confidence))

    def advance(self, seconds: float) -> None:
        """Integrate the field over ``seconds`` of simulated time (whole Euler steps, remainder carried)."""
        self._t_pending += seconds
        n = int(self._t_pending / self.p.dt + 1e-9)
        if n:
            self.net.step(n)
            self._t_pending -= n * self.p.dt

    def target(self) -> tuple[float, float] | None:
        """The peak's position (m), or None while there is no peak."""
        peak = self.net.peak_xy(FIELD, threshold=0.0)
        return None if peak is None else (peak[0] + self.origin[0], peak[1] + self.origin[1])

    def reset(self) -> None:
        """Forget the target (a new action begins)."""
        self.net.clear_stimuli()
        self.net.reset()
        self._t_pending = 0.0
