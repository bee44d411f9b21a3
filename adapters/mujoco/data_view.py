"""MuJoCo's data as one flat float64 array, so that a native function takes it as one argument;
the addresses of MuJoCo's functions, so that native code calls them without the bindings.

Each array argument of a numba function costs ~0.15 µs to pass, and the tick reads seven of
MuJoCo's arrays. MuJoCo allocates every array of ``mjData`` in one buffer (mjdata.h:
"main buffer; all pointers point in it"), so one view spanning the arrays a tick needs,
with their offsets, replaces them. The view does not own the memory: its owner keeps the
``MjData`` alive as long as the view.
"""

from __future__ import annotations

import ctypes
from pathlib import Path

import mujoco
import numpy as np


def data_view(data: mujoco.MjData, names: tuple[str, ...]) -> tuple[np.ndarray, dict[str, int]]:
    """A float64 array over ``data``'s buffer from the first to the end of the last of the named
    arrays, and the offset (in elements) of each."""
    arrays = {name: getattr(data, name) for name in names}
    for name, array in arrays.items():
        if array.dtype != np.float64 or not array.flags.c_contiguous:
            raise ValueError(f"mjData.{name} is not a contiguous float64 array")
    starts = {name: array.ctypes.data for name, array in arrays.items()}
    base = min(starts.values())
    end = max(starts[name] + array.nbytes for name, array in arrays.items())
    if any((start - base) % 8 for start in starts.values()):
        raise ValueError("mjData arrays are not aligned to float64")
    view = np.ctypeslib.as_array((ctypes.c_double * ((end - base) // 8)).from_address(base))
    return view, {name: (start - base) // 8 for name, start in starts.items()}


def function_address(name: str) -> int:
    """Address of a function of the MuJoCo library that the bindings load (the same file, so
    the same loaded library), for native code to call."""
    folder = Path(mujoco.__file__).parent
    for pattern in ("libmujoco.so*", "libmujoco*.dylib", "mujoco.dll"):
        for path in sorted(folder.glob(pattern)):
            library = ctypes.CDLL(str(path))
            return ctypes.cast(getattr(library, name), ctypes.c_void_p).value
    raise RuntimeError(f"no MuJoCo library next to {mujoco.__file__}")
