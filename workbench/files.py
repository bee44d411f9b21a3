"""Writing files so that a failed or killed run leaves nothing half-written behind.

A single file is written beside its target and renamed over it. A folder of generated files
is built whole in a fresh sibling folder (a copy of the old one plus the new files) and
swapped in by renames recorded in a journal beside it; a run killed during the swap leaves
the journal, and the next write to that folder completes the swap before anything else.
"""

from __future__ import annotations

import contextlib
import errno
import glob
import json
import os
import shutil
import stat
import tempfile
from collections.abc import Mapping
from pathlib import Path


def write_atomic(path: Path, text: str) -> None:
    """Replace the file ``path`` (through a symlink: its target) by ``text``, keeping the
    file's permission bits; a temporary file beside it is renamed into place."""
    target = path.resolve()
    mode = stat.S_IMODE(target.stat().st_mode) if target.exists() else None
    handle, temporary = tempfile.mkstemp(
        dir=target.parent, prefix=f".{target.name}.", suffix=".tmp"
    )
    try:
        with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)
        if mode is not None:
            os.chmod(temporary, mode)
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def write_tree(output: Path, files: Mapping[str, str | bytes]) -> list[Path]:
    """Write every file below the folder ``output`` (relative path -> content), or none:
    files already there and not named in ``files`` stay as they were."""
    recover(output)
    if output.is_dir() and not os.access(output, os.W_OK | os.X_OK):  # read-only stays so
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(output))
    output.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{output.name}.new-", dir=output.parent))
    try:
        if output.is_dir():
            shutil.copytree(output, staging, symlinks=True, dirs_exist_ok=True)
            shutil.copymode(output, staging)
        else:
            staging.chmod(0o777 & ~_umask())
        for relative, content in sorted(files.items()):
            staged = staging / relative
            staged.parent.mkdir(parents=True, exist_ok=True)
            if staged.is_symlink():  # a link copied from the old folder: replace, not follow
                staged.unlink()
            if isinstance(content, bytes):
                staged.write_bytes(content)
            else:
                staged.write_text(content, encoding="utf-8", newline="\n")
        if output.exists():
            _swap(output, staging)
        else:
            os.rename(staging, output)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return [output / relative for relative in sorted(files)]


def recover(output: Path) -> None:
    """Complete a swap of ``output`` that a killed run left in its journal; drop folders a
    killed run was still building."""
    journal = _journal(output)
    if journal.exists():
        with contextlib.suppress(ValueError, OSError, KeyError, TypeError):
            names = json.loads(journal.read_text(encoding="utf-8"))
            new, old = output.parent / names["new"], output.parent / names["old"]
            if new.is_dir():
                if output.exists() and not old.exists():
                    os.rename(output, old)
                os.rename(new, output)
        journal.unlink(missing_ok=True)
    for kind in ("new", "old"):
        pattern = f".{glob.escape(output.name)}.{kind}-*"
        for leftover in output.parent.glob(pattern):
            shutil.rmtree(leftover, ignore_errors=True)


def _swap(output: Path, staging: Path) -> None:
    """Old folder aside, new folder in: two renames, journaled so that a kill between them
    is completed by :func:`recover`."""
    old = staging.with_name(staging.name.replace(".new-", ".old-", 1))
    journal = _journal(output)
    write_atomic(journal, json.dumps({"new": staging.name, "old": old.name}))
    os.rename(output, old)
    os.rename(staging, output)
    journal.unlink()
    shutil.rmtree(old, ignore_errors=True)


def _journal(output: Path) -> Path:
    return output.with_name(f".{output.name}.lightrocks-swap")


def _umask() -> int:
    """The process's file-creation mask (read by setting it, then restoring it)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask
