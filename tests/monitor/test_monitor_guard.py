"""The monitor driven by a hostile client: a wrong ``Host`` (DNS rebinding), a foreign
``Origin``, the token only in a ``Referer``, the token in the URL of anything but the page's
first load, a page that would frame it, an address other machines reach without
``--monitor-public``. Each probe is refused and followed by a valid
request that must be answered. Every server here listens on 127.0.0.1 only."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.commands.monitoring import monitor_address
from lightrocks.app.web.guard import Guard, cookie_name

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")
websocket = pytest.importorskip("websockets.sync.client")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
WAIT = 120.0
"""Seconds the monitor may take to start (a limit, not a measurement)."""
TIMEOUT = 30.0


class Served:
    """A paused dry run with its monitor on a free loopback port."""

    def __init__(self, tmp_path: Path) -> None:
        err = tmp_path / "stderr.txt"
        command = [sys.executable, "-m", "lightrocks.app.cli", "run", str(SCREW_TASK)]
        command += ["--adapter", "dryrun", "--paused", "--monitor", "0"]
        env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
        with err.open("w") as stderr:
            self.process = subprocess.Popen(
                command, env=env, stdout=subprocess.DEVNULL, stderr=stderr
            )
        deadline, self.url = time.monotonic() + WAIT, ""
        while not self.url:
            assert self.process.poll() is None and time.monotonic() < deadline, err.read_text()
            time.sleep(0.1)
            said = [s for s in err.read_text().splitlines() if s.startswith("monitor: ")]
            self.url = said[0].removeprefix("monitor: ") if said else ""
        self.base, _, self.token = self.url.partition("?token=")
        self.base = self.base.rstrip("/")
        self.host = self.base.removeprefix("http://")
        self.port = int(self.host.rpartition(":")[2])

    def ask(self, path: str, method: str = "GET", **headers: str) -> tuple[int, dict, bytes]:
        request = urllib.request.Request(self.base + path, method=method, headers=headers)
        try:
            with urllib.request.urlopen(request, timeout=TIMEOUT) as answer:
                return answer.status, dict(answer.headers), answer.read()
        except urllib.error.HTTPError as refused:
            return refused.code, dict(refused.headers), refused.read()

    def cookie(self) -> str:
        return f"{cookie_name(self.port)}={self.token}"

    def valid(self) -> None:
        """A request of the page itself, which must be answered."""
        code, _, body = self.ask("/task.svg", Cookie=self.cookie())
        assert code == 200 and b"<svg" in body
        code, _, body = self.ask("/control/break?at=ScrewTask.Carry", "POST", Cookie=self.cookie())
        assert code == 200 and "paused" in json.loads(body)

    def stream(self, host: str = "", **headers: str):
        """The page's websocket; ``host`` names another host than the one connected to."""
        return self.stream_at("/stream", host, **headers)

    def stream_at(self, path: str, host: str = "", **headers: str):
        connection = socket.create_connection(("127.0.0.1", self.port), timeout=TIMEOUT)
        uri = f"ws://{host or self.host}{path}"
        return websocket.connect(
            uri, sock=connection, additional_headers=headers, open_timeout=TIMEOUT, max_size=None
        )


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    run = Served(tmp_path_factory.mktemp("monitor"))
    yield run
    run.process.kill()
    run.process.wait()


def test_the_first_load_exchanges_the_token_for_a_strict_cookie(served: Served) -> None:
    code, headers, body = served.ask(f"/?token={served.token}")
    assert code == 200 and b"LightRocks monitor" in body
    cookie = headers["set-cookie"]
    assert cookie.startswith(served.cookie() + ";")
    assert "HttpOnly" in cookie and "SameSite=Strict" in cookie
    code, _, body = served.ask("/", Cookie=served.cookie())
    assert code == 200 and b"LightRocks monitor" in body
    served.valid()


@pytest.mark.parametrize("path", ["/", "/task.svg", "/monitor.js", "/nowhere"])
def test_every_answer_carries_the_protective_headers(served: Served, path: str) -> None:
    for cookie in (served.cookie(), "none=0"):
        _, headers, _ = served.ask(path, Cookie=cookie)
        policy = headers["content-security-policy"]
        assert "frame-ancestors 'none'" in policy and "script-src 'self'" in policy
        assert "unsafe-inline" not in policy
        assert headers["referrer-policy"] == "no-referrer"
        assert headers["cache-control"] == "no-store"
        assert headers["x-frame-options"] == "DENY"
    served.valid()


