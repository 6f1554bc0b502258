"""Parameter sweeps on Dask (pge.sweeps, ``pge sweep``): same rows as in-process runs, on an embedded
LocalCluster and on a scheduler and worker started as separate processes; resume after a real kill;
failed runs as rows; one-line errors for bad input; the output directory's lock."""

from __future__ import annotations

import os
import re
import runpy
import signal
import socket
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import pge
from pge import sweeps

pd = pytest.importorskip("pandas")  # the test extra brings pandas, pyarrow and dask: this never skips in CI
import dask  # noqa: E402
from dask.distributed import Client, LocalCluster  # noqa: E402

GAS_STUDY = Path(__file__).resolve().parents[1] / "examples" / "studies" / "gas_sweep.py"
STATS = ("events", "collisions", "pair_collisions", "horizons", "predictions")

# A small gas: 20 discs for 1 simulated second, a few hundred events, well under a second a run.
SCENE = textwrap.dedent(
    """
    import os
    import time

    from pge import World
    from pge.scenes import disc_gas


    def scene(seed, density=0.1, elasticity=1.0, sleep=0.0, fail_seed=-1):
        log = os.environ.get("PGE_SWEEP_TEST_LOG")
        if log:
            with open(log, "a") as handle:  # one short append per call: lines never interleave
                handle.write(f"{seed} {density}\\n")
        time.sleep(sleep)
        if seed == fail_seed:
            raise ValueError(f"seed {seed} is refused")
        gas = disc_gas(20, area_fraction=density, speed=1.0, seed=seed)
        world = World(elasticity=elasticity)
        world.add_box(-0.05, -0.05, 1.1, 0.05, fixed=True, elasticity=1.0)
        world.add_box(-0.05, 1.0, 1.1, 0.05, fixed=True, elasticity=1.0)
        world.add_box(-0.05, 0.0, 0.05, 1.0, fixed=True, elasticity=1.0)
        world.add_box(1.0, 0.0, 0.05, 1.0, fixed=True, elasticity=1.0)
        for position, velocity in zip(gas.positions, gas.velocities):
            world.add_circle(position, gas.radius, mass=1.0, velocity=velocity, elasticity=elasticity)
        return world
    """
)


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "scene.py"
    path.write_text(SCENE)
    return path


@pytest.fixture(scope="module")
def client():
    """One 2-worker LocalCluster for the tests that do not test making one."""
    # A task whose worker dies is given up at once (not retried on 3 more workers): see the KilledWorker test.
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(cluster)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def in_process(scene_path, params, seed, until):
    """What the sweep must reproduce: the scene built and run here, without Dask."""
    world = runpy.run_path(str(scene_path))["scene"](seed=seed, **params)
    world.run_until(until)
    return world


def assert_same_as_in_process(frame, scene_path, names, until):
    for row in frame.itertuples():
        params = {name: getattr(row, name) for name in names}
        world = in_process(scene_path, params, row.seed, until)
        assert {name: getattr(row, name) for name in STATS} == {name: world.stats[name] for name in STATS}
        assert row.kinetic_energy == world.kinetic_energy()  # bit-identical: the engine is deterministic
        assert (row.momentum_x, row.momentum_y) == world.momentum()
        assert row.sim_time == world.time == until
        assert row.bodies == len(world)


# ---------------------------------------------------------------- parsing (no Dask)


def test_param_specs_give_spaced_values_and_typed_lists():
    assert sweeps.parse_param("density=0.05:0.4:8") == ("density", [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4])
    assert sweeps.parse_param("n=100:400:4") == ("n", [100, 200, 300, 400])  # whole steps stay ints
    assert sweeps.parse_param("n=1:2:3")[1] == [1.0, 1.5, 2.0]
    name, values = sweeps.parse_param(" elasticity = 0.9,1,true,min ")
    assert name == "elasticity" and values == [0.9, 1, True, "min"]
    assert [type(v) for v in values] == [float, int, bool, str]
    assert sweeps.parse_param("x=3") == ("x", [3])
    assert sweeps.parse_seeds("4") == [0, 1, 2, 3] and sweeps.parse_seeds("7,3") == [7, 3]


@pytest.mark.parametrize(
    "text",
    ["density", "=1,2", "2x=1", "density=", "density=0.1:0.4", "density=0.1:0.4:0", "density=a:1:3",
     "density=1,,2", "density=1,1", "density=nan", "seed=1,2", "collisions=1"],
)
def test_malformed_param_is_a_usage_error(text):
    with pytest.raises(sweeps.SweepUsageError):
        sweeps.parse_param(text)


