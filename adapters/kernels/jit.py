"""The decorator of every kernel: numba's ``njit``, cached, keyed on all kernel modules at once.

numba compiles a function once and caches it next to its module (``__pycache__``, or the
user's cache folder where that is not writable; ``NUMBA_CACHE_DIR`` overrides both), keyed on
the content of that module's file alone. A kernel, however, compiles in what it calls and the
buffer offsets it reads from the other kernel modules, so a cache keyed on its own file would
run stale code after one of them changed. Here the key is a digest of every module of the
``kernels`` package: a change in any of them compiles all kernels again on the next start.
The cache is still keyed on the CPU and written atomically, so processes may share it.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from numba import njit
from numba.core.caching import (
    CompileResultCacheImpl,
    FunctionCache,
    InTreeCacheLocator,
    UserProvidedCacheLocator,
    UserWideCacheLocator,
)


def digest(folder: Path) -> bytes:
    """One digest of the kernel modules in ``folder``, by name and content."""
    hashed = hashlib.sha256()
    for path in sorted(folder.glob("*.py")):
        hashed.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return hashed.digest()


KERNELS = digest(Path(__file__).parent)
"""The cache key of every kernel: the digest of all kernel modules as they are now."""


class _KernelStamp:
    """numba's source stamp of a cached function, made the digest of all kernel modules."""

    def get_source_stamp(self) -> bytes:
        return KERNELS


class _UserProvided(_KernelStamp, UserProvidedCacheLocator):
    """In ``NUMBA_CACHE_DIR`` when it is set."""


class _InTree(_KernelStamp, InTreeCacheLocator):
    """In ``__pycache__`` next to the module."""


class _UserWide(_KernelStamp, UserWideCacheLocator):
    """In the user's cache folder, where ``__pycache__`` is not writable."""


class _KernelCacheImpl(CompileResultCacheImpl):
    _locator_classes = [_UserProvided, _InTree, _UserWide]  # noqa: RUF012 (numba's name)


class _KernelCache(FunctionCache):
    _impl_class = _KernelCacheImpl


def kernel(function: Callable[..., Any]) -> Any:
    """``function`` compiled by numba with NumPy's error model (a division by zero gives
    inf/nan as in NumPy, with no Python check), cached under the kernels' digest: what
    ``njit(cache=True)`` does, with this cache in place of numba's own."""
    dispatcher = njit(error_model="numpy")(function)
    dispatcher._cache = _KernelCache(function)
    return dispatcher
