"""Property tests of what users type: scenario files, `--set` and `--param` values, generated valid and invalid.

Every invalid input ends in one line ``error: <file or option>: <key>: <message>``, exit status 2, no
traceback, and no output folder; every valid scenario loads and builds its episode (stopped just before it
runs). The failures these tests found are kept in tests/corpus/ and replayed by
`test_the_corpus_of_found_failures_stays_fixed`.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
from pathlib import Path
from unittest import mock

import pytest
import yaml
from hypothesis import HealthCheck, given, settings, strategies as st

from assistbot import catalogue, cli
from assistbot.episode.builder import override_paths, split_overrides
from assistbot.episode.runner import Episode
from assistbot.errors import UserError
from assistbot.human.profiles import PROFILES
from assistbot.sweep.spec import canon, check_value, parse_param_arg
from assistbot.world import layout

CORPUS = Path(__file__).parent / "corpus"
SETTINGS = settings(max_examples=100, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


@contextlib.contextmanager
def _fresh():
    """A new empty folder for one generated example (pytest's tmp_path is shared by all of a test's examples)."""
    with tempfile.TemporaryDirectory() as d:
        yield Path(d)


#: a small valid scenario
SMALL = {"name": "t", "objects": {"bottle": {"zone": "RWS", "state": "closed"}, "glass": {"zone": "HWS", "state": "empty"}},
         "human": {"profile": "passive"}}


class _Built(Exception):
    """Raised instead of running the episode: everything before it (loading, checking, building) succeeded."""


def _run_cli(args: list[str]) -> tuple[int, str]:
    """`assistbot ARGS` in this process with the episode itself replaced by `_Built`: (exit status, stderr)."""
    err = io.StringIO()

    def built(self, progress=None):
        raise _Built

    with mock.patch.object(Episode, "run", built), contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = cli.main(args)
        except _Built:
            status = None
    return status, err.getvalue()


# -- generated scenarios ------------------------------------------------------------------------------------
def _placements():
    return st.fixed_dictionaries({
        name: st.fixed_dictionaries({"zone": st.sampled_from(layout.ZONES), "state": st.sampled_from(catalogue.STATES[name])})
        for name in catalogue.TASK_OBJECTS})


@st.composite
def valid_scenarios(draw) -> dict:
    data = {"name": draw(st.from_regex(r"[a-z][a-z0-9_-]{0,11}", fullmatch=True)),
            "seed": draw(st.integers(0, 2**63)),
            "time_limit": draw(st.floats(0.1, 3600)),
            "objects": draw(_placements()),
            "human": {"profile": draw(st.sampled_from(list(PROFILES)))}}
    if draw(st.booleans()):
        data["human"]["speed"] = draw(st.floats(0.02, 1.0))
    if draw(st.booleans()):
        data["human"]["partner"] = draw(st.integers(0, 10**6) | st.fixed_dictionaries(
            {}, optional={"seed": st.integers(0, 10**6), "upper_arm": st.floats(0.86, 1.12), "rom": st.floats(0.0, 0.3)}))
    overrides = draw(st.fixed_dictionaries({}, optional={"vision.dropout": st.floats(0.0, 0.9),
                                                         "human.hesitation": st.floats(0.0, 10.0),
                                                         "perturb.cue_delay": st.floats(0.0, 5.0)}))
    if overrides:
        data["overrides"] = overrides
    return data


#: values of every kind a user's file might hold where something else was meant
JUNK = st.one_of(st.none(), st.booleans(), st.integers(-2**80, 2**80), st.floats(allow_nan=True, allow_infinity=True),
                 st.text(max_size=12), st.lists(st.integers(-3, 3), max_size=3),
                 st.dictionaries(st.text(max_size=4), st.integers(), max_size=2))


def _leaf_paths(data, prefix=()) -> list[tuple]:
    out = [prefix] if prefix else []
    if isinstance(data, dict):
        for k, v in data.items():
            out += _leaf_paths(v, prefix + (k,))
    return out


def _some_key(draw, data: dict) -> tuple[dict, str]:
    """A key anywhere in the nested mapping ``data``, drawn: (the mapping holding it, the key)."""
    path = draw(st.sampled_from(_leaf_paths(data)))
    parent = data
    for k in path[:-1]:
        parent = parent[k]
    return parent, path[-1]


@st.composite
def mutated_scenarios(draw) -> dict:
    """A valid scenario with one thing wrong (or, by chance, still right): a value replaced, a key removed or
    added, or an object placed off the table or in the other half."""
    data = draw(valid_scenarios())
    kind = draw(st.sampled_from(["replace", "delete", "add", "position"]))
    if kind == "position":
        name = draw(st.sampled_from(catalogue.TASK_OBJECTS))
        xy = draw(st.lists(st.floats(-2.0, 2.0) | st.floats(allow_nan=True, allow_infinity=True), min_size=2, max_size=2))
        data["objects"][name]["position"] = xy
        return data
    parent, key = _some_key(draw, data)
    if kind == "replace":
        parent[key] = draw(JUNK)
    elif kind == "delete":
        del parent[key]
    else:
        parent[draw(st.text(min_size=1, max_size=8))] = draw(JUNK)
    return data


def _expect_one_line(status, err: str, where: str, out: Path) -> None:
    assert "Traceback" not in err, err
    assert status == 2, (status, err)
    assert err.endswith("\n") and err.count("\n") == 1, err
    assert err.startswith(f"error: {where}"), err
    assert not out.exists(), "an output folder was made for input that was refused"


@settings(SETTINGS, max_examples=12)
@given(data=valid_scenarios())
def test_every_valid_scenario_loads_and_builds_its_episode(data):
    with _fresh() as tmp:
        path = tmp / "s.yaml"
        path.write_text(yaml.safe_dump(data))
        status, err = _run_cli(["run", str(path), "--out", str(tmp / "out"), "--no-video", "--perception", "oracle"])
    assert status is None, err


@SETTINGS
@given(data=mutated_scenarios())
def test_a_scenario_with_a_mistake_is_one_line_naming_the_file(data):
    try:
        text = yaml.safe_dump(data)
    except yaml.representer.RepresenterError:
        return
    with _fresh() as tmp:
        path, out = tmp / "s.yaml", tmp / "out"
        path.write_text(text)
        status, err = _run_cli(["run", str(path), "--out", str(out), "--no-video", "--perception", "oracle"])
        if status is not None:    # else the mutation left a valid scenario, and it built
            _expect_one_line(status, err, str(path), out)


@SETTINGS
@given(blob=st.binary(max_size=64) | st.text(max_size=40).map(str.encode))
def test_a_file_that_is_not_a_scenario_is_one_line(blob):
    with _fresh() as tmp:
        path, out = tmp / "s.yaml", tmp / "out"
        path.write_bytes(blob)
        status, err = _run_cli(["run", str(path), "--out", str(out), "--no-video", "--perception", "oracle"])
        _expect_one_line(status, err, str(path), out)


# -- sweep files ------------------------------------------------------------------------------------------------
@st.composite
def sweep_files(draw) -> dict:
    """A sweep file over the small scenario `s.yaml` beside it, maybe with one thing wrong."""
    data = {"scenario": "s.yaml", "params": {draw(PATHS): draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=3))},
            "seeds": draw(st.integers(1, 3)), "perception": draw(st.sampled_from(["vision", "oracle"]))}
    if draw(st.booleans()):
        parent, key = _some_key(draw, data)
        parent[key] = draw(JUNK)
    return data


@SETTINGS
@given(data=sweep_files())
def test_a_sweep_file_is_listed_or_refused_in_one_line(data):
    try:
        text = yaml.safe_dump(data)
    except yaml.representer.RepresenterError:
        return
    with _fresh() as tmp:
        (tmp / "s.yaml").write_text(yaml.safe_dump(SMALL))
        path, out = tmp / "sweep.yaml", tmp / "out"
        path.write_text(text)
        status, err = _run_cli(["sweep", str(path), "--out", str(out), "--dry-run"])
        if status != 0:
            _expect_one_line(status, err, "", out)


# -- --set and --param -----------------------------------------------------------------------------------------
#: text a user might type after PATH=
VALUE_TEXT = st.one_of(st.text(max_size=10), st.floats(allow_nan=True, allow_infinity=True).map(repr),
                       st.integers(-10**30, 10**30).map(str), st.sampled_from([".nan", "-.inf", "1e400", "[1, 2]", "{a: 1}", "", "~"]))


def _run_with_set(tmp: Path, assignment: str) -> tuple[int | None, str, Path]:
    """`assistbot run` of a small valid scenario with ``--set ASSIGNMENT``: (status, stderr, the output folder)."""
    scenario, out = tmp / "s.yaml", tmp / "out"
    scenario.write_text(yaml.safe_dump(SMALL))
    status, err = _run_cli(["run", str(scenario), "--out", str(out), "--no-video", "--perception", "oracle", "--set", assignment])
    return status, err, out


#: a path of each part as likely as one of the field architecture's many
PATHS = (st.sampled_from([p for p in override_paths() if p.startswith("cognition.")])
         | st.sampled_from([p for p in override_paths() if not p.startswith("cognition.")]))


@settings(SETTINGS, max_examples=50)    # a value taken builds a whole episode
@given(path=PATHS, value=VALUE_TEXT)
def test_a_set_value_is_taken_or_refused_in_one_line(path, value):
    with _fresh() as tmp:
        status, err, out = _run_with_set(tmp, f"{path}={value}")
        if status is not None:
            _expect_one_line(status, err, f"--set: {path}: ", out)
            return
    # taken: then a sweep takes it too (one check per part, whichever way the value came)
    check_value(path, canon(yaml.safe_load(value)), "sweep")


@SETTINGS
@given(path=PATHS, values=st.lists(VALUE_TEXT, min_size=1, max_size=3))
def test_a_swept_value_is_refused_in_one_line_or_taken_by_the_episode_too(path, values):
    """What `--param` accepts, an episode's overrides accept: a sweep never fails in its workers."""
    text = f"{path}=" + ",".join(values)
    try:
        param = parse_param_arg(text)
    except UserError as exc:
        assert exc.where == "--param" and "\n" not in exc.line()
        return
    for v in param.value_list():
        split_overrides({path: v}, "sweep")


# -- the corpus ----------------------------------------------------------------------------------------------
def _corpus_cases() -> list[Path]:
    return sorted((CORPUS / "scenarios").glob("*"))


@pytest.mark.parametrize("path", _corpus_cases(), ids=lambda p: p.name)
def test_the_corpus_of_found_failures_stays_fixed(tmp_path, path):
    out = tmp_path / "out"
    status, err = _run_cli(["run", str(path), "--out", str(out), "--no-video", "--perception", "oracle"])
    _expect_one_line(status, err, str(path), out)


@pytest.mark.parametrize("line", [ln for ln in (CORPUS / "set-values.txt").read_text().splitlines() if ln and not ln.startswith("#")]
                         if (CORPUS / "set-values.txt").exists() else [])
def test_the_corpus_of_found_set_values_stays_fixed(tmp_path, line):
    status, err, out = _run_with_set(tmp_path, line)
    _expect_one_line(status, err, f"--set: {line.partition('=')[0]}: ", out)