@pytest.mark.parametrize("text", ["0", "-2", "x", "1,1", "1,b"])
def test_malformed_seeds_is_a_usage_error(text):
    with pytest.raises(sweeps.SweepUsageError):
        sweeps.parse_seeds(text)


def test_expand_and_run_id():
    grid = sweeps.expand({"a": [1, 2], "b": "0.5,1.0", "c": 7})
    assert grid == [{"a": a, "b": b, "c": 7} for a in (1, 2) for b in (0.5, 1.0)]
    assert sweeps.expand({}) == [{}]
    first = sweeps.run_id("s.py:scene", {"a": 1, "b": 0.5}, 3, 1.0)
    assert first == sweeps.run_id("s.py:scene", {"b": 0.5, "a": 1}, 3, 1)  # order of names and int until do not matter
    others = {
        sweeps.run_id("s.py:scene", {"a": 1.0, "b": 0.5}, 3, 1.0),  # 1.0 is not 1: the scene may tell them apart
        sweeps.run_id("s.py:scene", {"a": 1, "b": 0.5}, 4, 1.0),
        sweeps.run_id("s.py:scene", {"a": 1, "b": 0.5}, 3, 2.0),
        sweeps.run_id("t.py:scene", {"a": 1, "b": 0.5}, 3, 1.0),
    }
    assert first not in others and len(others) == 4 and re.fullmatch(r"[0-9a-f]{16}", first)


def test_bad_api_arguments_raise_before_any_work(scene_file, tmp_path):
    with pytest.raises(TypeError):
        pge.sweep(scene_file, {"density": [object()]}, until=1)
    with pytest.raises(ValueError):
        pge.sweep(scene_file, {"density": [0.1]}, until=-1)
    with pytest.raises(TypeError):
        pge.sweep(scene_file, seeds=[0, True], until=1)
    with pytest.raises(TypeError):
        pge.sweep(42, until=1)
    empty = tmp_path / "empty.py"
    empty.write_text("x = 1\n")
    with pytest.raises(sweeps.SweepUsageError, match="defines no function 'scene'"):
        pge.sweep(empty, until=1)


def test_import_pge_does_not_import_the_sweep_dependencies():
    code = "import sys, pge; print(sorted(m for m in ('dask', 'distributed', 'pyarrow', 'pandas') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert out.stdout.strip() == "[]"


# ---------------------------------------------------------------------- on Dask


def test_local_cluster_rows_equal_in_process_runs(scene_file, tmp_path):
    """2 parameters x 3 seeds on a 2-worker LocalCluster: the same numbers as running each scene here."""
    params = {"density": [0.1, 0.2], "elasticity": [0.9, 1.0]}
    frame = pge.sweep(scene_file, params, seeds=3, until=1.0, out=tmp_path / "out", workers=2, progress=False)
    assert len(frame) == 12 and frame.error_type.isna().all()
    assert list(zip(frame.density, frame.elasticity, frame.seed)) == [
        (d, e, s) for d in (0.1, 0.2) for e in (0.9, 1.0) for s in range(3)
    ]
    assert frame.run_id.is_unique and (frame.scene == "scene.py:scene").all()
    assert len(set(frame.worker)) == 2 and f":{os.getpid()}" not in "".join(frame.worker)
    assert (frame.collisions > 20).all()
    assert_same_as_in_process(frame, scene_file, ["density", "elasticity"], 1.0)
    assert len(list((tmp_path / "out" / "runs").glob("*.parquet"))) == 12
    again = pd.read_parquet(tmp_path / "out" / "runs")  # the dataset reads back as one table
    assert sorted(again.run_id) == sorted(frame.run_id)


def test_a_failing_run_is_a_row_with_its_error_and_events_are_recorded(client):
    """A closure scene (cloudpickled to the workers) that raises for one seed; --events' table."""
    build = runpy.run_path(str(GAS_STUDY))["scene"]
    refused = 1

    def scene(seed, density):
        if seed == refused:
            raise ValueError(f"seed {seed} is refused")
        return build(seed, density=density, n=12)

    summary = sweeps.SweepSummary()
    runs, events = pge.sweep(
        scene, {"density": [0.1, 0.2]}, seeds=3, until=0.5, events=True, client=client, progress=False, summary=summary
    )
    assert (summary.total, summary.ran, summary.skipped, summary.failed) == (6, 6, 0, 2)
    failed = runs[runs.seed == refused]
    assert list(failed.error_type) == ["ValueError", "ValueError"]
    assert list(failed.error_message) == ["seed 1 is refused"] * 2
    for text in failed.error_traceback:
        assert text.startswith("Traceback") and "ValueError: seed 1 is refused" in text
    assert failed.collisions.isna().all()
    good = runs[runs.seed != refused]
    assert good.error_type.isna().all() and (good.collisions > 0).all()
    counts = events.groupby("run_id").size()
    for row in good.itertuples():
        assert counts[row.run_id] == row.collisions  # one event row per collision
    assert set(events.run_id) == set(good.run_id)
    assert ((events.time >= 0) & (events.time <= 0.5)).all() and (events.impulse > 0).all()
    assert ((events.normal_x**2 + events.normal_y**2 - 1).abs() < 1e-9).all()


