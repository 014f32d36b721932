"""What a sweep is: scenarios x a grid of parameter values x seeds, from the command line or a YAML file.

A parameter is a dotted path and a value spec:

    cognition.k=0.5,1,2                 a list (YAML scalars: numbers, words such as ag/sg)
    cognition.k=0.5:2:4                 a range: 4 evenly spaced values 0.5, 1, 1.5, 2 (ends included)
    cognition.k=0.1:10:3:log            the same with geometric spacing: 0.1, 1, 10
    human.reaction_delay=uniform(0.2,3)x4   4 random draws, seeded by --sample-seed and the path
    objects.glass.position=[-0.25,0.1],[-0.2,0.15]   object places as [x, y] pairs (table metres)
    objects.glass.position.x=-0.3:-0.2:3             or one coordinate, the other kept from the scenario
    agent=dnf,fsm                       the robot's mind (assistbot.agents), as the scenario key ``agent:``
    human.partner=randint(0,9999)x50    people of the partner population (assistbot.human.population), by seed;
                                        also 0:99:100 (partners 0 to 99)

Random specs: uniform(a,b), loguniform(a,b), normal(mean,sd), randint(a,b) (ends included),
choice(a|b|c), each followed by ``xN``. The same sample seed gives the same values, so a
sweep with random values resumes like any other.

A sweep file holds the same in YAML::

    scenarios: [paper-fig5]            # or  scenario: paper-fig5
    params:
      cognition.k: 0.6:1.4:3           # any value spec, or a YAML list
      human.reaction_delay: [0.3, 1.5, 3.0]
    seeds: 3                           # a count (scenario seed, +1, +2) or a list [0, 7, 9]
    perception: oracle                 # vision (default) or oracle
    time_limit: 120                    # optional: replaces the scenarios' time limits
    sample_seed: 0                     # optional: seeds the random value specs
    sample: 200                        # optional: run only this many of the grid's episodes (all seeds),
                                       #   drawn at random (seeded by sample_seed): a big space, sampled
    out: render/sweeps/k-delay         # optional: the results folder (relative to where you run)
"""

from __future__ import annotations

import difflib
import math
import re
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from assistbot import catalogue
from assistbot.episode.perturb import PERTURB_PARAMS, check_perturb_value
from assistbot.errors import UserError
from assistbot.scenario import VISION_PARAMS, check_vision_value

OBJECT_PATHS = tuple(f"objects.{o}.{k}" for o in catalogue.TASK_OBJECTS
                     for k in ("position", "position.x", "position.y", "zone", "state"))
#: paths that change the scenario itself rather than override a parameter: the partner's profile
SCENARIO_PATHS = ("human.profile", "agent")
FILE_KEYS = ("scenario", "scenarios", "params", "seeds", "perception", "time_limit", "sample_seed", "sample", "out")
PERCEPTIONS = ("vision", "oracle")
_RANDOM = re.compile(r"^\s*([a-z_]+)\s*\((.*)\)\s*[x×*]\s*(\d+)\s*$", re.IGNORECASE)
_DISTRIBUTIONS = ("uniform", "loguniform", "normal", "randint", "choice")


def valid_paths() -> list[str]:
    """Every parameter path a sweep may vary: the overrides' and the scenario's own."""
    from assistbot.episode.builder import override_paths

    return override_paths() + list(OBJECT_PATHS) + list(SCENARIO_PATHS)


def check_path(path: str, where: str) -> None:
    """Raise UserError naming the closest valid paths when ``path`` is not one."""
    paths = valid_paths()
    if path in paths:
        return
    close = difflib.get_close_matches(path, paths, n=3, cutoff=0.5)
    if not close:  # a typo in the last component: try among paths sharing the first component
        head = path.split(".", 1)[0]
        close = difflib.get_close_matches(path, [p for p in paths if p.startswith(head + ".")], n=3, cutoff=0.3)
    hint = f"; did you mean {', '.join(close)}?" if close else "; see the valid paths with 'assistbot sweep --list-paths'"
    raise UserError(where, path, "unknown parameter path" + hint)


