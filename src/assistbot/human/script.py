"""The ``human:`` block of a scenario file: profile, parameters and a script of steps.

Schema (YAML)::

    human:
      profile: active            # active | passive | slow
      reaction_delay: 0.8        # optional overrides of the profile's parameters
      speed: 0.2                 # mean hand speed, m/s
      grip: ag                   # preferred grip for hand-overs: ag | sg
      grip_convention: seed      # what the grips mean: seed (hand over from above, pour from the side) |
                                 #   swapped (hand over from the side, pour from above); sets grip
      wrong_grip: 0.3            # chance of first trying the other grip (default policy)
      hesitation: 0.0            # s of pause before each motion
      hold_out_dx: 0.0           # where things are held out: m from the nominal point (x, y within
      hold_out_dy: 0.0           #   ±0.08, z within ±0.06)
      hold_out_dz: 0.0
      drop_chance: 0.0           # chance of letting go of an object just lifted (weakness)
      tremor_amplitude: 0.0      # m, a tremor of the hand (tremor_frequency: Hz, 4-8)
      partner: 12                # a person of the population (human.population): a seed, or a mapping
                                 #   of attributes {upper_arm: 1.05, rom: 0.2, ...}; the parameters above
                                 #   still override what the partner changes of the profile
      script:                    # optional; an active human without one uses its default policy
        - {do: grasp, object: bottle, grip: side, hold_out: true}
        - {do: put_down, object: bottle, at: [-0.25, -0.15]}
        - {do: request, gesture: open_hand}
        - {do: wait, seconds: 2}
        - {do: pull_stopper, after: {robot_said: "invite:remove_stopper"}}
        - {do: drink, after: glass_full}

Steps: grasp (object, grip, hold_out), hold_out, put_down (object, at), hand_over (object,
grip), take (object), request (gesture: open_hand), point (object), pull_stopper,
turn_glass, pour (grip), drink, wait (seconds).  Grips: ag/above, sg/side.  ``after:`` one event:
``robot_said: <tag>``, ``robot_holds: <object>``, ``robot_offers: <object>``,
``robot_requests``, ``stopper_removed``, ``glass_full``, ``glass_upright``,
``time: <s>``, ``done: <step>``.  Mistakes raise `UserError(where, key, message)`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.human.population import LIMITS as PARTNER_LIMITS, Partner, check_convention, parse_partner
from assistbot.human.profiles import HOLD_OUT_REGION, PROFILES, Profile

OBJECTS = catalogue.TASK_OBJECTS
GRIPS = {"ag": "ag", "above": "ag", "sg": "sg", "side": "sg"}
#: step -> (behaviour, allowed keys, required keys)
STEPS: dict[str, tuple[str, tuple[str, ...], tuple[str, ...]]] = {
    "grasp": ("grasp", ("object", "grip", "hold_out"), ("object",)),
    "hold_out": ("hold_out", ("object",), ()),
    "put_down": ("put_down", ("object", "at"), ()),
    "hand_over": ("hand_to_robot", ("object", "grip"), ("object",)),
    "take": ("take_from_robot", ("object",), ()),
    "request": ("request", ("gesture", "hold"), ()),
    "point": ("point", ("object",), ("object",)),
    "pull_stopper": ("pull_stopper", (), ()),
    "turn_glass": ("turn_glass", (), ()),
    "pour": ("pour", ("grip",), ()),
    "drink": ("drink", (), ()),
    "wait": ("wait", ("seconds",), ("seconds",)),
}
EVENTS_WITH_OBJECT = ("robot_holds", "robot_offers")
EVENTS_PLAIN = ("robot_requests", "stopper_removed", "glass_full", "glass_upright")
EVENTS = ("robot_said", *EVENTS_WITH_OBJECT, *EVENTS_PLAIN, "time", "done")
PARAMS = ("reaction_delay", "speed", "grip", "grip_convention", "wrong_grip", "hesitation", "hold_out_dx", "hold_out_dy", "hold_out_dz",
          "drop_chance", "tremor_amplitude", "tremor_frequency", "partner")


def _known_tags() -> set[str]:
    from assistbot.task.drinking import UTTERANCES

    return {u.tag for pool in UTTERANCES.values() for u in pool.values()}


@dataclass(frozen=True)
class Step:
    do: str
    args: dict = field(default_factory=dict)
    after: tuple[str, Any] | None = None

    @property
    def behaviour(self) -> str:
        return STEPS[self.do][0]

    def behaviour_args(self, profile: Profile) -> dict:
        a = dict(self.args)
        if self.do in ("grasp", "hand_over"):
            a["grip"] = GRIPS[a.get("grip", profile.grip)]
        if self.do == "pour":
            a["grip"] = GRIPS[a.get("grip", profile.pour_grip)]
        if self.do == "request":
            a.pop("gesture", None)
        if "at" in a:
            a["at"] = tuple(a["at"])
        return a


@dataclass(frozen=True)
class HumanConfig:
    profile: str = "active"
    overrides: dict = field(default_factory=dict)
    script: tuple[Step, ...] = ()

    @property
    def partner(self) -> Partner:
        """The person: the population's (``human.partner``), else the default person."""
        return self.overrides.get("partner") or Partner()

    def profile_params(self) -> Profile:
        """The profile as this person behaves: the partner's changes, then the scenario's own parameters."""
        params = {k: v for k, v in self.overrides.items() if k != "partner"}
        return self.partner.profile(PROFILES[self.profile]).with_(**params)


