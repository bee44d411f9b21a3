"""The studio's web server: the page, a chart's diagram and state, edits, renames, undo and
runs; on the monitor's stack (starlette on uvicorn), behind the shared guard
(:mod:`lightrocks.app.web.guard`), on the loopback interface only.

The token printed with the URL is set as a strict cookie by the page's first load; every
other request carries it. The guard also refuses requests that name another host than the
one served (a page of another site that rebinds its name to this machine) and requests from
another site's page, and answers with a strict content security policy; this server writes
model files.

Each request is checked once, against its schema (:mod:`.requests`, :mod:`.operations`):
one that does not fit is answered 400 naming the field; a refusal of the model (a conflict,
an edit that does not fit, a chart that is not there) has its own status; anything else is
a bug of ours, answered 500 and logged (:func:`lightrocks.app.web.routes.answered`).

A run started from the page is served by the monitor's own app, mounted below ``/run``
(:mod:`.runs`). Checking, drawing and writing happen in worker threads, so that the page's
sockets keep flowing meanwhile.
"""

from __future__ import annotations

import asyncio
import secrets
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.requests import HTTPConnection, Request
from starlette.responses import Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.websockets import WebSocket

from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.studio.edits import EditError
from lightrocks.app.studio.history import Conflict, Unwritten
from lightrocks.app.studio.operations import operation
from lightrocks.app.studio.requests import Chart, HistoryStep, NewChart, Rename, StartRun, Target
from lightrocks.app.studio.runs import Busy, Runs, adapters, robots
from lightrocks.app.studio.texts import stamp
from lightrocks.app.studio.workspace import NoSuchChart, Studio
from lightrocks.app.web import routes
from lightrocks.app.web.guard import Guard
from lightrocks.app.web.routes import answered, guarded, json_object
from lightrocks.app.web.schema import parsed
from lightrocks.app.web.serving import serve
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.generators import GenerationError

HOST = "127.0.0.1"
PAGE = "lightrocks.app.studio.page"
ASSETS = {"studio.js": PAGE, "run.js": PAGE, "studio.css": PAGE, **routes.SHARED}
"""The files the page loads and the packages they ship in."""
WATCH_PERIOD = 0.05
"""Seconds between two looks at the files' modification times for an open page."""
REFUSALS: dict[type[Exception], int] = {
    NoSuchChart: 404,
    Conflict: 409,
    Busy: 409,
    EditError: 422,
    SyntaxProblem: 422,
    ModelError: 422,
    RunError: 422,
    GenerationError: 422,
    Unwritten: 500,
}
"""The model's refusals and the status each is answered with (nothing is written then)."""

studio_route = answered(REFUSALS)


class StudioServer:
    def __init__(self, studio: Studio) -> None:
        self.studio = studio
        self.token = secrets.token_urlsafe(16)
        self.runs = Runs(studio.folders, studio.shown)

    def app(self, guard: Guard) -> Starlette:
        app = Starlette(routes=[*ROUTES, Mount("/run", app=CurrentRun(self.runs, guard))])
        app.state.server = self
        app.state.guard = guard
        return app

    def serve(self, port: int = 0) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, HOST, port, self.token, "studio")


def _studio(connection: HTTPConnection) -> Studio:
    return connection.app.state.server.studio


def _runs(connection: HTTPConnection) -> Runs:
    return connection.app.state.server.runs


@guarded
@studio_route
async def charts(request: Request) -> Any:
    return await asyncio.to_thread(_studio(request).charts)


@guarded
@studio_route
async def catalogue(request: Request) -> Any:
    return await asyncio.to_thread(_studio(request).catalogue)


@guarded
@studio_route
async def diagram(request: Request) -> Response:
    chart = parsed(Chart, request.query_params).chart
    svg = await asyncio.to_thread(_studio(request).diagram, chart)
    return Response(svg, media_type="image/svg+xml")


@guarded
@studio_route
async def state(request: Request) -> Any:
    chart = parsed(Chart, request.query_params).chart
    return await asyncio.to_thread(_studio(request).state, chart)


@guarded
@studio_route
async def edit(request: Request) -> Any:
    """One edit of the level in view; the chart's state afterwards."""
    body = await json_object(request)
    target, change = parsed(Target, body), operation(body)
    studio = _studio(request)

    def work() -> dict[str, Any]:
        studio.edit(target.chart, target.version, target.level, change)
        return studio.state(target.chart)

    return await asyncio.to_thread(work)


@guarded
@studio_route
async def preview(request: Request) -> Any:
    """What an edit would do; nothing is written."""
    body = await json_object(request)
    target, change = parsed(Target, body), operation(body)
    work = _studio(request).preview
    return await asyncio.to_thread(work, target.chart, target.version, target.level, change)