def test_a_run_that_kills_its_worker_is_a_row_and_the_others_go_on(client):
    build = runpy.run_path(str(GAS_STUDY))["scene"]

    def scene(seed):
        if seed == 1:
            os._exit(3)  # the worker process dies: no exception reaches the sweep, only Dask's verdict
        return build(seed, n=12)

    runs = pge.sweep(scene, seeds=3, until=0.2, client=client, progress=False)
    assert list(runs.error_type.fillna("")) == ["", "KilledWorker", ""]
    assert (runs.collisions.fillna(0) > 0).tolist() == [True, False, True]
    client.wait_for_workers(2, timeout=60)  # the nanny has started a new worker for the next tests


def test_resume_skips_written_runs_and_retries_failed_ones_on_request(client, scene_file, tmp_path, monkeypatch):
    log = tmp_path / "calls.log"
    monkeypatch.setenv("PGE_SWEEP_TEST_LOG", str(log))  # the client's workers started before: they see no log
    out = tmp_path / "out"
    first = sweeps.SweepSummary()
    frame = pge.sweep(
        scene_file, {"fail_seed": 2}, seeds=4, until=0.2, out=out, client=client, progress=False, summary=first
    )
    (out / "runs" / f"{frame.run_id[0]}.parquet").unlink()
    second = sweeps.SweepSummary()
    again = pge.sweep(
        scene_file, {"fail_seed": 2}, seeds=4, until=0.2, out=out, client=client, progress=False, summary=second
    )
    assert (first.ran, first.failed, second.ran, second.skipped, second.failed) == (4, 1, 1, 3, 1)
    assert list(again.run_id) == list(frame.run_id)
    third = sweeps.SweepSummary()
    pge.sweep(
        scene_file, {"fail_seed": 2}, seeds=4, until=0.2, out=out, client=client, progress=False,
        retry_failed=True, summary=third,
    )
    assert (third.ran, third.skipped, third.failed) == (1, 3, 1)


def test_a_second_sweep_into_the_same_directory_is_refused(scene_file, tmp_path):
    import fcntl

    out = tmp_path / "out"
    out.mkdir()
    with open(out / ".lock", "a+") as held:
        fcntl.flock(held.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)  # as a running sweep holds it
        held.write("pid 1 on elsewhere\n")
        held.flush()
        with pytest.raises(sweeps.SweepLockedError, match="another pge sweep is writing here"):
            pge.sweep(scene_file, seeds=1, until=0.1, out=out, progress=False)
        result = run_cli(str(scene_file), "--until", "0.1", "--out", str(out))
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1 and "another pge sweep is writing here (pid 1 on elsewhere)" in result.stderr


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_for_port(port: int, process, seconds: float) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        assert process.poll() is None, "the dask scheduler exited"
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            return
        except OSError:
            time.sleep(0.2)
    raise AssertionError(f"no dask scheduler on port {port} after {seconds} s")


def stop(process) -> None:
    """Kill a process started in its own session and everything it started; bounded waits."""
    if process.poll() is None:
        try:
            os.killpg(process.pid, signal.SIGTERM)
            process.wait(timeout=10)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            pass
    try:
        os.killpg(process.pid, signal.SIGKILL)  # the worker's nanny child too
    except ProcessLookupError:
        pass
    process.wait(timeout=10)


