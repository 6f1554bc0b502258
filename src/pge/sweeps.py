"""Parameter sweeps: every combination of parameters and seeds, run on Dask, rows in Parquet.

A sweep runs a *scene* once per combination of parameter values and seed and
records one row per run. The scene contract::

    def scene(seed, **params) -> pge.World

``scene`` builds and returns a World (nothing run yet, or run a little: the
sweep calls ``world.run_until(until)`` on whatever it gets). It is called with
the seed and every swept parameter as keyword arguments, so
``def scene(seed, density=0.1, elasticity=1.0)`` works. A scene is either a
callable (pickled to the workers with cloudpickle, so closures and functions
defined in a notebook or in ``__main__`` work) or the path of a Python file
defining it (``"gas.py"``, or ``"gas.py:name"`` for a function not called
``scene``). A file's source is read once by the caller and shipped to the
workers, which execute it as a module: a cluster's workers need pge
installed, not the caller's file system.

Runs go to Dask: an embedded ``LocalCluster`` (processes, one single-threaded
worker per core) unless a scheduler address or a ``distributed.Client`` is
given. Each run's row (parameters, seed, simulated and wall time,
``world.stats``, kinetic energy and momentum at the end, error type and
message if it raised) is written, when the run finishes, as one Parquet file
``OUT/runs/<run_id>.parquet``; with ``events=True`` every collision of the run
goes to ``OUT/events/<run_id>.parquet``. ``run_id`` is a hash of the scene's
label, the parameters, the seed and ``until``, so a sweep started again with
the same arguments skips the runs already written (resume), and files are
written to a temporary name and renamed into place (a killed sweep leaves no
half file). A lock file ``OUT/.lock`` (``flock``, released by the kernel
even if the sweep is killed) makes a second sweep into the same directory
fail at once with a clear error instead of interleaving writes.

Reading a finished sweep: ``pandas.read_parquet("OUT/runs")`` (and
``"OUT/events"``, joined on ``run_id``). The command line is ``pge sweep``
(see ``pge sweep --help`` and docs/sweeps.md).

This module imports dask, pyarrow and pandas only inside the functions that
need them (they are the optional ``sweep`` extra), so ``import pge`` stays
light.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import numbers
import os
import re
import socket
import sys
import time
import traceback
import types
import uuid
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

__all__ = [
    "sweep",
    "run_one",
    "parse_param",
    "parse_values",
    "parse_seeds",
    "expand",
    "run_id",
    "SceneFile",
    "SweepUsageError",
    "SweepLockedError",
    "MissingExtraError",
    "EXTRA_HINT",
]

#: The one line that tells a user how to get the sweep's dependencies.
EXTRA_HINT = "pip install 'pge[sweep]'"

#: Columns of the runs table besides the parameters and ``world.stats``; a
#: parameter may not take one of these names (nor a stats name).
BASE_COLUMNS = (
    "run_id",
    "scene",
    "seed",
    "until",
    "sim_time",
    "setup_time",
    "wall_time",
    "bodies",
    "kinetic_energy",
    "momentum_x",
    "momentum_y",
    "worker",
    "error_type",
    "error_message",
    "error_traceback",
)

#: Columns of the events table: one row per collision.
EVENT_COLUMNS = (
    "run_id",
    "time",
    "a",
    "b",
    "a_name",
    "b_name",
    "point_x",
    "point_y",
    "normal_x",
    "normal_y",
    "impulse",
    "approach_speed",
)

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
# Linearly spaced values are rounded to this many significant digits, so that
# 0.05:0.4:8 gives 0.1 and not 0.09999999999999999 (they are labels people read
# and type again; 12 digits is far below any physical parameter's precision).
_SPACING_DIGITS = 12


class SweepUsageError(ValueError):
    """Bad sweep input: a malformed parameter or seed list, or a scene that cannot be used."""


class SweepLockedError(RuntimeError):
    """Another sweep holds the output directory's lock."""


class MissingExtraError(ImportError):
    """dask, pyarrow or pandas is not installed (the ``sweep`` extra)."""


def _require_extras() -> None:
    missing = []
    for module in ("dask.distributed", "pyarrow.parquet", "pandas"):
        try:
            __import__(module)
        except ImportError:
            missing.append(module.split(".")[0])
    if missing:
        raise MissingExtraError(f"pge sweep needs {', '.join(missing)} (the sweep extra): {EXTRA_HINT}")