def canon(value: Any) -> Any:
    """A value in the one form used for job ids, rows and overrides (floats with 10 significant digits)."""
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, (int, float)):
        v = float(value)
        rounded = float(f"{v:.10g}")
        return rounded if math.isfinite(rounded) else v    # the largest floats round up to infinity
    if isinstance(value, str):
        s = value.strip()
        try:
            return canon(float(s))
        except ValueError:
            return s
    if isinstance(value, (list, tuple)):
        return [canon(v) for v in value]
    if hasattr(value, "item"):  # numpy scalars
        return canon(value.item())
    return value


def _numbers(text: str, where: str, path: str, what: str) -> list[float]:
    out = []
    for part in text.split(","):
        try:
            out.append(float(part))
        except ValueError:
            raise UserError(where, path, f"{what}: {part.strip()!r} is not a number") from None
    return out


def _random_values(path: str, dist: str, args: str, n: int, where: str, sample_seed: int) -> list[Any]:
    import numpy as np

    dist = dist.lower()
    if dist not in _DISTRIBUTIONS:
        raise UserError(where, path, f"unknown random spec {dist}(...); use one of {', '.join(d + '(...)xN' for d in _DISTRIBUTIONS)}")
    if n < 1:
        raise UserError(where, path, f"{dist}(...)x{n}: draw at least one value")
    rng = np.random.default_rng([int(sample_seed), zlib.crc32(path.encode())])
    if dist == "choice":
        options = [canon(v) for v in args.split("|") if v.strip()]
        if not options:
            raise UserError(where, path, "choice(a|b|c)xN: give the options separated by |")
        return [options[i] for i in rng.integers(0, len(options), size=n)]
    nums = _numbers(args, where, path, f"{dist}(...)")
    if len(nums) != 2:
        raise UserError(where, path, f"{dist}(a,b)xN takes two numbers, got {len(nums)}")
    a, b = nums
    if dist == "normal":
        if b <= 0:
            raise UserError(where, path, f"normal(mean,sd)xN: sd must be > 0, got {b:g}")
        draws = rng.normal(a, b, size=n)
    else:
        ordered = a <= b if dist == "randint" else a < b
        if not ordered:
            raise UserError(where, path, f"{dist}(a,b)xN needs a < b, got {a:g}, {b:g}")
        if dist == "uniform":
            draws = rng.uniform(a, b, size=n)
        elif dist == "loguniform":
            if a <= 0:
                raise UserError(where, path, f"loguniform(a,b)xN needs 0 < a, got {a:g}")
            draws = np.exp(rng.uniform(math.log(a), math.log(b), size=n))
        else:
            if a != int(a) or b != int(b):
                raise UserError(where, path, f"randint(a,b)xN takes whole numbers, got {a:g}, {b:g}")
            draws = rng.integers(int(a), int(b) + 1, size=n)
    return [float(f"{float(v):.6g}") for v in draws]


def _range_values(path: str, text: str, where: str) -> list[float]:
    parts = [p.strip() for p in text.split(":")]
    log = len(parts) == 4 and parts[3].lower() == "log"
    if len(parts) != 3 and not log:
        raise UserError(where, path, f"a range is START:STOP:COUNT (or START:STOP:COUNT:log), got {text!r}")
    try:
        a, b = float(parts[0]), float(parts[1])
        n = float(parts[2])
    except ValueError:
        raise UserError(where, path, f"a range is START:STOP:COUNT with numbers, got {text!r}") from None
    if n != int(n) or n < 1:
        raise UserError(where, path, f"a range's COUNT is a whole number >= 1, got {parts[2]!r}")
    n = int(n)
    if n == 1:
        return [a]
    if log:
        if a <= 0 or b <= 0:
            raise UserError(where, path, f"a log range needs positive ends, got {text!r}")
        la, lb = math.log(a), math.log(b)
        return [math.exp(la + (lb - la) * i / (n - 1)) for i in range(n)]
    return [a + (b - a) * i / (n - 1) for i in range(n)]


