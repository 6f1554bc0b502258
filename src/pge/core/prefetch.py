"""A hint to the processor: start loading an array row into cache now, for use later.

The event loop knows the next event's bodies as soon as it has popped the current
one (the queue's new earliest entry names them in its key), and an event's own
work takes about a microsecond. Among a hundred thousand bodies their rows are
rarely in cache; asking for them one event ahead lets the loads run while the
current event is processed instead of stalling the next one. The grid does the same
for a prediction's candidates (``pge.core.grid.gather``): the first row of each cell's
list before the lists are walked, and each candidate's row as it is found.
"""

from __future__ import annotations

import llvmlite.binding as llvm
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

#: the intrinsic's name: pointers are untyped ("opaque") from LLVM 15 on
_PREFETCH = "llvm.prefetch.p0" if llvm.llvm_version_info[0] >= 15 else "llvm.prefetch.p0i8"


@intrinsic
def prefetch_row(typingctx, array, row):
    """Ask for the cache line holding the start of ``array[row]`` (a read, kept in all
    cache levels); no effect on the program's results, and no fault for any row."""
    if not isinstance(array, types.Array) or not isinstance(row, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        kind, row_type = signature.args
        view = context.make_array(kind)(context, builder, args[0])
        index = context.cast(builder, args[1], row_type, types.intp)
        stride = builder.extract_value(view.strides, 0)
        # Plain address arithmetic, no load: prefetching an address outside the array
        # is harmless (the hint is dropped), so no bounds check is needed.
        address = builder.add(builder.ptrtoint(view.data, cgutils.intp_t), builder.mul(index, stride))
        byte_pointer = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        function = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [byte_pointer, i32, i32, i32]), _PREFETCH
        )
        builder.call(function, [builder.inttoptr(address, byte_pointer), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return types.void(array, row), codegen