# ----------------------------------------------------------------- parameters


def _stat_names() -> tuple[str, ...]:
    from pge.core.layout import STAT_NAMES  # plain integers and names: no compiling

    return tuple(STAT_NAMES)


def _check_name(name: str) -> str:
    if not _NAME.match(name):
        raise SweepUsageError(f"parameter name must be a Python identifier, got {name!r}")
    if name in BASE_COLUMNS or name in _stat_names():
        raise SweepUsageError(f"parameter name {name!r} is taken by a result column; rename the parameter")
    return name


def _scalar(text: str, name: str):
    """One value of a comma list: int if it reads as one, else float, else true/false, else the text."""
    text = text.strip()
    if not text:
        raise SweepUsageError(f"parameter {name!r} has an empty value")
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        lowered = text.lower()
        if lowered in ("true", "false"):
            return lowered == "true"
        return text
    if not math.isfinite(value):
        raise SweepUsageError(f"parameter {name!r}: value {text!r} is not finite")
    return value


def _number(text: str, name: str, what: str):
    value = _scalar(text, name)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SweepUsageError(f"parameter {name!r}: {what} of A:B:N must be a number, got {text.strip()!r}")
    return value


def _spaced(a, b, n: int) -> list:
    if n == 1:
        return [a]
    if isinstance(a, int) and isinstance(b, int) and (b - a) % (n - 1) == 0:
        step = (b - a) // (n - 1)
        return [a + i * step for i in range(n)]
    values = [float(f"{a + (b - a) * i / (n - 1):.{_SPACING_DIGITS}g}") for i in range(n)]
    values[-1] = float(b)
    return values


def parse_values(name: str, spec: str) -> list:
    """The values of one parameter from its text: ``A:B:N`` or a comma list.

    ``A:B:N`` is N evenly spaced values from A to B inclusive (integers if A
    and B are integers and the spacing is whole, else floats rounded to 12
    significant digits); ``v1,v2,...`` is a list whose items stay ints when
    they read as ints, else floats, ``true``/``false`` booleans, else text.
    A single value is a list of one. Raises SweepUsageError when malformed.
    """
    spec = spec.strip()
    if not spec:
        raise SweepUsageError(f"parameter {name!r} has no values")
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) != 3:
            raise SweepUsageError(f"parameter {name!r}: a range is A:B:N (N values from A to B), got {spec!r}")
        a = _number(parts[0], name, "A")
        b = _number(parts[1], name, "B")
        try:
            n = int(parts[2])
        except ValueError:
            n = 0
        if n < 1:
            raise SweepUsageError(f"parameter {name!r}: N of A:B:N must be a whole number >= 1, got {parts[2]!r}")
        return _spaced(a, b, n)
    values = [_scalar(item, name) for item in spec.split(",")]
    _check_distinct(name, values)
    return values


def _check_distinct(name: str, values: list) -> None:
    keys = [_canonical(v) for v in values]
    if len(set(keys)) != len(keys):
        raise SweepUsageError(f"parameter {name!r} lists a value twice: {values!r}")


def parse_param(text: str) -> tuple[str, list]:
    """``NAME=VALUES`` (the text of one ``--param``) as ``(name, values)``; see parse_values."""
    name, sep, spec = text.partition("=")
    if not sep:
        raise SweepUsageError(
            f"--param must be NAME=VALUES (e.g. density=0.05:0.4:8 or elasticity=0.9,1.0), got {text!r}"
        )
    name = _check_name(name.strip())
    return name, parse_values(name, spec)


def _value(name: str, value):
    """A parameter value as the plain Python scalar the run id and the Parquet column take."""
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()  # numpy scalars
    if isinstance(value, bool) or isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        value = float(value)
        if not math.isfinite(value):
            raise ValueError(f"parameter {name!r}: value {value!r} is not finite")
        return value
    raise TypeError(
        f"parameter {name!r}: values must be numbers, booleans or strings, got {type(value).__name__} {value!r}"
    )


