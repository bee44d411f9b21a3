"""Writing files so that a failed or killed run leaves nothing half-written behind.

A single file is written beside its target and renamed over it. A new folder of generated
files is built whole beside where it goes and renamed into place. Into an existing folder,
the files are staged inside it first; a journal listing them is written before the first
one is moved in, and removed after the last: a run killed in between leaves the journal, and
the next write to that folder moves the remaining files before anything else (a run killed
before the journal leaves only its staging folder, which the next write deletes).
"""

from __future__ import annotations

import contextlib
import glob
import json
import os
import shutil
import stat
import tempfile
from collections.abc import Mapping
from pathlib import Path

STAGING = ".lightrocks-staging-"
JOURNAL = ".lightrocks-journal"


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
    """Write every file below the folder ``output`` (relative path -> content), or none;
    files already there and not named in ``files`` stay as they are."""
    recover(output)
    created = not output.exists()
    if created:
        output.parent.mkdir(parents=True, exist_ok=True)
    if created:  # beside it, named after it, so that the next write finds a leftover
        staging = Path(tempfile.mkdtemp(prefix=_sibling(output), dir=output.parent))
    else:
        staging = Path(tempfile.mkdtemp(prefix=STAGING, dir=output))
    try:
        for relative, content in sorted(files.items()):
            staged = staging / relative
            staged.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, bytes):
                staged.write_bytes(content)
            else:
                staged.write_text(content, encoding="utf-8", newline="\n")
        if created:
            staging.chmod(0o777 & ~_umask())
            os.rename(staging, output)
        else:
            write_atomic(output / JOURNAL, json.dumps([staging.name, sorted(files)]))
            _move_in(output, staging, sorted(files))
            (output / JOURNAL).unlink()
    finally:  # once journaled, the staged files belong to the next write's recovery
        if created or not (output / JOURNAL).exists():
            shutil.rmtree(staging, ignore_errors=True)
    return [output / relative for relative in sorted(files)]


def recover(output: Path) -> None:
    """Finish the moves a killed write into ``output`` recorded in its journal; delete
    staging folders that no journal names."""
    for leftover in output.parent.glob(glob.escape(_sibling(output)) + "*"):
        shutil.rmtree(leftover, ignore_errors=True)
    if not output.is_dir():
        return
    journal = output / JOURNAL
    if journal.exists():
        with contextlib.suppress(ValueError, TypeError):
            staging_name, relatives = json.loads(journal.read_text(encoding="utf-8"))
            staging = output / Path(staging_name).name
            if staging.is_dir():
                _move_in(output, staging, [r for r in relatives if _staged(staging, r)])
        journal.unlink()
    for leftover in output.glob(STAGING + "*"):
        shutil.rmtree(leftover, ignore_errors=True)


def _staged(staging: Path, relative: object) -> bool:
    """A journal entry that names a staged file below the folder (nothing outside it)."""
    if not isinstance(relative, str) or Path(relative).is_absolute():
        return False
    return ".." not in Path(relative).parts and (staging / relative).is_file()


def _sibling(output: Path) -> str:
    return f".{output.name}{STAGING}"


def _move_in(output: Path, staging: Path, relatives: list[str]) -> None:
    for relative in relatives:
        target = output / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        os.replace(staging / relative, target)


def _umask() -> int:
    """The process's file-creation mask (read by setting it, then restoring it)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask
