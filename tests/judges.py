"""Where the outside judges live, and what a test does when one is missing.

``make judges`` (and ``.ci/run``) put the judges that no registry carries into one folder,
``$LIGHTROCKS_JUDGES`` or ``~/.cache/lightrocks/judges``: ``matiec/`` (iec2c and lib/),
``beremiz/`` (the PLC IDE) and ``beremiz-venv/`` (the Python it runs on). Locally a test
whose judge is missing skips with the reason; under ``CI=true`` it fails instead, naming the
judge and the command that provides it, so that no judge is ever dropped in silence.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import NoReturn

import pytest

JUDGES = Path(os.environ.get("LIGHTROCKS_JUDGES") or Path.home() / ".cache/lightrocks/judges")


def missing(judge: str, provider: str) -> NoReturn:
    """Skip (locally) or fail (in CI) because ``judge`` is absent; ``provider`` says how to
    get it."""
    message = f"{judge} not found: {provider}"
    if os.environ.get("CI") == "true":
        pytest.fail(f"{message} (CI runs every judge)", pytrace=False)
    pytest.skip(message)
