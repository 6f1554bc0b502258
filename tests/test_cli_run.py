"""pge run SCRIPT --record FILE --until T: the run is recorded to FILE and the simulation stops at T."""

from __future__ import annotations

import pytest

import pge
from pge.classic import reset
from pge.classic.session import STATE
from pge.cli import main
from pge.recording import open_recording

GAME = """\
import pge
pge.interactive()
pge.box(0.0, 0.0, 1.0, 0.05, pge.rgb(0.2, 0.3, 0.4)).fix()
ball = pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0, 0)).mass(1)
pge.gravity()
pge.at_time(0.2, lambda e, o: None)
pge.run({duration})
print("after run", pge.get_time(), ball.get_ypos())
"""


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """A temporary working directory, a fresh headless session, PGE_HEADLESS restored afterwards."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("PGE_HEADLESS", "1")
    reset()
    yield tmp_path
    reset()


def _script(directory, duration=3, extra=""):
    path = directory / "game.py"
    path.write_text(GAME.format(duration=duration) + extra)
    return path


def test_record_and_until_give_a_recording_of_exactly_that_span(workdir, capsys):
    """--record out.pgerec --until 0.5 on a script that asks for 3 s: 51 frames up to 0.5 s, events included."""
    script = _script(workdir)
    assert main(["run", "--headless", "--record", "out.pgerec", "--until", "0.5", str(script)]) == 0
    captured = capsys.readouterr()
    assert "after run 0.5 " in captured.out and "recording written to out.pgerec" in captured.err
    recording = open_recording(workdir / "out.pgerec")
    assert recording.complete and recording.duration == 0.5 and recording.end_time == 0.5
    assert len(recording) == 51 and recording.frame(50).time == pytest.approx(0.5, abs=1e-12)
    assert recording.event_counts == {"collisions": 1, "timers": 1}
    frame = recording.frame(20)
    assert tuple(frame.circles.centres[0]) == (0.5, 0.5 - 0.5 * 9.81 * frame.time**2)
    assert sorted(p.name for p in workdir.iterdir()) == ["game.py", "out.pgerec"]  # no output.pgerec


def test_until_ends_a_script_that_runs_in_a_loop(workdir, capsys):
    """A script calling run() forever stops at --until: the run reaching T returns, the next one ends the script."""
    script = _script(
        workdir, duration=0.25, extra="while True:\n    pge.run(0.25)\n    print('tick', pge.get_time())\n"
    )
    assert main(["run", "--headless", "--until", "0.75", str(script)]) == 0
    out = capsys.readouterr().out.split()
    ticks = [float(out[k + 1]) for k, word in enumerate(out) if word == "tick"]
    assert ticks == [0.5, 0.75]
    assert STATE.until == float("inf")  # the limit applied to that script only


def test_until_longer_than_the_script_changes_nothing(workdir, capsys):
    """--until beyond what the script asks for leaves its run as it is."""
    script = _script(workdir, duration=0.2)
    assert main(["run", "--headless", "--record", "short.pgerec", "--until", "5", str(script)]) == 0
    assert "after run 0.2 " in capsys.readouterr().out
    recording = open_recording(workdir / "short.pgerec")
    assert recording.end_time == pytest.approx(0.2) and len(recording) == 21


def test_record_redirects_a_script_that_records_itself(workdir, capsys):
    """A script calling pge.record() writes to the --record path, not output.pgerec."""
    path = workdir / "game.py"
    path.write_text("import pge\npge.record()\n" + GAME.format(duration=0.3).split("\n", 1)[1])
    assert main(["run", "--headless", "--record", "mine.pgerec", str(path)]) == 0
    assert not (workdir / "output.pgerec").exists()
    assert len(open_recording(workdir / "mine.pgerec")) == 31


def test_nothing_recorded_when_the_script_never_runs(workdir, capsys):
    """A script that never calls run() leaves no file, and pge run says so."""
    path = workdir / "idle.py"
    path.write_text("import pge\npge.circle(0.5, 0.5, 0.1, pge.white())\n")
    assert main(["run", "--headless", "--record", "idle.pgerec", str(path)]) == 0
    assert "nothing recorded" in capsys.readouterr().err
    assert not (workdir / "idle.pgerec").exists()


def test_run_option_errors_are_one_line(workdir, capsys):
    """A negative --until, a --record in a missing directory and a missing script give one line each."""
    script = _script(workdir)
    cases = [
        (["run", "--until", "-1", str(script)], 2, "--until"),
        (["run", "--until", "soon", str(script)], 2, "--until"),
        (["run", "--record", str(workdir / "no" / "x.pgerec"), str(script)], 1, "does not exist"),
        (["run", "--record", "x.pgerec", str(workdir / "nope.py")], 1, "nope.py: no such file"),
    ]
    for argv, expected, fragment in cases:
        code = main(argv)
        err = capsys.readouterr().err.strip().splitlines()
        assert code == expected and len(err) == 1 and err[0].startswith("pge: error: ") and fragment in err[0], err
    assert not list(workdir.glob("*.pgerec"))


def test_run_options_limit_the_facade_run_loop(workdir):
    """run_options(until=T) caps every run() of the classic facade at T; reset() lifts it."""
    from pge.classic.runloop import run_options

    run_options(until=0.3)
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.1, 0.0)
    pge.run(10)
    assert pge.get_time() == 0.3
    with pytest.raises(SystemExit):
        pge.run(1)
    with pytest.raises(ValueError, match="until must not be negative"):
        run_options(until=-1)
    reset()
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1)
    pge.run(0.5)
    assert pge.get_time() == 0.5