def test_a_scheduler_and_a_worker_started_as_separate_processes(scene_file, tmp_path):
    dask = Path(sys.executable).with_name("dask")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    common = {"cwd": tmp_path, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "start_new_session": True}
    processes = []
    try:
        processes.append(
            subprocess.Popen(
                [str(dask), "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"], **common
            )
        )
        wait_for_port(port, processes[0], 60)
        processes.append(
            subprocess.Popen(
                [str(dask), "worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                 "--local-directory", str(tmp_path / "worker")],
                **common,
            )
        )
        with Client(address, timeout="30s") as probe:
            probe.wait_for_workers(1, timeout=120)
        frame = pge.sweep(
            scene_file, {"density": [0.1, 0.15]}, seeds=2, until=0.5, scheduler=address, progress=False
        )
    finally:
        for process in reversed(processes):
            stop(process)
    assert len(frame) == 4 and frame.error_type.isna().all()
    assert len(set(frame.worker)) == 1 and f":{os.getpid()}" not in frame.worker[0]
    assert_same_as_in_process(frame, scene_file, ["density"], 0.5)


# ------------------------------------------------------------------ command line


def run_cli(*args, env=None, timeout=300, **options):
    return subprocess.run(
        [sys.executable, "-m", "pge.cli", "sweep", *args],
        capture_output=True, text=True, timeout=timeout, env=env, **options,
    )


def test_a_sweep_killed_half_way_runs_only_the_missing_runs_when_started_again(scene_file, tmp_path):
    out = tmp_path / "out"
    args = [str(scene_file), "--param", "sleep=0.4", "--seeds", "10", "--until", "0.2", "--out", str(out),
            "--workers", "2", "-q"]
    first_log, second_log = tmp_path / "first.log", tmp_path / "second.log"
    process = subprocess.Popen(
        [sys.executable, "-m", "pge.cli", "sweep", *args],
        env={**os.environ, "PGE_SWEEP_TEST_LOG": str(first_log)},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        deadline = time.monotonic() + 180
        while len(list((out / "runs").glob("*.parquet"))) < 3:
            assert process.poll() is None, "the sweep ended before it could be killed"
            assert time.monotonic() < deadline, "no 3 runs written in 180 s"
            time.sleep(0.05)
    finally:
        stop_now = process.poll() is None
        os.killpg(process.pid, signal.SIGKILL)  # the command, its LocalCluster and workers: no clean-up at all
        process.wait(timeout=10)
    assert stop_now
    written = {path.stem for path in (out / "runs").glob("*.parquet")}
    assert 3 <= len(written) < 10

    result = run_cli(*args[:-1], env={**os.environ, "PGE_SWEEP_TEST_LOG": str(second_log)})
    assert result.returncode == 0, result.stderr
    assert f"10 runs ({10 - len(written)} run now, {len(written)} already written, 0 failed)" in result.stdout
    frame = pd.read_parquet(out / "runs")
    assert len(frame) == 10 and frame.run_id.is_unique and frame.error_type.isna().all()
    again = sorted(int(line.split()[0]) for line in second_log.read_text().splitlines())
    missing = sorted(frame[~frame.run_id.isin(written)].seed)
    assert again == missing  # the second sweep ran exactly the runs that were not written
    assert not list((out / "runs").glob(".*.tmp"))  # a killed writer's leftovers are cleared


def test_cli_errors_are_one_line(scene_file, tmp_path):
    def check(result, status, *words):
        assert result.returncode == status, result.stderr
        assert result.stderr.startswith("pge: error: ") and result.stderr.count("\n") == 1, result.stderr
        for word in words:
            assert word in result.stderr

    out = str(tmp_path / "out")
    check(run_cli(str(scene_file), "--param", "density", "--until", "1", "--out", out), 2, "NAME=VALUES")
    check(run_cli(str(scene_file), "--param", "density=0.1:0.2", "--until", "1", "--out", out), 2, "A:B:N")
    check(run_cli(str(scene_file), "--seeds", "x", "--until", "1", "--out", out), 2, "--seeds")
    check(run_cli(str(scene_file), "-p", "density=0.1", "-p", "density=0.2", "--until", "1", "--out", out), 2, "twice")
    empty = tmp_path / "empty.py"
    empty.write_text("def other(seed):\n    pass\n")
    check(run_cli(str(empty), "--until", "1", "--out", out), 2, "defines no function 'scene'")
    check(run_cli(str(tmp_path / "nowhere.py"), "--until", "1", "--out", out), 2, "no such scene file")
    broken = tmp_path / "broken.py"
    broken.write_text("def scene(seed:\n")
    check(run_cli(str(broken), "--until", "1", "--out", out), 2, "syntax error")
    assert not (tmp_path / "out").exists()  # nothing written for bad input


def test_without_the_extra_the_command_names_it(scene_file, tmp_path, capsys, monkeypatch):
    from pge.cli import main

    monkeypatch.setitem(sys.modules, "pyarrow", None)  # as if not installed: importing it raises ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    status = main(["sweep", str(scene_file), "--until", "1", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 1 and err.count("\n") == 1
    assert err == "pge: error: pge sweep needs pyarrow (the sweep extra): pip install 'pge[sweep]'\n"
    with pytest.raises(sweeps.MissingExtraError, match=re.escape("pip install 'pge[sweep]'")):
        pge.sweep(scene_file, until=1)
