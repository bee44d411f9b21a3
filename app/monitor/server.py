"""The monitor's web server: the page, the task's SVG, a websocket of the run's records and
the control requests; every request carries the token printed with the URL, as the cookie
the page's first load sets or (tools) as ``Authorization: Bearer``; only that first load
takes it in the URL (see :mod:`.guard`).

uvicorn serves on a daemon thread of its own, so the run's loop never waits for a browser.
"""

from __future__ import annotations

import asyncio
import secrets
import time
from contextlib import suppress
from dataclasses import dataclass, field
from importlib.resources import files
from typing import Any

from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.feed import Feed
from lightrocks.app.monitor.guard import Guard, serve

PUSH_PERIOD = 0.1
"""Seconds between two pushes of new records to a page."""
SCRIPTS = ("monitor.js", "diagram.js", "plots.js")
NOT_IN_THE_URL = (
    "the token goes in the cookie the page's first load sets, or in an 'Authorization: "
    "Bearer' header; only the page's first load takes it in the URL"
)


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
        the whole app, see :class:`~.guard.Guarded`)."""
        from starlette.applications import Starlette
        from starlette.requests import Request
        from starlette.responses import HTMLResponse, JSONResponse, Response
        from starlette.routing import Route, WebSocketRoute
        from starlette.websockets import WebSocket

        def allowed(request: Request | WebSocket) -> bool:
            """The token as the cookie or an ``Authorization: Bearer`` header, not in the
            URL (only the page's first load may carry it there; the studio, which mounts
            this app with a guard of its own, still takes it there too)."""
            port = request.scope["server"][1]
            authorization = request.headers.get("authorization")
            return guard.admits(request.cookies, authorization, request.query_params, port)

        def refusal(request: Request | WebSocket) -> str:
            if guard.url_once and "token" in request.query_params:
                return NOT_IN_THE_URL
            return "a valid token is needed"

        page = files("lightrocks.app.monitor.page")

        async def index(request: Request) -> Response:
            """The page; its first load, with the token in the URL, sets the cookie that
            the page's later requests carry (the page then drops the token from the URL).
            The page's text is the same for everyone: the token is in no link of it."""
            if not (allowed(request) or guard.in_query(request.query_params)):
                return Response("a valid token is needed", status_code=403)
            text = page.joinpath("index.html").read_text(encoding="utf-8")
            cookie = {"Set-Cookie": guard.cookie(request.scope["server"][1])}
            return HTMLResponse(text, headers=cookie)

        def asset(name: str, media_type: str) -> Any:
            async def serve(request: Request) -> Response:
                return Response(
                    page.joinpath(name).read_text(encoding="utf-8"), media_type=media_type
                )

            return serve

        async def task_svg(request: Request) -> Response:
            if not allowed(request):
                return Response(refusal(request), status_code=403)
            return Response(self.svg, media_type="image/svg+xml")

        async def control(request: Request) -> Response:
            if not allowed(request):
                return JSONResponse({"error": refusal(request)}, status_code=403)
            if self.replay is not None:
                return JSONResponse({"error": "a replay has no run to control"}, status_code=409)
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
                c.toggle_breakpoint(request.query_params.get("at", ""))
            else:
                return JSONResponse({"error": f"no action '{action}'"}, status_code=404)
            return JSONResponse(self.status())

        async def stream(socket: WebSocket) -> None:
            if not allowed(socket):
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

        return Starlette(
            routes=[
                Route("/", index),
                *(Route(f"/{n}", asset(n, "text/javascript")) for n in SCRIPTS),
                Route("/monitor.css", asset("monitor.css", "text/css")),
                Route("/task.svg", task_svg),
                Route("/control/{action}", control, methods=["POST"]),
                WebSocketRoute("/stream", stream),
            ]
        )

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
