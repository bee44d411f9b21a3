"""The outputs a user sees from ``check`` and ``generate`` on the shipped examples, as one
manifest of SHA-256 digests: the application may be rearranged, its outputs may not change.

``python tests/app/outputs.py`` rewrites ``outputs.json`` from the installed ``lightrocks``
(run it only where an output is meant to change, and say why in the commit).
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MANIFEST = Path(__file__).with_name("outputs.json")
SOURCES = {
    "examples": [],
    "tests/generators/models/plant": [],
    "tests/app/models": ["--path", "examples"],  # findings of every kind, on purpose
}
FORMATS = ["text", "json", "sarif", "github"]
TARGETS = ["python", "sfc", "dot", "plcopen", "ecore"]


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _lightrocks(*arguments: str) -> subprocess.CompletedProcess[bytes]:
    command = [str(Path(sys.executable).with_name("lightrocks")), *arguments]
    return subprocess.run(command, cwd=ROOT, capture_output=True, timeout=600, check=False)


def manifest() -> dict[str, str]:
    """Digest of every check report and generated file, with each command's exit code."""
    found: dict[str, str] = {}
    for source, path in SOURCES.items():
        for form in FORMATS:
            done = _lightrocks("check", source, *path, "--format", form)
            found[f"check {source} {form}"] = f"{done.returncode} {_digest(done.stdout)}"
        for target in TARGETS:
            with tempfile.TemporaryDirectory() as out:
                done = _lightrocks("generate", source, *path, "--target", target, "-o", out)
                said = (done.stdout + done.stderr).replace(out.encode(), b"OUT")
                found[f"generate {source} {target}"] = f"{done.returncode} {_digest(said)}"
                for file in sorted(Path(out).rglob("*")):
                    if file.is_file():
                        name = file.relative_to(out).as_posix()
                        found[f"{source} {target} {name}"] = _digest(file.read_bytes())
    return found


if __name__ == "__main__":
    MANIFEST.write_text(json.dumps(manifest(), indent=1, sort_keys=True) + "\n")
    print(f"{MANIFEST.relative_to(ROOT)} written")