def _normalise_params(params) -> dict[str, list]:
    if params is None:
        return {}
    if not isinstance(params, dict):
        raise TypeError(f"params must be a dict of name -> values, got {type(params).__name__}")
    out = {}
    for name, values in params.items():
        if not isinstance(name, str):
            raise TypeError(f"parameter names must be strings, got {name!r}")
        _check_name(name)
        if isinstance(values, str):
            values = parse_values(name, values)
        elif isinstance(values, (list, tuple, range)) or (hasattr(values, "tolist") and hasattr(values, "ndim")):
            values = [_value(name, v) for v in (values.tolist() if hasattr(values, "tolist") else values)]
        else:
            values = [_value(name, values)]
        if not values:
            raise SweepUsageError(f"parameter {name!r} has no values")
        _check_distinct(name, values)
        out[name] = values
    return out


def expand(params) -> list[dict]:
    """Every combination of the parameters' values, the first parameter varying slowest.

    ``params`` maps a name to a list of values, a single value, or a spec
    string as ``parse_values`` reads it. ``expand({})`` is ``[{}]``: one run
    per seed with no parameters.
    """
    params = _normalise_params(params)
    names = list(params)
    return [dict(zip(names, combo)) for combo in itertools.product(*(params[n] for n in names))]


def parse_seeds(text: str) -> list[int]:
    """``--seeds``: ``N`` for seeds 0 to N-1, or a comma list of seeds (``3,7,11``)."""
    text = text.strip()
    try:
        if "," in text:
            seeds = [int(item) for item in text.split(",")]
        else:
            count = int(text)
            if count < 1:
                raise SweepUsageError(f"--seeds must be a count >= 1 or a comma list of seeds, got {text!r}")
            seeds = list(range(count))
    except ValueError as error:
        if isinstance(error, SweepUsageError):
            raise
        raise SweepUsageError(
            f"--seeds must be a count (20) or a comma list of whole numbers (1,5,9), got {text!r}"
        ) from None
    if len(set(seeds)) != len(seeds):
        raise SweepUsageError(f"--seeds lists a seed twice: {text!r}")
    return seeds


def _normalise_seeds(seeds) -> list[int]:
    if isinstance(seeds, bool):
        raise TypeError(f"seeds must be a count or a list of integers, got {seeds!r}")
    if isinstance(seeds, numbers.Integral):
        if seeds < 1:
            raise ValueError(f"seeds must be at least 1, got {seeds!r}")
        return list(range(int(seeds)))
    try:
        seeds = list(seeds)
    except TypeError:
        raise TypeError(f"seeds must be a count or a list of integers, got {seeds!r}") from None
    if not seeds:
        raise ValueError("seeds is an empty list")
    for seed in seeds:
        if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
            raise TypeError(f"seeds must be integers, got {seed!r}")
    seeds = [int(s) for s in seeds]
    if len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds lists a seed twice: {seeds!r}")
    return seeds


def _canonical(value) -> str:
    # json keeps int 1 and float 1.0 apart and prints floats with repr's shortest
    # round-trip digits, so equal inputs always hash equal on every platform.
    return json.dumps(value)


def run_id(scene_label: str, params: dict, seed: int, until: float) -> str:
    """The deterministic id of one run: a 16-hex-digit hash of scene label, parameters, seed and ``until``."""
    key = json.dumps(
        {"scene": scene_label, "params": sorted(params.items()), "seed": seed, "until": float(until)},
        sort_keys=True,
    )
    return hashlib.sha256(key.encode()).hexdigest()[:16]


# ---------------------------------------------------------------------- scenes

# Scene files already executed in this process, by (source hash, path): a
# worker runs many runs of one scene and executes its file once.
_LOADED: dict[tuple[str, str], types.ModuleType] = {}


