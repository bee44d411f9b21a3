"""The language server on stdin and stdout, on pygls's own transport, with every request
answered.

pygls's reader stays silent for good after a frame with a broken header, and answers no
request whose body it cannot read. So pygls reads stdin through a :class:`Screen`: frames are
read by :mod:`.framing`, what can be served is handed on as a well-formed frame, and what
cannot is answered here with a JSON-RPC error (with the request's id where it can be found,
else null). Both write through one :class:`Output`, a whole message at a time.
"""

from __future__ import annotations

import json
import re
import sys
import threading
from typing import Any, BinaryIO

from lsprotocol.types import EXIT, SHUTDOWN
from pygls.lsp.server import LanguageServer
from pygls.protocol import JsonRPCProtocol

from lightrocks.app.lsp.framing import Frame, FrameReader

PARSE_ERROR, INVALID_REQUEST, INVALID_PARAMS = -32700, -32600, -32602

_ID = re.compile(rb'"id"\s*:\s*(-?\d{1,18}|"(?:[^"\\]|\\.){0,256}")')
"""A request's id in a body that is no JSON: found where clients write it, before params."""


def serve(server: LanguageServer) -> None:
    """Serve on stdin and stdout until the stream ends or the client says ``exit``."""
    output = Output(sys.stdout.buffer)
    server.start_io(Screen(sys.stdin.buffer, output, server.protocol), output)  # type: ignore[arg-type]


class Output:
    """The client's stream, shared by pygls and the screen: each write is one whole message,
    flushed at once."""

    def __init__(self, stream: BinaryIO) -> None:
        self._stream = stream
        self._lock = threading.Lock()

    def write(self, data: bytes) -> None:
        with self._lock:
            self._stream.write(data)
            self._stream.flush()

    def flush(self) -> None:
        """Every write is flushed already."""

    def close(self) -> None:
        with self._lock:
            self._stream.close()


class Screen:
    """The stream pygls reads: only frames of JSON-RPC 2.0 messages that fit their method,
    each framed as pygls expects (``Content-Length: N``, a blank line, N bytes)."""

    def __init__(self, stream: BinaryIO, output: Output, protocol: JsonRPCProtocol) -> None:
        self._frames = FrameReader(stream)
        self._output = output
        self._protocol = protocol
        self._pending = b""
        self._shutting_down = False

    def readline(self) -> bytes:
        if not self._pending:
            self._pending = self._next()
        end = self._pending.find(b"\n") + 1 or len(self._pending)
        line, self._pending = self._pending[:end], self._pending[end:]
        return line

    def read(self, size: int) -> bytes:
        data, self._pending = self._pending[:size], self._pending[size:]
        return data

    def _next(self) -> bytes:
        """The next frame pygls may read; nothing at the end of the input."""
        while True:
            frame = self._frames.next()
            if frame is None:
                return b""
            body = self._served(frame)
            if body is not None:
                return b"Content-Length: %d\r\n\r\n" % len(body) + body

    def _served(self, frame: Frame) -> bytes | None:
        """A frame's body when pygls can serve it; else ``None``, answered with the error
        that says why it cannot be."""
        if frame.skipped:  # the body of a frame with a broken header: answer its request
            ident = _found_id(frame.skipped)
            if ident is not None:
                self._answer(ident, PARSE_ERROR, "the header of this message was broken")
            return None
        if frame.problem:
            self._answer(None, PARSE_ERROR, f"broken frame: {frame.problem}")
            return None
        raw, problem = _decoded(frame.body)
        if problem:
            self._answer(_found_id(frame.body), PARSE_ERROR, problem)
            return None
        request = isinstance(raw, dict) and "method" in raw and "id" in raw
        ident = raw.get("id") if isinstance(raw, dict) else None
        if not isinstance(raw, dict) or raw.get("jsonrpc") != "2.0":
            self._answer(ident, INVALID_REQUEST, "not a JSON-RPC 2.0 message")
            return None
        if request and self._shutting_down and raw["method"] != EXIT:
            self._answer(ident, INVALID_REQUEST, "the server is shutting down")
            return None
        if "method" in raw:  # a response is matched to its request by pygls alone
            try:
                self._protocol.structure_message(raw)
            except Exception:
                if request:
                    method = raw.get("method")
                    self._answer(ident, INVALID_PARAMS, f"the message does not fit {method}")
                return None
        self._shutting_down |= request and raw["method"] == SHUTDOWN
        return frame.body

    def _answer(self, ident: Any, code: int, message: str) -> None:
        """An error response; a null id where the request's own is missing or no id at all."""
        if not isinstance(ident, int | str) or isinstance(ident, bool):
            ident = None
        error = {"code": code, "message": message}
        body = json.dumps({"jsonrpc": "2.0", "id": ident, "error": error}).encode("utf-8")
        header = f"Content-Length: {len(body)}\r\n"
        header += "Content-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n"
        self._output.write(header.encode("ascii") + body)


def _decoded(body: bytes) -> tuple[Any, str]:
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as error:
        return None, f"the message is not UTF-8 (byte {error.start})"
    try:
        return json.loads(text), ""
    except RecursionError:
        return None, "the message is nested too deeply"
    except ValueError as error:
        return None, f"the message is no JSON: {error}"


def _found_id(body: bytes) -> int | str | None:
    """The id of the request in a body that cannot be read, where it can be found."""
    raw, problem = _decoded(body)
    if not problem and isinstance(raw, dict):
        return raw.get("id")
    found = _ID.search(body[:65536])
    if found is None:
        return None
    try:
        return json.loads(found.group(1).decode("utf-8", "replace"))
    except ValueError:
        return None
