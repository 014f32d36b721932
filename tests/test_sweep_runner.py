"""The sweep runner with a stand-in executor (no episodes): resume, crashed episodes, early stop, interrupt."""

from __future__ import annotations

import pytest

from _scenarios import TINY
from assistbot.errors import UserError
from assistbot.sweep import Param, SweepSpec, build_jobs, run_sweep
from assistbot.sweep.results import read_rows


class FakeExecutor:
    """Yields a made-up row per job; jobs whose seed is in ``crash_seeds`` raise; stops after ``stop_after``."""

    def __init__(self, crash_seeds=(), stop_after=None):
        self.crash_seeds = set(crash_seeds)
        self.stop_after = stop_after
        self.ran: list[str] = []
        self.closed = False

    def describe(self):
        return "fake"

    def run(self, jobs):
        for i, job in enumerate(jobs):
            if self.stop_after is not None and i == self.stop_after:
                raise KeyboardInterrupt
            self.ran.append(job.id)
            row = {"job_id": job.id, "scenario": job.scenario, **job.params, "seed": job.seed,
                   "perception": job.perception, "time_limit": job.time_limit}
            if job.seed in self.crash_seeds:
                yield {**row, "status": "crashed", "error": "RuntimeError: boom", "traceback": "x"}
            else:
                yield {**row, "status": "ok", "success": job.params["cognition.k"] > 1, "time_to_drink": 10.0 * job.seed,
                       "end_reason": "drink", "decisions": "A > B", "n_decisions": 2, "errors_communicated": 0,
                       "spilled_fraction": 0.0, "min_distance_human": 0.3, "sim_time": 3.0, "wall_seconds": 1.0,
                       "cpu_seconds": 1.0, "scenario_sha": job.scenario_sha}

    def close(self):
        self.closed = True


@pytest.fixture
def spec(tmp_path):
    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    return SweepSpec(scenarios=[str(p)], seeds=3, perception="oracle",
                     params=[Param.parse("cognition.k", "0.8,1.2"), Param.parse("human.reaction_delay", "0.2,1")])


def test_crashed_episodes_go_to_errors_csv_and_run_again_on_resume(spec, tmp_path):
    out = tmp_path / "out"
    ex = FakeExecutor(crash_seeds={1})
    o = run_sweep(spec, out, executor=ex, progress=False, log=lambda m: None)
    assert (o.total, o.ran, o.crashed, o.complete) == (12, 8, 4, False) and ex.closed
    _, rows = read_rows(out / "results.csv")
    assert len(rows) == 8 and {r["seed"] for r in rows} == {"0", "2"}
    _, errors = read_rows(out / "errors.csv")
    assert len(errors) == 4 and errors[0]["error"] == "RuntimeError: boom"
    ex2 = FakeExecutor()
    o2 = run_sweep(spec, out, executor=ex2, progress=False, log=lambda m: None)
    assert (o2.skipped, o2.ran, o2.crashed, o2.complete) == (8, 4, 0, True)
    crashed_ids = {j.id for j in build_jobs(spec) if j.seed == 1}
    assert set(ex2.ran) == crashed_ids
    _, rows2 = read_rows(out / "results.csv")
    assert rows2[:8] == rows and len({r["job_id"] for r in rows2}) == 12


def test_a_sweep_whose_first_episodes_all_raise_stops_early(spec, tmp_path):
    ex = FakeExecutor(crash_seeds={0, 1, 2})
    o = run_sweep(spec, tmp_path / "out", executor=ex, progress=False, log=lambda m: None)
    assert o.aborted and "boom" in o.aborted and len(ex.ran) == 4 and o.ran == 0


def test_interrupt_saves_what_finished_and_tells_the_outcome(spec, tmp_path):
    out = tmp_path / "out"
    with pytest.raises(KeyboardInterrupt) as e:
        run_sweep(spec, out, executor=FakeExecutor(stop_after=5), progress=False, log=lambda m: None)
    assert e.value.outcome.ran == 5 and e.value.outcome.interrupted
    import pyarrow.parquet as pq

    assert pq.read_table(out / "results.parquet").num_rows == 5
    o = run_sweep(spec, out, executor=FakeExecutor(), progress=False, log=lambda m: None)
    assert (o.skipped, o.ran) == (5, 7)


