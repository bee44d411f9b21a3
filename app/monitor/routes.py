"""The monitor's routes: the page, the task's SVG, the control requests and the websocket of
the run's records. Each handler finds its monitor as ``app.state.monitor`` and the guard as
``app.state.guard`` (:mod:`lightrocks.app.web.routes`); the ``Host`` and ``Origin`` checks
wrap the whole app (:class:`~lightrocks.app.web.guard.Guarded`)."""

from __future__ import annotations

import asyncio
from contextlib import suppress
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from starlette.applications import Starlette
from starlette.requests import HTTPConnection, Request
from starlette.responses import Response
from starlette.routing import Route, WebSocketRoute
from starlette.websockets import WebSocket

from lightrocks.app.web import routes
from lightrocks.app.web.guard import Guard
from lightrocks.app.web.routes import answered, guarded
from lightrocks.app.web.schema import parsed

if TYPE_CHECKING:
    from lightrocks.app.monitor.server import Monitor

PUSH_PERIOD = 0.1
"""Seconds between two pushes of new records to a page."""
PAGE = "lightrocks.app.monitor.page"
ASSETS = {"monitor.js": PAGE, "plots.js": PAGE, "monitor.css": PAGE, **routes.SHARED}
"""The files the page loads and the packages they ship in."""


@dataclass(frozen=True)
class Breakpoint:
    """``control/break?at=PATH``: the state or transition to toggle a breakpoint at."""

    at: str


def _monitor(connection: HTTPConnection) -> Monitor:
    return connection.app.state.monitor


@guarded
async def task_svg(request: Request) -> Response:
    return Response(_monitor(request).svg, media_type="image/svg+xml")


@guarded
@answered({})
async def control(request: Request) -> Any:
    """Pause, resume, step, abort, or a breakpoint toggled; the run's status."""
    monitor = _monitor(request)
    if monitor.replay is not None:
        return routes.refused(409, "a replay has no run to control")
    action = request.path_params["action"]
    c = monitor.control
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
    return monitor.status()


async def stream(socket: WebSocket) -> None:
    """The run's records so far, then the new ones with the status every push period; a
    replay's records at once."""
    if not routes.guard_of(socket).allows(socket):
        await socket.close(code=1008)
        return
    monitor = _monitor(socket)
    await socket.accept()
    if monitor.replay is not None:
        await socket.send_json({"title": monitor.title, "replay": monitor.replay})
        with suppress(Exception):  # until the page goes away
            while True:
                await socket.receive_text()
        return
    number, history = monitor.feed.history()
    await socket.send_json({"title": monitor.title, "history": history})
    try:
        while True:
            over = bool(monitor.summary)
            number, fresh = monitor.feed.since(number)
            await socket.send_json({"records": fresh, "status": monitor.status()})
            monitor.sent[id(socket)] = number if over else 0
            await asyncio.sleep(PUSH_PERIOD)
    except Exception:  # the page went away
        return
    finally:
        monitor.sent.pop(id(socket), None)


ROUTES = [
    Route("/", routes.first_load(PAGE)),
    *routes.assets(ASSETS),
    Route("/task.svg", task_svg),
    Route("/control/{action}", control, methods=["POST"]),
    WebSocketRoute("/stream", stream),
]


def app(monitor: Monitor, guard: Guard) -> Starlette:
    """The monitor's app; ``guard`` knows the token."""
    made = Starlette(routes=ROUTES)
    made.state.monitor = monitor
    made.state.guard = guard
    return made
