"""Steps shared by the hand-over tests in the physics (imported by test modules; pytest puts tests/ on sys.path)."""

from __future__ import annotations

import numpy as np

from assistbot.human.behaviours import hold_out_point


def hold_out_until_there(w, human, obj: str, tol: float, limit: float = 15.0) -> None:
    """Run the person alone until she holds ``obj`` out at her hold-out point (within ``tol`` m) and her reach there
    is over, or ``limit`` s of simulated time have passed."""
    def there() -> bool:
        hand = w.site_pos("human_r_grasp")
        return (w.human_holding() == obj and np.linalg.norm(hand - hold_out_point(human)) < tol
                and human.arm.arrived(w.time, tol))
    while not there() and w.time < limit:
        human.tick(w.time)
        w.step(10)