def test_two_different_scenarios_with_one_name_are_refused(spec, tmp_path):
    other = tmp_path / "other.yaml"
    other.write_text(TINY.replace("passive", "active"))
    spec.scenarios.append(str(other))
    with pytest.raises(UserError, match="rows are told apart by scenario name"):
        build_jobs(spec)
    spec.scenarios[-1] = spec.scenarios[0]  # the same one twice is just deduplicated
    assert len(build_jobs(spec)) == 12


def test_report_on_fake_results(spec, tmp_path):
    from assistbot.sweep import write_report

    out = tmp_path / "out"
    run_sweep(spec, out, executor=FakeExecutor(), progress=False, log=lambda m: None)
    paths = write_report(out)
    md = paths[0].read_text()
    assert "6/12 drank" in md  # k = 1.2 drinks
    assert "| 1.2 | 6 | 6 | 1.00 |" in md and "| 0.8 | 6 | 0 | 0.00 |" in md
    assert "time to drink 10.0 s [" in md  # seeds 0, 1, 2 -> 0, 10, 20 s
    page = paths[1].read_text()
    assert paths[1].name == "report.html" and "<table>" in page and "<h2>Episodes</h2>" in page
    assert page.count("<tr class=") == 12 and "--keep-runs" in page     # no run folders kept: no links


def test_report_counts_the_expected_decision_sequence(spec, tmp_path):
    from assistbot.sweep import write_report

    out = tmp_path / "out"
    run_sweep(spec, out, executor=FakeExecutor(), progress=False, log=lambda m: None)
    md = write_report(out, expect="A > B")[0].read_text()
    assert "## Expected decision sequence" in md and "| 0.8 | 6 | 6 | 1.00 |" in md
    md = write_report(out, expect="A")[0].read_text()
    assert "| 0.8 | 6 | 0 | 0.00 |" in md.split("## Expected decision sequence")[1]
    md = write_report(out, expect="A > ...")[0].read_text()  # a prefix
    assert "| 0.8 | 6 | 6 | 1.00 |" in md.split("## Expected decision sequence")[1]


class MatrixExecutor(FakeExecutor):
    """Rows of a task-space sweep: the passive partner never drinks with the glass on their side (stalled);
    one active episode touches the person 2 cm deep."""

    def run(self, jobs):
        for job in jobs:
            self.ran.append(job.id)
            p = job.params
            fail = p["human.profile"] == "passive" and p["objects.glass.zone"] == "HWS"
            deep = p["human.profile"] == "active" and p["objects.glass.zone"] == "RWS" and job.seed == 0
            yield {"job_id": job.id, "scenario": job.scenario, **p, "seed": job.seed, "perception": job.perception,
                   "time_limit": job.time_limit, "status": "ok", "success": not fail, "time_to_drink": None if fail else 50.0,
                   "end_reason": "stalled" if fail else "drink", "end_detail": "", "decisions": "A", "n_decisions": 1,
                   "n_failed_actions": 0, "errors_communicated": 0, "spilled_fraction": 0.0, "min_distance_human": 0.2,
                   "touched_person": deep, "touch_depth": 0.02 if deep else 0.0, "touch_force": 0.0, "sim_time": 50.0,
                   "wall_seconds": 1.0, "cpu_seconds": 1.0, "scenario_sha": job.scenario_sha}


