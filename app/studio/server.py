"""The studio's web server: the page, a chart's diagram and state, and edits; on the
monitor's stack (starlette on uvicorn) and behind the monitor's guard, on the loopback
interface only.

The token printed with the URL is set as a strict cookie by the page's first load; every
other request carries it. The guard also refuses requests that name another host than the
one served (a page of another site that rebinds its name to this machine) and requests from
another site's page, and answers with the monitor's content security policy (see
:mod:`lightrocks.app.monitor.guard`); this server writes model files.
"""

from __future__ import annotations

import asyncio
import secrets
from importlib.resources import files
from pathlib import Path
from typing import Any

from lightrocks.app.errors import ModelError
from lightrocks.app.monitor.guard import Guard, serve
from lightrocks.app.studio.workspace import Conflict, Studio, stamp
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.generators import GenerationError

HOST = "127.0.0.1"
PAGES = {
    "studio.js": ("lightrocks.app.studio.page", "text/javascript"),
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

    def app(self, guard: Guard) -> Any:
        from starlette.applications import Starlette
        from starlette.requests import Request
        from starlette.responses import HTMLResponse, JSONResponse, Response
        from starlette.routing import Route, WebSocketRoute
        from starlette.websockets import WebSocket

        def guarded(handler: Any) -> Any:
            async def serve(request: Request) -> Response:
                port = request.scope["server"][1]
                if not guard.authorised(request.cookies, request.query_params, port):
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

        async def charts(request: Request) -> Response:
            return JSONResponse(self.studio.charts())

        async def diagram(request: Request) -> Response:
            chart = request.query_params.get("chart", "")
            try:
                svg = self.studio.diagram(chart)
            except KeyError as error:
                return JSONResponse({"error": str(error.args[0])}, status_code=404)
            except (GenerationError, ModelError) as error:
                return JSONResponse({"error": str(error)}, status_code=422)
            return Response(svg, media_type="image/svg+xml")

        async def state(request: Request) -> Response:
            try:
                return JSONResponse(self.studio.state(request.query_params.get("chart", "")))
            except KeyError as error:
                return JSONResponse({"error": str(error.args[0])}, status_code=404)

        async def catalogue(request: Request) -> Response:
            return JSONResponse(self.studio.catalogue())

        async def body_of(request: Request) -> dict[str, Any]:
            try:
                body = await request.json()
            except ValueError:
                raise BadRequest("the request's body is not JSON") from None
            if not isinstance(body, dict):
                raise BadRequest("the request's body is not a JSON object")
            return body

        def answering(handler: Any) -> Any:
            """Refusals as JSON with a status that says why; nothing is written then."""

            async def serve(request: Request) -> Response:
                try:
                    return JSONResponse(await handler(request))
                except BadRequest as error:
                    return JSONResponse({"error": str(error)}, status_code=400)
                except Conflict as error:
                    return JSONResponse({"error": str(error)}, status_code=409)
                except KeyError as error:
                    message = str(error.args[0]) if error.args else "missing"
                    if not message.startswith("no "):
                        message = f"missing {message}"
                    return JSONResponse({"error": message}, status_code=422)
                except (SyntaxProblem, ValueError) as error:  # an EditError among them
                    return JSONResponse({"error": str(error)}, status_code=422)
                except OSError as error:
                    message = f"cannot write {error.filename or 'the file'}: {error.strerror}"
                    return JSONResponse({"error": message}, status_code=500)

            return serve

        def edit_of(body: dict[str, Any]) -> tuple[str, str, str]:
            chart, seen, level = (body.get(k) for k in ("chart", "version", "level"))
            if not all(isinstance(v, str) for v in (chart, seen, level)):
                raise BadRequest("an edit names the chart, its version and the level as texts")
            return chart, seen, level

        async def edit(request: Request) -> dict[str, Any]:
            body = await body_of(request)
            chart, seen, level = edit_of(body)
            self.studio.edit(chart, seen, level, body)
            if body.get("op") == "rename" and body.get("element") == "":
                chart = f"{chart.rpartition('.')[0]}.{body['to']}".lstrip(".")
            return self.studio.state(chart)

        async def preview(request: Request) -> dict[str, Any]:
            body = await body_of(request)
            return self.studio.preview(*edit_of(body), body)

        async def history(request: Request) -> dict[str, Any]:
            await body_of(request)
            way = request.path_params["way"]
            if way not in ("undo", "redo"):
                raise KeyError(f"no '{way}'")
            done = self.studio.undo() if way == "undo" else self.studio.redo()
            return {"done": done, "history": self.studio.history()}

        async def new(request: Request) -> dict[str, Any]:
            body = await body_of(request)
            given = [body.get(k, "") for k in ("package", "name", "layer", "cell")]
            if not all(isinstance(v, str) for v in given):
                raise BadRequest("a new chart names its package, name, layer and cell as texts")
            return {"chart": self.studio.create(*given)}

        async def events(socket: WebSocket) -> None:
            """A message each time the model files change on disk: the stamp of the files'
            state (the page's own edits come back with it) and the files that changed."""
            if not guard.authorised(socket.cookies, socket.query_params, socket.scope["server"][1]):
                await socket.close(code=1008)
                return
            await socket.accept()
            seen = dict((f[0], f[1:]) for f in self.studio.fingerprint())
            try:
                while True:
                    await asyncio.sleep(WATCH_PERIOD)
                    fingerprint = self.studio.fingerprint()
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
                Route("/charts", guarded(charts)),
                Route("/diagram.svg", guarded(diagram)),
                Route("/state", guarded(state)),
                Route("/catalogue", guarded(catalogue)),
                Route("/edit", guarded(answering(edit)), methods=["POST"]),
                Route("/preview", guarded(answering(preview)), methods=["POST"]),
                Route("/history/{way}", guarded(answering(history)), methods=["POST"]),
                Route("/new", guarded(answering(new)), methods=["POST"]),
                WebSocketRoute("/events", events),
            ]
        )

    def serve(self, port: int = 0) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, HOST, port, self.token, "studio")
