"""Reading a trace file that ``run --trace`` wrote, for plots and replays."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from lightrocks.app.monitor.schema import TEXT_FIELDS, RecordError, check

STATE_KINDS = {kind for kind, fields in TEXT_FIELDS.items() if "state" in fields}


class TraceError(ValueError):
    """The file is not a trace this tool can read."""


def read_trace(path: Path, note: Callable[[str], None] = lambda _: None) -> list[dict[str, Any]]:
    """The records of a trace file. A last line without its line break that is no record was
    cut off by a run that was killed: the records before it are read, and ``note`` is told."""
    lines = path.read_bytes().split(b"\n")
    records = []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            records.append(_record(path, number, line))
        except TraceError:
            if number < len(lines):
                raise
            note(f"{path}:{number}: the last line is cut off (was the run killed?); read up to it")
    return records


def _record(path: Path, number: int, line: bytes) -> dict[str, Any]:
    try:
        record = json.loads(line.decode("utf-8"))
    except UnicodeDecodeError:
        raise TraceError(f"{path}:{number}: not UTF-8 text") from None
    except json.JSONDecodeError:
        raise TraceError(f"{path}:{number}: not a JSON line") from None
    except RecursionError:
        raise TraceError(f"{path}:{number}: nested too deeply") from None
    if not isinstance(record, dict) or "time" not in record or "kind" not in record:
        raise TraceError(f"{path}:{number}: not a trace record")
    try:
        check(record)
    except RecordError as error:
        raise TraceError(f"{path}:{number}: {error}") from None
    return record


def header(records: list[dict[str, Any]]) -> tuple[Path | None, list[Path]]:
    """The model file a trace names in its ``run`` record and its model path."""
    first = records[0] if records else {}
    if first.get("kind") != "run" or not isinstance(first.get("model"), str):
        return None, []
    return Path(first["model"]), [Path(p) for p in first.get("path", []) if isinstance(p, str)]


def check_states(records: list[dict[str, Any]], known: set[str], model: Path) -> None:
    """Every state the trace names is one of the model's (``known``, their paths)."""
    for record in records:
        state = record.get("state") if record["kind"] in STATE_KINDS else None
        if state is not None and state not in known:
            raise TraceError(
                f"the trace names the state {state}, which {model.name} does not have: "
                "was the run recorded with another model? give it with --model"
            )


def task_name(records: list[dict[str, Any]]) -> str:
    """The top state the trace entered first."""
    entered = next((r for r in records if r["kind"] == "enter"), None)
    if entered is None or not isinstance(entered.get("state"), str):
        raise TraceError("the trace enters no state")
    return entered["state"].split("/")[0]