def test_the_task_space_report_gives_arrangements_profiles_and_failure_kinds(tmp_path):
    from assistbot.sweep import write_report

    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    spec = SweepSpec(scenarios=[str(p)], seeds=2, perception="oracle",
                     params=[Param.parse("objects.glass.zone", "HWS,RWS"), Param.parse("objects.glass.state", "empty"),
                             Param.parse("objects.bottle.zone", "RWS"), Param.parse("objects.bottle.state", "open"),
                             Param.parse("human.profile", "active,passive")])
    jobs = build_jobs(spec)
    assert {j.scenario_data["human"]["profile"] for j in jobs} == {"active", "passive"}
    assert all("human.profile" not in j.overrides for j in jobs)
    out = tmp_path / "out"
    run_sweep(spec, out, executor=MatrixExecutor(), progress=False, log=lambda m: None)
    md = write_report(out)[0].read_text()
    assert "## Per arrangement" in md and "| bottle RWS open, glass HWS empty | 4 | 2 | 0.50 |" in md
    assert "| bottle RWS open, glass HWS empty | 2/2 | **0/2** |" in md   # active, passive
    assert "pairs where fewer than two thirds drank: 1 of 4" in md
    assert "| stalled | 2 | 0.25 |" in md
    assert "| overlap with the person > 1 cm | 1 | 2.0 cm |" in md
    with pytest.raises(UserError, match="unknown profile"):
        Param.parse("human.profile", "lazy")


class AgentExecutor(FakeExecutor):
    """Rows of an agent comparison: the fsm fails once the cue comes 1 s late or later, with a failed action."""

    def run(self, jobs):
        for job in jobs:
            self.ran.append(job.id)
            p = job.params
            fail = p.get("agent") == "fsm" and p["perturb.cue_delay"] >= 1
            yield {"job_id": job.id, "scenario": job.scenario, **p, "seed": job.seed, "perception": job.perception,
                   "time_limit": job.time_limit, "status": "ok", "success": not fail, "time_to_drink": None if fail else 40.0,
                   "end_reason": "repeating" if fail else "drink", "end_detail": "", "decisions": "A", "n_decisions": 1,
                   "n_failed_actions": 2 if fail else 0, "errors_communicated": 0, "answered_cues": 1 if fail else 3,
                   "ignored_cues": 3 if fail else 1, "uncued_decisions": 2 if fail else 0, "spilled_fraction": 0.0,
                   "min_distance_human": 0.2, "touched_person": False, "touch_depth": 0.0, "touch_force": 0.0,
                   "sim_time": 40.0, "wall_seconds": 1.0, "cpu_seconds": 1.0, "scenario_sha": job.scenario_sha}


def test_report_by_agent_splits_each_perturbation_by_agent(tmp_path):
    from assistbot.sweep import write_report

    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    spec = SweepSpec(scenarios=[str(p)], seeds=2, perception="oracle",
                     params=[Param.parse("agent", "dnf,fsm"), Param.parse("perturb.cue_delay", "0,1,2")])
    out = tmp_path / "out"
    run_sweep(spec, out, executor=AgentExecutor(), progress=False, log=lambda m: None)
    paths = write_report(out, by="agent")
    md = paths[0].read_text()
    assert "### perturb.cue_delay, by agent" in md
    assert "| 0 | fsm | 2 | 2 | 1.00 |" in md and "| 1 | fsm | 2 | 0 | 0.00 |" in md and "| 2 | dnf | 2 | 2 | 1.00 |" in md
    assert "| 1 | fsm | 2 | 0 | 0.00 | [0.00, 0.66] | – | – | 2.00 |" in md   # failed actions per episode
    # then errors communicated, the share of cued decisions that ignored the cue, decisions without a cue
    assert "| 1 | fsm | 2 | 0 | 0.00 | [0.00, 0.66] | – | – | 2.00 | 0.00 | 0.75 | 2.00 |" in md
    assert "| 1 | dnf | 2 | 2 | 1.00 | [0.34, 1.00] | 40.0 | [40.0, 40.0] | 0.00 | 0.00 | 0.25 | 0.00 |" in md
    assert any(x.name == "success_vs_perturb.cue_delay.png" for x in paths)
    with pytest.raises(UserError, match="--by: human.profile: not a swept parameter.*agent, perturb.cue_delay"):
        write_report(out, by="human.profile")