@pytest.mark.parametrize(
    "host", ["evil.example:{port}", "evil.example", "127.0.0.1:1", "localhost.evil.example:{port}"]
)
def test_a_request_naming_another_host_is_refused(served: Served, host: str) -> None:
    named = host.format(port=served.port)
    for path, method in (("/", "GET"), ("/task.svg", "GET"), ("/control/abort", "POST")):
        code, _, _ = served.ask(path, method, Host=named, Cookie=served.cookie())
        assert code == 403, (path, named)
    with pytest.raises(Exception, match="403"), served.stream(named, Cookie=served.cookie()):
        pass
    served.valid()
    assert served.process.poll() is None, "the abort went through"


@pytest.mark.parametrize("origin", ["http://evil.example", "null", "http://127.0.0.1:1"])
def test_a_request_from_another_origin_is_refused(served: Served, origin: str) -> None:
    code, _, _ = served.ask("/control/abort", "POST", Origin=origin, Cookie=served.cookie())
    assert code == 403
    with (
        pytest.raises(Exception, match="403"),
        served.stream(Origin=origin, Cookie=served.cookie()),
    ):
        pass
    served.valid()
    own = f"http://{served.host}"
    code, _, _ = served.ask(
        "/control/break?at=ScrewTask", "POST", Origin=own, Cookie=served.cookie()
    )
    assert code == 200
    with served.stream(Origin=own, Cookie=served.cookie()) as opened:
        assert "history" in json.loads(opened.recv(timeout=TIMEOUT))
    assert served.process.poll() is None, "the abort went through"


def test_the_token_in_a_referer_opens_nothing(served: Served) -> None:
    referer = served.url
    for path, method in (("/", "GET"), ("/task.svg", "GET"), ("/control/abort", "POST")):
        assert served.ask(path, method, Referer=referer)[0] == 403
    with pytest.raises(Exception, match="403"), served.stream(Referer=referer):
        pass
    served.valid()


def test_a_wrong_token_or_cookie_opens_nothing(served: Served) -> None:
    wrong = f"{cookie_name(served.port)}=x{served.token}"
    assert served.ask("/task.svg", Cookie=wrong)[0] == 403
    assert served.ask(f"/task.svg?token=x{served.token}")[0] == 403
    assert served.ask("/task.svg", Authorization=f"Bearer x{served.token}")[0] == 403
    assert served.ask("/task.svg", Authorization=f"Basic {served.token}")[0] == 403
    other_port = f"{cookie_name(served.port + 1)}={served.token}"
    assert served.ask("/task.svg", Cookie=other_port)[0] == 403
    served.valid()


@pytest.mark.parametrize(
    ("path", "method"),
    [("/task.svg", "GET"), ("/control/break?at=ScrewTask", "POST"), ("/control/abort", "POST")],
)
def test_the_token_in_the_url_opens_no_endpoint_but_the_first_load(
    served: Served, path: str, method: str
) -> None:
    """Only the page's first load takes the token in its URL: a tool sends it as a header,
    the page as the cookie that load set, so it travels in no other URL (logs, history)."""
    joined = "&" if "?" in path else "?"
    code, _, body = served.ask(f"{path}{joined}token={served.token}", method)
    assert code == 403
    assert b"Authorization" in body and b"first load" in body
    assert served.process.poll() is None, "the abort went through"
    with pytest.raises(Exception, match="403"), served.stream_at(f"/stream?token={served.token}"):
        pass
    served.valid()


def test_a_tool_sends_the_token_as_a_bearer_header(served: Served) -> None:
    bearer = {"Authorization": f"Bearer {served.token}"}
    code, _, body = served.ask("/task.svg", **bearer)
    assert code == 200 and b"<svg" in body
    code, _, body = served.ask("/control/break?at=ScrewTask.Carry", "POST", **bearer)
    assert code == 200 and "paused" in json.loads(body)
    with served.stream(**bearer) as opened:
        assert "history" in json.loads(opened.recv(timeout=TIMEOUT))
    code, _, body = served.ask("/", **bearer)
    assert code == 200 and b"LightRocks monitor" in body
    served.valid()


