"""Rearranging the application changes none of the outputs users see: every check report and
generated file of the examples equals the manifest written from an earlier main."""

from __future__ import annotations

import json

from outputs import MANIFEST, manifest


def test_check_and_generate_outputs_are_unchanged() -> None:
    expected = json.loads(MANIFEST.read_text())
    found = manifest()
    changed = sorted(k for k in expected.keys() | found.keys() if expected.get(k) != found.get(k))
    assert not changed, f"outputs that differ from {MANIFEST.name}: {changed}"
