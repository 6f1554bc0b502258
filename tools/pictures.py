"""Contact sheets of the example scenes (issue 19: "look at their pictures").

For each scene this runs it and writes one PNG, ``docs/pictures/<scene>.png``: a grid of
frames of the world (``World.picture``) at evenly spaced times, each labelled with its time,
and with the number of overlapping pairs when there are any.

Scenes: ``toppling`` and ``matchsticks`` (the scenes of examples/toppling.py and
examples/matchsticks.py, rebuilt here with the World API so that pygame is not needed),
``stack`` (10 boxes dropped with 1 cm gaps and sideways offsets), ``pyramid`` (15 boxes),
``ledge`` (a box with its centroid 2 cm past a ledge's edge, which should tip and fall),
``dominoes`` (a flicked row of 6): these four as tests/test_islands.py builds them; and
``ledge-pushed`` (a box sliding over the ledge's edge, which should tip and fall too).

Each scene runs in its own subprocess, which saves its frames as it goes; a run that takes
longer than ``--limit`` seconds of wall time (default 120, counted from when the world is
built, after imports and a warm-up) is stopped and its sheet says so. A first warm-up process
compiles the Numba kernels (2-3 minutes on a cold cache) so that the limit measures the
physics only.

    NUMBA_CACHE_DIR=/tmp/nc .venv/bin/python tools/pictures.py                 # everything
    .venv/bin/python tools/pictures.py --scenes stack ledge                    # some
    .venv/bin/python tools/pictures.py --frames 12 --log /tmp/pictures.jsonl   # + numbers

Each sheet's title gives the commit (and whether src/ had uncommitted changes), the run's
wall time and its event count. ``--log`` appends one JSON line per frame (time, events, wall
time, overlaps, and every moving body's position, angle and sleep state), to check in numbers
what the pictures show.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
G = 9.81
#: pixels on the longer side of one frame of a sheet.
TILE = 300
#: overlaps deeper than this are counted on a frame's label.
OVERLAP_TOLERANCE = 1e-6


def rgb(r: float, g: float, b: float) -> tuple[int, int, int]:
    """A colour given as 0..1 floats (as ``pge.rgb``) as 0..255 integers, for ``body.data``."""
    return tuple(int(round(255 * max(0.0, min(1.0, v)))) for v in (r, g, b))


# ---------------------------------------------------------------------- scenes


def toppling():
    """examples/toppling.py: a ball knocks over a tall block; a tilted crate, a spinning plank
    and a spinning wedge drop onto the floor of a walled unit square."""
    from pge import World

    world = World(gravity=(0.0, -G), elasticity=0.5, allow_overlap=True)
    wood = rgb(0.55, 0.35, 0.2)
    world.add_box(0.0, 0.0, 1.0, 0.05, fixed=True, friction=0.5, data={"colour": wood}, name="floor")
    world.add_box(0.0, 0.05, 0.02, 0.95, fixed=True, data={"colour": wood})
    world.add_box(0.98, 0.05, 0.02, 0.95, fixed=True, data={"colour": wood})
    world.add_box(0.3, 0.05, 0.04, 0.2, mass=0.2, friction=0.5, data={"colour": rgb(0.85, 0.25, 0.2)}, name="block")
    world.add_circle((0.08, 0.22), 0.03, mass=0.3, velocity=(1.5, 0.0), friction=0.2,
                     data={"colour": rgb(0.95, 0.8, 0.2)}, name="ball")
    world.add_box(0.6, 0.45, 0.1, 0.1, mass=0.5, friction=0.5, angle=0.5, data={"colour": rgb(0.3, 0.55, 0.9)},
                  name="crate")
    world.add_box(0.76, 0.67, 0.12, 0.06, mass=0.5, friction=0.5, angle=-0.9, angular_velocity=3.0,
                  data={"colour": rgb(0.3, 0.7, 0.4)}, name="plank")
    world.add_polygon([(0.84, 0.85), (0.94, 0.85), (0.89, 0.93)], mass=0.2, friction=0.5, angular_velocity=-6.0,
                      data={"colour": rgb(0.6, 0.3, 0.8)}, name="wedge")
    return world


def matchsticks():
    """examples/matchsticks.py: four matchboxes of fixed sticks, each with a blue ball inside;
    three thrown balls knock out every stick they hit; a freed blue ball reaching the floor is
    collected (removed). Every elasticity is 1. (The example's countdown text is left out.)"""
    from pge import World

    world = World(gravity=(0.0, -G), elasticity=1.0, allow_overlap=True)
    wall, stick = 0.01, 0.01
    wood, match, blue = rgb(0.55, 0.35, 0.2), rgb(0.9, 0.75, 0.45), rgb(0.2, 0.35, 0.9)
    sticks, trapped = set(), set()
    thrown = [
        world.add_circle((0.19, 0.8), 0.04, mass=1.25, velocity=(0.8, -0.5), data={"colour": rgb(0.95, 0.8, 0.2)}),
        world.add_circle((0.57, 0.75), 0.04, mass=1.0, velocity=(-0.7, 0.9), data={"colour": rgb(0.75, 0.75, 0.8)}),
        world.add_circle((0.81, 0.7), 0.04, mass=0.75, velocity=(-1.1, -0.2), data={"colour": rgb(0.8, 0.45, 0.2)}),
    ]
    floor = world.add_box(0.0, 0.0, 1.0, wall, fixed=True, data={"colour": wood}, name="floor")
    world.add_box(0.0, 1.0 - wall, 1.0, wall, fixed=True, data={"colour": wood})
    world.add_box(0.0, 0.0, wall, 1.0, fixed=True, data={"colour": wood})
    world.add_box(1.0 - wall, 0.0, wall, 1.0, fixed=True, data={"colour": wood})
    for k in range(4):
        x, y, width, height = 0.08 + 0.23 * k, 0.1, 0.17, 0.2
        for box in (
            (x, y, width, stick),
            (x, y + height - stick, width, stick),
            (x, y + stick, stick, height - 2 * stick),
            (x + width - stick, y + stick, stick, height - 2 * stick),
        ):
            sticks.add(world.add_box(*box, fixed=True, data={"colour": match}).id)
        ball = world.add_circle((x + width / 2, y + stick + 0.06), 0.035, mass=1.5, velocity=(0.15, 0.0),
                                data={"colour": blue})
        trapped.add(ball.id)

    def knock_out(event):
        """A thrown ball hit a stick: the stick is removed."""
        for body in (event.a, event.b):
            if body.alive and body.id in sticks:
                sticks.discard(body.id)
                world.remove(body)

    def collect(event):
        """A freed blue ball reached the floor: it is removed."""
        for body in (event.a, event.b):
            if body.alive and body.id in trapped:
                trapped.discard(body.id)
                world.remove(body)

    for ball in thrown:
        world.on_collision(knock_out, ball)
    world.on_collision(collect, floor)
    return world


def _floor_world():
    """tests/test_islands.py's floor: a fixed slab whose top face is y = 0."""
    from pge import World

    world = World(gravity=(0.0, -G), bounds=(-2.0, -1.0, 2.0, 3.0))
    world.add_box(-2.0, -1.0, 4.0, 1.0, fixed=True)
    return world


def stack(seed: int = 0):
    """10 boxes 0.2 x 0.2 dropped with 1 cm gaps and sideways offsets drawn from +-0.005
    (test_a_stack_of_10_boxes_dropped_with_gaps_and_offsets_settles_and_then_makes_no_events)."""
    import numpy as np

    world = _floor_world()
    rng = np.random.default_rng(seed)
    for k in range(10):
        world.add_box(-0.1 + rng.uniform(-0.005, 0.005), k * 0.21 + 0.01, 0.2, 0.2, mass=1.0, friction=0.5,
                      elasticity=0.3)
    return world


def pyramid(rows: int = 5):
    """A pyramid of 15 boxes, each 2 mm narrower than its 0.2 pitch and 0.5 mm above the row
    under it (test_a_pyramid_of_15_boxes_stands_and_then_makes_no_events)."""
    world = _floor_world()
    for r in range(rows):
        for c in range(rows - r):
            x = -rows * 0.1 + r * 0.1 + c * 0.2
            world.add_box(x + 0.001, r * 0.2005, 0.198, 0.2, mass=1.0, friction=0.6, elasticity=0.1)
    return world


def ledge(d: float = 0.02):
    """A 0.2 box at rest on a ledge (top y = 0, edge x = 0) with its centroid ``d`` past the
    edge; a floor 1.8 below (test_a_box_past_a_ledge_tips_over_its_edge_as_the_pivot_ode_says).
    It should pivot about the edge, slip off at about 0.31 s and fall to the floor."""
    from pge import World

    world = World(gravity=(0.0, -G), bounds=(-2.0, -2.0, 2.0, 2.0))
    world.add_box(-2.0, -1.0, 2.0, 1.0, fixed=True)
    world.add_box(-2.0, -2.0, 4.0, 0.2, fixed=True)
    world.add_box(d - 0.1, 0.0, 0.2, 0.2, mass=1.0, friction=1.0, elasticity=0.0)
    return world


def ledge_pushed():
    """The same ledge, with the box pushed over it: it starts wholly on the ledge (centroid
    5 cm before the edge) sliding at 0.5 m/s with friction 0.1, so that friction alone would
    stop it with its centroid 7.7 cm past the edge. It should tip over the edge and fall once
    its centroid passes the edge (at about 0.1 s)."""
    from pge import World

    world = World(gravity=(0.0, -G), bounds=(-2.0, -2.0, 2.0, 2.0))
    world.add_box(-2.0, -1.0, 2.0, 1.0, fixed=True)
    world.add_box(-2.0, -2.0, 4.0, 0.2, fixed=True)
    world.add_box(-0.15, 0.0, 0.2, 0.2, mass=1.0, friction=0.1, elasticity=0.0, velocity=(0.5, 0.0))
    return world


def dominoes(count: int = 6):
    """A row of 6 dominoes 0.02 x 0.2, 0.1 apart; the first is flicked towards the others
    (angular velocity -8 rad/s) (test_dominoes_topple_in_order)."""
    world = _floor_world()
    row = [world.add_box(-0.5 + 0.1 * k, 0.0, 0.02, 0.2, mass=0.1, friction=0.5, elasticity=0.0)
           for k in range(count)]
    row[0].angular_velocity = -8.0
    return world


#: name -> (builder, duration in simulated seconds, region shown (x0, y0, x1, y1), frames).
SCENES = {
    "toppling": (toppling, 6.0, (0.0, 0.0, 1.0, 1.0), 12),
    "matchsticks": (matchsticks, 15.0, (0.0, 0.0, 1.0, 1.0), 12),
    "stack": (stack, 3.0, (-0.9, -0.1, 0.9, 2.3), 10),
    "pyramid": (pyramid, 3.0, (-0.8, -0.1, 0.8, 1.2), 10),
    "ledge": (ledge, 1.5, (-0.8, -2.0, 1.0, 0.4), 10),
    "ledge-pushed": (ledge_pushed, 1.5, (-0.8, -2.0, 1.0, 0.4), 10),
    "dominoes": (dominoes, 2.0, (-0.65, -0.05, 0.35, 0.3), 10),
}


# ---------------------------------------------------------------------- the worker


def _body_states(world) -> list:
    """Every moving body's id, position, angle and sleep state, rounded for the log."""
    states = []
    for body in world.bodies:
        if body.is_fixed:
            continue
        x, y = body.position
        states.append([body.id, round(x, 6), round(y, 6), round(body.angle, 6), bool(body.asleep)])
    return states


def work(scene: str, frames: int, folder: Path, duration: float) -> None:
    """Run one scene (in a subprocess): save frame k as ``folder/frame-k.png``
    and its numbers as a line of ``folder/frames.jsonl``, and write ``folder/started`` once the
    world is built (the parent's wall-time limit counts from then)."""
    import warnings

    warnings.simplefilter("ignore")  # OverlapWarning, LeftWorldWarning: the pictures show them
    builder, _, region, _ = SCENES[scene]
    try:
        _warm()
    except Exception:  # the scene itself will show what is wrong
        pass
    world = builder()
    start = time.perf_counter()
    (folder / "started").write_text(str(time.time()))
    with open(folder / "frames.jsonl", "a") as log:
        for k in range(frames):
            t = duration * k / (frames - 1)
            try:
                world.run_until(t)
            except Exception as error:  # TooFastError, EventStormError, ...: shown on the sheet
                record = {"k": k, "t": world.time, "error": f"{type(error).__name__}: {error}"[:300]}
                log.write(json.dumps(record) + "\n")
                log.flush()
                try:
                    world.picture(folder / f"frame-{k}.png", size=TILE, bounds=region)
                except Exception:
                    pass
                return
            world.picture(folder / f"frame-{k}.png", size=TILE, bounds=region)
            overlaps = world.overlaps(OVERLAP_TOLERANCE)
            record = {
                "k": k,
                "t": t,
                "wall": round(time.perf_counter() - start, 3),
                "events": world.stats.get("events"),
                "overlaps": len(overlaps),
                "deepest": max((depth for _, _, depth in overlaps), default=0.0),
                "bodies": _body_states(world),
            }
            log.write(json.dumps(record) + "\n")
            log.flush()


def _warm() -> None:
    """Compile (or load from Numba's cache) the kernels a run needs, on a small scene of every
    kind of contact (box on floor, ball into a box, a tumbling triangle, a removal), so that a
    run's wall time measures its physics and not the compiler."""
    import warnings

    from pge import World

    warnings.simplefilter("ignore")
    world = World(gravity=(0.0, -G), bounds=(-1.0, -1.0, 1.0, 1.0), elasticity=0.5)
    world.add_box(-1.0, -1.0, 2.0, 0.5, fixed=True)
    world.add_box(0.0, -0.5, 0.05, 0.2, mass=0.2, friction=0.5)
    world.add_circle((-0.3, -0.4), 0.03, mass=0.3, velocity=(1.5, 0.0), friction=0.2)
    world.add_box(0.3, -0.3, 0.1, 0.1, mass=0.5, friction=0.5, angle=0.5)
    world.add_polygon([(0.6, 0.0), (0.7, 0.0), (0.65, 0.08)], mass=0.2, friction=0.5, angular_velocity=-6.0)
    gone = world.add_box(-0.9, -0.5, 0.05, 0.05, fixed=True)
    world.on_collision(lambda event: None)
    world.run_until(0.3)
    world.remove(gone)
    world.run_until(1.0)
    world.picture(size=64)
    world.overlaps(OVERLAP_TOLERANCE)


def warm_up() -> None:
    """Compile the kernels (errors are printed, not raised)."""
    try:
        _warm()
    except Exception as error:
        print(f"warm-up: {type(error).__name__}: {error}", file=sys.stderr)


# ---------------------------------------------------------------------- the parent


def run_one(scene: str, frames: int, limit: float, duration: float) -> dict:
    """Run ``scene`` in a subprocess, stopping it after ``limit`` wall seconds
    from when its world is built; returns its frames (images and numbers) and how it ended."""
    from PIL import Image

    with tempfile.TemporaryDirectory(prefix=f"pictures-{scene}-") as name:
        folder = Path(name)
        command = [sys.executable, str(Path(__file__).resolve()), "--worker", scene, str(folder),
                   "--frames", str(frames), "--duration", repr(duration)]
        began = time.time()
        process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
        stopped = False
        while process.poll() is None:
            time.sleep(0.2)
            started = folder / "started"
            if started.exists() and time.time() - float(started.read_text() or began) > limit:
                process.kill()
                stopped = True
            elif time.time() - began > limit + 900:  # never built its world (compiling for ever?)
                process.kill()
                stopped = True
        stderr = process.communicate()[1] or ""
        wall = time.time() - began
        records = []
        if (folder / "frames.jsonl").exists():
            records = [json.loads(line) for line in (folder / "frames.jsonl").read_text().splitlines() if line]
        images = []
        for record in records:
            path = folder / f"frame-{record['k']}.png"
            if path.exists():
                with Image.open(path) as image:
                    images.append((record, image.copy()))
        built = (folder / "started").exists()
        run_wall = records[-1].get("wall") if records and "wall" in records[-1] else None
    return {
        "scene": scene,
        "frames": images,
        "records": records,
        "stopped": stopped,
        "returncode": process.returncode,
        "stderr": stderr.strip().splitlines()[-3:] if process.returncode and not stopped else [],
        "wall": wall,
        "run_wall": run_wall,
        "built": built,
    }


def provenance() -> str:
    """The commit the pictures were made from, and whether src/ had uncommitted changes."""
    try:
        commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "src"], capture_output=True,
                               text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "commit unknown"
    return f"commit {commit}" + (" + uncommitted changes in src/" if dirty else "")


