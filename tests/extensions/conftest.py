"""The worked extension package, built as a wheel and installed into a virtual environment of
its own that sees the project's packages, so the project's environment stays as it is."""

from .peg_package import installed  # noqa: F401 (the fixture of this folder's tests)
