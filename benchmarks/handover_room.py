"""How much room the robot's hand leaves the person's on the full glass it holds out: for each way of gripping
it, the largest clearance between any of the person's hand geoms and any of the robot's, over the poses of
that grip on the glass. Negative: the hands overlap by that much at best.

Run: .venv/bin/python benchmarks/handover_room.py

Runs the shipped Fig. 4 scenario (oracle percept) until the robot has held the full glass out for 0.6 s,
then places the person's hand (its geoms in the open posture and in the grip's closed one, as the MJCF
has them relative to the hand) in each candidate pose and measures it against the robot's hand with
`mujoco.mj_geomDistance`; nothing is simulated further. A candidate pose puts the hand's grasp site on
the glass (within SITE_ON_GLASS of its wall, as a grip that holds), at a height above the glass's base,
with the fingers turned about the vertical by a yaw from the line from the shoulder, the hand shifted
along its fingers and off the glass. The grips: the side grip turned about the fingers' axis from thumb
up (the person's side grip) toward palm down (her grip from above), with any yaw or with the fingers within
15 deg of the line from the shoulder (as a right arm reaches).
"""

from __future__ import annotations

import itertools

import numpy as np

from assistbot.episode.builder import build_episode
from assistbot.human.arm import ORIENT, rot_z
from assistbot.human.room import hand_room
from assistbot.robot.primitives.handing_over import OFFER_PHASE
from assistbot.scenario import load_scenario

#: m: the farthest the grasp site lies outside the glass's wall in a candidate pose
SITE_ON_GLASS = 0.01
#: (name, turn about the fingers' axis from thumb up toward palm down in degrees, closed posture, the most the
#: fingers turn from the line from the shoulder in degrees)
GRIPS = (("side grip, thumb up", 0, "sg", 90), ("side grip, thumb up, +-15", 0, "sg", 15),
         ("side grip turned 30 deg", 30, "sg", 90), ("side grip turned 60 deg", 60, "sg", 90),
         ("from above, palm down", 90, "ag", 90), ("from above, +-15", 90, "ag", 15))
HEIGHTS = np.arange(0.0, 0.101, 0.01)
YAWS = np.radians(np.arange(-90, 91, 15))
ALONG = np.arange(-0.04, 0.021, 0.02)
OFF = np.arange(-0.01, 0.031, 0.01)


def _held_out(ep) -> None:
    since = None
    while not ep.tick():
        prim = ep.actor.primitive
        if prim is not None and prim.progress.phase == OFFER_PHASE:
            since = since if since is not None else ep.world.time
            if ep.world.time > since + 0.6:
                return
    raise SystemExit("the episode ended before the robot held the glass out")


def main() -> None:
    ep = build_episode(load_scenario("fig4-fill-and-hand-over"), perception="oracle")
    d = ep.world.data
    _held_out(ep)
    glass = d.xpos[ep.world.body_id["glass"]].copy()
    room = hand_room(ep.world)
    shoulder = ep.partner.arm.shoulder_xy
    bearing = float(np.arctan2(glass[1] - shoulder[1], glass[0] - shoulder[0]))

    print(f"the robot holds the full glass out at {np.round(glass, 3)} m; clearance (cm, + apart, - overlapping) "
          "of the best pose of each grip at each height of its grasp site above the glass's base:")
    print(f"{'grip':26s}" + "".join(f"{100 * s:6.0f}" for s in HEIGHTS))
    for name, turn, posture, turned in GRIPS:
        best = {}
        for s, yaw, along, off in itertools.product(HEIGHTS, YAWS[np.abs(YAWS) <= np.radians(turned) + 1e-9], ALONG, OFF):
            R = rot_z(bearing + yaw) @ ORIENT["sg"] @ rot_z(np.radians(turn))
            # shifted back along the fingers (-R[:, 2] points along them) and off the glass (against the palm's normal)
            target = glass + np.array([0.0, 0.0, s]) + along * R[:, 2] - off * R[:, 1]
            if ep.world.surface_distance("glass", target) > SITE_ON_GLASS:
                continue
            c = min(room.clearance(d, "open", target, R), room.clearance(d, posture, target, R))
            best[round(s, 2)] = max(best.get(round(s, 2), -1.0), c)
        print(f"{name:26s}" + "".join(f"{100 * best.get(round(s, 2), np.nan):+6.1f}" for s in HEIGHTS))


if __name__ == "__main__":
    main()
