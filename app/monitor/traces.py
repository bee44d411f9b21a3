"""Reading a trace file that ``run --trace`` wrote, for plots and replays."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any


class TraceError(ValueError):
    """The file is not a trace this tool can read."""


def read_trace(path: Path) -> list[dict[str, Any]]:
    records = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip():
            continue
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            raise TraceError(f"{path}:{number}: not a JSON line") from None
        except RecursionError:
            raise TraceError(f"{path}:{number}: nested too deeply") from None
        if not isinstance(record, dict) or "time" not in record or "kind" not in record:
            raise TraceError(f"{path}:{number}: not a trace record")
        records.append(record)
    return records


def header(records: list[dict[str, Any]]) -> tuple[Path | None, list[Path]]:
    """The model file a trace names in its ``run`` record and its model path."""
    first = records[0] if records else {}
    if first.get("kind") != "run" or not isinstance(first.get("model"), str):
        return None, []
    return Path(first["model"]), [Path(p) for p in first.get("path", []) if isinstance(p, str)]


def task_name(records: list[dict[str, Any]]) -> str:
    """The top state the trace entered first."""
    entered = next((r for r in records if r["kind"] == "enter"), None)
    if entered is None or not isinstance(entered.get("state"), str):
        raise TraceError("the trace enters no state")
    return entered["state"].split("/")[0]
