"""Module constants of the original ``pge`` module, with their original values.

Object kinds (``obj.type``), devices, event kinds, the program name and the
PGE version this module is compatible with, the default frame rate and black.
"""

from __future__ import annotations

__all__ = [
    "colour_t",
    "box_t",
    "circle_t",
    "spring_t",
    "fb_box_t",
    "fb_circle_t",
    "fb_text_t",
    "batch_d",
    "pyg_d",
    "no_event",
    "frame_event",
    "collision_event",
    "function_event",
    "spring_event",
    "final_event",
    "program_name",
    "version_number",
    "Black",
    "DEFAULT_FPS",
    "DEFAULT_ELASTICITY",
    "DEFAULT_GRAVITY",
    "VELOCITY_DAMPING",
    "STILL_COMPONENT",
    "KIND_NAMES",
]

# kinds of object (the value of ``obj.type``)
colour_t, box_t, circle_t, spring_t, fb_box_t, fb_circle_t, fb_text_t = range(7)
# devices
batch_d, pyg_d = 0, 1
# kinds of event
no_event, frame_event, collision_event, function_event, spring_event, final_event = range(6)

program_name = "pge"
#: the version of the original PGE whose API this module reproduces.
version_number = "4.0"
Black = (0, 0, 0)

#: frames per second until ``fps()`` is called (the original's ``framesPerSecond``).
DEFAULT_FPS = 100.0
#: elasticity of every object until ``elasticity()`` is called.
DEFAULT_ELASTICITY = 0.98
#: the factor the original's velocity reads and writes multiply both components by (its
#: ``checkStationary``); ``velocity_damping(1.0)`` turns it off.
VELOCITY_DAMPING = 0.98
#: velocity components below this (in size) are set to 0 when a read or write damps them
STILL_COMPONENT = 0.01
#: the default of ``gravity(value=...)``: y acceleration in world units per second squared.
DEFAULT_GRAVITY = -9.81

#: words used in messages for each kind of object.
KIND_NAMES = {
    colour_t: "colour",
    box_t: "box",
    circle_t: "circle",
    spring_t: "spring",
    fb_box_t: "foreground/background box",
    fb_circle_t: "foreground/background circle",
    fb_text_t: "text",
}