def test_the_page_echoes_the_token_nowhere(served: Served) -> None:
    token = served.token.encode()
    code, headers, body = served.ask(f"/?token={served.token}")
    assert code == 200 and token not in body
    assert "location" not in {k.lower() for k in headers}
    for script in ("/monitor.js", "/diagram.js", "/plots.js", "/monitor.css"):
        code, _, text = served.ask(script, Cookie=served.cookie())
        assert code == 200 and token not in text
        assert b"token=" not in text, script
    code, _, svg = served.ask("/task.svg", Cookie=served.cookie())
    assert code == 200 and token not in svg
    served.valid()


def test_an_address_other_machines_reach_needs_monitor_public(tmp_path: Path, capsys) -> None:
    model = str(SCREW_TASK)
    assert main(["run", model, "--adapter", "dryrun", "--monitor", "0.0.0.0:0"]) == 2
    said = capsys.readouterr().err
    assert "--monitor-public" in " ".join(said.split())
    assert monitor_address("0.0.0.0:0", public=True) == ("0.0.0.0", 0)
    assert "plain HTTP" in " ".join(capsys.readouterr().err.split())
    assert monitor_address("localhost:0") == ("localhost", 0)
    assert main(["run", model, "--adapter", "dryrun", "--monitor-public"]) == 2


def test_a_public_monitor_still_checks_the_host() -> None:
    guard = Guard("0.0.0.0", "t")
    assert guard.host_allowed("192.0.2.7:8765", 8765)
    assert guard.host_allowed("[2001:db8::1]:8765", 8765)
    assert not guard.host_allowed("rebound.example:8765", 8765)
    assert not guard.host_allowed("192.0.2.7:80", 8765)
    loopback = Guard("127.0.0.1", "t")
    assert loopback.host_allowed("localhost:8765", 8765)
    assert loopback.host_allowed("[::1]:8765", 8765)
    assert not loopback.host_allowed("192.0.2.7:8765", 8765)


def test_a_guard_takes_the_token_from_a_url_once_only_where_it_is_told() -> None:
    strict, lenient = Guard("127.0.0.1", "t", url_once=True), Guard("127.0.0.1", "t")
    cookie, query = {cookie_name(8765): "t"}, {"token": "t"}
    for guard in (strict, lenient):
        assert guard.admits(cookie, None, {}, 8765)
        assert guard.admits({}, "Bearer t", {}, 8765) and guard.admits({}, "bearer  t ", {}, 8765)
        assert not guard.admits({}, "Bearer x", {}, 8765) and not guard.admits({}, "t", {}, 8765)
        assert not guard.admits({cookie_name(8766): "t"}, None, {}, 8765)
        assert guard.in_query(query)  # the page's first load
    assert not strict.admits({}, None, query, 8765)
    assert lenient.admits({}, None, query, 8765)  # the studio's, until it follows


def test_a_control_request_that_does_not_fit_is_refused_naming_the_field(served: Served) -> None:
    code, _, body = served.ask("/control/break", "POST", Cookie=served.cookie())
    assert (code, json.loads(body)) == (400, {"error": "missing 'at'", "field": "at"})
    code, _, body = served.ask("/control/sideways", "POST", Cookie=served.cookie())
    assert (code, json.loads(body)) == (404, {"error": "no action 'sideways'"})
    served.valid()


def test_a_route_asks_the_guard_with_the_connection_it_serves() -> None:
    """What the monitor's and the studio's routes ask: :meth:`Guard.allows` and its
    refusal, from the request's cookies, headers, query and port."""

    class Connection:
        def __init__(self, cookies=None, headers=None, query=None) -> None:
            self.cookies, self.headers = cookies or {}, headers or {}
            self.query_params, self.scope = query or {}, {"server": ("127.0.0.1", 8765)}

    strict, lenient = Guard("127.0.0.1", "t", url_once=True), Guard("127.0.0.1", "t")
    for guard in (strict, lenient):
        assert guard.allows(Connection(cookies={cookie_name(8765): "t"}))
        assert guard.allows(Connection(headers={"authorization": "Bearer t"}))
        assert not guard.allows(Connection())
        assert guard.refusal(Connection()) == "a valid token is needed"
    in_url = Connection(query={"token": "t"})
    assert lenient.allows(in_url) and not strict.allows(in_url)
    assert "first load" in strict.refusal(in_url)