@dataclass(frozen=True)
class SceneFile:
    """A scene given as a file: its path, the function's name and the file's source.

    The source travels with the task, so a worker executes exactly what the
    caller read, whether or not it sees the same file system.
    """

    path: str
    function: str
    source: str

    @property
    def label(self) -> str:
        """``file.py:function``: the scene's name in results and run ids."""
        return f"{Path(self.path).name}:{self.function}"

    def load(self) -> Callable:
        """Execute the file (once per process) and return its scene function."""
        digest = hashlib.sha256(self.source.encode()).hexdigest()
        module = _LOADED.get((digest, self.path))
        if module is None:
            # A real module in sys.modules, so that dataclasses, pickling and
            # relative lookups inside the scene file work as in an imported file.
            name = f"pge_sweep_scene_{digest[:12]}"
            module = types.ModuleType(name)
            module.__file__ = self.path
            folder = str(Path(self.path).parent)
            if os.path.isdir(folder) and folder not in sys.path:
                sys.path.append(folder)  # the scene file may import modules next to it
            sys.modules[name] = module
            try:
                exec(compile(self.source, self.path, "exec"), module.__dict__)
            except BaseException:
                del sys.modules[name]
                raise
            _LOADED[(digest, self.path)] = module
        function = getattr(module, self.function, None)
        if not callable(function):
            raise SweepUsageError(
                f"{self.path} defines no function {self.function!r} "
                f"(expected: def {self.function}(seed, **params) -> pge.World)"
            )
        return function


def _split_scene_path(text: str) -> tuple[str, str]:
    head, sep, tail = text.rpartition(":")
    if sep and head and _NAME.match(tail) and not os.path.exists(text):
        return head, tail
    return text, "scene"


