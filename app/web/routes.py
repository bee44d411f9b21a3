"""What the monitor's and the studio's routes share on starlette: the token check, answers
as JSON with each refusal under the status that says why, the page's first load and the
static files it loads.

An app built from these keeps its :class:`~.guard.Guard` as ``app.state.guard``. A handler
answers with a ``Response``, or with what JSON holds; a request that does not fit its schema
(:class:`~.schema.BadRequest`) is answered 400 naming the field, a refusal the app names
(a conflict, a chart that is not there, an edit that does not fit) with its status, and
anything else is our bug: 500, logged with its traceback.
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Awaitable, Callable, Mapping
from importlib.resources import files
from pathlib import PurePath
from typing import Any

from starlette.requests import HTTPConnection, Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from lightrocks.app.web.guard import NO_TOKEN, Guard
from lightrocks.app.web.schema import BadRequest

PAGE = "lightrocks.app.web.page"
SHARED = {"diagram.js": PAGE}
"""The scripts every page loads, with the package they ship in."""
MEDIA = {".js": "text/javascript", ".css": "text/css"}
LOG = logging.getLogger("lightrocks.app.web")

Handler = Callable[[Request], Awaitable[Any]]


def guard_of(connection: HTTPConnection) -> Guard:
    return connection.app.state.guard


def refused(status: int, message: str, field: str | None = None) -> JSONResponse:
    """A refusal as the pages read it: ``{"error": …}``, with the field it is about."""
    body = {"error": message} if field is None else {"error": message, "field": field}
    return JSONResponse(body, status_code=status)


def guarded(handler: Handler) -> Handler:
    """``handler`` for holders of the token only (see :meth:`Guard.allows`)."""

    @functools.wraps(handler)
    async def checked(request: Request) -> Any:
        guard = guard_of(request)
        if not guard.allows(request):
            return refused(403, guard.refusal(request))
        return await handler(request)

    return checked


def answered(refusals: Mapping[type[Exception], int]) -> Callable[[Handler], Handler]:
    """``handler``'s result as JSON (a ``Response`` as it is), a bad request as 400, each
    exception of ``refusals`` with its status and any other as 500, logged."""

    def wrap(handler: Handler) -> Handler:
        @functools.wraps(handler)
        async def answer(request: Request) -> Response:
            try:
                result = await handler(request)
            except BadRequest as error:
                return refused(400, str(error), error.field)
            except Exception as error:
                status = next((s for k, s in refusals.items() if isinstance(error, k)), None)
                if status is None:
                    LOG.exception("%s %s failed", request.method, request.url.path)
                    return refused(500, f"the server failed ({type(error).__name__}); see its log")
                if status >= 500:
                    LOG.error("%s %s: %s", request.method, request.url.path, error)
                return refused(status, str(error))
            return result if isinstance(result, Response) else JSONResponse(result)

        return answer

    return wrap


async def json_object(request: Request) -> dict[str, Any]:
    """The request's body, a JSON object."""
    try:
        body = await request.json()
    except ValueError:
        raise BadRequest("the request's body is not JSON") from None
    if not isinstance(body, dict):
        raise BadRequest("the request's body is not a JSON object")
    return body


def first_load(package: str) -> Handler:
    """The page (``index.html`` of ``package``): its first load, with the token in the URL,
    sets the cookie that the page's later requests carry. The page's text is the same for
    everyone: the token is in no link of it."""

    async def index(request: Request) -> Response:
        guard = guard_of(request)
        if not (guard.allows(request) or guard.in_query(request.query_params)):
            return refused(403, NO_TOKEN)
        text = files(package).joinpath("index.html").read_text(encoding="utf-8")
        cookie = {"Set-Cookie": guard.cookie(request.scope["server"][1])}
        return HTMLResponse(text, headers=cookie)

    return index


def assets(shipped: Mapping[str, str]) -> list[Route]:
    """A route for each static file the page loads (file name -> the package it ships in),
    with the media type of its suffix; they hold nothing secret and need no token."""

    def route(name: str, package: str) -> Route:
        media = MEDIA[PurePath(name).suffix]

        async def serve(request: Request) -> Response:
            text = files(package).joinpath(name).read_text(encoding="utf-8")
            return Response(text, media_type=media)

        return Route(f"/{name}", serve)

    return [route(name, package) for name, package in shipped.items()]
