"""Sweep specs without running episodes: value specs, paths, jobs and ids, results files, statistics, CLI errors."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest

from _scenarios import TINY
from assistbot.errors import UserError
from assistbot.sweep import Param, SweepSpec, build_jobs, job_id, parse_seeds, parse_values
from assistbot.sweep.results import ResultStore, columns_for, read_rows
from assistbot.sweep.spec import load_sweep_file
from assistbot.sweep.stats import mean_ci, wilson


@pytest.fixture
def tiny(tmp_path):
    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    return p


def cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "assistbot.cli", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=120)


# -- value specs -----------------------------------------------------------------------------------
def test_lists_ranges_and_log_ranges():
    assert parse_values("cognition.k", "0.5,1,2") == [0.5, 1.0, 2.0]
    assert parse_values("cognition.k", "0.5:2:4") == [0.5, 1.0, 1.5, 2.0]
    assert parse_values("cognition.k", "0.1:0.3:3") == [0.1, 0.2, 0.3]  # no 0.30000000000000004
    assert parse_values("cognition.k", "0.1:10:3:log") == [0.1, 1.0, 10.0]
    assert parse_values("cognition.k", "1e-3,2") == [0.001, 2.0]
    assert parse_values("human.grip", "ag,sg,ag") == ["ag", "sg"]
    assert parse_values("objects.glass.position", "[-0.2,0.1],[-0.3,0.2]") == [[-0.2, 0.1], [-0.3, 0.2]]
    assert parse_values("cognition.k", [1, 2]) == [1.0, 2.0]


def test_random_specs_are_seeded_by_sample_seed_and_path():
    a = parse_values("cognition.k", "uniform(0.5,2)x4", sample_seed=0)
    assert len(a) == 4 and all(0.5 <= v <= 2 for v in a)
    assert parse_values("cognition.k", "uniform(0.5,2)x4", sample_seed=0) == a
    assert parse_values("cognition.k", "uniform(0.5,2)x4", sample_seed=1) != a
    assert parse_values("human.speed", "uniform(0.5,2)x4", sample_seed=0) != a
    assert all(0.1 <= v <= 10 for v in parse_values("cognition.k", "loguniform(0.1,10)x5"))
    assert set(parse_values("cognition.k", "randint(1,3)x20")) <= {1.0, 2.0, 3.0}
    assert set(parse_values("human.grip", "choice(ag|sg)x10")) <= {"ag", "sg"}


@pytest.mark.parametrize("spec, message", [
    ("0.5:2", "START:STOP:COUNT"),
    ("0.5:2:x", "START:STOP:COUNT"),
    ("0.5:2:2.5", "whole number"),
    ("gauss(0,1)x3", "unknown random spec"),
    ("uniform(2,1)x3", "a < b"),
    ("uniform(1)x3", "two numbers"),
    ("", "no values"),
])
def test_bad_value_specs_name_the_problem(spec, message):
    with pytest.raises(UserError) as e:
        Param.parse("cognition.k", spec)
    assert message in e.value.message and e.value.key == "cognition.k"


def test_unknown_paths_list_the_closest_valid_ones():
    with pytest.raises(UserError) as e:
        Param.parse("cognition.kk", "1")
    assert "unknown parameter path" in e.value.message and "cognition.k" in e.value.message
    with pytest.raises(UserError) as e:
        Param.parse("human.reaction_dealy", "1")
    assert "human.reaction_delay" in e.value.message
    with pytest.raises(UserError) as e:
        Param.parse("objects.glass.positon", "[0,0]")
    assert "objects.glass.position" in e.value.message


def test_values_are_checked_by_their_owners():
    with pytest.raises(UserError, match="between 0.02 and 1.0"):
        Param.parse("human.speed", "0.5,5")
    with pytest.raises(UserError, match=r"\[0, 1\)"):
        Param.parse("vision.dropout", "0.2,1.5")
    with pytest.raises(UserError, match="must be a number"):
        Param.parse("cognition.k", "fast")
    assert Param.parse("human.grip", "ag,side,sg").values == ("ag", "sg")  # one spelling per grip


def test_seeds():
    assert parse_seeds("3") == 3
    assert parse_seeds("0,4,9") == [0, 4, 9]
    assert parse_seeds("7,") == [7]
    for bad in ("0", "x", "1,-2"):
        with pytest.raises(UserError):
            parse_seeds(bad)


# -- jobs ---------------------------------------------------------------------------------------------
def test_grid_times_seeds_gives_jobs_with_stable_distinct_ids(tiny):
    spec = SweepSpec(scenarios=[str(tiny)], seeds=2, perception="oracle",
                     params=[Param.parse("cognition.k", "0.8,1.2"), Param.parse("human.reaction_delay", "0.2:1:2")])
    jobs = build_jobs(spec)
    assert len(jobs) == 8 and len({j.id for j in jobs}) == 8
    assert [j.id for j in build_jobs(spec)] == [j.id for j in jobs]
    assert {j.seed for j in jobs} == {0, 1}
    j = jobs[0]
    assert j.id == job_id("tiny", {"cognition.k": 0.8, "human.reaction_delay": 0.2}, 0, "oracle", 3.0)
    assert j.overrides == {"cognition.k": 0.8, "human.reaction_delay": 0.2}
    # the id does not depend on how a value was written, nor on the order of the parameters
    same = SweepSpec(scenarios=[str(tiny)], seeds=[0], perception="oracle",
                     params=[Param.parse("human.reaction_delay", "0.2"), Param.parse("cognition.k", "0.80")])
    assert build_jobs(same)[0].id == j.id
    # extending a sweep keeps the ids of the jobs it had
    more = SweepSpec(scenarios=[str(tiny)], seeds=3, perception="oracle",
                     params=[Param.parse("cognition.k", "0.8,1.2,1.6"), Param.parse("human.reaction_delay", "0.2:1:2")])
    assert {j.id for j in jobs} < {j.id for j in build_jobs(more)}


def test_object_positions_build_a_modified_valid_scenario(tiny):
    spec = SweepSpec(scenarios=[str(tiny)], perception="oracle",
                     params=[Param.parse("objects.glass.position", "[-0.25,0.1],[-0.3,0.2]"),
                             Param.parse("objects.bottle.position.y", "0.0,0.1")])
    jobs = build_jobs(spec)
    assert len(jobs) == 4
    glass = [j.scenario_data["objects"]["glass"]["position"] for j in jobs]
    assert [-0.25, 0.1] in glass and [-0.3, 0.2] in glass
    bottle = {tuple(j.scenario_data["objects"]["bottle"]["position"]) for j in jobs}
    assert bottle == {(0.2, 0.0), (0.2, 0.1)}  # x kept from the RWS default place
    assert all(not k.startswith("objects.") for j in jobs for k in j.overrides)
    from assistbot.scenario import parse_scenario

    assert parse_scenario(jobs[0].scenario_data).objects.glass.position == (-0.25, 0.1)


def test_object_position_in_the_wrong_half_names_path_value_and_scenario(tiny):
    spec = SweepSpec(scenarios=[str(tiny)], perception="oracle", params=[Param.parse("objects.glass.position.x", "-0.2,0.2")])
    with pytest.raises(UserError) as e:
        build_jobs(spec)
    assert e.value.key == "objects.glass.position" and "0.2" in e.value.message and "tiny" in e.value.message


def test_sweep_file(tmp_path, tiny):
    f = tmp_path / "s.yaml"
    f.write_text("scenarios: [tiny.yaml]\nparams:\n  cognition.k: 0.8:1.2:2\n  human.reaction_delay: [0.2, 1]\n"
                 "seeds: 2\nperception: oracle\ntime_limit: 2\n")
    spec = load_sweep_file(f)
    assert spec.scenarios == [str(tiny)] and spec.grid_size() == 4 and spec.time_limit == 2
    assert len(build_jobs(spec)) == 8
    f.write_text("scenarios: [tiny.yaml]\nparms: {}\n")
    with pytest.raises(UserError, match="did you mean params"):
        load_sweep_file(f)


# -- results files --------------------------------------------------------------------------------------
def test_store_repairs_a_torn_last_line_and_refuses_other_parameters(tmp_path):
    cols = columns_for(["cognition.k"])
    store = ResultStore(tmp_path, cols)
    assert store.open() == {}
    store.append({"job_id": "a1", "scenario": "s", "cognition.k": 0.5, "seed": 0, "success": True, "time_to_drink": 12.5})
    store.close()
    with open(tmp_path / "results.csv", "a") as fh:
        fh.write("b2,s,0.7,1,ora")  # a kill in the middle of a write
    store = ResultStore(tmp_path, cols)
    done = store.open()
    assert list(done) == ["a1"] and done["a1"]["time_to_drink"] == "12.5"
    store.close()
    assert (tmp_path / "results.csv").read_text().endswith("\n")
    import pyarrow.parquet as pq

    t = pq.read_table(tmp_path / "results.parquet")
    assert t.num_rows == 1 and t.column("success").to_pylist() == [True]
    with pytest.raises(UserError, match="sweeps human.speed"):
        ResultStore(tmp_path, columns_for(["human.speed"])).open()
    header, rows = read_rows(tmp_path / "results.csv")
    assert header == cols and len(rows) == 1


# -- statistics -----------------------------------------------------------------------------------------
def test_wilson_and_mean_intervals():
    lo, hi = wilson(5, 10)
    assert lo == pytest.approx(0.2366, abs=1e-4) and hi == pytest.approx(0.7634, abs=1e-4)
    lo, hi = wilson(0, 10)
    assert lo == 0.0 and hi == pytest.approx(0.2775, abs=1e-4)
    assert wilson(0, 0) == (0.0, 1.0)
    for n in range(1, 40):  # the ends are exact: a rate of 0 or 1 is inside its interval, never by -1e-17
        assert wilson(0, n)[0] == 0.0 and wilson(n, n)[1] == 1.0
        for s in range(n + 1):
            lo, hi = wilson(s, n)
            assert lo <= s / n <= hi
    m, lo, hi = mean_ci([1.0, 2.0, 3.0])
    assert m == 2.0 and lo == pytest.approx(2 - 2.4842, abs=1e-3) and hi == pytest.approx(2 + 2.4842, abs=1e-3)


# -- the command line: bad specs are one line and exit 2 ---------------------------------------------------
def _free_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


@pytest.mark.parametrize("args, expect", [
    (["--param", "cognition.kk=1,2"], "cognition.kk: unknown parameter path; did you mean cognition.k"),
    (["--param", "human.reaction_dealy=1"], "did you mean human.reaction_delay"),
    (["--param", "cognition.k=0.5:2"], "cognition.k: a range is START:STOP:COUNT"),
    (["--param", "cognition.k=uniform(1,2)"], "a random spec ends with xN"),
    (["--param", "cognition.k=[1,2"], "cannot read the values"),
    (["--param", "human.speed=3"], "human.speed: mean hand speed"),
    (["--param", "cognition.k"], "expected PATH=VALUES"),
    (["--param", "objects.glass.position.x=0.2"], "is not in the HWS"),
    (["--seeds", "many"], "seeds"),
    (["--address", "auto"], "add --executor ray"),
    (["--executor", "ray", "--address", "127.0.0.1:{port}"], "--address: 127.0.0.1:{port}: no Ray cluster there"),
])
def test_bad_specs_exit_2_with_one_line(tiny, tmp_path, args, expect):
    port = _free_port()
    args = [a.format(port=port) for a in args]
    r = cli("sweep", tiny, "--perception", "oracle", "--out", tmp_path / "out", *args)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert expect.format(port=port) in lines[0]
    assert "Traceback" not in r.stderr
    assert not (tmp_path / "out" / "results.csv").exists() or "address" in " ".join(args)


def test_dry_run_lists_the_jobs(tiny, tmp_path):
    r = cli("sweep", tiny, "--param", "cognition.k=0.8,1.2", "--param", "human.reaction_delay=0.2:1:2", "--seeds", "2",
            "--perception", "oracle", "--out", tmp_path / "out", "--dry-run")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("8 episodes (0 done")
    assert r.stdout.count(" todo ") == 8


def test_list_paths():
    r = cli("sweep", "--list-paths")
    assert r.returncode == 0
    paths = r.stdout.split()
    assert "cognition.k" in paths and "human.reaction_delay" in paths and "objects.glass.position" in paths
