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

import secrets
from importlib.resources import files
from typing import Any

from lightrocks.app.errors import ModelError
from lightrocks.app.monitor.guard import Guard, serve
from lightrocks.app.studio.workspace import Conflict, Studio
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


class StudioServer:
    def __init__(self, studio: Studio) -> None:
        self.studio = studio
        self.token = secrets.token_urlsafe(16)

    def app(self, guard: Guard) -> Any:
        from starlette.applications import Starlette
        from starlette.requests import Request
        from starlette.responses import HTMLResponse, JSONResponse, Response
        from starlette.routing import Route

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

        async def edit(request: Request) -> Response:
            body = await request.json()
            chart = str(body.get("chart", ""))
            try:
                self.studio.edit(chart, str(body.get("version")), str(body.get("level")), body)
            except Conflict as error:
                return JSONResponse({"error": str(error)}, status_code=409)
            except KeyError as error:
                return JSONResponse({"error": f"missing {error}"}, status_code=422)
            except (SyntaxProblem, ValueError) as error:  # an EditError among them
                return JSONResponse({"error": str(error)}, status_code=422)
            return JSONResponse(self.studio.state(chart))

        return Starlette(
            routes=[
                Route("/", guarded(index)),
                *(Route(f"/{name}", asset(name)) for name in PAGES),
                Route("/charts", guarded(charts)),
                Route("/diagram.svg", guarded(diagram)),
                Route("/state", guarded(state)),
                Route("/edit", guarded(edit), methods=["POST"]),
            ]
        )

    def serve(self, port: int = 0) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, HOST, port, self.token, "studio")
