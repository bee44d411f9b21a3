"""Runs started from the studio's page, watched with the monitor's own pieces: the feed,
the execution control and the watch of ``run --monitor`` (:mod:`app.monitor`), its server
app mounted below ``/run`` of the studio (the stream, pause, resume, step, abort and
breakpoints, and the monitor's page itself with its plots).

One run at a time, in a thread of the studio's process, through the one pipeline every
front door takes (check, generate once per content, load, run).
"""

from __future__ import annotations

import os
import shutil
import tempfile
import threading
from collections.abc import Callable
from dataclasses import dataclass
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

from lightrocks.app.studio.edits import EditError

PNG_END = b"IEND\xaeB`\x82"
"""The last bytes of a whole PNG file."""


class Busy(Exception):
    """A run is under way: one at a time."""


@dataclass
class Run:
    chart: str
    monitor: Any
    thread: threading.Thread
    result: Any = None
    error: str = ""
    view: Path | None = None
    """The folder of the frames of the simulated cell while MuJoCo runs (see ``frame``)."""

    def frame(self) -> bytes:
        """The newest whole frame of the simulated cell (PNG), or nothing yet.

        MuJoCo's offscreen renderer draws them as ``run --video FOLDER`` does (headless, 30
        frames per second of simulated time); the page fetches a few a second."""
        if self.view is None:
            return b""
        try:
            names = sorted(p.name for p in os.scandir(self.view) if p.name.endswith(".png"))
        except OSError:
            return b""
        for name in names[:-2]:  # seen or never to be seen: the folder stays small
            (self.view / name).unlink(missing_ok=True)
        for name in reversed(names[-2:]):  # the newest may be half-written
            try:
                data = (self.view / name).read_bytes()
            except OSError:
                continue
            if data.endswith(PNG_END):
                return data
        return b""


def adapters() -> list[str]:
    """The adapters installed (``lightrocks list adapters``)."""
    return sorted(e.name for e in entry_points(group="lightrocks.adapters"))


def robots() -> list[str]:
    """The robots registered (``lightrocks list robots``)."""
    from lightrocks.app.robots import registered

    return sorted(registered())


class Runs:
    """The studio's run, if it started one."""

    def __init__(self, folders: list[Path], shown: Callable[[Path], str]) -> None:
        self.folders = folders
        self.shown = shown
        self.current: Run | None = None
        self._lock = threading.Lock()

    def scripts(self) -> list[str]:
        """The dry run's outcome scripts below the studio's folders, as the page names them."""
        found = {f.resolve() for folder in self.folders for f in folder.rglob("*.dryrun.json")}
        return sorted(self.shown(f) for f in found)

    def script_path(self, shown: str) -> Path | None:
        if not shown:
            return None
        for folder in self.folders:
            for found in folder.rglob("*.dryrun.json"):
                if self.shown(found.resolve()) == shown:
                    return found.resolve()
        raise EditError(f"no outcome script '{shown}' below the studio's folders")

    def start(
        self, chart: str, model: Path, adapter: str, script: str, paused: bool, robot: str = ""
    ) -> Run:
        """Check, generate and load the chart (for ``robot`` in its cell's robot slot, where
        one is named), then run it in a thread, watched; refused while another run is under
        way. The model's errors, an unknown robot and a wrong script are refused before
        anything runs (``ModelError``, ``RunError``)."""
        from lightrocks.app import pipeline
        from lightrocks.app.monitor.watch import monitor_for
        from lightrocks.app.robots import choose
        from lightrocks.app.script import read_script
        from lightrocks.app.specs import run_spec

        if adapter and adapter not in adapters():
            raise EditError(f"no adapter '{adapter}'; known: {', '.join(adapters())}")
        with self._lock:
            if self.current is not None and self.current.thread.is_alive():
                raise Busy(f"{self.current.chart} is running: abort it first")
            chosen = choose(robot) if robot else None
            cls = pipeline.load(model, self.folders, chosen)
            file = self.script_path(script)
            scripted = read_script(file, cls) if file else None
            frames = (
                tempfile.mkdtemp(prefix="lightrocks-studio-view-") if adapter == "mujoco" else None
            )
            spec = run_spec(
                cls,
                model,
                self.folders,
                (),
                adapter or None,
                script=scripted,
                video=frames,
                robot=chosen,
            )
            monitor, watch = monitor_for(model, self.folders, cls.NAME, paused=paused)
            run = Run(chart, monitor, threading.Thread(daemon=True, name="studio-run"))
            run.view = Path(frames) if frames else None

            def work() -> None:
                try:
                    run.result = pipeline.run(spec, cls, watch=watch)
                    monitor.summary["outcome"] = run.result.outcome
                except Exception as error:  # the page shows it; the studio keeps serving
                    run.error = f"{type(error).__name__}: {error}"
                    monitor.summary["error"] = run.error
                finally:
                    monitor.control.end()
                    if run.view is not None:
                        shutil.rmtree(run.view, ignore_errors=True)

            run.thread = threading.Thread(target=work, daemon=True, name="studio-run")
            self.current = run
            run.thread.start()
            return run

    def status(self) -> dict[str, Any]:
        run = self.current
        if run is None:
            return {"running": False, "chart": ""}
        return {
            "running": run.thread.is_alive(),
            "chart": run.chart,
            "outcome": run.result.outcome if run.result is not None else "",
            "error": run.error,
            "view": run.view is not None,
        }
