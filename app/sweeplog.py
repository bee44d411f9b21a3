"""The journal of a sweep: its arguments, then every finished run, one JSON line each, in the
output folder as the runs finish. A sweep stopped by Ctrl-C or killed keeps its finished
runs, and ``sweep --resume`` runs only the others, with the same seeds."""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict
from pathlib import Path
from typing import IO, Any

from lightrocks.app.errors import RunError
from lightrocks.app.run import RunResult

NAME = "sweep.jsonl"

Done = dict[tuple[int, int], RunResult]
"""Finished runs by (index of the grid point, seed)."""


def _result(fields: Mapping[str, Any]) -> RunResult:
    values = dict(fields)
    values["skills"] = [tuple(skill) for skill in values["skills"]]
    values["active"] = tuple(values["active"])
    return RunResult(**values)


def finished_runs(output: Path, arguments: Mapping[str, Any], note: Callable[[str], None]) -> Done:
    """The runs a sweep with the same ``arguments`` finished into ``output`` before it was
    stopped; a last line a kill cut off is left out."""
    path = output / NAME
    if not path.is_file():
        note(f"{path} does not exist: the sweep starts from its first run")
        return {}
    lines = path.read_bytes().split(b"\n")
    entries = []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            entries.append((number, json.loads(line.decode("utf-8"))))
        except (ValueError, RecursionError):
            if number < len(lines):
                raise RunError(f"--resume: {path}:{number} is not a line of a journal") from None
            note(f"{path}:{number}: the last line is cut off (was the sweep killed?)")
    if not entries:
        note(f"{path} holds no run: the sweep starts from its first run")
        return {}
    if entries[0][1] != {"sweep": dict(arguments)}:
        raise RunError(
            f"--resume: {path} is a sweep with other arguments or models; "
            "give the same ones, or leave out --resume to start again"
        )
    done: Done = {}
    for number, entry in entries[1:]:
        try:
            done[entry["point"], entry["result"]["seed"]] = _result(entry["result"])
        except (KeyError, TypeError):
            raise RunError(f"--resume: {path}:{number} is not a line of a journal") from None
    return done


class Journal:
    """Appends each finished run to ``output/sweep.jsonl`` as it finishes: a kill at any
    moment loses no run that finished before it. The file is started by the first run that
    finishes, so a sweep that ran nothing writes nothing."""

    def __init__(
        self, output: Path, arguments: Mapping[str, Any], points: Sequence[Any], done: Done
    ) -> None:
        self.output = output
        self.arguments = dict(arguments)
        self.index = {point: i for i, point in enumerate(points)}
        self.done = dict(done)
        self._stream: IO[str] | None = None

    def add(self, point: Any, result: RunResult) -> None:
        if self._stream is None:
            self._stream = self._start()
        key = (self.index[point], result.seed)
        self.done[key] = result
        self._stream.write(json.dumps({"point": key[0], "result": asdict(result)}) + "\n")

    def _start(self) -> IO[str]:
        """A new journal with the runs kept from before, replacing the old one whole."""
        self.output.mkdir(parents=True, exist_ok=True)
        path = self.output / NAME
        fresh = path.with_name(f".{NAME}.tmp")
        with fresh.open("w", encoding="utf-8") as stream:
            stream.write(json.dumps({"sweep": self.arguments}) + "\n")
            for (point, _), result in sorted(self.done.items()):
                stream.write(json.dumps({"point": point, "result": asdict(result)}) + "\n")
        fresh.replace(path)
        return path.open("a", encoding="utf-8", buffering=1)

    def close(self) -> None:
        if self._stream is not None:
            self._stream.close()
            self._stream = None
