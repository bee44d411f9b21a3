"""``lightrocks lsp`` answers every request and outlives broken frames: a header that is no
number, a missing or oversized Content-Length, a line that is no header, a body that is not
UTF-8, not JSON or nested 100,000 deep, params that do not fit the method. Each probe is
followed by a valid request that must be answered, within a deadline."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pipe_session import DEADLINE, Session, frame, request


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    root = tmp_path_factory.mktemp("workspace")
    (root / "A.lr").write_text("statechart A {\n  initial state S;\n}\n", encoding="utf-8")
    started = Session(root)
    yield started
    started.close()


BROKEN_FRAMES = {
    "length no number": b"Content-Length: abc\r\n\r\n" + request(900, "shutdown", None),
    "no length": b"Content-Type: application/vscode-jsonrpc\r\n\r\n" + request(901, "x", None),
    "oversized length": b"Content-Length: 99999999999999\r\n\r\n",
    "no header at all": b"hello\r\n\r\n",
    "length too short": frame(request(902, "shutdown", None), b"10"),
}


@pytest.mark.parametrize("probe", sorted(BROKEN_FRAMES))
def test_a_broken_frame_costs_that_frame_only(session: Session, probe: str) -> None:
    session.send(BROKEN_FRAMES[probe])
    session.still_serves()
    assert session.process.poll() is None


@pytest.mark.parametrize(
    ("body", "code"),
    [
        (
            b'{"jsonrpc": "2.0", "id": 77, "method": "textDocument/hover", "params": "\xff\xfe"}',
            -32700,
        ),
        (b'{"jsonrpc": "2.0", "id": 78, "method": "textDocument/hover", "params": ', -32700),
        (
            b'{"jsonrpc": "2.0", "id": 79, "params": ' + b"[" * 100_000 + b"]" * 100_000 + b"}",
            -32700,
        ),
        (request(80, "textDocument/hover", {"textDocument": 5, "position": "here"}), -32602),
        (request(81, "textDocument/definition", None), -32602),
        (json.dumps({"id": 82, "method": "textDocument/hover"}).encode(), -32600),
        (request(83, "no/such/method", {}), -32601),
    ],
)
def test_every_request_is_answered(session: Session, body: bytes, code: int) -> None:
    ident = int(body.split(b'"id": ')[1].split(b",")[0])
    session.send(frame(body))
    answer = session.answer(ident)
    assert answer["error"]["code"] == code, answer
    session.still_serves()


def test_a_body_that_is_no_json_object_is_answered_with_a_null_id(session: Session) -> None:
    session.send(frame(b"[1, 2, 3]"))
    assert session.answer(None)["error"]["code"] == -32600
    session.still_serves()


@settings(max_examples=25, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(garbage=st.binary(max_size=200))
def test_garbage_between_frames_never_silences_the_server(session: Session, garbage: bytes):
    session.send(garbage + b"\r\n\r\n")
    session.still_serves()


def test_the_server_exits_cleanly_at_the_end_of_its_input(tmp_path: Path) -> None:
    (tmp_path / "A.lr").write_text("statechart A {\n  initial state S;\n}\n", encoding="utf-8")
    ended = Session(tmp_path)
    ended.send(b"Content-Length: 5\r\n\r\n{")  # cut off: the client went away mid-message
    ended.process.stdin.close()
    assert ended.process.wait(timeout=DEADLINE) == 0
