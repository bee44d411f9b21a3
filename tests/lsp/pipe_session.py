"""A language server over plain pipes, spoken to frame by frame: for the tests that send what
no client library would (broken frames, deep models)."""

from __future__ import annotations

import json
import queue
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

DEADLINE = 60.0
"""Seconds an answer may take (a limit, not a measurement; the machine is shared)."""


def frame(body: bytes, length: bytes | None = None) -> bytes:
    length = str(len(body)).encode() if length is None else length
    return b"Content-Length: " + length + b"\r\n\r\n" + body


def request(ident: int, method: str, params: Any) -> bytes:
    body = {"jsonrpc": "2.0", "id": ident, "method": method, "params": params}
    return json.dumps(body).encode()


class Session:
    """A language server over pipes; its messages read by a thread into a queue."""

    def __init__(self, root: Path) -> None:
        command = [sys.executable, "-m", "lightrocks.app.cli", "lsp"]
        self.process = subprocess.Popen(
            command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
        )
        self.messages: queue.Queue[dict[str, Any]] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        self.next_id = 1
        answer = self.ask("initialize", {"capabilities": {}, "rootUri": root.as_uri()})
        assert "result" in answer, answer
        self.send(frame(json.dumps({"jsonrpc": "2.0", "method": "initialized"}).encode()))
        self.document = (root / "A.lr").as_uri()

    def _read(self) -> None:
        stream = self.process.stdout
        while True:
            length = None
            while True:
                line = stream.readline()
                if not line:
                    return
                if line.strip() == b"":
                    break
                name, _, value = line.decode().partition(":")
                if name.lower() == "content-length":
                    length = int(value)
            self.messages.put(json.loads(stream.read(length)))

    def send(self, data: bytes) -> None:
        self.process.stdin.write(data)
        self.process.stdin.flush()

    def answer(self, ident: Any) -> dict[str, Any]:
        """The response to ``ident``; notifications and other answers in between are passed."""
        while True:
            try:
                message = self.messages.get(timeout=DEADLINE)
            except queue.Empty:
                pytest.fail(f"no answer to request {ident!r} within {DEADLINE} s")
            if "method" not in message and message.get("id") == ident:
                return message

    def ask(self, method: str, params: Any) -> dict[str, Any]:
        ident, self.next_id = self.next_id, self.next_id + 1
        self.send(frame(request(ident, method, params)))
        return self.answer(ident)

    def still_serves(self) -> None:
        symbols = {"textDocument": {"uri": self.document}}
        answer = self.ask("textDocument/documentSymbol", symbols)
        assert "result" in answer, answer

    def close(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()
