"""The studio's server in this process: bad input to every endpoint is refused with a clear
error and writes nothing; a change on disk is pushed to an open page's socket."""

from __future__ import annotations

import dataclasses
import json
import shutil
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("starlette", reason="the studio needs the 'monitor' extra")

from lightrocks.app.studio import requests
from lightrocks.app.studio.operations import OPERATIONS
from lightrocks.app.studio.server import StudioServer
from lightrocks.app.studio.workspace import Studio

ROOT = Path(__file__).resolve().parents[2]
AHEAD = "din_rail_ahead.tasks.AssembleRailAhead"


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    models = shutil.copytree(ROOT / "examples", tmp_path_factory.mktemp("studio") / "examples")
    url = StudioServer(Studio([models])).serve()
    return url, models


def post(url: str, path: str, data: bytes | None) -> tuple[int, dict]:
    base, _, query = url.partition("?")
    call = urllib.request.Request(
        f"{base.rstrip('/')}/{path}?{query}", data, {"Content-Type": "application/json"}
    )
    try:
        with urllib.request.urlopen(call, timeout=60) as answer:
            return answer.status, json.loads(answer.read())
    except urllib.error.HTTPError as error:
        return error.code, json.loads(error.read())


def state(url: str) -> dict:
    base, _, query = url.partition("?")
    with urllib.request.urlopen(f"{base}state?{query}&chart={AHEAD}", timeout=60) as answer:
        return json.loads(answer.read())


def snapshot(models: Path) -> dict[Path, str]:
    return {f: f.read_text() for f in models.rglob("*.lr*")}


@pytest.mark.parametrize(
    ("path", "body", "status", "message"),
    [
        ("edit", b"{not json", 400, "not JSON"),
        ("edit", b"[1, 2]", 400, "not a JSON object"),
        ("edit", {"version": None, "op": "move"}, 400, "missing 'version'"),
        ("edit", {"op": "move", "state": "PlugTerminal3"}, 400, "missing 'steps'"),
        ("edit", {"op": "move", "state": "PlugTerminal3", "steps": "x"}, 400, "whole number"),
        ("edit", {"op": "add-state", "name": ["x"], "imports": "A"}, 400, "must be a text"),
        ("edit", {"op": "add-state", "name": "A", "imports": 3}, 400, "must be a text"),
        ("edit", {"op": "add-state", "name": "A", "imports": "a; b"}, 422, "qualified chart name"),
        (
            "edit",
            {"op": "set-transition", "source": "go", "target": "PlugTerminal1", "guard": "1 +"},
            422,
            "guard: syntax error",
        ),
        ("edit", {"op": "set-parameters", "parameters": [["Length", "x"]]}, 400, "a list of"),
        ("edit", {"op": "set-parameters", "parameters": [], "level": "x.Y"}, 422, "not one of"),
        ("edit", {"op": "rename", "element": "PlugTerminal1", "to": "X"}, 400, "no edit 'rename'"),
        ("edit", {"op": "nothing"}, 400, "no edit 'nothing'"),
        ("edit", {"op": "move", "chart": "no.Such", "state": "A", "steps": 1}, 404, "no.Such"),
        ("rename", {"element": "PlugTerminal1", "to": "two words"}, 422, "not a name"),
        ("rename", {"element": "PlugTerminal1"}, 400, "missing 'to'"),
        ("rename", {"element": "PlugTerminal1", "to": None, "level": 3}, 400, "'level'"),
        ("preview", b"", 400, "not JSON"),
        ("preview", {"op": "add-condition", "kind": "middle", "name": "x"}, 422, "'start'"),
        ("history/undo", {}, 422, "nothing to undo"),
        ("history/sideways", {}, 400, "'way' must be one of 'undo', 'redo'"),
        ("history/undo", b"-", 400, "not JSON"),
        ("new", {"package": "din_rail.tasks", "name": 3}, 400, "'name' must be a text"),
        ("new", {"package": "din_rail.tasks"}, 400, "missing 'name'"),
        ("new", {"package": "din_rail.tasks", "name": "Bad Name"}, 422, "is not a name"),
        ("new", {"package": "din_rail.tasks", "name": "PlugTerminal"}, 422, "there already"),
        ("new", {"package": "../up", "name": "X"}, 422, "not a package name"),
    ],
)
def test_bad_input_is_refused_with_a_reason_and_nothing_written(
    served, path: str, body, status: int, message: str
) -> None:
    url, models = served
    before = snapshot(models)
    if isinstance(body, dict) and path in ("edit", "preview", "rename"):  # None: left out
        known = {"chart": AHEAD, "version": state(url)["version"], "level": AHEAD}
        body = {k: v for k, v in {**known, **body}.items() if v is not None}
    data = json.dumps(body).encode() if isinstance(body, dict) else body
    got, answer = post(url, path, data)
    assert (got, message in answer.get("error", "")) == (status, True), answer
    assert snapshot(models) == before


BODIES = [
    *((path, schema) for path in ("edit", "preview") for schema in OPERATIONS.values()),
    *(("rename", schema) for schema in (requests.Target, requests.Rename)),
    ("new", requests.NewChart),
    ("runs/start", requests.StartRun),
]
"""Each route with a JSON body and each schema its body is checked against."""


