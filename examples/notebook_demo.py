# %% [markdown]
# # Watching a pge World in a notebook
#
# Open this file in Jupyter (or VS Code) as a notebook: each `# %%` line starts a cell. Run as a
# plain script (`python examples/notebook_demo.py`) it writes the same things to `out/` instead.
#
# A World shows itself as a picture; `world.animate(until=...)` runs it and plays the run inline.

# %%
from pathlib import Path

from pge import World

world = World(gravity=(0.0, -9.81), elasticity=0.9)
world.add_box(0.0, 0.0, 1.0, 0.04, fixed=True, name="floor")
world.add_box(0.0, 0.04, 0.04, 0.96, fixed=True, name="left wall")
world.add_box(0.96, 0.04, 0.04, 0.96, fixed=True, name="right wall")
world.add_polygon([(0.04, 0.45), (0.55, 0.04), (0.04, 0.04)], fixed=True, name="slope")
ball = world.add_circle((0.12, 0.6), 0.04, mass=1.0, name="ball", data={"colour": (250, 200, 0)})
crate = world.add_box(0.62, 0.3, 0.12, 0.12, mass=2.0, velocity=(0.0, 1.0), name="crate")
world  # the last expression of a cell is displayed: here, the picture of the world now

# %% [markdown]
# Run two seconds and watch them: play, pause, step, seek and the speed are under the scene, and
# the collisions are listed beside it.

# %%
run = world.animate(until=2.0)
run

# %% [markdown]
# The world has moved on to t = 2 s; its picture shows where everything ended up.

# %%
print(f"t = {world.time:g} s, ball at ({ball.position[0]:.3f}, {ball.position[1]:.3f})")
world

# %%
if __name__ == "__main__":  # as a script: write what the notebook would show
    out = Path("out")
    world.picture(out / "notebook_demo.png")
    run.save(out / "notebook_demo.html")
    print(f"wrote {out / 'notebook_demo.png'} and {out / 'notebook_demo.html'} ({run.frames} frames)")
