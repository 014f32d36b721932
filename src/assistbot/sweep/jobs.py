"""A sweep's episodes: one `Job` per scenario x grid point x seed, each with a stable id.

The id is a hash of what decides the episode's outcome as the sweep names it
(scenario name, swept parameter values, seed, perception, time limit), so the
same command builds the same ids and a resumed sweep skips the rows it has.
A job carries the scenario's YAML mapping (with swept object places applied)
rather than a file path, so that it runs unchanged on another machine.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import zlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.sweep.spec import SweepSpec


@dataclass(frozen=True)
class Job:
    id: str
    scenario: str
    params: dict[str, Any]  # every swept path -> its value in this job
    seed: int
    perception: str
    time_limit: float
    scenario_data: dict[str, Any] = field(repr=False, default_factory=dict)  # the scenario mapping to run
    scenario_path: str | None = None
    scenario_sha: str = ""
    overrides: dict[str, Any] = field(default_factory=dict)  # non-object params, as episode overrides
    run_dir: str | None = None  # with --keep-runs: the episode's own run folder (as `assistbot run` writes one)


def job_id(scenario: str, params: dict[str, Any], seed: int, perception: str, time_limit: float) -> str:
    key = {"scenario": scenario, "params": {k: params[k] for k in sorted(params)}, "seed": int(seed),
           "perception": perception, "time_limit": float(time_limit)}
    return hashlib.sha1(json.dumps(key, sort_keys=True).encode()).hexdigest()[:12]


def scenario_sha(data: dict[str, Any]) -> str:
    return hashlib.sha1(json.dumps(data, sort_keys=True, default=str).encode()).hexdigest()[:10]


def _objects_mapping(scenario) -> dict[str, dict[str, Any]]:
    arr = scenario.objects
    out = {}
    for name in catalogue.TASK_OBJECTS:
        p = arr.placement(name)
        entry: dict[str, Any] = {"zone": p.zone, "state": p.state}
        if p.position is not None:
            entry["position"] = [float(c) for c in p.position]
        out[name] = entry
    return out


def apply_object_params(scenario, values: dict[str, Any], where: str) -> dict[str, Any] | None:
    """The scenario's ``objects`` mapping with swept zones, states and places; None when nothing is swept there.

    Raises UserError naming the path, the value and the scenario when the result is not a valid
    arrangement (off the table, in the wrong half, overlapping), as `assistbot.world.Arrangement` says.
    """
    from assistbot.world import Arrangement

    obj_values = {k: v for k, v in values.items() if k.startswith("objects.")}
    if not obj_values:
        return None
    mapping = _objects_mapping(scenario)
    # zone and state first: a coordinate falls back on the (possibly new) zone's default place
    for path in sorted(obj_values, key=lambda p: ("position" in p, p)):
        _, name, key = path.split(".", 2)
        v = obj_values[path]
        if key in ("zone", "state"):
            mapping[name][key] = v
            if key == "zone":
                mapping[name].pop("position", None)
        elif key == "position":
            mapping[name]["position"] = [float(c) for c in v]
        else:
            if "position" not in mapping[name]:
                zone_only = Arrangement.from_mapping({n: {k: e[k] for k in ("zone", "state")} for n, e in mapping.items()}, where)
                mapping[name]["position"] = list(zone_only.position(name))
            mapping[name]["position"][0 if key == "position.x" else 1] = float(v)
    try:
        Arrangement.from_mapping(mapping, where)
    except UserError as exc:
        shown = ", ".join(f"{k}={json.dumps(v)}" for k, v in sorted(obj_values.items()))
        raise UserError(where, exc.key, f"{shown} in scenario {scenario.name}: {exc.message}") from None
    return mapping


def scenario_data_with(scenario, values: dict[str, Any], where: str) -> dict[str, Any]:
    """The scenario's mapping with the values of the paths that edit it (`is_scenario_path`: objects, the
    partner's profile, the agent) set; the other paths are overrides and are left out."""
    from assistbot.sweep.spec import check_value

    data = copy.deepcopy(scenario.raw)
    objects = apply_object_params(scenario, values, where)
    if objects is not None:
        data["objects"] = objects
    if "human.profile" in values:
        data["human"] = {**(data.get("human") or {}), "profile": check_value("human.profile", values["human.profile"], where)}
    if "agent" in values:
        data["agent"] = check_value("agent", values["agent"], where)
    return data


def build_jobs(spec: SweepSpec) -> list[Job]:
    """Every episode of the sweep, seeds outermost (each full pass over the grid is one seed); with
    ``spec.sample``, that many of them drawn at random (seeded by ``spec.sample_seed``), in the same order."""
    from assistbot.scenario import load_scenario
    from assistbot.sweep.spec import check_value, is_scenario_path

    jobs: list[Job] = []
    paths = [p.path for p in spec.params]
    grid = list(itertools.product(*(p.values for p in spec.params))) if spec.params else [()]
    names: dict[str, tuple[str, str]] = {}  # scenario name -> (as given, content hash)
    for name in spec.scenarios:
        scenario = load_scenario(name)
        base = copy.deepcopy(scenario.raw)
        sha = scenario_sha(base)
        if scenario.name in names:
            if names[scenario.name][1] == sha:
                continue  # the same scenario named twice
            raise UserError(spec.source, name, f"is also named {scenario.name!r}, like {names[scenario.name][0]}; "
                            "rows are told apart by scenario name: give one of them another name")
        names[scenario.name] = (name, sha)
        tl = float(spec.time_limit if spec.time_limit is not None else scenario.time_limit)
        points = []
        for combo in grid:
            values = {path: (list(v) if isinstance(v, tuple) else v) for path, v in zip(paths, combo)}
            data = scenario_data_with(scenario, values, spec.source)
            data["time_limit"] = tl
            overrides = {k: check_value(k, v, spec.source) for k, v in values.items() if not is_scenario_path(k)}
            points.append((values, data, overrides))
        for seed in spec.seeds_for(scenario.seed):
            for values, data, overrides in points:
                jid = job_id(scenario.name, values, seed, spec.perception, tl)
                jobs.append(Job(id=jid, scenario=scenario.name, params=values, seed=seed, perception=spec.perception,
                                time_limit=tl, scenario_data=data,
                                scenario_path=str(scenario.path) if scenario.path else None,
                                scenario_sha=sha, overrides=overrides))
    if spec.sample is not None and spec.sample < len(jobs):
        rng = np.random.default_rng([spec.sample_seed, zlib.crc32(b"sample")])
        jobs = [jobs[i] for i in sorted(rng.choice(len(jobs), size=spec.sample, replace=False))]
    return jobs
