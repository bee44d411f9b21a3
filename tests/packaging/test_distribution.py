"""What ``pip install`` puts on a machine: one import package, ``lightrocks``, with its
data files; the repository's folder names are not importable on their own."""

from __future__ import annotations

import fnmatch
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SETUPTOOLS = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
PACKAGE_DIR: dict[str, str] = SETUPTOOLS["package-dir"]
DATA: list[str] = SETUPTOOLS["package-data"]["*"]


def shipped_folders() -> dict[str, Path]:
    """Every folder below a mapped top-level folder that holds a file (code or data), by the
    package name it installs as: what the hand-kept package list must name, no more, no less."""
    found = {}
    for package, folder in PACKAGE_DIR.items():
        for path in [ROOT / folder, *(ROOT / folder).rglob("*")]:
            if path.is_dir() and "__pycache__" not in path.parts and _files(path):
                relative = path.relative_to(ROOT / folder).parts
                found[".".join((package, *relative))] = path
    return found


def _files(folder: Path) -> list[Path]:
    return [p for p in folder.iterdir() if p.is_file() and p.suffix != ".pyc"]


def test_the_package_list_names_every_folder_that_holds_a_file() -> None:
    listed = set(SETUPTOOLS["packages"])
    folders = set(shipped_folders())
    assert sorted(folders - listed) == [], "add these to [tool.setuptools] packages"
    assert sorted(listed - folders) == [], "these listed packages have no folder of files"


def test_every_file_is_code_or_declared_data() -> None:
    undeclared = [
        str(path.relative_to(ROOT))
        for folder in shipped_folders().values()
        for path in _files(folder)
        if path.suffix != ".py" and not any(fnmatch.fnmatch(path.name, g) for g in DATA)
    ]
    assert undeclared == [], "add their patterns to [tool.setuptools.package-data]"


@pytest.fixture(scope="module")
def wheel(source: Path, tmp_path_factory: pytest.TempPathFactory) -> zipfile.ZipFile:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(source), "--no-deps", "-q", "-w", str(out)],
        check=True,
        capture_output=True,
    )
    (built,) = out.glob("lightrocks-*.whl")
    return zipfile.ZipFile(built)


def test_wheel_has_exactly_one_top_level_package(wheel: zipfile.ZipFile) -> None:
    top = {name.split("/")[0] for name in wheel.namelist()}
    assert {t for t in top if not t.endswith(".dist-info")} == {"lightrocks"}


def test_wheel_carries_every_module_and_data_file(wheel: zipfile.ZipFile) -> None:
    names = set(wheel.namelist())
    expected = {
        "/".join((*package.split("."), path.name))
        for package, folder in shipped_folders().items()
        for path in _files(folder)
    }
    assert sorted(expected - names) == []


def test_entry_points_name_the_namespace(wheel: zipfile.ZipFile) -> None:
    dist_info = next(n for n in wheel.namelist() if n.endswith("entry_points.txt"))
    text = wheel.read(dist_info).decode()
    assert "lightrocks = lightrocks.app.cli:main" in text
    values = [line.split("=", 1)[1].strip() for line in text.splitlines() if "=" in line]
    assert values and all(v.startswith("lightrocks.") for v in values)


@pytest.mark.parametrize(
    ("statement", "works"),
    [
        ("import lightrocks.runtime", True),
        ("import lightrocks.adapters.scenes", True),
        ("import runtime", False),
        ("import adapters", False),
    ],
)
def test_installed_names(tmp_path: Path, statement: str, works: bool) -> None:
    result = subprocess.run(
        [sys.executable, "-c", statement], cwd=tmp_path, capture_output=True, check=False
    )
    assert (result.returncode == 0) == works, result.stderr.decode()


def test_the_suite_cannot_import_the_folders_by_accident() -> None:
    with pytest.raises(ModuleNotFoundError):
        __import__("adapters.scenes")