def parse_values(path: str, spec: Any, where: str = "--param", sample_seed: int = 0) -> list[Any]:
    """A value spec (text, number or YAML list) -> the list of canonical values, duplicates removed."""
    if isinstance(spec, (list, tuple)):
        values = list(spec)
    elif isinstance(spec, (int, float)) and not isinstance(spec, bool):
        values = [spec]
    elif isinstance(spec, str):
        text = spec.strip()
        if not text:
            raise UserError(where, path, "no values given; e.g. 0.5,1,2 or 0.5:2:4 or uniform(0.5,2)x4")
        m = _RANDOM.match(text)
        if not m and re.match(r"^[a-z_]+\s*\(.*\)", text, re.IGNORECASE):
            raise UserError(where, path, f"a random spec ends with xN, the number of draws, e.g. uniform(0.5,2)x4; got {text!r}")
        if m:
            values = _random_values(path, m.group(1), m.group(2), int(m.group(3)), where, sample_seed)
        elif ":" in text and not text.startswith(("[", "{")):
            values = _range_values(path, text, where)
        else:
            try:
                loaded = yaml.safe_load("[" + text + "]")
            except yaml.YAMLError:
                raise UserError(where, path, f"cannot read the values {text!r}; e.g. 0.5,1,2 or 0.5:2:4 or uniform(0.5,2)x4") from None
            values = loaded
    else:
        raise UserError(where, path, f"expected values such as 0.5,1,2 or 0.5:2:4, got {spec!r}")
    out: list[Any] = []
    for v in values:
        c = canon(v)
        if isinstance(c, dict) or c is None:
            raise UserError(where, path, f"cannot use {v!r} as a value")
        if c not in out:
            out.append(c)
    if not out:
        raise UserError(where, path, "no values given")
    return out


def check_value(path: str, value: Any, where: str) -> Any:
    """Validate one value for a non-object path; return the value an episode override takes."""
    if path.startswith("cognition."):
        from assistbot.cognition.config import check_overrides

        check_overrides({path[len("cognition."):]: value}, where)
        return value
    if path == "agent":
        from assistbot.agents import agent_factory

        if not isinstance(value, str):
            raise UserError(where, path, f"must be an agent's name or package.module:factory, got {value!r}")
        agent_factory(value, where)
        return value
    if path == "human.profile":
        from assistbot.human.profiles import PROFILES

        if value not in PROFILES:
            raise UserError(where, path, f"unknown profile {value!r}; use one of {', '.join(PROFILES)}")
        return value
    if path == "human.partner":
        from assistbot.human.population import parse_partner

        parse_partner(value, where)
        return value      # the seed: rows and job ids name the partner by it
    if path.startswith("human."):
        from assistbot.human.script import check_param

        return check_param(path[len("human."):], value, where)
    if path in VISION_PARAMS:
        return check_vision_value(path, value, where)
    if path in PERTURB_PARAMS:
        return check_perturb_value(path, value, where)
    return value  # objects.*: checked against each scenario when the jobs are built


def is_scenario_path(path: str) -> bool:
    """A swept path that edits the scenario's mapping (objects, the partner's profile), not an override."""
    return path.startswith("objects.") or path in SCENARIO_PATHS


@dataclass(frozen=True)
class Param:
    """One swept parameter: its dotted path, its values, and the spec they came from."""

    path: str
    values: tuple
    spec: str = ""

    @classmethod
    def parse(cls, path: str, spec: Any, where: str = "--param", sample_seed: int = 0) -> "Param":
        path = str(path).strip()
        check_path(path, where)
        values = parse_values(path, spec, where, sample_seed)
        checked: list[Any] = []
        for v in values:
            if path.endswith(".position"):
                if not (isinstance(v, list) and len(v) == 2 and all(isinstance(c, float) for c in v)):
                    raise UserError(where, path, f"each value is an [x, y] pair in metres, e.g. [-0.25,0.1],[-0.2,0.15]; got {v!r}")
            elif path.endswith((".zone", ".state")) and path.startswith("objects."):
                if not isinstance(v, str):
                    raise UserError(where, path, f"each value is a word, got {v!r}")
            elif isinstance(v, list):
                raise UserError(where, path, f"takes single values, got the list {v!r}")
            else:
                v = canon(check_value(path, v, where))  # e.g. human.grip: side -> sg
            if v not in checked:
                checked.append(v)
        values = checked
        text = spec if isinstance(spec, str) else yaml.safe_dump(spec, default_flow_style=True).strip()
        return cls(path, tuple(tuple(v) if isinstance(v, list) else v for v in values), text)

    def value_list(self) -> list[Any]:
        return [list(v) if isinstance(v, tuple) else v for v in self.values]


