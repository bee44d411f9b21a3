"""The monitor's web server: the page, the task's SVG, a websocket of the run's records and
the control requests; every request carries the token printed with the URL, as the cookie
the page's first load sets or (tools) as ``Authorization: Bearer``; only that first load
takes it in the URL (see :mod:`lightrocks.app.web.guard`).

uvicorn serves on a daemon thread of its own, so the run's loop never waits for a browser.
"""

from __future__ import annotations

import asyncio
import secrets
import time
from contextlib import suppress
from dataclasses import dataclass, field
from typing import Any

from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.feed import Feed
from lightrocks.app.web.guard import Guard
from lightrocks.app.web.schema import parsed
from lightrocks.app.web.serving import serve

PUSH_PERIOD = 0.1
"""Seconds between two pushes of new records to a page."""
PAGE = "lightrocks.app.monitor.page"
ASSETS = {"monitor.js": PAGE, "plots.js": PAGE, "monitor.css": PAGE}
"""The page's own files; it loads the shared diagram script too."""


@dataclass(frozen=True)
class Breakpoint:
    """``control/break?at=PATH``: the state or transition to toggle a breakpoint at."""

    at: str


def parse_address(text: str) -> tuple[str, int]:
    """``[HOST:]PORT``; the host defaults to the loopback interface."""
    host, _, port = text.rpartition(":")
    if not port.isdigit() or not 0 <= int(port) < 65536:
        raise ValueError(f"--monitor expects [HOST:]PORT, got '{text}'")
    return host or "127.0.0.1", int(port)


@dataclass
class Monitor:
    feed: Feed
    control: RunControl
    svg: str
    title: str
    token: str = field(default_factory=lambda: secrets.token_urlsafe(16))
    summary: dict[str, Any] = field(default_factory=dict)
    """Outcome and measurements once the run is over."""
    replay: list[dict[str, Any]] | None = None
    """A recorded run's records, for a page that replays it instead of watching a run."""
    sent: dict[int, int] = field(default_factory=dict)
    """The number of the last record pushed to each open page (0 until the run is over)."""

    def app(self, guard: Guard) -> Any:
        """The routes; ``guard`` knows the token (the ``Host`` and ``Origin`` checks wrap
        the whole app, see :class:`~lightrocks.app.web.guard.Guarded`)."""
        from starlette.applications import Starlette
        from starlette.requests import Request
        from starlette.responses import Response
        from starlette.routing import Route, WebSocketRoute
        from starlette.websockets import WebSocket

        from lightrocks.app.web import routes

        @routes.guarded
        async def task_svg(request: Request) -> Response:
            return Response(self.svg, media_type="image/svg+xml")

        @routes.guarded
        @routes.answered({})
        async def control(request: Request) -> Any:
            if self.replay is not None:
                return routes.refused(409, "a replay has no run to control")
            action = request.path_params["action"]
            c = self.control
            if action == "pause":
                c.pause()
            elif action == "resume":
                c.resume()
            elif action == "step":
                c.step()
            elif action == "abort":
                c.abort()
            elif action == "break":
                c.toggle_breakpoint(parsed(Breakpoint, request.query_params).at)
            else:
                return routes.refused(404, f"no action '{action}'")
            return self.status()

        async def stream(socket: WebSocket) -> None:
            if not guard.allows(socket):
                await socket.close(code=1008)
                return
            await socket.accept()
            if self.replay is not None:
                await socket.send_json({"title": self.title, "replay": self.replay})
                with suppress(Exception):  # until the page goes away
                    while True:
                        await socket.receive_text()
                return
            number, history = self.feed.history()
            await socket.send_json({"title": self.title, "history": history})
            try:
                while True:
                    over = bool(self.summary)
                    number, fresh = self.feed.since(number)
                    await socket.send_json({"records": fresh, "status": self.status()})
                    self.sent[id(socket)] = number if over else 0
                    await asyncio.sleep(PUSH_PERIOD)
            except Exception:  # the page went away
                return
            finally:
                self.sent.pop(id(socket), None)

        app = Starlette(
            routes=[
                Route("/", routes.first_load(PAGE)),
                *routes.assets({**ASSETS, **routes.SHARED}),
                Route("/task.svg", task_svg),
                Route("/control/{action}", control, methods=["POST"]),
                WebSocketRoute("/stream", stream),
            ]
        )
        app.state.guard = guard
        return app

    def status(self) -> dict[str, Any]:
        c = self.control
        return {
            "paused": c.paused,
            "where": c.where,
            "breakpoints": sorted(c.breakpoints),
            **self.summary,
        }

    def drain(self, timeout: float = 15.0) -> None:
        """Give open pages up to ``timeout`` seconds to receive the end of the run and its
        summary, so a run that ends right away still shows its outcome (a busy machine may take
        seconds; a process without open pages ends at once)."""
        deadline = time.monotonic() + timeout
        while any(n < self.feed.last for n in list(self.sent.values())):
            if time.monotonic() > deadline:
                return
            time.sleep(0.02)

    def serve(self, host: str, port: int) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, host, port, self.token, "monitor", url_once=True)