def parse_human(mapping: Any, where: str = "scenario") -> HumanConfig:
    """Validate a scenario's ``human:`` mapping; raise UserError naming the key of the first mistake."""
    if mapping is None:
        return HumanConfig()
    if not isinstance(mapping, Mapping):
        raise UserError(where, "human", "must be a mapping (profile, script, ...)")
    unknown = sorted(set(mapping) - {"profile", "script", *PARAMS})
    if unknown:
        raise UserError(where, f"human.{unknown[0]}", f"unknown key; allowed: profile, script, {', '.join(PARAMS)}")
    profile = str(mapping.get("profile", "active"))
    if profile not in PROFILES:
        raise UserError(where, "human.profile", f"unknown profile {profile!r}; use one of {', '.join(PROFILES)}")
    overrides = {k: check_param(k, mapping[k], where) for k in PARAMS if k in mapping}
    script = mapping.get("script", [])
    if script is None:
        script = []
    if not isinstance(script, list):
        raise UserError(where, "human.script", "must be a list of steps such as {do: grasp, object: bottle}")
    steps = tuple(_parse_step(s, where, f"human.script[{i}]") for i, s in enumerate(script))
    return HumanConfig(profile, overrides, steps)


def check_param(k: str, v: Any, where: str) -> Any:
    """One of the person's parameters (PARAMS), checked; the value the person takes (a grip's short name, else
    a float). The one check for a scenario's ``human:`` block, ``--set human.*`` and a sweep's values."""
    if k == "partner":
        return parse_partner(v, where)
    if k == "grip_convention":
        return check_convention(v, where, "human.grip_convention")
    if k == "grip":
        if str(v).lower() not in GRIPS:
            raise UserError(where, "human.grip", f"unknown grip {v!r}; use ag (above) or sg (side)")
        return GRIPS[str(v).lower()]
    if isinstance(v, bool) or not isinstance(v, (int, float, str)):
        raise UserError(where, f"human.{k}", f"expected a number, got {v!r}")
    try:
        v = float(v)
    except ValueError:      # text that is no number
        raise UserError(where, f"human.{k}", f"expected a number, got {v!r}") from None
    if k == "wrong_grip" and not 0.0 <= v <= 1.0:
        raise UserError(where, "human.wrong_grip", f"a chance between 0 and 1, got {v:g}")
    if k == "speed" and not 0.02 <= v <= 1.0:
        raise UserError(where, "human.speed", f"mean hand speed in m/s between 0.02 and 1.0, got {v:g}")
    if k in ("reaction_delay", "hesitation") and not 0.0 <= v <= 10.0:
        raise UserError(where, f"human.{k}", f"seconds between 0 and 10, got {v:g}")
    if k in ("drop_chance", "tremor_amplitude", "tremor_frequency"):
        lo, hi = PARTNER_LIMITS[k]
        if not lo <= v <= hi:
            raise UserError(where, f"human.{k}", f"between {lo:g} and {hi:g}, got {v:g}")
    if k.startswith("hold_out_d"):
        limit = HOLD_OUT_REGION["xyz".index(k[-1])]
        if not -limit <= v <= limit:
            raise UserError(where, f"human.{k}", f"metres from the nominal hold-out point within ±{limit:g}, got {v:g}")
    return v