def contact_sheet(result: dict, frames: int, limit: float, duration: float, source: str = ""):
    """The grid of labelled frames of one run, with a title line saying how the run ended and
    where the code came from (``source``, see ``provenance``)."""
    from PIL import Image, ImageDraw

    region = SCENES[result["scene"]][2]
    x0, y0, x1, y1 = region
    k = TILE / max(x1 - x0, y1 - y0)
    width, height = max(1, round((x1 - x0) * k)), max(1, round((y1 - y0) * k))
    columns = min(frames, 6 if width < height else 4)
    rows = math.ceil(frames / columns)
    gap, label, title = 4, 30, 40
    sheet = Image.new("RGB", (columns * (width + gap) + gap, title + rows * (height + label + gap) + gap),
                      (245, 245, 245))
    draw = ImageDraw.Draw(sheet)
    ending = f"{result['scene']} - {frames} frames, 0 to {duration:g} s"
    if result["stopped"]:
        last = result["records"][-1]["t"] if result["records"] else 0.0
        ending += f" - STOPPED after {limit:g} s wall at t = {last:.3g} s"
    elif result["records"] and "error" in result["records"][-1]:
        ending += f" - {result['records'][-1]['error'][:90]}"
    elif result["returncode"]:
        ending += f" - worker failed: {' '.join(result['stderr'])[:90]}"
    elif result["run_wall"] is not None:
        ending += f" - {result['run_wall']:.1f} s wall, {result['records'][-1].get('events')} events"
    draw.text((gap, 6), ending, fill=(0, 0, 0))
    draw.text((gap, 20), f"labels: simulated time, overlapping pairs (> 1e-6) if any; {source}",
              fill=(90, 90, 90))
    for n, (record, image) in enumerate(result["frames"]):
        row, column = divmod(n, columns)
        left = gap + column * (width + gap)
        top = title + row * (height + label + gap)
        sheet.paste(image.resize((width, height)), (left, top + label))
        text = f"t = {record['t']:.3f} s"
        note = ""
        if "error" in record:
            note = record["error"].split(":")[0]
        elif record.get("overlaps"):
            note = f"{record['overlaps']} overlapping (max {record['deepest']:.2g})"
        draw.text((left + 2, top + 2), text, fill=(0, 0, 0))
        if note:
            draw.text((left + 2, top + 15), note, fill=(200, 0, 0))
    shown = len(result["frames"])
    if shown < frames and (result["stopped"] or result["returncode"]):
        row, column = divmod(shown, columns)
        left = gap + column * (width + gap)
        top = title + row * (height + label + gap)
        missing = duration * shown / (frames - 1)
        why = f"stopped: over {limit:g} s wall" if result["stopped"] else "the worker failed"
        draw.rectangle((left, top + label, left + width - 1, top + label + height - 1), outline=(200, 0, 0), width=2)
        draw.text((left + 6, top + label + 6), f"{why}\nbefore reaching t = {missing:.3f} s", fill=(200, 0, 0))
    return sheet