@guarded
@studio_route
async def rename(request: Request) -> Any:
    """A rename in every file that names the element; the state of the chart afterwards
    (a renamed chart under its new name)."""
    body = await json_object(request)
    target, asked = parsed(Target, body), parsed(Rename, body)
    studio = _studio(request)

    def work() -> dict[str, Any]:
        studio.rename(target.chart, target.version, target.level, asked.element, asked.to)
        chart = target.chart
        if asked.element == "":
            chart = f"{chart.rpartition('.')[0]}.{asked.to}".lstrip(".")
        return studio.state(chart)

    return await asyncio.to_thread(work)


@guarded
@studio_route
async def history(request: Request) -> Any:
    """Undo or redo the last edit; what was done and what undo and redo would do next."""
    await json_object(request)
    way = parsed(HistoryStep, request.path_params).way
    studio = _studio(request)

    def work() -> dict[str, Any]:
        done = studio.undo() if way == "undo" else studio.redo()
        return {"done": done, "history": studio.history()}

    return await asyncio.to_thread(work)


@guarded
@studio_route
async def new(request: Request) -> Any:
    asked = parsed(NewChart, await json_object(request))
    work = _studio(request).create
    chart = await asyncio.to_thread(work, asked.package, asked.name, asked.layer, asked.cell)
    return {"chart": chart}


@guarded
@studio_route
async def run_options(request: Request) -> Any:
    """What a run can be started with, and the status of the run under way."""
    runs = _runs(request)

    def work() -> dict[str, Any]:
        return {"adapters": adapters(), "robots": robots(), "scripts": runs.scripts()}

    return {**await asyncio.to_thread(work), **runs.status()}


@guarded
@studio_route
async def start(request: Request) -> Any:
    """A run of the chart, checked, generated and loaded first; the run's status."""
    asked = parsed(StartRun, await json_object(request))
    studio, runs = _studio(request), _runs(request)

    def work() -> dict[str, Any]:
        model = studio.component(asked.chart).loaded.path
        runs.start(asked.chart, model, asked.adapter, asked.script, asked.paused, asked.robot)
        return runs.status()

    return await asyncio.to_thread(work)


@guarded
@studio_route
async def frame(request: Request) -> Response:
    run = _runs(request).current
    data = await asyncio.to_thread(run.frame) if run is not None else b""
    if not data:
        return Response(status_code=204)
    return Response(data, media_type="image/png")


async def events(socket: WebSocket) -> None:
    """A message each time the model files change on disk: the stamp of the files' state
    (the page's own edits come back with it) and the files that changed."""
    if not routes.guard_of(socket).allows(socket):
        await socket.close(code=1008)
        return
    studio = _studio(socket)
    fingerprint = await asyncio.to_thread(studio.fingerprint)
    seen = {f[0]: f[1:] for f in fingerprint}
    await socket.accept()
    try:  # first the state now: the page may have loaded an older one
        await socket.send_json({"stamp": stamp(fingerprint), "files": []})
        while True:
            await asyncio.sleep(WATCH_PERIOD)
            fingerprint = await asyncio.to_thread(studio.fingerprint)
            now = {f[0]: f[1:] for f in fingerprint}
            if now != seen:
                files = sorted(set(now.items()) ^ set(seen.items()))
                shown = sorted({studio.shown(Path(f)) for f, _ in files})
                await socket.send_json({"stamp": stamp(fingerprint), "files": shown})
                seen = now
    except Exception:  # the page went away
        return


ROUTES = [
    Route("/", routes.first_load(PAGE)),
    *routes.assets(ASSETS),
    Route("/charts", charts),
    Route("/diagram.svg", diagram),
    Route("/state", state),
    Route("/catalogue", catalogue),
    Route("/edit", edit, methods=["POST"]),
    Route("/preview", preview, methods=["POST"]),
    Route("/rename", rename, methods=["POST"]),
    Route("/history/{way}", history, methods=["POST"]),
    Route("/new", new, methods=["POST"]),
    Route("/runs", run_options),
    Route("/runs/start", start, methods=["POST"]),
    Route("/runs/frame.png", frame),
    WebSocketRoute("/events", events),
]
"""Every route but the current run's, which each server mounts with its own runs."""


class CurrentRun:
    """The monitor's app of the run under way (its page, stream and controls), or a refusal
    before the first run."""

    def __init__(self, runs: Runs, guard: Guard) -> None:
        self.runs = runs
        self.guard = guard
        self.apps: dict[int, Any] = {}

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        run = self.runs.current
        if run is None:
            if scope["type"] == "websocket":
                await send({"type": "websocket.close", "code": 1008, "reason": "no run yet"})
                return
            body = b'{"error": "no run yet"}'
            headers = [(b"content-type", b"application/json")]
            await send({"type": "http.response.start", "status": 404, "headers": headers})
            await send({"type": "http.response.body", "body": body})
            return
        if id(run.monitor) not in self.apps:
            self.apps = {id(run.monitor): run.monitor.app(self.guard)}
        await self.apps[id(run.monitor)](scope, receive, send)
