"""The studio behind the shared guard, driven by a hostile client: no token, a wrong token,
a wrong ``Host`` (DNS rebinding), a foreign ``Origin``, on reads, on writes and on the
change socket. Each probe is refused and writes nothing; the page's own requests (the
cookie its first load set, its own origin) are answered. The server listens on 127.0.0.1
only."""

from __future__ import annotations

import json
import shutil
import socket
import urllib.error
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("starlette", reason="the studio needs the 'monitor' extra")
pytest.importorskip("websockets", reason="the studio needs the 'monitor' extra")

from lightrocks.app.studio.server import StudioServer
from lightrocks.app.studio.workspace import Studio
from lightrocks.app.web.guard import cookie_name

ROOT = Path(__file__).resolve().parents[2]
TIMEOUT = 30.0
NEW = json.dumps({"package": "screwing.tasks", "name": "Intruder"}).encode()


class Served:
    def __init__(self, models: Path) -> None:
        self.models = models
        self.url = StudioServer(Studio([models])).serve()
        base, _, self.token = self.url.partition("/?token=")
        self.host = base.removeprefix("http://")
        self.port = int(self.host.rpartition(":")[2])
        self.base = base

    def cookie(self) -> str:
        return f"{cookie_name(self.port)}={self.token}"

    def ask(
        self, path: str, data: bytes | None = None, **headers: str
    ) -> tuple[int, dict[str, str], bytes]:
        request = urllib.request.Request(self.base + path, data, headers)
        if data is not None:
            request.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(request, timeout=TIMEOUT) as answer:
                return answer.status, dict(answer.headers), answer.read()
        except urllib.error.HTTPError as refused:
            return refused.code, dict(refused.headers), refused.read()

    def events(self, host: str = "", path: str = "/events", **headers: str):
        from websockets.sync.client import connect

        connection = socket.create_connection(("127.0.0.1", self.port), timeout=TIMEOUT)
        uri = f"ws://{host or self.host}{path}"
        return connect(uri, sock=connection, additional_headers=headers, open_timeout=TIMEOUT)

    def written(self) -> bool:
        return (self.models / "screwing" / "tasks" / "Intruder.lr").exists()


@pytest.fixture(scope="module")
def served(tmp_path_factory) -> Served:
    folder = tmp_path_factory.mktemp("studio") / "examples"
    models = shutil.copytree(ROOT / "examples" / "screwing", folder / "screwing")
    return Served(models)


def test_the_first_load_exchanges_the_token_for_a_strict_cookie(served: Served) -> None:
    code, headers, body = served.ask(f"/?token={served.token}")
    assert code == 200 and b"LightRocks studio" in body
    assert headers["set-cookie"].startswith(served.cookie() + ";")
    assert "HttpOnly" in headers["set-cookie"] and "SameSite=Strict" in headers["set-cookie"]
    assert served.ask("/charts", Cookie=served.cookie())[0] == 200
    assert served.ask("/charts", Authorization=f"Bearer {served.token}")[0] == 200


@pytest.mark.parametrize(
    "headers",
    [{}, {"Cookie": "none=0"}, {"Authorization": "Bearer x"}, {"Referer": "{url}"}],
    ids=["none", "other cookie", "wrong bearer", "referer"],
)
def test_a_request_without_the_token_is_refused(served: Served, headers: dict) -> None:
    given = {k: v.format(url=served.url) for k, v in headers.items()}
    for path in ("/", "/charts", "/state?chart=screwing.tasks.ScrewTask", "/runs"):
        code, _, body = served.ask(path, **given)
        assert (code, json.loads(body)) == (403, {"error": "a valid token is needed"}), path
    assert served.ask("/new", NEW, **given)[0] == 403
    assert served.ask("/history/undo", b"{}", **given)[0] == 403
    assert not served.written()
    wrong = f"{cookie_name(served.port)}=x{served.token}"
    assert served.ask("/charts", Cookie=wrong)[0] == 403


@pytest.mark.parametrize(
    "host", ["evil.example:{port}", "evil.example", "127.0.0.1:1", "localhost.evil.example:{port}"]
)
def test_a_request_naming_another_host_is_refused(served: Served, host: str) -> None:
    named = host.format(port=served.port)
    assert served.ask("/charts", Host=named, Cookie=served.cookie())[0] == 403
    assert served.ask("/new", NEW, Host=named, Cookie=served.cookie())[0] == 403
    with pytest.raises(Exception, match="403"), served.events(named, Cookie=served.cookie()):
        pass
    assert not served.written()


@pytest.mark.parametrize("origin", ["http://evil.example", "null", "http://127.0.0.1:1"])
def test_a_request_from_another_origin_is_refused(served: Served, origin: str) -> None:
    assert served.ask("/new", NEW, Origin=origin, Cookie=served.cookie())[0] == 403
    with (
        pytest.raises(Exception, match="403"),
        served.events(Origin=origin, Cookie=served.cookie()),
    ):
        pass
    assert not served.written()
    own = f"http://{served.host}"
    assert served.ask("/charts", Origin=own, Cookie=served.cookie())[0] == 200
    with served.events(Origin=own, Cookie=served.cookie()) as opened:
        assert "stamp" in json.loads(opened.recv(timeout=TIMEOUT))


def test_a_socket_without_the_token_is_closed(served: Served) -> None:
    from websockets.exceptions import ConnectionClosed, InvalidStatus

    with pytest.raises((ConnectionClosed, InvalidStatus)), served.events() as opened:
        opened.recv(timeout=TIMEOUT)
    with served.events(path=f"/events?token={served.token}") as opened:
        assert "stamp" in json.loads(opened.recv(timeout=TIMEOUT))


@pytest.mark.parametrize("path", ["/", "/charts", "/studio.js", "/diagram.js", "/nowhere"])
def test_every_answer_carries_the_protective_headers(served: Served, path: str) -> None:
    for cookie in (served.cookie(), "none=0"):
        _, headers, _ = served.ask(path, Cookie=cookie)
        policy = headers["content-security-policy"]
        assert "frame-ancestors 'none'" in policy and "script-src 'self'" in policy
        assert "unsafe-inline" not in policy
        assert headers["referrer-policy"] == "no-referrer"
        assert headers["x-frame-options"] == "DENY"


def test_both_pages_load_one_diagram_script(served: Served) -> None:
    from importlib.resources import files

    shipped = files("lightrocks.app.web.page").joinpath("diagram.js").read_text(encoding="utf-8")
    code, headers, body = served.ask("/diagram.js")
    assert code == 200 and body.decode() == shipped
    assert headers["content-type"].startswith("text/javascript")
    assert not (ROOT / "app" / "monitor" / "page" / "diagram.js").exists()
    assert not (ROOT / "app" / "studio" / "page" / "diagram.js").exists()
