"""A population of partners: people with their own bodies, impairments and habits, drawn from a seed.

A `Partner` has three parts:

- `Body`: the right arm's segment lengths and the sitting shoulder height as ratios to the default
  person (whose arm is a 50th-percentile adult's), the seat moved back or aside, and a reduced range of
  motion of the joints that carry the hand out. Built in the physics: `assistbot.human.body.apply_body` edits the human in the MJCF spec of
  the scene and of the arm's own IK model alike.
- impairment and habits, which are parameters of the person's behaviour (`Profile` fields): a tremor of
  the hand, slower motions, a chance of letting go of a lifted object, hesitation, a later reaction,
  and where the person holds things out.

`sample_partner(seed)` draws one deterministically. The body's ranges are the 5th-percentile woman to
the 95th-percentile man of adult anthropometry (approximately, from Pheasant and Haslegrave,
*Bodyspace*, 3rd ed., British adults 19-65): shoulder-elbow length 300-395 mm around a 350 mm middle,
elbow-fingertip length 400-510 mm around 455 mm, sitting shoulder height 505-645 mm around 575 mm. The
three are correlated through one stature draw. The hand itself keeps its size (the grips and the
vision templates are built for it).

A scenario names a partner under ``human.partner``: an integer (drawn from the population with that
seed) or a mapping of the attributes below (any left out keep the default person's value).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields
from typing import Any, Mapping

import numpy as np

from assistbot.errors import UserError
from assistbot.human.profiles import GRIP_CONVENTIONS, HOLD_OUT_REGION, Profile

#: (5th percentile, 95th percentile) as ratios to the default person, from the ranges in the module docstring
UPPER_ARM_RANGE = (300 / 350, 395 / 350)
FOREARM_RANGE = (400 / 455, 510 / 455)
SHOULDER_HEIGHT_RANGE = (505 / 575, 645 / 575)
#: m the seat may be moved back from the table (the default seat has the torso at the table's edge: it
#: cannot come closer) and to either side
SEAT_BACK_MAX = 0.08
SEAT_SIDE_MAX = 0.08
#: largest narrowing of the reach joints' ranges toward the resting posture (`human.body.ROM_JOINTS`)
ROM_MAX = 0.30
#: tremor of the hand: amplitude (m) and frequency (Hz) ranges
TREMOR_AMPLITUDE_MAX = 0.015
TREMOR_FREQUENCY_RANGE = (4.0, 8.0)
#: largest chance of letting go of an object just lifted
DROP_CHANCE_MAX = 0.10
#: how often each impairment occurs in the population
P_TREMOR, P_ROM, P_WEAK, P_HESITANT = 0.4, 0.4, 0.3, 0.3
#: the people a vision template library may be built from (`assistbot templates --partners 0:999`). Experiments on
#: partners the robot has never met draw from 1000 on (`make partners`: 1000-1099), so nothing the robot
#: knows was built from them.
LIBRARY_SEEDS = range(0, 1000)
UNSEEN_FROM = 1000


@dataclass(frozen=True)
class Body:
    """The partner's body as built in the physics (ratios to the default person; seat in m)."""

    upper_arm: float = 1.0          # shoulder-elbow length
    forearm: float = 1.0            # elbow-wrist length
    shoulder_height: float = 1.0    # shoulder above the seat (the torso, head and arm move with it)
    seat_back: float = 0.0          # m farther from the table than the default seat
    seat_side: float = 0.0          # m to the person's left (+) or right (-)
    rom: float = 0.0                # the reach joints' ranges narrowed by this fraction toward the resting posture

    def is_default(self) -> bool:
        return self == Body()


@dataclass(frozen=True)
class Partner:
    """One person: a body, and what they change of a profile's behaviour (``None``: the profile's own)."""

    seed: int | None = None
    body: Body = field(default_factory=Body)
    speed_factor: float = 1.0         # hand speed relative to the profile's (weakness: slower)
    reaction_factor: float = 1.0      # reaction delay relative to the profile's
    hesitation: float = 0.0           # s added to the profile's pause before each motion
    drop_chance: float = 0.0          # chance of letting go of an object just lifted (weakness)
    tremor_amplitude: float = 0.0     # m, of the hand
    tremor_frequency: float = 6.0     # Hz
    hold_out_dx: float = 0.0          # where things are held out: m from the nominal point
    hold_out_dy: float = 0.0
    hold_out_dz: float = 0.0
    grip_convention: str = "seed"     # what their grips mean (profiles.GRIP_CONVENTIONS)

    def profile(self, base: Profile) -> Profile:
        """``base`` as this person behaves: slower or quicker, with their impairment, hold-out habit and grips."""
        convention = {"grip_convention": self.grip_convention} if self.grip_convention != "seed" else {}
        return base.with_(speed=base.speed * self.speed_factor, reaction_delay=base.reaction_delay * self.reaction_factor,
                          hesitation=base.hesitation + self.hesitation, drop_chance=self.drop_chance,
                          tremor_amplitude=self.tremor_amplitude, tremor_frequency=self.tremor_frequency,
                          hold_out_dx=self.hold_out_dx, hold_out_dy=self.hold_out_dy, hold_out_dz=self.hold_out_dz,
                          **convention)

    def to_dict(self) -> dict:
        """The partner's attributes, flat (as a scenario's ``human.partner`` mapping takes them)."""
        d = {k: v for k, v in asdict(self).items() if k != "body" and not (k == "seed" and v is None)}
        d.update(asdict(self.body))
        return d


