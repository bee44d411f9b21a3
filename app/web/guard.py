"""Who may reach a page's server (the monitor's and the studio's): the holder of its URL, from
its own page, at the address served.

- **Token**: printed once, in the URL of the first load; that load sets it as a cookie
  (``HttpOnly``, ``SameSite=Strict``: no other site's page sends it) and the page drops it
  from the address bar. Every other request carries the cookie, or (tools) the header
  ``Authorization: Bearer TOKEN``; the token in the query of any other request than the
  page's first load is refused, so that it never travels in a URL again (logs, history,
  shared links).
- **Host**: a request must name the address served. A page of another site whose name
  resolves to this machine (DNS rebinding) names its own site, and is refused. For a loopback
  address the names are ``127.0.0.1``, ``localhost`` and ``[::1]``; for one open to other
  machines, any IP address (rebinding needs a name) and this machine's own names.
- **Origin**: a browser names the page that sends a request; one from any other origin (a
  cross-site form, a websocket opened by another page) is refused. Tools send none.
- **Headers** on every answer: no referrer, no caching, a content security policy that runs
  only the server's own scripts and lets no page frame it.
"""

from __future__ import annotations

import ipaddress
import secrets
import socket
from collections.abc import Mapping
from functools import cache
from typing import Any

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
NO_TOKEN = "a valid token is needed"
NOT_IN_THE_URL = (
    "the token goes in the cookie the page's first load sets, or in an 'Authorization: "
    "Bearer' header; only the page's first load takes it in the URL"
)


def is_loopback(host: str) -> bool:
    """Whether ``host`` (a name or address, IPv6 with or without brackets) is this machine
    only."""
    if host.lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def _is_address(name: str) -> bool:
    try:
        ipaddress.ip_address(name.strip("[]"))
    except ValueError:
        return False
    return True


@cache
def _own_names() -> frozenset[str]:
    names = {socket.gethostname(), socket.getfqdn()}
    return frozenset(n.lower() for n in names if n)


def cookie_name(port: int) -> str:
    """One cookie per port: cookies do not tell ports apart, monitors on two ports do."""
    return f"lightrocks-monitor-{port}"


def _split(header: str) -> tuple[str, str]:
    """``Host`` -> (name, port); a header without port means port 80."""
    header = header.lower()
    if header.startswith("["):  # [::1]:8765
        name, _, rest = header.partition("]")
        return name + "]", rest.removeprefix(":") if rest else "80"
    name, separator, port = header.rpartition(":")
    return (name, port) if separator else (header, "80")


class Guard:
    def __init__(self, host: str, token: str, *, url_once: bool = False) -> None:
        self.host = host.lower()
        """The address served, as given to ``--monitor``."""
        self.token = token
        self.url_once = url_once
        """Only the page's first load takes the token in its URL (the monitor's servers);
        otherwise any request may (the studio's, and a monitor's app mounted in it)."""

    def host_allowed(self, header: str, port: int) -> bool:
        """Whether the ``Host`` header names the address served, with its port."""
        name, given = _split(header)
        if given != str(port):
            return False
        if name in LOOPBACK_NAMES or name == self.host:
            return True
        return not is_loopback(self.host) and (_is_address(name) or name in _own_names())

    @staticmethod
    def origin_allowed(origin: str | None, host_header: str) -> bool:
        """No ``Origin`` (no browser's cross-origin request), or this server's own."""
        return origin is None or origin.lower() == f"http://{host_header.lower()}"

    def allows(self, connection: Any) -> bool:
        """Whether a request or websocket (starlette's ``HTTPConnection``) of a route other
        than the page's first load carries the token (see :meth:`admits`)."""
        return self.admits(
            connection.cookies,
            connection.headers.get("authorization"),
            connection.query_params,
            connection.scope["server"][1],
        )

    def refusal(self, connection: Any) -> str:
        """Why :meth:`allows` refused ``connection``."""
        if self.url_once and "token" in connection.query_params:
            return NOT_IN_THE_URL
        return NO_TOKEN

    def holds_token(self, cookies: Mapping[str, str], authorization: str | None, port: int) -> bool:
        """The token as the cookie the first load set, or as ``Authorization: Bearer``."""
        scheme, _, given = (authorization or "").strip().partition(" ")
        bearer = given.strip() if scheme.lower() == "bearer" else ""
        return any(self._matches(g) for g in (cookies.get(cookie_name(port), ""), bearer))

    def admits(
        self, cookies: Mapping[str, str], authorization: str | None, query: Mapping[str, str],
        port: int,
    ) -> bool:  # fmt: skip
        """A request other than the page's first load: the cookie or the bearer header, or
        the query too where the token is not taken from a URL once only."""
        held = self.holds_token(cookies, authorization, port)
        return held or (not self.url_once and self.in_query(query))

    def in_query(self, query: Mapping[str, str]) -> bool:
        """The token as ``?token=``: what the printed URL carries to the page's first load."""
        return self._matches(query.get("token", ""))

    def _matches(self, given: str) -> bool:
        return bool(given) and secrets.compare_digest(given.encode(), self.token.encode())

    def cookie(self, port: int) -> str:
        """The ``Set-Cookie`` value that hands the token to the page's later requests."""
        return f"{cookie_name(port)}={self.token}; Path=/; HttpOnly; SameSite=Strict"


def headers(host_header: str = "") -> dict[str, str]:
    """What every answer carries; the page's websocket goes to ``host_header``."""
    connect = f"'self' ws://{host_header}" if host_header else "'self'"
    policy = (
        "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
        f"connect-src {connect}; frame-ancestors 'none'; base-uri 'none'; form-action 'none'"
    )
    return {
        "Content-Security-Policy": policy,
        "Referrer-Policy": "no-referrer",
        "Cache-Control": "no-store",
        "X-Frame-Options": "DENY",
        "X-Content-Type-Options": "nosniff",
    }


class Guarded:
    """The ASGI app behind the checks of ``Host`` and ``Origin`` (HTTP and websocket), its
    answers with the headers above. The token is the routes' to check."""

    def __init__(self, app: Any, guard: Guard) -> None:
        self.app = app
        self.guard = guard

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        given = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        host = given.get("host", "")
        if not self.guard.host_allowed(host, scope["server"][1]):
            await _refuse(scope, send, "the Host header names another address than the one served")
            return
        if not self.guard.origin_allowed(given.get("origin"), host):
            await _refuse(scope, send, "a page of another origin may not use this server")
            return
        extra = [(k.lower().encode(), v.encode("latin-1")) for k, v in headers(host).items()]

        async def send_with_headers(message: dict[str, Any]) -> None:
            if message["type"] == "http.response.start":
                message = {**message, "headers": [*message.get("headers", []), *extra]}
            await send(message)

        await self.app(scope, receive, send_with_headers)


async def _refuse(scope: dict[str, Any], send: Any, reason: str) -> None:
    """403; a websocket is refused before it opens."""
    if scope["type"] == "websocket":
        await send({"type": "websocket.close", "code": 1008, "reason": reason})
        return
    body = reason.encode()
    start_headers = [(b"content-type", b"text/plain; charset=utf-8")]
    start_headers += [(b"content-length", str(len(body)).encode())]
    start_headers += [(k.lower().encode(), v.encode()) for k, v in headers().items()]
    await send({"type": "http.response.start", "status": 403, "headers": start_headers})
    await send({"type": "http.response.body", "body": body})
