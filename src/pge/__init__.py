"""pge: a predictive 2D physics and game engine.

The modern entry point is ``pge.World``; bodies are circles and convex
polygons moving under constant accelerations, and every collision is found at
its exact time.
"""

from pge import _jit_cache  # noqa: F401  (must come first: it configures the kernel cache)
from pge.bodies import Body
from pge.events import Collision, Frame, Stop, Timer
from pge.shapes import Circle, Polygon
from pge.world import World

__version__ = "0.1.0"

__all__ = ["World", "Body", "Circle", "Polygon", "Collision", "Timer", "Frame", "Stop", "__version__"]