#: the attributes a ``human.partner`` mapping may set, with their allowed ranges
LIMITS: dict[str, tuple[float, float]] = {
    "upper_arm": UPPER_ARM_RANGE, "forearm": FOREARM_RANGE, "shoulder_height": SHOULDER_HEIGHT_RANGE,
    "seat_back": (0.0, SEAT_BACK_MAX), "seat_side": (-SEAT_SIDE_MAX, SEAT_SIDE_MAX), "rom": (0.0, ROM_MAX),
    "speed_factor": (0.3, 2.0), "reaction_factor": (0.3, 3.0), "hesitation": (0.0, 3.0),
    "drop_chance": (0.0, DROP_CHANCE_MAX), "tremor_amplitude": (0.0, TREMOR_AMPLITUDE_MAX),
    "tremor_frequency": TREMOR_FREQUENCY_RANGE,
    **{f"hold_out_d{a}": (-r, r) for a, r in zip("xyz", HOLD_OUT_REGION)},
}
BODY_KEYS = tuple(f.name for f in fields(Body))


def _between(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(lo + (hi - lo) * rng.random())


def sample_partner(seed: int) -> Partner:
    """The partner with this seed: the same seed gives the same person, on any machine."""
    rng = np.random.default_rng([0x9A27, int(seed)])
    # one stature draw between the 5th and 95th percentile correlates the body's lengths
    stature = rng.random()

    def size(rng_range: tuple[float, float]) -> float:
        s = float(np.clip(0.8 * stature + 0.2 * rng.random(), 0.0, 1.0))
        return round(rng_range[0] + (rng_range[1] - rng_range[0]) * s, 4)

    body = Body(upper_arm=size(UPPER_ARM_RANGE), forearm=size(FOREARM_RANGE), shoulder_height=size(SHOULDER_HEIGHT_RANGE),
                seat_back=round(_between(rng, 0.0, SEAT_BACK_MAX), 4),
                seat_side=round(_between(rng, -SEAT_SIDE_MAX, SEAT_SIDE_MAX), 4),
                rom=round(_between(rng, 0.05, ROM_MAX), 3) if rng.random() < P_ROM else 0.0)
    weak = rng.random() < P_WEAK
    tremor = rng.random() < P_TREMOR
    hesitant = rng.random() < P_HESITANT
    return Partner(
        seed=int(seed), body=body,
        speed_factor=round(_between(rng, 0.6, 0.9) if weak else _between(rng, 0.85, 1.2), 3),
        reaction_factor=round(_between(rng, 0.7, 1.6), 3),
        hesitation=round(_between(rng, 0.2, 1.0), 3) if hesitant else 0.0,
        drop_chance=round(_between(rng, 0.02, DROP_CHANCE_MAX), 3) if weak else 0.0,
        tremor_amplitude=round(_between(rng, 0.002, TREMOR_AMPLITUDE_MAX), 4) if tremor else 0.0,
        tremor_frequency=round(_between(rng, *TREMOR_FREQUENCY_RANGE), 2),
        **{f"hold_out_d{a}": round(_between(rng, -r, r), 4) for a, r in zip("xyz", HOLD_OUT_REGION)},
    )


def parse_seed_range(text: str, where: str, key: str) -> range:
    """``A:B``, population seeds A to B inclusive (0 <= A <= B); anything else is a `UserError` naming ``key``."""
    a, sep, b = str(text).partition(":")
    if not sep or not a.strip().isdigit() or not b.strip().isdigit() or int(b) < int(a):
        raise UserError(where, key, f"expected A:B (population seeds, 0 <= A <= B), got {text!r}")
    return range(int(a), int(b) + 1)


def check_convention(value: Any, where: str, key: str) -> str:
    """A grip convention's name (profiles.GRIP_CONVENTIONS); anything else is a `UserError` naming ``key``."""
    if str(value) not in GRIP_CONVENTIONS:
        raise UserError(where, key, f"unknown grip convention {value!r}; use one of {', '.join(GRIP_CONVENTIONS)}")
    return str(value)


def parse_partner(value: Any, where: str, key: str = "human.partner") -> Partner:
    """A scenario's ``human.partner``: an integer seed of the population, or a mapping of attributes (LIMITS),
    optionally with ``seed`` to start from that sampled person. Mistakes raise `UserError` naming the key."""
    if isinstance(value, bool):
        raise UserError(where, key, f"a partner seed (integer >= 0) or a mapping of attributes, got {value!r}")
    if isinstance(value, Partner):
        return value
    if (isinstance(value, (int, np.integer)) or (isinstance(value, float) and value.is_integer())
            or (isinstance(value, str) and value.strip().isdigit())):
        n = int(value)
        if n < 0:
            raise UserError(where, key, f"a partner seed is an integer >= 0, got {n}")
        return sample_partner(n)
    if not isinstance(value, Mapping):
        raise UserError(where, key, f"a partner seed (integer >= 0) or a mapping of attributes, got {value!r}")
    unknown = sorted(set(value) - {"seed", "grip_convention", *LIMITS})
    if unknown:
        raise UserError(where, f"{key}.{unknown[0]}",
                        f"unknown attribute; allowed: seed, grip_convention, {', '.join(LIMITS)}")
    base = parse_partner(value["seed"], where, f"{key}.seed") if "seed" in value else Partner()
    attrs = base.to_dict()
    if "grip_convention" in value:
        attrs["grip_convention"] = check_convention(value["grip_convention"], where, f"{key}.grip_convention")
    for k in LIMITS:
        if k not in value:
            continue
        v = value[k]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise UserError(where, f"{key}.{k}", f"expected a number, got {v!r}")
        lo, hi = LIMITS[k]
        if not lo - 1e-12 <= float(v) <= hi + 1e-12:
            raise UserError(where, f"{key}.{k}", f"between {lo:.4g} and {hi:.4g}, got {float(v):g}")
        attrs[k] = float(v)
    body = Body(**{k: attrs.pop(k) for k in BODY_KEYS})
    return Partner(body=body, **attrs)