@pytest.mark.parametrize(("path", "schema"), BODIES, ids=lambda v: getattr(v, "__name__", v))
def test_each_request_type_names_its_bad_field_with_400(served, minimal, path, schema) -> None:
    """A field left out, or a JSON object where a text, number, list or flag belongs."""
    url, models = served
    before = snapshot(models)
    known = {"chart": AHEAD, "version": "0", "level": AHEAD, "element": "", "to": "X"}
    whole = {**known, **minimal(schema)}
    for field in (f.name for f in dataclasses.fields(schema)):
        left_out = {k: v for k, v in whole.items() if k != field}
        for body in ([left_out] if field in minimal(schema) else []) + [{**whole, field: {}}]:
            status, answer = post(url, path, json.dumps(body).encode())
            assert (status, answer.get("field")) == (400, field), (body, answer)
            assert f"'{field}'" in answer["error"]
    assert snapshot(models) == before


@pytest.mark.parametrize("path", ["state", "diagram.svg"])
def test_a_query_without_its_chart_is_refused_and_an_unknown_chart_is_not_found(
    served, path: str
) -> None:
    url, _ = served
    status, body = get(url, path)
    assert (status, json.loads(body)) == (400, {"error": "missing 'chart'", "field": "chart"})
    status, body = get(url, f"{path}", "&chart=no.Such")
    assert status == 404 and "no statechart 'no.Such'" in json.loads(body)["error"]


def test_a_bug_of_the_server_is_answered_500_and_logged(tmp_path: Path, caplog) -> None:
    class Broken(Studio):
        def charts(self) -> list[dict[str, str]]:
            raise ZeroDivisionError("a bug")

    url = StudioServer(Broken([tmp_path])).serve()
    status, body = get(url, "charts")
    assert status == 500
    assert json.loads(body) == {"error": "the server failed (ZeroDivisionError); see its log"}
    logged = [r for r in caplog.records if r.name == "lightrocks.app.web"]
    assert logged and logged[0].exc_info[0] is ZeroDivisionError
    assert "GET /charts failed" in logged[0].getMessage()


def test_a_change_on_disk_is_pushed_to_an_open_page(served) -> None:
    from websockets.sync.client import connect

    url, models = served
    base, _, query = url.partition("?")
    path = models / "din_rail" / "tasks" / "PlugTerminal.lr"
    with connect(f"{base.replace('http', 'ws')}events?{query}", open_timeout=30) as socket:
        first = json.loads(socket.recv(timeout=30))
        assert first == {"stamp": state(url)["stamp"], "files": []}
        path.write_text(path.read_text() + "// touched\n")
        news = json.loads(socket.recv(timeout=30))
    assert news["files"] == ["examples/din_rail/tasks/PlugTerminal.lr"]
    assert news["stamp"] == state(url)["stamp"]
    path.write_text(path.read_text().removesuffix("// touched\n"))


def test_a_token_less_socket_is_closed(served) -> None:
    from websockets.exceptions import ConnectionClosed, InvalidStatus
    from websockets.sync.client import connect

    url, _ = served
    base = url.partition("?")[0]
    address = f"{base.replace('http', 'ws')}events"
    with pytest.raises((ConnectionClosed, InvalidStatus)), connect(address) as socket:
        socket.recv(timeout=30)


def get(url: str, path: str, more: str = "") -> tuple[int, bytes]:
    base, _, query = url.partition("?")
    try:
        with urllib.request.urlopen(f"{base}{path}?{query}{more}", timeout=60) as answer:
            return answer.status, answer.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def test_a_run_is_served_by_the_monitor_s_app_below_run(served) -> None:
    url, _ = served
    assert get(url, "run/")[0] == 404  # no run yet
    options = json.loads(get(url, "runs")[1])
    assert "dryrun" in options["adapters"]
    assert "lwr" in options["robots"]
    assert "examples/din_rail/assembled.dryrun.json" in options["scripts"]
    for body, message in [
        ({"chart": "din_rail.tasks.AssembleRail", "adapter": "warp"}, "no adapter 'warp'"),
        ({"chart": "din_rail.tasks.AssembleRail", "robot": "atlas"}, "unknown robot 'atlas'"),
        ({"chart": "no.Such", "adapter": "dryrun"}, "no statechart 'no.Such'"),
        ({"chart": "din_rail.tasks.AssembleRail", "script": "x.json"}, "no outcome script"),
        ({"chart": "din_rail.tasks.AssembleRail", "paused": "yes"}, "true or false"),
    ]:
        status, answer = post(url, "runs/start", json.dumps(body).encode())
        assert status in (400, 404, 422) and message in answer["error"], answer
    start = {"chart": "din_rail.tasks.AssembleRail", "adapter": "dryrun",
             "script": "examples/din_rail/assembled.dryrun.json"}  # fmt: skip
    status, answer = post(url, "runs/start", json.dumps(start).encode())
    assert status == 200 and answer["chart"] == "din_rail.tasks.AssembleRail"
    deadline = time.monotonic() + 60
    while json.loads(get(url, "runs")[1])["running"]:
        assert time.monotonic() < deadline
        time.sleep(0.1)
    assert json.loads(get(url, "runs")[1])["outcome"] == "assembled"
    page = get(url, "run/")
    assert page[0] == 200 and b"monitor.js" in page[1]  # the monitor's own page, with plots
    assert get(url, "run/task.svg")[1].startswith(b"<svg")
    assert get(url, "runs/frame.png")[0] == 204  # a dry run draws no cell