def main(argv=None) -> int:
    """Parse the command line; run the worker, or run every scene and write the sheets."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", nargs="+", choices=list(SCENES), default=list(SCENES), help="scenes to draw")
    parser.add_argument("--frames", type=int, default=None,
                        help="frames per sheet (8-12 is readable; default: each scene's own, 10 or 12)")
    parser.add_argument("--duration", type=float, default=None,
                        help="simulated seconds shown (default: each scene's own)")
    parser.add_argument("--limit", type=float, default=120.0, help="wall seconds before a run is stopped")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "pictures", help="folder of the sheets")
    parser.add_argument("--log", type=Path, default=None, help="append every frame's numbers (JSON lines) here")
    parser.add_argument("--no-warm-up", action="store_true", help="skip compiling the kernels first")
    parser.add_argument("--worker", nargs=2, metavar=("SCENE", "FOLDER"), help=argparse.SUPPRESS)
    parser.add_argument("--warm-up-only", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.frames is not None and args.frames < 2:
        parser.error("--frames must be at least 2")
    sys.path.insert(0, str(ROOT / "src"))
    if args.warm_up_only:
        warm_up()
        return 0
    if args.worker:
        scene, folder = args.worker
        work(scene, args.frames or SCENES[scene][3], Path(folder), args.duration or SCENES[scene][1])
        return 0
    if not args.no_warm_up:
        began = time.time()
        subprocess.run([sys.executable, str(Path(__file__).resolve()), "--warm-up-only"], check=False)
        print(f"warm-up (kernel compilation): {time.time() - began:.1f} s", flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    source = provenance()
    print(f"pictures of {source}", flush=True)
    for scene in args.scenes:
        duration = args.duration or SCENES[scene][1]
        frames = args.frames or SCENES[scene][3]
        result = run_one(scene, frames, args.limit, duration)
        sheet = contact_sheet(result, frames, args.limit, duration, source)
        path = args.out / f"{scene}.png"
        sheet.save(path)
        if args.log is not None:
            with open(args.log, "a") as log:
                for record in result["records"]:
                    log.write(json.dumps({"scene": scene, **record}) + "\n")
        last = result["records"][-1] if result["records"] else {}
        how = ("STOPPED" if result["stopped"] else last.get("error", "").split(":")[0] or
               ("failed" if result["returncode"] else "ok"))
        run_wall = "-" if result["run_wall"] is None else f"{result['run_wall']:.1f}"
        if result["stopped"]:
            run_wall = f">{args.limit:g}"
        print(f"{scene:13s} {how:10s} run {run_wall:>6s} s wall, process {result['wall']:.1f} s, "
              f"t = {last.get('t', 0.0):.3f}, events {last.get('events')}, overlaps {last.get('overlaps')}"
              f" -> {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}", flush=True)
        for line in result["stderr"]:
            print(f"    {line}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