def test_the_overview_puts_several_sweeps_side_by_side_by_agent(tmp_path):
    """Two sweeps of one comparison (one per perturbation): one table each in overview.md, one column each in
    overview.png; from the command line, several folders without --by are refused with exit 2."""
    import subprocess
    import sys

    from assistbot.sweep.overview import write_overview

    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    dirs = []
    for name, levels in (("late", "0,1"), ("later", "0,2")):
        spec = SweepSpec(scenarios=[str(p)], seeds=1, perception="oracle",
                         params=[Param.parse("agent", "dnf,fsm"), Param.parse("perturb.cue_delay", levels)])
        dirs.append(tmp_path / name)
        run_sweep(spec, dirs[-1], executor=AgentExecutor(), progress=False, log=lambda m: None)
    md_path, png = write_overview(dirs, "agent", tmp_path / "overview")
    md = md_path.read_text()
    assert md.index("## late") < md.index("## later")
    late, later = md.split("## later")
    assert "| 1 | fsm | 1 | 0 | 0.00 |" in late and "| 2 | fsm |" not in late
    assert "| 2 | fsm | 1 | 0 | 0.00 | [0.00, 0.79] | – | – | 2.00 |" in later and "| 0 | dnf | 1 | 1 | 1.00 |" in later
    assert png.stat().st_size > 10_000
    r = subprocess.run([sys.executable, "-m", "assistbot.cli", "report", *map(str, dirs)], capture_output=True, text=True)
    assert r.returncode == 2 and "--by" in r.stderr and "Traceback" not in r.stderr
    with pytest.raises(UserError, match="human.profile is not a swept parameter"):
        write_overview(dirs, "human.profile", tmp_path / "o2")


def test_a_results_folder_of_another_version_is_refused_with_the_reason(tmp_path):
    """Resuming into a folder whose results lack a column this version writes: said so, not a crash; the folder
    is left as it was."""
    from assistbot.sweep.results import ResultStore, columns_for

    ours = columns_for(["agent"])
    old = [c for c in ours if c not in ("answered_cues", "ignored_cues", "uncued_decisions")]
    (tmp_path / "results.csv").write_text(",".join(old) + "\n")
    before = (tmp_path / "results.csv").read_bytes()
    with pytest.raises(UserError, match="written by another version of assistbot.*another --out"):
        ResultStore(tmp_path, ours).open()
    with pytest.raises(UserError, match="holds a sweep over agent, this one sweeps human.profile"):
        ResultStore(tmp_path, columns_for(["human.profile"])).open()
    assert (tmp_path / "results.csv").read_bytes() == before


class PartnerExecutor(AgentExecutor):
    """Rows of a partner sweep: partners with a tremor fail, the others drink."""

    def run(self, jobs):
        from assistbot.human.population import parse_partner

        for row in super().run(jobs):
            fail = parse_partner(row["human.partner"], "test").tremor_amplitude > 0
            row.update(success=not fail, time_to_drink=None if fail else 40.0, end_reason="stalled" if fail else "drink")
            yield row


def test_a_partner_sweep_is_sampled_from_its_grid_and_reported_by_partner_attribute(tmp_path):
    from assistbot.human.population import sample_partner
    from assistbot.sweep import write_report

    p = tmp_path / "tiny.yaml"
    p.write_text(TINY)
    spec = SweepSpec(scenarios=[str(p)], seeds=1, perception="oracle", sample=12, sample_seed=3,
                     params=[Param.parse("human.partner", "1000:1019:20"), Param.parse("human.profile", "active,passive")])
    jobs = build_jobs(spec)
    assert len(jobs) == 12 and [j.id for j in jobs] == [j.id for j in build_jobs(spec)]      # the same draw each time
    assert len({(j.params["human.partner"], j.params["human.profile"]) for j in jobs}) == 12
    out = tmp_path / "out"
    run_sweep(spec, out, executor=PartnerExecutor(), progress=False, log=lambda m: None)
    md = write_report(out)[0].read_text()
    trembling = sum(sample_partner(int(j.params["human.partner"])).tremor_amplitude > 0 for j in jobs)
    assert 0 < trembling < 12
    assert f"| tremor | yes | {trembling} | 0 | 0.00 |" in md
    assert f"| tremor | no | {12 - trembling} | {12 - trembling} | 1.00 |" in md
    assert "## human.partner" not in md           # by attribute, not a row per partner
    with pytest.raises(UserError, match="sample"):
        SweepSpec(scenarios=[str(p)], sample=0)
