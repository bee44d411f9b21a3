"""The wheel and the sdist as ``pip install`` gets them: each installed into a new virtual
environment that cannot see the source tree, where every command runs.

Installing mujoco, pin and numba again would take minutes, so the new environment gets the
distribution alone (``--no-deps``) and reaches its dependencies through a plain path line to
this environment's site-packages, beside copies of that folder's ``.pth`` files (pin's
cmeel needs its own). The editable install's ``.pth`` file is not copied, and a path line runs
none, so ``lightrocks`` imports from the new environment only, as the first check proves;
``pip check`` then proves the wheel's declared dependencies met."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import time
import tomllib
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from http.cookiejar import CookieJar
from importlib.metadata import Distribution, version
from pathlib import Path
from urllib.parse import urljoin

import pytest

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
SITE = Path(sysconfig.get_paths()["purelib"])
DEADLINE = 120.0
"""Seconds a command may take on a busy machine."""
TASK = ("examples/screwing/tasks/ScrewTask.lr", "--path", "examples")
DRY_RUN = ("--adapter", "dryrun", "--script", "examples/screwing/screwed.dryrun.json")
PLAIN = ("examples/plain/Turnstile.lr", "--path", "examples")
"""A task with a cell (the dry run generates its domain module) and a plain chart, which
every generator takes."""


@pytest.fixture(scope="module")
def builder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The Python of an environment with the build system's requirements, as pip's isolated
    build has them; its hooks are called directly, for the sdist too."""
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["build-system"]["requires"]
    env = tmp_path_factory.mktemp("builder")
    python = _environment(env)
    _ok([sys.executable, "-m", "pip", "--python", str(python), "install", "-q", *requires])
    return python


@pytest.fixture(params=["wheel", "sdist"])
def built(request: pytest.FixtureRequest, builder: Path, source: Path, tmp_path: Path) -> Path:
    """The wheel, built from the sources or from the sdist built from them."""
    if request.param == "wheel":
        return _build(builder, source, "build_wheel", tmp_path / "dist")
    sdist = _build(builder, source, "build_sdist", tmp_path / "sdist")
    with tarfile.open(sdist) as archive:
        archive.extractall(tmp_path / "unpacked", filter="data")
    unpacked = tmp_path / "unpacked" / sdist.name.removesuffix(".tar.gz")
    return _build(builder, unpacked, "build_wheel", tmp_path / "dist")


@pytest.fixture
def installed(built: Path, tmp_path: Path) -> Path:
    """The ``bin`` folder of a new environment with the wheel installed."""
    python = _environment(tmp_path / "venv")
    _ok([sys.executable, "-m", "pip", "--python", str(python), "install", "-q", "--no-deps", built])
    site = Path(_ok([python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]))
    (site / "_dependencies.pth").write_text(f"{SITE}\n")  # sorts before the copies below
    for pth in SITE.glob("*.pth"):
        if not pth.name.startswith("__editable__"):
            shutil.copy(pth, site)
    return python.parent


def test_every_command_runs_where_only_the_distribution_is(
    installed: Path, tmp_path: Path, subtests: pytest.Subtests
) -> None:
    work = tmp_path / "work"
    shutil.copytree(ROOT / "examples", work / "examples")
    run = _runner(installed, work)

    with subtests.test("lightrocks imports from the new environment only"):
        where = json.loads(run("python", "-c", WHERE))
        assert all(Path(p).is_relative_to(installed.parent) for p in where), where
    with subtests.test("pip check"):
        _ok([sys.executable, "-m", "pip", "--python", str(installed / "python"), "check"])
    with subtests.test("--version"):
        assert run("lightrocks", "--version") == version("lightrocks")
    kinds = re.search(r"\{([\w,]+)\}", run("lightrocks", "list", "--help"))[1].split(",")
    for what in kinds:
        with subtests.test("list", what=what):
            assert run("lightrocks", "list", what)
    with subtests.test("check"):
        assert "0 error(s)" in run("lightrocks", "check", "examples")
    with subtests.test("verify"):
        assert "0 error(s)" in run("lightrocks", "verify", *TASK)
    for target in _targets(installed):
        with subtests.test("generate", target=target):
            run("lightrocks", "generate", *PLAIN, "--target", target, "-o", f"out/{target}")
            assert any((work / "out" / target).rglob("*.*"))
    with subtests.test("run on the dry run"):
        assert "outcome: screwed" in run("lightrocks", "run", *TASK, *DRY_RUN)
    with subtests.test("convert"):
        assert "statechart Turnstile" in run(
            "lightrocks", "convert", PLAIN[0], "--to", "sc", "--stdout"
        )
    with subtests.test("lsp"):
        _initialize_and_shut_down(installed / "lightrocks", work)
    with subtests.test("studio"):
        _assert_page([installed / "lightrocks", "studio", "examples"], work, "studio")
    with subtests.test("run --monitor"):
        monitored = [installed / "lightrocks", "run", *TASK, *DRY_RUN]
        _assert_page([*monitored, "--monitor", "0", "--paused"], work, "monitor")
    with subtests.test("a missing part is named"):
        studio = installed.parent.glob("lib/python*/site-packages/lightrocks/app/studio")
        shutil.rmtree(next(studio))
        answer = _command([installed / "lightrocks", "studio", "examples"], work)
        assert answer.returncode == 1, answer.stderr
        assert "the studio is missing from this installation" in answer.stderr
        assert "lightrocks.app.studio" in answer.stderr and "pip install" not in answer.stderr