def parse_param_arg(text: str, sample_seed: int = 0) -> Param:
    """``PATH=VALUES`` from the command line."""
    path, eq, spec = text.partition("=")
    if not eq or not path.strip():
        raise UserError("--param", text, "expected PATH=VALUES, e.g. cognition.k=0.5,1,2 or human.reaction_delay=0.2:3:4")
    return Param.parse(path.strip(), spec, "--param", sample_seed)


def parse_seeds(spec: Any, where: str = "--seeds") -> int | list[int]:
    """A count N (the scenario's seed and the N-1 after it) or an explicit list ``3,7,11`` (``7,`` for one)."""
    if isinstance(spec, bool):
        raise UserError(where, "seeds", f"a count or a list of seeds, got {spec!r}")
    if isinstance(spec, int):
        if spec < 1:
            raise UserError(where, "seeds", f"a count >= 1, got {spec}")
        return spec
    if isinstance(spec, (list, tuple)):
        items = list(spec)
    else:
        text = str(spec).strip()
        if "," not in text:
            try:
                n = int(text)
            except ValueError:
                raise UserError(where, "seeds", f"a count such as 3 or a list such as 0,4,9, got {text!r}") from None
            return parse_seeds(n, where)
        items = [p for p in text.split(",") if p.strip()]
    out = []
    for s in items:
        try:
            v = int(str(s).strip())
        except ValueError:
            raise UserError(where, "seeds", f"seeds are whole numbers >= 0, got {s!r}") from None
        if v < 0:
            raise UserError(where, "seeds", f"seeds are whole numbers >= 0, got {v}")
        if v not in out:
            out.append(v)
    if not out:
        raise UserError(where, "seeds", "give at least one seed")
    return out


@dataclass
class SweepSpec:
    """Scenarios x parameter grid x seeds, plus how each episode runs."""

    scenarios: list[str]
    params: list[Param] = field(default_factory=list)
    seeds: int | list[int] = 1
    perception: str = "vision"
    time_limit: float | None = None
    sample_seed: int = 0
    source: str = "--param"  # where mistakes are reported: --param or the sweep file
    out: str | None = None
    sample: int | None = None  # run only this many episodes of the grid x seeds, drawn with sample_seed

    def __post_init__(self) -> None:
        if not self.scenarios:
            raise UserError(self.source, "scenarios", "name at least one scenario (a file or a shipped name)")
        if self.perception not in PERCEPTIONS:
            raise UserError(self.source, "perception", f"use {' or '.join(PERCEPTIONS)}, got {self.perception!r}")
        if self.time_limit is not None:
            tl = self.time_limit
            if isinstance(tl, bool) or not isinstance(tl, (int, float)) or not 0 < tl <= 3600:
                raise UserError(self.source, "time_limit", f"simulated seconds in (0, 3600], got {tl!r}")
        if self.sample is not None and (isinstance(self.sample, bool) or not isinstance(self.sample, int) or self.sample < 1):
            raise UserError(self.source, "sample", f"a number of episodes >= 1, got {self.sample!r}")
        seen = set()
        for p in self.params:
            if p.path in seen:
                raise UserError(self.source, p.path, "given twice; list all its values in one spec")
            seen.add(p.path)

    def seeds_for(self, scenario_seed: int) -> list[int]:
        if isinstance(self.seeds, int):
            return [scenario_seed + i for i in range(self.seeds)]
        return list(self.seeds)

    def grid_size(self) -> int:
        n = 1
        for p in self.params:
            n *= len(p.values)
        return n

    def with_param(self, param: Param) -> None:
        """Add a parameter, replacing one with the same path (command-line --param over a sweep file)."""
        self.params = [p for p in self.params if p.path != param.path] + [param]

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"scenarios": list(self.scenarios),
                             "params": {p.path: p.value_list() for p in self.params},
                             "seeds": self.seeds, "perception": self.perception, "sample_seed": self.sample_seed}
        if self.time_limit is not None:
            d["time_limit"] = self.time_limit
        if self.sample is not None:
            d["sample"] = self.sample
        return d