def _resolve_scene(scene, function: str | None = None):
    """``(what the workers get, label)`` for a callable or a scene file path; checks the file."""
    if callable(scene):
        module = getattr(scene, "__module__", None) or "?"
        name = getattr(scene, "__qualname__", None) or getattr(scene, "__name__", None) or type(scene).__name__
        return scene, f"{module}.{name}"
    if not isinstance(scene, (str, os.PathLike)):
        raise TypeError(f"scene must be a callable or the path of a Python file, got {type(scene).__name__}")
    path, name = _split_scene_path(os.fspath(scene))
    if function is not None:
        name = function
    if not _NAME.match(name):
        raise SweepUsageError(f"scene function name must be a Python identifier, got {name!r}")
    try:
        source = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SweepUsageError(f"{path}: no such scene file") from None
    except IsADirectoryError:
        raise SweepUsageError(f"{path}: is a directory, not a scene file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise SweepUsageError(f"{path}: cannot read the scene file: {error}") from None
    ref = SceneFile(str(Path(path).resolve()), name, source)
    # Load it here too: a missing function or a broken file is one error now,
    # not the same error in every row.
    try:
        ref.load()
    except SweepUsageError:
        raise
    except SyntaxError as error:
        raise SweepUsageError(f"{path}:{error.lineno}: syntax error in the scene file: {error.msg}") from None
    except Exception as error:
        raise SweepUsageError(f"{path}: the scene file failed to load: {type(error).__name__}: {error}") from None
    return ref, ref.label


# ------------------------------------------------------------------------ runs


def _event_row(record) -> tuple:
    a, b = record.a, record.b
    return (
        record.time,
        a.id,
        b.id,
        None if a.name is None else str(a.name),
        None if b.name is None else str(b.name),
        record.point[0],
        record.point[1],
        record.normal[0],
        record.normal[1],
        record.impulse,
        record.approach_speed,
    )


def run_one(scene, params: dict, seed: int, until: float, events: bool = False) -> tuple[dict, list | None]:
    """Build ``scene(seed=seed, **params)``, run it to ``until`` and measure it, here and now.

    This is what every Dask task runs. Returns ``(row, collisions)``: the
    row holds sim_time, setup_time (building the scene), wall_time (running
    it), bodies, every ``world.stats`` counter, kinetic_energy,
    momentum_x/y, worker (host:pid) and, if building or running raised, the
    error's type, message and traceback (the other values then stay None).
    ``collisions`` is a list of tuples in EVENT_COLUMNS order without the
    run_id (None unless ``events``); a failed run keeps those before the error.
    ``scene`` is a callable or a SceneFile.
    """
    from pge.world import World

    row: dict[str, Any] = {"worker": f"{socket.gethostname()}:{os.getpid()}"}
    collisions: list | None = [] if events else None
    started = time.perf_counter()
    stage = "setup_time"
    try:
        build = scene.load() if isinstance(scene, SceneFile) else scene
        world = build(seed=seed, **params)
        if not isinstance(world, World):
            raise TypeError(f"the scene returned {type(world).__name__}, not a pge.World")
        row["setup_time"] = time.perf_counter() - started
        stage = "wall_time"
        started = time.perf_counter()
        if collisions is not None:
            world.on_collision(lambda record: collisions.append(_event_row(record)))
        world.run_until(until)
        row["wall_time"] = time.perf_counter() - started
        row["sim_time"] = world.time
        row["bodies"] = len(world)
        row.update(world.stats)
        row["kinetic_energy"] = world.kinetic_energy()
        row["momentum_x"], row["momentum_y"] = world.momentum()
    except Exception as error:  # recorded in the row: one bad run must not stop a sweep
        row[stage] = time.perf_counter() - started
        row["error_type"] = type(error).__name__
        row["error_message"] = str(error)
        row["error_traceback"] = traceback.format_exc()
    return row, collisions


# ---------------------------------------------------------------------- output


def _param_type(pa, values: list):
    if all(isinstance(v, bool) for v in values):
        return pa.bool_()
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return pa.int64()
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return pa.float64()
    return pa.string()


def _column_value(kind, value):
    import pyarrow as pa

    if kind == pa.string() and not isinstance(value, str):
        return json.dumps(value)  # a mixed column shows numbers as their JSON text
    if kind == pa.float64():
        return float(value)
    return value


def _runs_schema(params: dict[str, list]):
    import pyarrow as pa

    fields = [
        ("run_id", pa.string()),
        ("scene", pa.string()),
        ("seed", pa.int64()),
        *((name, _param_type(pa, values)) for name, values in params.items()),
        ("until", pa.float64()),
        ("sim_time", pa.float64()),
        ("setup_time", pa.float64()),
        ("wall_time", pa.float64()),
        ("bodies", pa.int64()),
        *((name, pa.int64()) for name in _stat_names()),
        ("kinetic_energy", pa.float64()),
        ("momentum_x", pa.float64()),
        ("momentum_y", pa.float64()),
        ("worker", pa.string()),
        ("error_type", pa.string()),
        ("error_message", pa.string()),
        ("error_traceback", pa.string()),
    ]
    return pa.schema(fields)


def _events_schema():
    import pyarrow as pa

    kinds = {"run_id": pa.string(), "a": pa.int64(), "b": pa.int64(), "a_name": pa.string(), "b_name": pa.string()}
    return pa.schema([(name, kinds.get(name, pa.float64())) for name in EVENT_COLUMNS])


def _events_table(run: str, collisions: list):
    import pyarrow as pa

    columns = list(zip(*collisions)) if collisions else [[] for _ in EVENT_COLUMNS[1:]]
    schema = _events_schema()
    arrays = [pa.array([run] * len(collisions), pa.string())]
    arrays += [pa.array(list(column), schema.field(i + 1).type) for i, column in enumerate(columns)]
    return pa.Table.from_arrays(arrays, schema=schema)


class _Store:
    """One sweep's output directory: the lock, part files written atomically, what is done."""

    def __init__(self, out, events: bool) -> None:
        self.root = Path(out)
        self.runs = self.root / "runs"
        self.events = self.root / "events" if events else None
        for folder in (self.runs, self.events):
            if folder is not None:
                folder.mkdir(parents=True, exist_ok=True)
        self._lock = self._acquire()
        # Only the lock holder writes, so a temporary file now is a leftover of a killed sweep.
        for folder in (self.runs, self.events):
            if folder is not None:
                for leftover in folder.glob(".*.tmp"):
                    leftover.unlink(missing_ok=True)

    def _acquire(self):
        path = self.root / ".lock"
        handle = open(path, "a+", encoding="utf-8")
        try:
            import fcntl
        except ImportError:  # not POSIX: atomic renames still keep every part file whole
            return handle
        try:
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.seek(0)
            owner = handle.read().strip() or "unknown"
            handle.close()
            raise SweepLockedError(
                f"{self.root}: another pge sweep is writing here ({owner}); wait for it to finish or use another --out"
            ) from None
        handle.seek(0)
        handle.truncate()
        handle.write(f"pid {os.getpid()} on {socket.gethostname()}\n")
        handle.flush()
        return handle

    def close(self) -> None:
        """Release the lock (closing the file releases the flock)."""
        if self._lock is not None:
            self._lock.close()
            self._lock = None

    def _part(self, folder: Path, run: str) -> Path:
        return folder / f"{run}.parquet"

    def done(self, retry_failed: bool) -> set[str]:
        """Run ids with a complete row (and events file, if wanted) already written."""
        done = {path.stem for path in self.runs.glob("*.parquet")}
        if self.events is not None:
            done &= {path.stem for path in self.events.glob("*.parquet")}
        if retry_failed and done:
            import pyarrow.parquet as pq

            for run in list(done):
                if pq.read_table(self._part(self.runs, run), columns=["error_type"]).column(0)[0].is_valid:
                    done.discard(run)
        return done

    def _write(self, table, target: Path) -> None:
        import pyarrow.parquet as pq

        temporary = target.with_name(f".{target.stem}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
        try:
            pq.write_table(table, temporary)
            os.replace(temporary, target)  # atomic: readers see the old file or the whole new one
        finally:
            temporary.unlink(missing_ok=True)

    def write(self, run: str, row_table, collisions) -> None:
        """Write one run: its events first, then its row, which marks the run as done."""
        if self.events is not None:
            self._write(_events_table(run, collisions or []), self._part(self.events, run))
        self._write(row_table, self._part(self.runs, run))

    def read(self, folder: Path, runs: list[str]):
        import pyarrow as pa
        import pyarrow.parquet as pq

        tables = [pq.read_table(self._part(folder, run)) for run in runs]
        return pa.concat_tables(tables, promote_options="default") if tables else None


# ------------------------------------------------------------------------ dask


class _Cluster:
    """The Dask client of a sweep: the caller's, one on a scheduler, or an embedded LocalCluster."""

    def __init__(self, client=None, scheduler: str | None = None, workers: int | None = None) -> None:
        from dask.distributed import Client, LocalCluster

        self._owned = []
        if client is not None:
            self.client = client
            return
        if scheduler is not None:
            self.client = Client(scheduler, timeout="30s")
            self._owned = [self.client]
            return
        import logging

        count = workers or os.cpu_count() or 1
        # Processes, not threads: the engine's Python parts hold the GIL. One thread
        # per worker because a run uses one core. No dashboard: no port to clash over.
        cluster = LocalCluster(
            n_workers=count,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            silence_logs=logging.ERROR,
        )
        self.client = Client(cluster)
        self._owned = [self.client, cluster]

    def close(self) -> None:
        """Close what this sweep opened (never the caller's client)."""
        for thing in self._owned:
            try:
                thing.close()
            except Exception:  # shutting down a cluster that is already going is not an error
                pass
        self._owned = []


def _check_until(until) -> float:
    if isinstance(until, bool) or not isinstance(until, numbers.Real):
        raise TypeError(f"until must be a number of seconds, got {until!r}")
    until = float(until)
    if not (until >= 0.0 and math.isfinite(until)):
        raise ValueError(f"until must be a finite time >= 0, got {until!r}")
    return until


@dataclass
class SweepSummary:
    """What a sweep did: runs in total, run now, found already written, and failed
    (among all its rows, those already written included)."""

    total: int = 0
    ran: int = 0
    skipped: int = 0
    failed: int = 0
    first_failure: str | None = None


def sweep(
    scene,
    params=None,
    *,
    seeds=1,
    until,
    out=None,
    events: bool = False,
    scheduler: str | None = None,
    client=None,
    workers: int | None = None,
    progress: bool = True,
    retry_failed: bool = False,
    function: str | None = None,
    summary: SweepSummary | None = None,
):
    """Run ``scene`` for every combination of ``params`` and every seed on Dask.

    Args:
        scene: ``scene(seed, **params) -> pge.World``, or the path of a file
            defining it (``"gas.py"`` or ``"gas.py:name"``).
        params: name -> list of values, a single value, or a spec string
            (``"0.05:0.4:8"``, ``"0.9,1.0"``); every combination is run.
        seeds: a count N (seeds 0 to N-1) or a list of integer seeds.
        until: simulated time each run is run to (``world.run_until(until)``).
        out: directory for the Parquet dataset (``out/runs``, ``out/events``);
            runs already written there are not run again. None keeps
            everything in memory (no resume).
        events: also record every collision (a second table).
        scheduler: address of a running Dask scheduler (``tcp://host:port``);
            default: an embedded LocalCluster of ``workers`` processes (one
            per core).
        client: a ``dask.distributed.Client`` to use instead (left open).
        workers: worker processes of the embedded LocalCluster.
        progress: show a tqdm progress bar.
        retry_failed: run again the runs in ``out`` that recorded an error.
        function: the scene function's name in a scene file (default ``scene``).
        summary: a SweepSummary to fill in with the counts.

    Returns:
        A pandas DataFrame, one row per run in grid order (first parameter
        slowest, seeds fastest); with ``events=True`` a pair
        ``(runs, events)`` of DataFrames, events joined to runs on run_id.

    Raises:
        MissingExtraError: dask, pyarrow or pandas is missing.
        SweepUsageError (a ValueError): bad parameters or scene.
        SweepLockedError: another sweep is writing to ``out``.
    """
    _require_extras()
    from dask.distributed import as_completed
    from tqdm.auto import tqdm

    if sum(x is not None for x in (scheduler, client)) > 1:
        raise ValueError("give at most one of scheduler and client")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be a whole number >= 1, got {workers!r}")
    ref, label = _resolve_scene(scene, function)
    grid_params = _normalise_params(params)
    grid = expand(grid_params)
    seed_list = _normalise_seeds(seeds)
    until = _check_until(until)
    runs = [(run_id(label, combo, seed, until), combo, seed) for combo in grid for seed in seed_list]
    schema = _runs_schema(grid_params)
    summary = summary if summary is not None else SweepSummary()
    summary.total = len(runs)

    import pyarrow as pa

    def row_table(run, combo, seed, row):
        values = {"run_id": run, "scene": label, "seed": seed, "until": until, **row}
        for name, value in combo.items():
            values[name] = _column_value(schema.field(name).type, value)
        return pa.Table.from_pylist([{name: values.get(name) for name in schema.names}], schema=schema)

    store = _Store(out, events) if out is not None else None
    memory_rows: dict[str, Any] = {}
    memory_events: dict[str, Any] = {}
    try:
        done = store.done(retry_failed) if store is not None else set()
        todo = [run for run in runs if run[0] not in done]
        summary.skipped = len(runs) - len(todo)
        if todo:
            cluster = _Cluster(client, scheduler, workers)
            try:
                token = uuid.uuid4().hex[:8]
                futures = {}
                for run, combo, seed in todo:
                    future = cluster.client.submit(
                        run_one, ref, combo, seed, until, events, key=f"pge-run-{run}-{token}", pure=False
                    )
                    futures[future] = (run, combo, seed)
                bar = tqdm(total=len(runs), initial=summary.skipped, unit="run", desc="pge sweep", disable=not progress)
                try:
                    for future in as_completed(futures):
                        run, combo, seed = futures.pop(future)
                        try:
                            row, collisions = future.result()
                        except Exception as error:  # the task itself died (worker killed, unpicklable scene...)
                            row = {"error_type": type(error).__name__, "error_message": str(error)}
                            collisions = [] if events else None
                        future.release()
                        if row.get("error_type") is not None:
                            summary.failed += 1
                            if summary.first_failure is None:
                                where = ", ".join(f"{k}={v!r}" for k, v in combo.items())
                                where = f"seed {seed}" + (f", {where}" if where else "")
                                summary.first_failure = f"{where}: {row['error_type']}: {row['error_message']}"
                        table = row_table(run, combo, seed, row)
                        if store is not None:
                            store.write(run, table, collisions)
                        else:
                            memory_rows[run] = table
                            if events:
                                memory_events[run] = _events_table(run, collisions or [])
                        summary.ran += 1
                        bar.update(1)
                        bar.set_postfix(failed=summary.failed, refresh=False)
                finally:
                    bar.close()
                    for future in futures:  # interrupted: do not leave work queued on a shared scheduler
                        future.cancel()
            finally:
                cluster.close()
        ids = [run for run, _, _ in runs]
        if store is not None:
            runs_table = store.read(store.runs, ids)
            events_table = store.read(store.events, ids) if events else None
        else:
            runs_table = pa.concat_tables([memory_rows[run] for run in ids])
            events_table = pa.concat_tables([memory_events[run] for run in ids]) if events else None
    finally:
        if store is not None:
            store.close()
    # Failures among all the sweep's rows, those found already written included.
    failed_column = runs_table.column("error_type")
    summary.failed = failed_column.length() - failed_column.null_count
    frame = runs_table.to_pandas()
    if events:
        return frame, events_table.to_pandas()
    return frame
