"""The worked extension package (``extensions/lightrocks-peg``), its models, and a virtual
environment of its own that sees the project's packages, so the project's environment stays
as it is."""

from __future__ import annotations

import shutil
import site
import subprocess
import sys
import venv
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "extensions" / "lightrocks-peg"
MODELS = PACKAGE / "models"
EXAMPLES = ROOT / "examples"


Run = Callable[..., subprocess.CompletedProcess]


class Environment:
    """A virtual environment whose ``lightrocks`` is the project's, plus what is installed."""

    def __init__(self, folder: Path) -> None:
        venv.create(folder, with_pip=True)
        self.python = folder / "bin" / "python"
        own = self.run_python("-c", "import site; print(site.getsitepackages()[0])")
        project = site.getsitepackages()[0]
        pth = Path(own.stdout.strip()) / "lightrocks-project.pth"
        pth.write_text(f"import site; site.addsitedir({project!r})\n")

    def run_python(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [str(self.python), *args], capture_output=True, text=True, check=False
        )

    def lightrocks(self, *args: str) -> subprocess.CompletedProcess:
        return self.run_python("-m", "lightrocks.app.cli", *args)

    def pip(self, *args: str) -> None:
        result = self.run_python("-m", "pip", "--quiet", *args)
        assert result.returncode == 0, result.stderr


def build_wheel(folder: Path) -> Path:
    """The package's wheel, built from a copy so that no build files land in the repository."""
    source = folder / "source"
    shutil.copytree(PACKAGE, source, ignore=shutil.ignore_patterns("__pycache__"))
    command = [sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", str(folder)]
    result = subprocess.run([*command, str(source)], capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    return next(folder.glob("lightrocks_peg-*.whl"))


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Environment:
    """An environment with lightrocks-peg installed; the last test uninstalls it."""
    folder = tmp_path_factory.mktemp("peg")
    environment = Environment(folder / "venv")
    environment.pip("install", "--no-deps", str(build_wheel(folder)))
    return environment
