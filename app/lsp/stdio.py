"""The language server on stdin and stdout: every request gets an answer.

pygls's own reader stays silent for good after a frame with a broken header, and answers no
request whose body it cannot read. Here frames are read by :mod:`.framing`; what cannot be
served is answered with a JSON-RPC error (with the request's id where it can be found, else
null), and everything else goes to pygls as before.
"""

from __future__ import annotations

import asyncio
import json
import re
import sys
import threading
from typing import Any

from lsprotocol.types import EXIT, ResponseError, ResponseErrorMessage
from pygls.io_ import StdoutWriter
from pygls.lsp.server import LanguageServer

from lightrocks.app.lsp.framing import Frame, FrameReader

PARSE_ERROR, INVALID_REQUEST, INVALID_PARAMS, INTERNAL_ERROR = -32700, -32600, -32602, -32603

_ID = re.compile(rb'"id"\s*:\s*(-?\d{1,18}|"(?:[^"\\]|\\.){0,256}")')
"""A request's id in a body that is no JSON: found where clients write it, before params."""


def serve(server: LanguageServer) -> None:
    """Serve on stdin and stdout until the stream ends or the client says ``exit``."""
    server._stop_event = threading.Event()
    server.protocol.set_writer(StdoutWriter(sys.stdout.buffer))
    reader = FrameReader(sys.stdin.buffer)
    try:
        asyncio.run(_loop(server, reader))
    except BrokenPipeError:
        pass  # the client is gone
    except (KeyboardInterrupt, SystemExit):
        pass
    finally:
        server.shutdown()


async def _loop(server: LanguageServer, reader: FrameReader) -> None:
    loop = asyncio.get_running_loop()
    while not server._stop_event.is_set():
        frame = await loop.run_in_executor(server.thread_pool, reader.next)
        if frame is None:
            return
        dispatch(server, frame)


def dispatch(server: LanguageServer, frame: Frame) -> None:
    """One frame: handed to pygls, or answered with the error that says why it cannot be."""
    if frame.skipped:  # the body of a frame with a broken header: answer its request
        ident = _found_id(frame.skipped)
        if ident is not None:
            _answer(server, ident, PARSE_ERROR, "the header of this message was broken")
        return
    if frame.problem:
        _answer(server, None, PARSE_ERROR, f"broken frame: {frame.problem}")
        return
    raw, problem = _decoded(frame.body)
    if problem:
        _answer(server, _found_id(frame.body), PARSE_ERROR, problem)
        return
    request = isinstance(raw, dict) and "method" in raw and "id" in raw
    ident = raw.get("id") if isinstance(raw, dict) else None
    if not isinstance(raw, dict) or raw.get("jsonrpc") != "2.0":
        _answer(server, ident, INVALID_REQUEST, "not a JSON-RPC 2.0 message")
        return
    if request and server.protocol._shutdown and raw["method"] != EXIT:
        _answer(server, ident, INVALID_REQUEST, "the server is shutting down")
        return
    try:
        message = server.protocol.structure_message(raw)
    except Exception:
        if request or "method" not in raw:
            _answer(server, ident, INVALID_PARAMS, f"the message does not fit {raw.get('method')}")
        return
    try:
        server.protocol.handle_message(message)
    except Exception as error:  # pygls answers a handler's faults; this is its own
        if request:
            _answer(server, ident, INTERNAL_ERROR, f"{type(error).__name__}: {error}")


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


def _answer(server: LanguageServer, ident: Any, code: int, message: str) -> None:
    """An error response; a null id where the request's own is missing or no id at all."""
    if not isinstance(ident, int | str) or isinstance(ident, bool):
        ident = None
    error = ResponseError(code=code, message=message)
    server.protocol._send_data(ResponseErrorMessage(id=ident, error=error))
