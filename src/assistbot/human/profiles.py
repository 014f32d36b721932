"""User profiles: named parameter sets of the simulated partner (seed paper, section IV-D)."""

from __future__ import annotations

from dataclasses import dataclass, replace

#: how far (m) a person's hold-out point may lie from the nominal one, per axis (x, y, z)
HOLD_OUT_REGION = (0.08, 0.08, 0.06)
#: what a person's grips mean (their convention): the grip they hand things over with, and the one they pour
#: with. The seed's partner hands over from above and pours from the side; a person may do it the other way.
#: (An upside-down glass is turned upright from the side either way: from above, half a turn is beyond a forearm.)
GRIP_CONVENTIONS: dict[str, tuple[str, str]] = {"seed": ("ag", "sg"), "swapped": ("sg", "ag")}


@dataclass(frozen=True)
class Profile:
    """Parameters of one kind of partner.

    initiative      acts on its own toward drinking (active) or only answers requests (passive)
    reaction_delay  s between perceiving a robot act (speech tag or gesture) and responding
    speed           mean hand speed of a reach (m/s); peak speed of a minimum-jerk reach is 1.875x
    grip            preferred grip for hand-overs and hold-outs: "ag" (above) or "sg" (side)
    grip_convention what the person's grips mean (GRIP_CONVENTIONS): "seed" or "swapped"; setting it sets
                    ``grip`` to the convention's hand-over grip, and the pour's grip (`pour_grip`)
    wrong_grip      chance (0..1) that the default policy first grasps with the other grip
    hesitation      s of pause before each motion (a person who hesitates)
    hold_out_dx/dy/dz  where this person holds things out and the open hand: m from the nominal
                    point (behaviours.HOLD_OUT), within HOLD_OUT_REGION
    drop_chance     chance (0..1) of letting go of an object just lifted (weakness); it falls in the physics
    tremor_amplitude, tremor_frequency  a tremor of the hand: m (0: none) along one direction, Hz
    """

    name: str
    initiative: bool
    reaction_delay: float = 0.8
    speed: float = 0.20
    grip: str = "ag"
    wrong_grip: float = 0.3
    hesitation: float = 0.0
    hold_out_dx: float = 0.0
    hold_out_dy: float = 0.0
    hold_out_dz: float = 0.0
    drop_chance: float = 0.0
    tremor_amplitude: float = 0.0
    tremor_frequency: float = 6.0
    grip_convention: str = "seed"

    @property
    def pour_grip(self) -> str:
        """The grip this person pours with."""
        return GRIP_CONVENTIONS[self.grip_convention][1]

    def hand_over_grip(self, obj: str) -> str:
        """The grip this person hands ``obj`` over with: the bottle with their own, the glass from the side."""
        return self.grip if obj == "bottle" else "sg"

    @property
    def hold_out_offset(self) -> tuple[float, float, float]:
        return (self.hold_out_dx, self.hold_out_dy, self.hold_out_dz)

    def with_(self, **changes) -> "Profile":
        if "grip_convention" in changes and "grip" not in changes:
            changes["grip"] = GRIP_CONVENTIONS[changes["grip_convention"]][0]
        return replace(self, **changes)


PROFILES: dict[str, Profile] = {
    "active": Profile("active", initiative=True, reaction_delay=0.6, speed=0.20, grip="ag", wrong_grip=0.3),
    "passive": Profile("passive", initiative=False, reaction_delay=1.0, speed=0.18, grip="ag", wrong_grip=0.0),
    "slow": Profile("slow", initiative=True, reaction_delay=1.5, speed=0.08, grip="ag", wrong_grip=0.3, hesitation=0.8),
}
