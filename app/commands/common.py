"""What every command of the ``lightrocks`` command line shares: the registry of commands,
exit codes, usage errors and the checks of paths and options that the commands take."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Sequence
from importlib.util import find_spec
from pathlib import Path
from typing import Any

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2

Command = Callable[[argparse.Namespace], int]
COMMANDS: dict[str, tuple[Callable[[argparse._SubParsersAction], None], Command]] = {}


def command(
    configure: Callable[[argparse._SubParsersAction], None],
) -> Callable[[Command], Command]:
    """Register a sub-command: ``configure`` adds its parser, the function runs it."""

    def register(run: Command) -> Command:
        COMMANDS[run.__name__.removeprefix("cmd_")] = (configure, run)
        return run

    return register


def note(message: str) -> None:
    """A remark on stderr that does not stop the command; shown neutralised."""
    from lightrocks.workbench.report import printable

    print(f"lightrocks: note: {printable(message)}", file=sys.stderr)


def complain(message: str) -> None:
    """An error that is not a wrong use of the command (exit 1) on stderr; neutralised."""
    from lightrocks.workbench.report import printable

    print(f"lightrocks: error: {printable(message)}", file=sys.stderr)


class UsageError(Exception):
    """Wrong use of the command line: reported with exit code 2."""


class MissingPart(Exception):
    """A part of LightRocks itself is not installed: a broken installation, not a wrong use
    nor a missing extra (exit code 1)."""


def require(feature: str, parts: Sequence[str], modules: Sequence[str], extra: str) -> None:
    """Refuse ``feature`` where what it runs on is absent, naming what: its own ``parts``
    (modules of LightRocks, a broken installation) or the ``modules`` that ``extra`` brings."""
    lost = [part for part in parts if not _installed(part)]
    if lost:
        raise MissingPart(
            f"{feature} is missing from this installation of lightrocks ({', '.join(lost)} "
            "not found): reinstall lightrocks"
        )
    missing = [module for module in modules if not _installed(module)]
    if missing:
        raise UsageError(f"{feature} needs {', '.join(missing)}: pip install 'lightrocks[{extra}]'")


def _installed(module: str) -> bool:
    try:
        return find_spec(module) is not None
    except ModuleNotFoundError:  # a parent package is missing
        return False


def existing_paths(paths: Sequence[str]) -> list[Path]:
    """The given files and folders; anything else (a FIFO, a device) is never read."""
    missing = [p for p in paths if not Path(p).exists()]
    if missing:
        raise UsageError(f"no such file or folder: {', '.join(missing)}")
    special = [p for p in paths if not (Path(p).is_file() or Path(p).is_dir())]
    if special:
        raise UsageError(f"not a regular file or folder: {', '.join(special)}")
    return [Path(p) for p in paths]


def statechart_file(path: str) -> Path:
    """The one ``.lr`` file ``run`` takes."""
    [model] = existing_paths([path])
    if model.is_dir():
        raise UsageError(f"{path} is a folder: run takes one statechart file (.lr)")
    if model.suffix != ".lr":
        raise UsageError(f"{path} is not a statechart file (.lr): run takes one")
    return model.resolve()


def trace_file(path: str | None) -> Path | None:
    """Where ``--trace`` writes: a new or regular file in an existing folder."""
    if path is None:
        return None
    trace = Path(path)
    if trace.exists() and not trace.is_file():
        raise UsageError(f"--trace: {path} is not a regular file")
    if not trace.parent.is_dir():
        raise UsageError(f"--trace: no such folder: {trace.parent}")
    if not os.access(trace.parent, os.W_OK):
        raise UsageError(f"--trace: cannot write to folder {trace.parent}")
    return trace


def path_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--path",
        action="append",
        default=[],
        metavar="DIR",
        help="model-path folder (package = sub-folder); repeatable",
    )


def run_arguments(parser: argparse.ArgumentParser, params: str) -> None:
    """What every command that runs a statechart takes: the model, the adapter and its robot,
    parameter values (``params`` says what they are to this command), the success outcome,
    the model path."""
    parser.add_argument("model", help="the .lr file of the statechart to run")
    parser.add_argument("--adapter", help="adapter name (see 'list adapters'); none for plain")
    parser.add_argument(
        "--robot",
        metavar="NAME",
        help="the robot in the cell's robot slot (see 'list robots'; default: the adapter's, "
        "the LWR)",
    )
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE", help=params)
    parser.add_argument(
        "--success", metavar="OUTCOME", help="outcome that counts as success (default: the first)"
    )
    path_option(parser)


def option(text: str) -> tuple[str, str]:
    """A generator option ``NAME=VALUE``."""
    name, separator, value = text.partition("=")
    if not separator or not name:
        raise UsageError(f"option '{text}' is not NAME=VALUE")
    return name, value


def all_cocos() -> list[Any]:
    from lightrocks.workbench.check import all_cocos as every_coco

    return every_coco()


def keep_parses_on_disk() -> None:
    """Parse results outlive the process: the next run does not parse an unchanged file."""
    from lightrocks.app import parsestore
    from lightrocks.workbench import parsecache

    parsecache.use_store(parsestore.DiskStore())
