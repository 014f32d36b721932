"""The tremor's regulation (`assistbot.human.tremor.Tremor`): it scales its command by how far the hand moves at
the tremor's frequency, but a slow swing of the hand just freed from a brace (the sag under a full glass the
robot has let go of) is not read as an arm that hardly trembles, to be driven three times harder: that spilt
the glass in a partner's hand. Fed with a simulated hand (no physics): the hand makes ``gain`` times the command."""

from __future__ import annotations

import math

import numpy as np

from assistbot.human.tremor import SCALE_RANGE, Tremor

DT = 0.02
UP = np.array([0.0, 0.0, 1.0])


def _watch(tr: Tremor, t: float, seconds: float, gain: float, swing=lambda s: 0.0) -> float:
    """The hand makes ``gain`` times the commanded tremor plus ``swing(s)`` (m, s since the start of this spell)."""
    for k in range(int(round(seconds / DT))):
        s = k * DT
        tr.observe(t + s, UP * (gain * float(tr.offset(t + s) @ UP) + swing(s)))
    return t + seconds


def test_the_command_settles_where_the_hand_makes_the_drawn_amplitude():
    tr = Tremor(0.01, 6.0, UP, DT)
    _watch(tr, 0.0, 6.0, gain=2.0)
    assert math.isclose(tr.scale, 0.5, rel_tol=0.1), tr.scale


def test_a_moment_of_little_tremor_after_a_brace_is_let_go_does_not_drive_it_up():
    tr = Tremor(0.01, 5.5, UP, DT)
    t = _watch(tr, 0.0, 6.0, gain=1.3)
    before = tr.scale
    tr.pause()                                  # braced: the robot holds what the hand holds
    # freed, the hand sinks 5 cm under the full glass over 0.4 s, hardly trembling meanwhile, then trembles as before
    sag = lambda s: -0.05 * min(s / 0.4, 1.0)   # noqa: E731
    t = _watch(tr, t, 0.6, gain=0.2, swing=sag)
    peak = tr.scale
    for _ in range(5):
        t = _watch(tr, t, 0.2, gain=1.3, swing=lambda s: -0.05)
        peak = max(peak, tr.scale)
    assert peak < 1.5 * before, (before, peak, SCALE_RANGE)
    _watch(tr, t, 6.0, gain=1.3)
    assert math.isclose(tr.scale, before, rel_tol=0.1), (before, tr.scale)      # and it settles where it was
