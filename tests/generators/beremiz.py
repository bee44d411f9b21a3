"""Beremiz, the open-source PLC IDE, as the judge of the PLCopen target.

Beremiz is found through ``BEREMIZ=<dir>`` (its source folder, ``Beremiz_cli.py`` inside) or in
the judges' folder that ``make judges`` fills; it runs on the Python of
``BEREMIZ_PYTHON=<file>`` or of the virtual environment beside it (``beremiz-venv``), never on
the project's. Its headless build looks for MatIEC in a folder ``matiec`` beside its own.
"""

from __future__ import annotations

import json
import os
import subprocess
from dataclasses import dataclass
from pathlib import Path

from judges import JUDGES

LOADER = """
import json, os, sys
home = os.getcwd()
sys.path.insert(0, home)
import fake_wx  # Beremiz's stand-in for the GUI toolkit, as its CLI uses it
import ProjectController  # imported first, as the CLI does: it settles a circular import
from PLCControler import PLCControler
for path in sys.argv[1:]:
    controller = PLCControler()
    error = controller.OpenXMLFile(path)
    if error:
        print(json.dumps({"path": path, "load": error}))
        continue
    text, errors, warnings = controller.GenerateProgram(path + ".st")
    print(json.dumps({"path": path, "errors": errors, "warnings": warnings, "text": text}))
"""
"""Load each PLCopen file with Beremiz's loader and turn it into IEC text with its generator."""

PROJECT = """<?xml version='1.0' encoding='utf-8'?>
<BeremizRoot xmlns:xsd="http://www.w3.org/2001/XMLSchema" URI_location="LOCAL://">
  <TargetType/>
  <Libraries Enable_Python_Library="false"/>
</BeremizRoot>
"""
"""A Beremiz project's own settings: a local target, no Python library."""


@dataclass(frozen=True)
class Beremiz:
    home: Path
    python: Path


def beremiz() -> Beremiz | None:
    given = os.environ.get("BEREMIZ")
    home = Path(given) if given else JUDGES / "beremiz"
    python = Path(os.environ.get("BEREMIZ_PYTHON") or home.parent / "beremiz-venv/bin/python")
    found = (home / "Beremiz_cli.py").is_file() and python.is_file()
    return Beremiz(home, python) if found else None


@dataclass(frozen=True)
class Loaded:
    """What Beremiz made of one PLCopen file: a load error, or its generator's findings and
    the IEC text it wrote."""

    path: str
    load: str = ""
    errors: tuple = ()
    warnings: tuple = ()
    text: str = ""


def load(judge: Beremiz, files: list[Path]) -> list[Loaded]:
    done = subprocess.run(
        [str(judge.python), "-c", LOADER, *map(str, files)],
        cwd=judge.home, capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    loaded = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    return [Loaded(**{k: tuple(v) if isinstance(v, list) else v for k, v in r.items()})
            for r in loaded]  # fmt: skip


def build(judge: Beremiz, document: Path, folder: Path) -> tuple[bool, str]:
    """Build a PLCopen file as a Beremiz project, headless: (built, the build's output)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "plc.xml").write_bytes(document.read_bytes())
    (folder / "beremiz.xml").write_text(PROJECT)
    done = subprocess.run(
        [str(judge.python), "Beremiz_cli.py", "--project-home", str(folder), "build"],
        cwd=judge.home, capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    said = done.stdout + done.stderr
    return "Successfully built." in said, said