WHERE = """
import importlib.metadata, json, lightrocks, lightrocks.app, sys
assert not any("editable" in name for name in sys.modules), "the editable finder is loaded"
dist = importlib.metadata.distribution("lightrocks")
print(json.dumps([*lightrocks.__path__, lightrocks.app.__file__, str(dist.locate_file(""))]))
"""
"""Where the import package and the distribution's metadata are found."""


def _targets(installed: Path) -> list[str]:
    """Every generator the installed distribution declares."""
    (info,) = installed.parent.glob("lib/python*/site-packages/lightrocks-*.dist-info")
    entries = Distribution.at(info).entry_points.select(group="lightrocks.generators")
    assert entries
    return sorted(entry.name for entry in entries)


def _environment(folder: Path) -> Path:
    """A new virtual environment without pip (this one's pip installs into it)."""
    _ok([sys.executable, "-m", "venv", "--without-pip", folder])
    return folder / "bin" / "python"


def _build(python: Path, folder: Path, hook: str, out: Path) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    script = f"from setuptools import build_meta; print(build_meta.{hook}({str(out)!r}))"
    name = _ok([python, "-c", script], cwd=folder).splitlines()[-1]
    return out / name


def _environ(cwd: Path) -> dict[str, str]:
    """This process's environment without what would lead a new one to the source tree."""
    hidden = ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME", "PYTHONSTARTUP")
    environ = {k: v for k, v in os.environ.items() if k not in hidden}
    return {**environ, "XDG_CACHE_HOME": str(cwd / ".cache")}


def _command(command: list, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    cwd = cwd or Path.cwd()
    return subprocess.run(
        [str(part) for part in command],
        cwd=cwd,
        env=_environ(cwd),
        capture_output=True,
        text=True,
        timeout=DEADLINE,
        check=False,
    )


def _ok(command: list, cwd: Path | None = None) -> str:
    """The output of a command that must succeed."""
    answer = _command(command, cwd)
    assert answer.returncode == 0, f"{command}: {answer.stdout}{answer.stderr}"
    return answer.stdout.strip()


def _runner(installed: Path, work: Path):
    def run(program: str, *arguments: str) -> str:
        return _ok([installed / program, *arguments], work)

    return run


def _message(body: dict) -> bytes:
    data = json.dumps(body).encode()
    return b"Content-Length: %d\r\n\r\n" % len(data) + data


def _initialize_and_shut_down(program: Path, work: Path) -> None:
    """The language server answers ``initialize`` and ``shutdown`` over stdio, then exits."""
    requests = [
        {"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}},
        {"jsonrpc": "2.0", "method": "initialized", "params": {}},
        {"jsonrpc": "2.0", "id": 2, "method": "shutdown"},
        {"jsonrpc": "2.0", "method": "exit"},
    ]
    answer = subprocess.run(
        [str(program), "lsp"],
        cwd=work,
        env=_environ(work),
        input=b"".join(_message(r) for r in requests),
        capture_output=True,
        timeout=DEADLINE,
        check=False,
    )
    answers = {m.get("id"): m for m in _messages(answer.stdout) if "id" in m}
    assert "capabilities" in answers[1]["result"], answers
    assert answers[2].get("result", "absent") is None, answers
    assert answer.returncode == 0, answer.stderr.decode()


def _messages(stream: bytes) -> Iterator[dict]:
    """The messages of a stream of base protocol frames (headers, a blank line, a body)."""
    while stream:
        head, _, stream = stream.partition(b"\r\n\r\n")
        length = int(re.search(rb"Content-Length: *(\d+)", head, re.IGNORECASE)[1])
        body, stream = stream[:length], stream[length:]
        yield json.loads(body)


@contextmanager
def _serving(command: list, work: Path, name: str) -> Iterator[str]:
    """A command that serves a page, until the block ends: the URL it printed."""
    log = work / f"{name}.err"
    with log.open("w") as stderr:
        process = subprocess.Popen(
            [str(part) for part in command],
            cwd=work,
            env=_environ(work),
            stdout=subprocess.DEVNULL,
            stderr=stderr,
        )
    try:
        prefix, url, until = f"{name}: ", "", time.monotonic() + DEADLINE
        while not url and process.poll() is None and time.monotonic() < until:
            time.sleep(0.1)
            lines = log.read_text().splitlines()
            url = next((s.removeprefix(prefix) for s in lines if s.startswith(prefix)), "")
        assert url, f"{name} printed no URL: {log.read_text()}"
        yield url
    finally:
        process.kill()
        process.wait()


def _assert_page(command: list, work: Path, name: str) -> None:
    """The page a command serves and every script and style sheet it names."""
    with _serving(command, work, name) as url:
        _assert_served(url)


def _assert_served(url: str) -> None:
    opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor(CookieJar()))
    with opener.open(url, timeout=DEADLINE) as answer:
        page = answer.read().decode()
    assets = re.findall(r'(?:src|href)="([\w.-]+\.(?:js|css))"', page)
    assert assets, page
    for asset in assets:
        with opener.open(urljoin(url, asset), timeout=DEADLINE) as answer:
            assert answer.status == 200 and answer.read(), asset
