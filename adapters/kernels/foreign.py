"""Native code that reaches other libraries' memory and functions: a C function called by its
address (MuJoCo's ``mj_jacSite`` and ``mj_fullM``) and float64 arrays read in place at an
address (Pinocchio's data)."""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.extending import intrinsic


@intrinsic
def c_call(typingctx, function, arguments):
    """Call the C function at address ``function`` with a tuple of integer ``arguments``, all
    passed as pointers but the last, passed as a C int if there are five (MuJoCo's
    ``mj_jacSite(m, d, jacp, jacr, site)`` and ``mj_fullM(m, d, dst)``)."""
    count = len(arguments)
    signature = types.void(function, arguments)

    def codegen(context, builder, sig, args):
        pointer = ir.IntType(8).as_pointer()
        values = [builder.extract_value(args[1], i) for i in range(count)]
        kinds = [pointer] * count
        if count == 5:
            kinds[4] = ir.IntType(32)
        converted = [
            builder.trunc(v, kind) if kind is not pointer else builder.inttoptr(v, pointer)
            for v, kind in zip(values, kinds, strict=True)
        ]
        target = builder.inttoptr(args[0], ir.FunctionType(ir.VoidType(), kinds).as_pointer())
        builder.call(target, converted)
        return context.get_dummy_value()

    return signature, codegen


@intrinsic
def doubles_at(typingctx, address):
    """A pointer to the float64 values at ``address``, for ``carray``/``farray`` to read another
    library's arrays in place (Pinocchio's data, whose arrays Eigen allocates once)."""
    signature = types.CPointer(types.float64)(address)

    def codegen(context, builder, sig, args):
        return builder.inttoptr(args[0], context.get_value_type(sig.return_type))

    return signature, codegen
