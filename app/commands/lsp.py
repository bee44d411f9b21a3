"""``lightrocks lsp``: the language server over stdio, for editors."""

from __future__ import annotations

import argparse

from lightrocks.app.commands.common import command


def _configure_lsp(sub: argparse._SubParsersAction) -> None:
    sub.add_parser("lsp", help="serve the language server protocol over stdio (for editors)")


@command(_configure_lsp)
def cmd_lsp(args: argparse.Namespace) -> int:
    from lightrocks.app.lsp.server import main as serve  # only editors need pygls

    return serve()
