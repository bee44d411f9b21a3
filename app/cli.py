"""The ``lightrocks`` command line: one parser over the registered commands (see
:mod:`app.commands`); exit 0 clean, 1 findings, 2 usage, 130 interrupted."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from importlib.metadata import version

from lightrocks.app import checkstore, commands  # noqa: F401  (registers the commands)
from lightrocks.app.commands.common import (
    COMMANDS,
    EXIT_FINDINGS,
    EXIT_OK,
    EXIT_USAGE,
    MissingPart,
    UsageError,
    keep_parses_on_disk,
)
from lightrocks.workbench import checkcache, report

__all__ = ["EXIT_FINDINGS", "EXIT_OK", "EXIT_USAGE", "main", "parser"]


def parser() -> argparse.ArgumentParser:
    main_parser = argparse.ArgumentParser(
        prog="lightrocks", description="LightRocks language workbench"
    )
    main_parser.add_argument("--version", action="version", version=version("lightrocks"))
    sub = main_parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for configure, _ in COMMANDS.values():
        configure(sub)
    return main_parser


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    checkcache.use_store(checkstore.DiskStore())  # an unchanged workspace is not checked again
    if args.command not in ("check", "lsp"):  # check parses only on a miss; lsp keeps memory
        keep_parses_on_disk()
    try:
        return COMMANDS[args.command][1](args)
    except UsageError as error:
        _complain(f"error: {error}")
        return EXIT_USAGE
    except MissingPart as error:
        _complain(f"error: {error}")
        return EXIT_FINDINGS
    except KeyboardInterrupt:
        _complain("interrupted")
        return 130
    except Exception as error:
        if os.environ.get("LIGHTROCKS_DEBUG"):
            raise
        if isinstance(error, ModuleNotFoundError) and (error.name or "").startswith("lightrocks."):
            _complain(
                f"error: {error.name} is missing from this installation: reinstall lightrocks"
            )
            return EXIT_FINDINGS
        detail = repr(error) if len(repr(error)) <= 300 else repr(error)[:300] + "…"
        _complain(f"internal error: {detail} (set LIGHTROCKS_DEBUG=1 for the traceback)")
        return EXIT_FINDINGS


def _complain(message: str) -> None:
    print(f"lightrocks: {report.printable(message)}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
