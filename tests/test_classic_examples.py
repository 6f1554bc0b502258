"""Every example in examples/ runs headless to completion, writes no file, and its result makes sense."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
NAMES = ["ball_in_a_box", "breakout", "bagatelle", "snooker", "matchsticks", "rotation", "springs_chain", "toppling"]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """Run all examples at once (PGE_HEADLESS=1, each in an empty directory); name -> (process, fields, dir)."""
    env = {key: value for key, value in os.environ.items() if not key.startswith("SDL_")}
    env["PGE_HEADLESS"] = "1"
    running = {}
    for name in NAMES:
        where = tmp_path_factory.mktemp(name)
        process = subprocess.Popen(
            [sys.executable, str(EXAMPLES / f"{name}.py")],
            cwd=where,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        running[name] = (process, where)
    done = {}
    for name, (process, where) in running.items():
        out, err = process.communicate(timeout=240)
        lines = [line for line in out.splitlines() if line.startswith("RESULT ")]
        fields = dict(item.split("=", 1) for item in lines[-1].split()[1:]) if lines else {}
        done[name] = (process.returncode, err, fields, where)
    return done


def ran(results, name) -> dict:
    code, err, fields, where = results[name]
    assert code == 0, err
    assert fields.get("example") == name
    assert list(where.iterdir()) == []  # headless runs write no file (no output.raw)
    return fields


def test_every_example_is_tested():
    """The list of tested examples is the examples directory (less the World API's notebook demo,
    which tests/test_view.py runs)."""
    assert sorted(NAMES) == sorted(p.stem for p in EXAMPLES.glob("*.py") if p.stem != "notebook_demo")


def test_ball_in_a_box(results):
    """The balls bounced many times, are all inside the box and kept their energy (elasticity 1)."""
    fields = ran(results, "ball_in_a_box")
    assert fields["inside"] == "True"
    assert abs(float(fields["energy_drift"])) < 1e-9
    assert int(fields["wall_bounces"]) > 50 and int(fields["ball_bounces"]) > 0
    assert float(fields["time"]) == 10.0
    assert int(fields["frames"]) == 1000 + int(fields["wall_bounces"]) + int(fields["ball_bounces"])


def test_breakout(results):
    """Bricks left plus bricks knocked out is 27, some were knocked out, one ball per life lost."""
    fields = ran(results, "breakout")
    bricks, knocked, lives, balls = (int(fields[k]) for k in ("bricks", "knocked", "lives", "balls"))
    assert bricks + knocked == 27 and knocked > 0
    assert 0 <= lives <= 3
    assert balls == (3 if lives == 0 else 1 + 3 - lives)
    assert int(fields["seconds"]) == 20


def test_bagatelle(results):
    """Every launched ball was scored or is still in play; the score adds up cup values."""
    fields = ran(results, "bagatelle")
    launched, scored, in_play, score = (int(fields[k]) for k in ("launched", "scored", "in_play", "score"))
    assert launched == scored + in_play and launched >= 10 and scored > 0
    assert 10 * scored <= score <= 50 * scored and score % 10 == 0


def test_snooker(results):
    """Reds potted plus reds left is 10, the shots were played, balls met and all lie on the cloth."""
    fields = ran(results, "snooker")
    assert int(fields["potted"]) + int(fields["reds"]) == 10
    assert int(fields["shots"]) >= 6 and int(fields["kisses"]) > 0
    assert fields["inside"] == "True"


def test_matchsticks(results):
    """Sticks left plus sticks knocked out is 16; freed balls were collected; the countdown ran out."""
    fields = ran(results, "matchsticks")
    assert int(fields["sticks"]) + int(fields["knocked"]) == 16 and int(fields["knocked"]) > 0
    assert int(fields["collected"]) + int(fields["trapped"]) == 4
    assert int(fields["thrown"]) == 3 and int(fields["countdown"]) == 0


def test_rotation(results):
    """The polygons turned (rotation physics: they spin and off-centre hits change the spin), collided,
    and stayed in the room."""
    fields = ran(results, "rotation")
    assert fields["turned"] == "True" and fields["spins_changed"] == "True"
    assert fields["ramps_still"] == "True" and fields["inside"] == "True"
    assert int(fields["collisions"]) > 10
    assert float(fields["time"]) == 8.0


def test_springs_chain(results):
    """The damped chain settled at the analytic lengths l0 + (N - j) m g / k; the bungee rope snapped once,
    at its snap length, and the jumper fell to the floor."""
    fields = ran(results, "springs_chain")
    assert float(fields["max_error"]) < 1e-9
    lengths = [float(x) for x in fields["lengths"].split(",")]
    assert len(lengths) == 4 and all(a > b for a, b in zip(lengths, lengths[1:]))
    assert int(fields["snaps"]) == 1 and fields["rope_deleted"] == "True" and int(fields["springs"]) == 4
    assert abs(float(fields["snap_length"]) - 0.45) < 1e-9
    assert 0.0 < float(fields["snap_time"]) < 1.0
    assert 0.05 - 1e-9 <= float(fields["jumper_y"]) < 0.3
    assert float(fields["time"]) == 20.0


def test_toppling(results):
    """The ball knocked the block over onto its side, the dropped crates, plank and wedge settled, every body
    rests and nothing happened for the last seconds; no overlaps."""
    fields = ran(results, "toppling")
    assert fields["toppled"] == "True"
    assert abs(abs(float(fields["block_angle"])) - 1.5707963267948966) < 1e-6
    assert fields["resting"] == "5/5" and fields["quiet"] == "True"
    assert int(fields["overlaps"]) == 0
    assert float(fields["time"]) == 6.0


@pytest.mark.parametrize("command", [["-m", "pge.classic"], ["-m", "pge.cli", "run"]])
def test_run_script_headless(tmp_path, command):
    """python -m pge.classic --headless SCRIPT and pge run --headless SCRIPT run a PGE script without a window."""
    script = tmp_path / "game.py"
    script.write_text(
        "import sys, pge\n"
        "pge.interactive()\n"
        "pge.circle(0.5, 0.5, 0.1, pge.white()).mass(1).velocity(0.1, 0)\n"
        "pge.run(0.5)\n"
        "print('time', pge.get_time(), 'frames', pge.get_frame_no(), sys.argv[1:])\n"
    )
    env = {key: value for key, value in os.environ.items() if key != "PGE_HEADLESS"}
    done = subprocess.run(
        [sys.executable, *command, "--headless", str(script), "extra"],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "time 0.5 frames 50 ['extra']" in done.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["game.py"]
