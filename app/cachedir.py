"""Where LightRocks keeps its caches (generated code, parse results and findings), and how
a JSON entry is put there."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path
from typing import Any


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


def put_json(target: Path, data: Any) -> None:
    """Write ``data`` as the JSON entry ``target`` (see ``put_text``)."""
    put_text(target, json.dumps(data, separators=(",", ":")))  # C encoder: json.dump has none


def put_text(target: Path, text: str) -> None:
    """Write ``text`` as the entry ``target`` in a private folder: staged in a temporary file
    and renamed into place, so readers never see half an entry."""
    target.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    handle, staged = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as file:
            file.write(text)
        os.replace(staged, target)
    except BaseException:
        Path(staged).unlink(missing_ok=True)
        raise
