"""A tremor of the hand with the amplitude it was drawn with, as the hand realises it.

The tremor is an oscillation of the commanded hand (`HumanArm`), but the arm's position servos are a lightly
damped mass-spring system whose resonance lies in the tremor band (4-8 Hz): commanded as drawn, the hand moved
up to 3.4 times as far (docs/measurements.md, "The tremor as drawn, and the stopper within reach"), and how
far depends on the posture and on what the hand holds. So the generator watches the hand (the person's own
sense of it): it demodulates, at the tremor's frequency, both the displacement it commands and the one the
hand makes (a lock-in over a few cycles) and scales its command by their ratio, so that the hand trembles by
the drawn amplitude whatever the body, posture or load. It watches the hand's deviation from its planned
path: the reach itself is not in it, and what is (the servos' lag, the sag under a load) varies far more
slowly than the tremor and averages out.
"""

from __future__ import annotations

import math

import numpy as np

#: s over which the hand's and the command's oscillations are demodulated: about three cycles of the
#: slowest tremor, short enough to follow a change of load (an object taken in hand)
WINDOW = 0.6
#: the command's scale stays within these (a hand that hardly moves is not driven without bound)
SCALE_RANGE = (0.2, 3.0)


class Tremor:
    """An oscillation of ``amplitude`` m at ``frequency`` Hz along ``direction`` (world), regulated so the
    measured hand realises that amplitude: `offset` is the commanded displacement, `observe` takes in where
    the hand is each control tick."""

    def __init__(self, amplitude: float, frequency: float, direction, dt: float) -> None:
        self.amplitude = float(amplitude)
        self.frequency = float(frequency)
        self.direction = np.asarray(direction, float) / np.linalg.norm(direction)
        self.scale = 1.0
        self._dt = float(dt)
        self._rate = min(1.0, self._dt / WINDOW)
        self._mean = None                  # the slow part of the deviation along the direction
        self._hand = np.zeros(2)           # the hand's oscillation at the frequency (in-phase, quadrature)
        self._command = np.zeros(2)        # the command's
        self._seen = 0.0                   # s observed
        self._fresh = 0.0                  # s observed since the hand was last watched again (`pause`)
        self._paused = False
        self._known = False                # the arm's gain has been measured once (the scale then follows it)

    def _phase(self, t: float) -> float:
        return 2.0 * math.pi * self.frequency * t

    def offset(self, t: float) -> np.ndarray:
        """The commanded displacement of the hand at time t (world, m). It sets in over the first two windows the
        free hand is watched (the arm's gain at the frequency is not known before the first has passed)."""
        onset = min(1.0, self._seen / (2.0 * WINDOW))
        return onset * self.scale * self.amplitude * math.sin(self._phase(t)) * self.direction

    def pause(self) -> None:
        """The hand is not watched for a while (braced on something stiff). What it made before does not tell
        what it makes when it is watched again: the load in it may have changed (an object taken over), and the
        first moments free are the spring-back of the brace let go, not the tremor. So the demodulation starts
        afresh then, and the command keeps its scale until a whole window has been watched."""
        self._paused = True

    def observe(self, t: float, off) -> None:
        """Take in how far the measured hand is off its planned position (world, m) at time t and rescale the
        command."""
        if self.amplitude == 0.0:
            return
        if self._paused:
            self._paused, self._fresh, self._mean = False, 0.0, None
            self._hand, self._command = np.zeros(2), np.zeros(2)
        y = float(np.asarray(off, float) @ self.direction)
        self._mean = y if self._mean is None else self._mean + self._rate * (y - self._mean)
        ref = np.array([math.sin(self._phase(t)), math.cos(self._phase(t))])
        c = float(self.offset(t) @ self.direction)
        self._hand += self._rate * ((y - self._mean) * ref - self._hand)
        self._command += self._rate * (c * ref - self._command)
        self._seen += self._dt
        self._fresh += self._dt
        if self._fresh < WINDOW:
            return
        made, asked = float(np.hypot(*self._hand)), float(np.hypot(*self._command))
        if made > 0.0 and asked > 0.0:
            # made / asked is the arm's gain at this frequency now: command the drawn amplitude over it. The
            # scale follows it over a window (in ratio), as the gain itself changes no faster: a slow swing of
            # the hand (a sag under a load just taken) read for a moment as little tremor must not triple it
            want = float(np.clip(asked / made, *SCALE_RANGE))
            follow = self._rate if self._known else 1.0
            self.scale = float(np.clip(self.scale * (want / self.scale) ** follow, *SCALE_RANGE))
            self._known = True
