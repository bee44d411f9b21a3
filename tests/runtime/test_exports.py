"""The runtime package's names load on first use: all of them resolve, and the language's
checks, which import the safe ranges alone, do not load the physics libraries."""

from __future__ import annotations

import subprocess
import sys

import pytest

import lightrocks.runtime as rt


@pytest.mark.parametrize("name", rt.__all__)
def test_every_exported_name_resolves(name: str) -> None:
    assert getattr(rt, name) is not None
    assert name in dir(rt)


def test_an_unknown_name_is_an_attribute_error() -> None:
    with pytest.raises(AttributeError, match="no attribute 'Nothing'"):
        rt.Nothing  # noqa: B018


def test_checking_safe_ranges_does_not_load_pinocchio() -> None:
    probe = (
        "import sys, lightrocks.languages.domain.ranges; "
        "print(sorted({'pinocchio', 'numpy', 'lightrocks.runtime.component'} & set(sys.modules)))"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"