def is_sweep_file(spec: str | Path) -> bool:
    """A YAML file whose mapping has ``params`` or ``scenarios`` and no ``objects`` (which scenarios have)."""
    p = Path(spec)
    if p.suffix not in (".yaml", ".yml") or not p.is_file():
        return False
    try:
        data = yaml.safe_load(p.read_text(encoding="utf-8"))
    except (OSError, yaml.YAMLError):
        return False
    return isinstance(data, dict) and "objects" not in data and bool({"params", "scenarios"} & set(data))


def load_sweep_file(path: str | Path, sample_seed: int | None = None) -> SweepSpec:
    """A sweep file; ``sample_seed`` (from the command line) replaces the file's."""
    p = Path(path)
    where = str(p)
    try:
        data = yaml.safe_load(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise UserError(where, "-", f"cannot read the file: {exc.strerror}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise UserError(where, f"line {mark.line + 1}" if mark else "-", f"not valid YAML: {getattr(exc, 'problem', exc)}") from None
    if sample_seed is not None and isinstance(data, dict):
        data = {**data, "sample_seed": sample_seed}
    return sweep_from_mapping(data, where, base=p.parent)


def sweep_from_mapping(data: Any, where: str, base: Path | None = None) -> SweepSpec:
    if not isinstance(data, dict):
        raise UserError(where, "-", "a sweep file is a YAML mapping with keys " + ", ".join(FILE_KEYS))
    for key in data:
        if key not in FILE_KEYS:
            close = difflib.get_close_matches(str(key), FILE_KEYS, n=1)
            hint = f"; did you mean {close[0]}?" if close else f"; allowed: {', '.join(FILE_KEYS)}"
            raise UserError(where, str(key), "unknown key" + hint)
    scen = data.get("scenarios", data.get("scenario"))
    if isinstance(scen, str):
        scen = [scen]
    if not isinstance(scen, list) or not scen or not all(isinstance(s, str) for s in scen):
        raise UserError(where, "scenarios", "a list of scenario names or files, e.g. [paper-fig5]")

    def resolve(s: str) -> str:  # scenario files named relative to the sweep file
        if base is not None and s.endswith((".yaml", ".yml")) and not Path(s).is_absolute() and (base / s).exists():
            return str(base / s)
        return s

    sample_seed = data.get("sample_seed", 0)
    if isinstance(sample_seed, bool) or not isinstance(sample_seed, int) or sample_seed < 0:
        raise UserError(where, "sample_seed", f"a whole number >= 0, got {sample_seed!r}")
    params_in = data.get("params") or {}
    if not isinstance(params_in, dict):
        raise UserError(where, "params", "a mapping of parameter paths to value specs, e.g. {cognition.k: 0.5:1.5:3}")
    params = [Param.parse(str(k), v, where, sample_seed) for k, v in params_in.items()]
    out = data.get("out")
    if out is not None and not isinstance(out, str):
        raise UserError(where, "out", "a folder path")
    return SweepSpec(scenarios=[resolve(s) for s in scen], params=params,
                     seeds=parse_seeds(data.get("seeds", 1), where), perception=str(data.get("perception", "vision")),
                     time_limit=data.get("time_limit"), sample_seed=sample_seed, source=where,
                     out=out, sample=data.get("sample"))
