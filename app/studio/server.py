"""The studio's web server: the page, a chart's diagram and state, edits, and runs; on the
monitor's stack (starlette on uvicorn) and behind the monitor's guard, on the loopback
interface only.

The token printed with the URL is set as a strict cookie by the page's first load; every
other request carries it. The guard also refuses requests that name another host than the
one served (a page of another site that rebinds its name to this machine) and requests from
another site's page, and answers with the monitor's content security policy (see
:mod:`lightrocks.app.monitor.guard`); this server writes model files.

A run started from the page is served by the monitor's own app, mounted below ``/run``
(:mod:`.runs`). Checking, drawing and writing happen in worker threads, so that the page's
sockets keep flowing meanwhile.
"""

from __future__ import annotations

import asyncio
import secrets
from collections.abc import Callable
from importlib.resources import files
from pathlib import Path
from typing import Any

from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.monitor.guard import Guard, serve
from lightrocks.app.studio.runs import Busy, Runs, adapters, robots
from lightrocks.app.studio.workspace import Conflict, Studio, stamp
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.generators import GenerationError

HOST = "127.0.0.1"
PAGES = {
    "studio.js": ("lightrocks.app.studio.page", "text/javascript"),
    "run.js": ("lightrocks.app.studio.page", "text/javascript"),
    "studio.css": ("lightrocks.app.studio.page", "text/css"),
    "diagram.js": ("lightrocks.app.monitor.page", "text/javascript"),
}
"""The files the page loads, the packages they ship in (the diagram is the monitor's) and
their media types."""
WATCH_PERIOD = 0.05
"""Seconds between two looks at the files' modification times for an open page."""


class BadRequest(Exception):
    """A request the page would never send: not JSON, or not the fields an edit has."""