def _parse_step(s: Any, where: str, key: str) -> Step:
    if not isinstance(s, Mapping) or "do" not in s:
        raise UserError(where, key, "each step is a mapping with a 'do' key, e.g. {do: grasp, object: bottle}")
    do = str(s["do"])
    if do not in STEPS:
        raise UserError(where, f"{key}.do", f"unknown step {do!r}; use one of {', '.join(STEPS)}")
    _, allowed, required = STEPS[do]
    extra = sorted(set(s) - {"do", "after", *allowed})
    if extra:
        raise UserError(where, f"{key}.{extra[0]}", f"unknown key for {do}; allowed: {', '.join(allowed) or '(none)'}, after")
    for r in required:
        if r not in s:
            raise UserError(where, f"{key}.{r}", f"missing; {do} needs {', '.join(required)}")
    args = {k: s[k] for k in allowed if k in s}
    if "object" in args and args["object"] not in OBJECTS:
        raise UserError(where, f"{key}.object", f"unknown object {args['object']!r}; the scene has {', '.join(OBJECTS)}")
    if "grip" in args:
        g = str(args["grip"]).lower()
        if g not in GRIPS:
            raise UserError(where, f"{key}.grip", f"unknown grip {args['grip']!r}; use ag/above or sg/side")
        args["grip"] = GRIPS[g]
    if "hold_out" in args and not isinstance(args["hold_out"], bool):
        raise UserError(where, f"{key}.hold_out", "true or false")
    if "gesture" in args and args["gesture"] != "open_hand":
        raise UserError(where, f"{key}.gesture", f"unknown gesture {args['gesture']!r}; use open_hand")
    for k in ("seconds", "hold"):
        if k in args:
            try:
                args[k] = float(args[k])
            except (TypeError, ValueError):
                raise UserError(where, f"{key}.{k}", f"expected seconds, got {args[k]!r}") from None
            if args[k] < 0:
                raise UserError(where, f"{key}.{k}", "must be >= 0")
    if "at" in args:
        try:
            x, y = (float(v) for v in args["at"])
        except (TypeError, ValueError):
            raise UserError(where, f"{key}.at", f"expected table coordinates [x, y] in metres, got {args['at']!r}") from None
        if x >= 0.0:
            raise UserError(where, f"{key}.at", f"x = {x:g} is in the RWS; the human acts in the HWS only (x < 0)")
        if not (-0.40 < x and -0.55 < y < 0.55):
            raise UserError(where, f"{key}.at", f"({x:g}, {y:g}) is off the table")
        args["at"] = (x, y)
    return Step(do, args, _parse_after(s.get("after"), where, f"{key}.after"))


def _parse_after(a: Any, where: str, key: str) -> tuple[str, Any] | None:
    if a is None:
        return None
    if isinstance(a, str):
        if a in EVENTS_PLAIN:
            return (a, None)
        raise UserError(where, key, f"unknown event {a!r}; use one of {', '.join(EVENTS)}")
    if not isinstance(a, Mapping) or len(a) != 1:
        raise UserError(where, key, "one event, e.g. {robot_said: 'invite:remove_stopper'} or stopper_removed")
    (kind, arg), = a.items()
    if kind not in EVENTS:
        raise UserError(where, key, f"unknown event {kind!r}; use one of {', '.join(EVENTS)}")
    if kind == "robot_said":
        tags = _known_tags()
        if arg not in tags:
            raise UserError(where, f"{key}.robot_said", f"unknown utterance tag {arg!r}; e.g. {', '.join(sorted(tags)[:4])}, ...")
    elif kind in EVENTS_WITH_OBJECT:
        if arg not in OBJECTS:
            raise UserError(where, f"{key}.{kind}", f"unknown object {arg!r}; the scene has {', '.join(OBJECTS)}")
    elif kind == "time":
        try:
            arg = float(arg)
        except (TypeError, ValueError):
            raise UserError(where, f"{key}.time", f"expected seconds, got {arg!r}") from None
    elif kind == "done":
        if arg not in STEPS:
            raise UserError(where, f"{key}.done", f"unknown step {arg!r}; use one of {', '.join(STEPS)}")
        arg = STEPS[arg][0]
    else:
        arg = None
    return (kind, arg)
