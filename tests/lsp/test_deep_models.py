"""The language server serves a model whose expressions nest as deep as a check accepts: a
flat sum and a flat disjunction of many terms are checked, hovered and coloured."""

from __future__ import annotations

import json
from pathlib import Path

from pipe_session import Session, frame

from lightrocks.workbench.depth import MAX_DEPTH


def test_a_flat_sum_at_the_depth_limit_is_served(tmp_path: Path) -> None:
    terms = MAX_DEPTH - 10
    total = " + ".join(["x"] * terms)
    guard = " || ".join(["x > 2"] * terms)
    text = (
        f"package t;\n\nstatechart Wide {{\n  parameters {{\n    Real x = 1;\n"
        f"    Real y = {total};\n  }}\n  initial state A;\n  final state B;\n"
        f"  A -> B [{guard}] go;\n}}\n"
    )
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "Wide.lr").write_text(text, encoding="utf-8")
    session = Session(tmp_path)
    try:
        uri = (tmp_path / "t" / "Wide.lr").as_uri()
        opened = {
            "textDocument": {"uri": uri, "languageId": "lightrocks", "version": 1, "text": text}
        }
        notification = {"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": opened}
        session.send(frame(json.dumps(notification).encode()))
        document = {"textDocument": {"uri": uri}}
        for line, column in ((5, 14 + 4 * (terms // 2)), (9, 12)):
            answer = session.ask(
                "textDocument/hover", {**document, "position": {"line": line, "character": column}}
            )
            assert "error" not in answer, answer
        for method in ("textDocument/semanticTokens/full", "textDocument/documentSymbol"):
            assert "result" in session.ask(method, document)
        assert session.process.poll() is None
    finally:
        session.close()
