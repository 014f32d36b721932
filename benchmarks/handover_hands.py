"""Where the robot's hand and the person's hand are when the robot hands the full glass over, and how deep they
overlap: the geometry any solid-hands hand-over has to work with.

Run: .venv/bin/python benchmarks/handover_hands.py

Runs the shipped Fig. 4 scenario (oracle percept, so vision plays no part) until the robot holds the full glass
out, and prints, relative to the glass's base (x toward the robot, y to the person's left, z up, cm), the
centre of the robot's palm and fingers; then follows the person's take and prints the
deepest overlap of any robot geom with any of the person's (`episode.touch.TouchMonitor`), which geoms, and
where the person's palm and fingers are then.
"""

from __future__ import annotations

import numpy as np

from assistbot.episode.builder import build_episode
from assistbot.robot.primitives.handing_over import OFFER_PHASE
from assistbot.scenario import load_scenario

ROBOT_HAND = ("robot_palm", "robot_f1_prox", "robot_f1_dist", "robot_f2_prox", "robot_f2_dist", "robot_f3_prox", "robot_f3_dist")
PERSON_HAND = ("human_r_palm", "human_r_index_prox", "human_r_index_dist", "human_r_middle_prox", "human_r_middle_dist",
               "human_r_thumb")


def _where(ep, names, glass) -> None:
    m, d = ep.world.model, ep.world.data
    for n in names:
        g = next((i for i in range(m.ngeom) if m.geom(i).name == n), None)
        if g is None:
            continue
        x, y, z = (d.geom_xpos[g] - glass) * 100
        print(f"  {n:22s} x {x:6.1f}  y {y:6.1f}  z {z:6.1f}")


def main() -> None:
    ep = build_episode(load_scenario("fig4-fill-and-hand-over"), perception="oracle")
    m, d = ep.world.model, ep.world.data
    glass_id = ep.world.body_id["glass"]
    offered = False
    worst, worst_at, worst_pair, layout = 0.0, None, ("", ""), None
    while not ep.tick():
        prim = ep.actor.primitive
        phase = prim.progress.phase if prim is not None else ""
        if phase == OFFER_PHASE and not offered and ep.world.human_holding() is None:
            offered = True
            glass = d.xpos[glass_id].copy()
            print(f"t = {ep.world.time:.1f} s: the robot holds the full glass out (glass base at {np.round(glass, 3)} m);")
            print("its hand, cm from the glass's base:")
            _where(ep, ROBOT_HAND, glass)
        if offered:
            depth, a, b = ep.task.touch.overlap()
            if depth > worst:
                worst, worst_at = depth, ep.world.time
                worst_pair = (m.geom(a).name or m.body(m.geom_bodyid[a]).name, m.body(m.geom_bodyid[b]).name)
                layout = {n: d.geom_xpos[i].copy() for i in range(m.ngeom) if (n := m.geom(i).name) in PERSON_HAND}
                glass_then = d.xpos[glass_id].copy()
        if offered and ep.world.human_holding() == "glass" and ep.world.robot_holding() is None:
            break
    if worst_at is None:
        print("no overlap during the take")
        return
    print(f"deepest overlap during the take: {100 * worst:.1f} cm at t = {worst_at:.1f} s, {worst_pair[0]} in {worst_pair[1]};")
    print("the person's hand then, cm from the glass's base:")
    for n in PERSON_HAND:
        if n in layout:
            x, y, z = (layout[n] - glass_then) * 100
            print(f"  {n:22s} x {x:6.1f}  y {y:6.1f}  z {z:6.1f}")


if __name__ == "__main__":
    main()
