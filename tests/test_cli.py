"""The command line as a user meets it: help, one-line errors with exit 2, the fields demo."""

from __future__ import annotations

import subprocess
import sys

from assistbot.cli import main


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "assistbot.cli", *args], capture_output=True, text=True)


def test_help_exits_zero_and_lists_commands():
    r = run_cli("--help")
    assert r.returncode == 0
    assert "fields-demo" in r.stdout


def test_bad_option_is_one_line_and_exit_two():
    r = run_cli("fields-demo", "--no-such-option")
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert "--no-such-option" in lines[0]
    assert "Traceback" not in r.stderr


def test_unknown_command_is_one_line_and_exit_two():
    r = run_cli("fly")
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "fly" in r.stderr


def test_bad_choice_names_the_option():
    r = run_cli("fields-demo", "--backend", "gpu")
    assert r.returncode == 2
    assert r.stderr.startswith("error: assistbot fields-demo: --backend")


def test_fields_demo_writes_its_plots(tmp_path, capsys):
    assert main(["fields-demo", "--out", str(tmp_path / "demo"), "--backend", "numpy"]) == 0
    names = sorted(p.name for p in (tmp_path / "demo").glob("*.png"))
    assert names == ["choice.png", "goal.png", "memory.png", "plane.png", "readout_x.png", "selection.png", "sensor.png",
                     "source_1.png", "source_2.png", "target.png", "weights.png"]
    assert str(tmp_path / "demo") in capsys.readouterr().out


def test_field_error_from_a_command_becomes_one_line(monkeypatch, capsys):
    import assistbot.fields.demo as demo
    from assistbot.fields import FieldError

    def broken(*_a, **_k):
        raise FieldError("field 'X'", "tau", "must be > 0, got -1")

    monkeypatch.setattr(demo, "run_demo", broken)
    assert main(["fields-demo"]) == 2
    assert capsys.readouterr().err == "error: field 'X': tau: must be > 0, got -1\n"


def test_a_reader_that_stops_reading_gets_no_traceback():
    """`assistbot list | head -1`: the pipe closes before the listing is written; the command ends quietly."""
    p = subprocess.Popen([sys.executable, "-m", "assistbot.cli", "list"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()                    # before the command has imported, let alone written anything
    err = p.stderr.read().decode()
    assert p.wait(timeout=60) == 1
    assert "Traceback" not in err and "BrokenPipeError" not in err, err