class StudioServer:
    def __init__(self, studio: Studio) -> None:
        self.studio = studio
        self.token = secrets.token_urlsafe(16)
        self.runs = Runs(studio.folders, studio.shown)

    def app(self, guard: Guard) -> Any:
        from starlette.applications import Starlette
        from starlette.requests import Request
        from starlette.responses import HTMLResponse, JSONResponse, Response
        from starlette.routing import Mount, Route, WebSocketRoute
        from starlette.websockets import WebSocket

        def allowed(request: Request | WebSocket) -> bool:
            return guard.authorised(
                request.cookies, request.query_params, request.scope["server"][1]
            )

        def guarded(handler: Any) -> Any:
            async def serve(request: Request) -> Response:
                if not allowed(request):
                    return Response("a valid token is needed", status_code=403)
                return await handler(request)

            return serve

        async def index(request: Request) -> Response:
            """The page; its first load, with the token in the URL, sets the cookie that the
            page's later requests carry."""
            page = files("lightrocks.app.studio.page").joinpath("index.html")
            cookie = {"Set-Cookie": guard.cookie(request.scope["server"][1])}
            return HTMLResponse(page.read_text(encoding="utf-8"), headers=cookie)

        def asset(name: str) -> Any:
            package, media = PAGES[name]

            async def serve(request: Request) -> Response:
                text = files(package).joinpath(name).read_text(encoding="utf-8")
                return Response(text, media_type=media)

            return serve

        async def diagram(request: Request) -> Response:
            chart = request.query_params.get("chart", "")
            try:
                svg = await asyncio.to_thread(self.studio.diagram, chart)
            except KeyError as error:
                return JSONResponse({"error": str(error.args[0])}, status_code=404)
            except (GenerationError, ModelError) as error:
                return JSONResponse({"error": str(error)}, status_code=422)
            return Response(svg, media_type="image/svg+xml")

        async def state(request: Request) -> Response:
            chart = request.query_params.get("chart", "")
            try:
                return JSONResponse(await asyncio.to_thread(self.studio.state, chart))
            except KeyError as error:
                return JSONResponse({"error": str(error.args[0])}, status_code=404)

        def reading(work: Callable[[], Any]) -> Any:
            async def serve(request: Request) -> Response:
                return JSONResponse(await asyncio.to_thread(work))

            return serve

        def posted(work: Callable[[dict[str, Any], Request], Any]) -> Any:
            """A request with a JSON object as its body, ``work`` done in a worker thread;
            refusals as JSON with a status that says why (nothing is written then)."""

            async def serve(request: Request) -> Response:
                try:
                    try:
                        body = await request.json()
                    except ValueError:
                        raise BadRequest("the request's body is not JSON") from None
                    if not isinstance(body, dict):
                        raise BadRequest("the request's body is not a JSON object")
                    return JSONResponse(await asyncio.to_thread(work, body, request))
                except BadRequest as error:
                    return JSONResponse({"error": str(error)}, status_code=400)
                except (Conflict, Busy) as error:
                    return JSONResponse({"error": str(error)}, status_code=409)
                except KeyError as error:
                    message = str(error.args[0]) if error.args else "missing"
                    if not message.startswith("no "):
                        message = f"missing '{message}'"
                    return JSONResponse({"error": message}, status_code=422)
                except (SyntaxProblem, ValueError, ModelError, RunError) as error:
                    return JSONResponse({"error": str(error)}, status_code=422)  # EditError too
                except OSError as error:
                    message = f"cannot write {error.filename or 'the file'}: {error.strerror}"
                    return JSONResponse({"error": message}, status_code=500)

            return guarded(serve)

        def edit_of(body: dict[str, Any]) -> tuple[str, str, str]:
            chart, seen, level = (body.get(k) for k in ("chart", "version", "level"))
            if not all(isinstance(v, str) for v in (chart, seen, level)):
                raise BadRequest("an edit names the chart, its version and the level as texts")
            return chart, seen, level

        def edit(body: dict[str, Any], request: Request) -> dict[str, Any]:
            chart, seen, level = edit_of(body)
            self.studio.edit(chart, seen, level, body)
            if body.get("op") == "rename" and body.get("element") == "":
                chart = f"{chart.rpartition('.')[0]}.{body['to']}".lstrip(".")
            return self.studio.state(chart)

        def preview(body: dict[str, Any], request: Request) -> dict[str, Any]:
            return self.studio.preview(*edit_of(body), body)

        def history(body: dict[str, Any], request: Request) -> dict[str, Any]:
            way = request.path_params["way"]
            if way not in ("undo", "redo"):
                raise KeyError(f"no '{way}'")
            done = self.studio.undo() if way == "undo" else self.studio.redo()
            return {"done": done, "history": self.studio.history()}

        def new(body: dict[str, Any], request: Request) -> dict[str, Any]:
            given = [body.get(k, "") for k in ("package", "name", "layer", "cell")]
            if not all(isinstance(v, str) for v in given):
                raise BadRequest("a new chart names its package, name, layer and cell as texts")
            return {"chart": self.studio.create(*given)}

        def start(body: dict[str, Any], request: Request) -> dict[str, Any]:
            given = [body.get(k, "") for k in ("chart", "adapter", "script", "robot")]
            if not all(isinstance(v, str) for v in given) or not isinstance(
                body.get("paused", False), bool
            ):
                raise BadRequest("a run names its chart, adapter, script and robot as texts")
            chart, adapter, script, robot = given
            model = self.studio.component(chart).loaded.path
            self.runs.start(chart, model, adapter, script, body.get("paused", False), robot)
            return self.runs.status()

        def run_options() -> dict[str, Any]:
            return {
                "adapters": adapters(),
                "robots": robots(),
                "scripts": self.runs.scripts(),
                **self.runs.status(),
            }

        async def frame(request: Request) -> Response:
            run = self.runs.current
            data = await asyncio.to_thread(run.frame) if run is not None else b""
            if not data:
                return Response(status_code=204)
            return Response(data, media_type="image/png")

        async def events(socket: WebSocket) -> None:
            """A message each time the model files change on disk: the stamp of the files'
            state (the page's own edits come back with it) and the files that changed."""
            if not allowed(socket):
                await socket.close(code=1008)
                return
            fingerprint = await asyncio.to_thread(self.studio.fingerprint)
            seen = {f[0]: f[1:] for f in fingerprint}
            await socket.accept()
            try:  # first the state now: the page may have loaded an older one
                await socket.send_json({"stamp": stamp(fingerprint), "files": []})
                while True:
                    await asyncio.sleep(WATCH_PERIOD)
                    fingerprint = await asyncio.to_thread(self.studio.fingerprint)
                    now = {f[0]: f[1:] for f in fingerprint}
                    if now != seen:
                        files = sorted(set(now.items()) ^ set(seen.items()))
                        shown = sorted({self.studio.shown(Path(f)) for f, _ in files})
                        await socket.send_json({"stamp": stamp(fingerprint), "files": shown})
                        seen = now
            except Exception:  # the page went away
                return

        return Starlette(
            routes=[
                Route("/", guarded(index)),
                *(Route(f"/{name}", asset(name)) for name in PAGES),
                Route("/charts", guarded(reading(self.studio.charts))),
                Route("/diagram.svg", guarded(diagram)),
                Route("/state", guarded(state)),
                Route("/catalogue", guarded(reading(self.studio.catalogue))),
                Route("/edit", posted(edit), methods=["POST"]),
                Route("/preview", posted(preview), methods=["POST"]),
                Route("/history/{way}", posted(history), methods=["POST"]),
                Route("/new", posted(new), methods=["POST"]),
                Route("/runs", guarded(reading(run_options))),
                Route("/runs/start", posted(start), methods=["POST"]),
                Route("/runs/frame.png", guarded(frame)),
                WebSocketRoute("/events", events),
                Mount("/run", app=CurrentRun(self.runs, guard)),
            ]
        )

    def serve(self, port: int = 0) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, HOST, port, self.token, "studio")


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
