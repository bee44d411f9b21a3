"""``run --script FILE``: outcomes (and plain sensor values) for the dry run, read from a JSON
file, so that every branch of a task can be walked without writing code. The file is checked
against the statechart first: every command it names is one the chart calls, every outcome
one that can end that command."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from lightrocks.app.errors import RunError
from lightrocks.runtime.contract import TIMEOUT

FAULT = "error"  # a scripted adapter fault

Script = dict[str, dict[str, Any]]
"""``{"outcomes": {"device.command": [outcome, …]}, "sensors": {"device.sensor": value}}``."""


def commands_of(cls: type) -> dict[str, set[str]]:
    """Every ``device.command`` the chart (with everything it imports) calls, and the
    outcomes that can end it."""
    found: dict[str, set[str]] = {}
    seen: set[type] = set()
    pending = [cls]
    while pending:
        current = pending.pop()
        if current in seen:
            continue
        seen.add(current)
        if getattr(current, "COMMAND", ""):
            key = f"{current.DEVICE}.{current.COMMAND}"
            found.setdefault(key, {TIMEOUT, FAULT}).update(current.OUTCOMES)
        pending.extend(getattr(current, "CHILDREN", {}).values())
    return found


def read_script(path: Path, cls: type) -> Script:
    """The script in ``path``, or a ``RunError`` that says what is wrong and where."""
    where = f"--script {path}"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise RunError(f"{where}: cannot read it: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise RunError(f"{where}: not a UTF-8 text file") from None
    except json.JSONDecodeError as error:
        raise RunError(f"{where}:{error.lineno}:{error.colno}: not JSON: {error.msg}") from None
    if not isinstance(data, dict) or not set(data) <= {"outcomes", "sensors"}:
        raise RunError(f'{where}: expected an object with "outcomes" and/or "sensors"')
    outcomes, sensors = data.get("outcomes", {}), data.get("sensors", {})
    if not isinstance(outcomes, dict) or not isinstance(sensors, dict):
        raise RunError(f'{where}: "outcomes" and "sensors" are objects keyed "device.name"')
    known = commands_of(cls)
    for command, planned in outcomes.items():
        if command not in known:
            calls = ", ".join(sorted(known)) or "none"
            raise RunError(f"{where}: {cls.NAME} never calls {command}; it calls: {calls}")
        if not isinstance(planned, list) or not all(isinstance(o, str) for o in planned):
            raise RunError(f'{where}: outcomes of {command} are a list of names, like ["done"]')
        for outcome in planned:
            if outcome not in known[command]:
                possible = ", ".join(sorted(known[command]))
                raise RunError(
                    f"{where}: {command} cannot end in '{outcome}'; it ends in: {possible}"
                )
    for sensor, value in sensors.items():
        device, _, name = sensor.partition(".")
        protocol = cls.CELL.DEVICES.get(device) if cls.CELL is not None else None
        if protocol is None or not isinstance(getattr(protocol, name, None), property):
            raise RunError(f"{where}: {cls.NAME}'s cell has no sensor {sensor}")
        if not isinstance(value, bool | int | float):
            raise RunError(
                f"{where}: {sensor} = {json.dumps(value)}: script a number (SI) or a boolean"
            )
    return {"outcomes": outcomes, "sensors": sensors}
