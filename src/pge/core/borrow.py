"""Borrowed arrays: the engine state seen by compiled code without reference counts.

Numba counts references to every array it handles: a compiled function that
receives the state tuple ``S`` adds one to each of its arrays on entry and takes
it off on exit, with an atomic instruction each, and an inlined helper that
reads ``S`` does the same again. In the event loop, where a handful of such
calls make an event, those counts were about 40 % of an event's time.

The state's arrays are owned by ``pge.core.state.EngineState`` for the whole of
a compiled call, and no compiled code keeps one of them past its call (the
state tuple is immutable and arrays grow only in Python, between calls). So a
long-running entry point may take the state as *borrowed*: the same arrays with
no owner record (a null ``meminfo``), for which Numba's count updates return at
once. Everything else about the arrays (data, shape, strides, type) is
unchanged, so no function is compiled again for them.
"""

from __future__ import annotations

from numba.core import cgutils, types
from numba.extending import intrinsic


def _dropped_owner(context, builder, kind, value):
    """The array ``value`` of type ``kind`` with its owner record set to null."""
    array = context.make_array(kind)(context, builder, value=value)
    array.meminfo = cgutils.get_null_value(array.meminfo.type)
    return array._getvalue()


@intrinsic
def borrowed(typingctx, state):
    """``state`` (a tuple of arrays) with every array's owner record dropped.

    Only for a tuple whose arrays a caller outside compiled code keeps alive until
    the compiled call that borrows them returns.
    """
    if not isinstance(state, types.BaseTuple) or not all(isinstance(t, types.Array) for t in state):
        return None

    def codegen(context, builder, signature, args):
        (value,) = args
        items = [
            _dropped_owner(context, builder, kind, builder.extract_value(value, k)) for k, kind in enumerate(state)
        ]
        return context.make_tuple(builder, state, items)

    return state(state), codegen


@intrinsic
def borrowed_array(typingctx, array):
    """``array`` with its owner record dropped: only for an argument of the compiled function
    that borrows it (its caller keeps it alive until that function returns), never for a
    local (Numba may release a local after its last use, before the borrowed copy's), and
    only where nothing stores or returns the copy.
    The contact solve's sweeps pass their arrays through small inlined helpers thousands of
    times a step, and each pass counted references (two atomic instructions) where the
    arithmetic around them is a few additions."""
    if not isinstance(array, types.Array):
        return None

    def codegen(context, builder, signature, args):
        return _dropped_owner(context, builder, array, args[0])

    return array(array), codegen
