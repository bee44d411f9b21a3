"""The run cache: generated Python packages kept in the user's cache folder.

An entry is keyed by the LightRocks version, the Python version and the generator's inputs
(every loaded model's path and text, the requested files), so an upgrade or an edit never
reuses stale code. It is written whole into a staging folder and renamed into place, carries
a manifest of its files' SHA-256 digests, and is verified against it before every import: a
half-written, edited or planted entry is rebuilt, never imported.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import sys
import tempfile
from collections.abc import Callable, Iterable, Mapping
from importlib.metadata import version
from pathlib import Path

from lightrocks.workbench.generators import GenerationError

MANIFEST = "manifest.json"


def cache_root() -> Path:
    """``$XDG_CACHE_HOME/lightrocks``, else the platform's per-user cache folder."""
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg:
        base = Path(xdg)
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches"
    elif os.name == "nt":
        base = Path(os.environ.get("LOCALAPPDATA") or Path.home() / "AppData" / "Local")
    else:
        base = Path.home() / ".cache"
    return base / "lightrocks"


def cache_key(generator: str, inputs: Iterable[tuple[str, bytes]]) -> str:
    """A digest of everything the generated code depends on."""
    digest = hashlib.sha256()
    for part in (version("lightrocks"), sys.implementation.cache_tag, generator):
        digest.update(part.encode() + b"\0")
    for name, content in inputs:
        digest.update(name.encode("utf-8", "surrogatepass") + b"\0" + content + b"\0")
    return digest.hexdigest()[:32]


def entry(root: Path, key: str, generate: Callable[[], Mapping[str, str]]) -> Path:
    """The verified folder of ``key``, generated and renamed into place when missing or
    corrupt. Processes building the same entry at once each stage their own folder; the
    first rename wins and the others use its entry."""
    folder = root / key
    if verified(folder):
        return folder
    files = dict(generate())
    files[MANIFEST] = json.dumps(
        {path: _digest(text.encode("utf-8")) for path, text in files.items()},
        indent=1,
        sort_keys=True,
    )
    try:
        return _publish(root, key, files)
    except OSError as error:
        raise GenerationError(f"cannot write the run cache {root}: {error.strerror}") from None


def _publish(root: Path, key: str, files: Mapping[str, str]) -> Path:
    """Write the files into a fresh staging folder and rename it to the entry in one step."""
    folder = root / key
    root.mkdir(mode=0o700, parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{key}.", dir=root))  # private: mode 0700
    try:
        for relative, text in files.items():
            path = staging / relative
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8", newline="\n")
        if (folder.exists() or folder.is_symlink()) and not verified(folder):
            _discard(folder)
        try:
            os.rename(staging, folder)
        except OSError:
            if not verified(folder):  # not an entry another process renamed in first
                raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return folder


def verified(folder: Path) -> bool:
    """The folder holds exactly the files its manifest lists, with the listed digests (no
    extra file, no bytecode that Python could load instead of the sources)."""
    if folder.is_symlink() or not folder.is_dir():
        return False
    try:
        manifest = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
        present = {
            path.relative_to(folder).as_posix()
            for path in folder.rglob("*")
            if not path.is_dir() or path.is_symlink()
        }
        if not isinstance(manifest, dict) or present != {*manifest, MANIFEST}:
            return False
        return all(_digest((folder / path).read_bytes()) == manifest[path] for path in manifest)
    except (OSError, ValueError):
        return False


def _digest(content: bytes) -> str:
    return hashlib.sha256(content).hexdigest()


def _discard(folder: Path) -> None:
    """Move a bad entry out of the way at once (a rename), then delete it."""
    aside = Path(tempfile.mkdtemp(prefix=".discarded-", dir=folder.parent))
    os.rename(folder, aside / "entry")
    shutil.rmtree(aside, ignore_errors=True)
