"""The worked extension package, built as a wheel and installed into a virtual environment of
its own that sees the project's packages, so the project's environment stays as it is."""

from __future__ import annotations

import pytest

from .peg_package import Environment, build_wheel


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Environment:
    """An environment with lightrocks-peg installed; the last test uninstalls it."""
    folder = tmp_path_factory.mktemp("peg")
    environment = Environment(folder / "venv")
    environment.pip("install", "--no-deps", str(build_wheel(folder)))
    return environment
