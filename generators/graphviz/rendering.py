"""Drawing DOT as SVG or PNG with whichever dot-compatible program this machine has.

The system's Graphviz ``dot`` is preferred; without it, ``graphviz-pure`` (a dependency of
the project, a self-contained dot-compatible program installed beside the Python
interpreter's scripts) draws the picture, so rendering works after set-up on any machine.
Every PNG carries the SHA-256 of the DOT it was drawn from in a ``tEXt`` chunk, so a picture
can be checked against its model without rendering it again.
"""

from __future__ import annotations

import hashlib
import shutil
import struct
import subprocess
import sysconfig
import zlib
from dataclasses import dataclass
from pathlib import Path

from lightrocks.workbench.generators import GenerationError

FORMATS = ("svg", "png")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
DOT_HASH_KEY = b"lightrocks:dot-sha256"


@dataclass(frozen=True)
class Renderer:
    name: str
    program: Path

    def __str__(self) -> str:
        return f"{self.name} ({self.program})"


def renderer() -> Renderer | None:
    """The system ``dot`` when it is on ``PATH``, else the bundled ``graphviz-pure``."""
    system = shutil.which("dot")
    if system is not None:
        return Renderer("Graphviz dot", Path(system))
    scripts = Path(sysconfig.get_path("scripts"))
    for candidate in (scripts / "graphviz-pure", shutil.which("graphviz-pure")):
        if candidate is not None and Path(candidate).is_file():
            return Renderer("graphviz-pure", Path(candidate))
    return None


def dot_hash(dot: str) -> str:
    return hashlib.sha256(dot.encode()).hexdigest()


def render(dot: str, fmt: str) -> bytes:
    """The picture of ``dot``; a PNG is stamped with the hash of ``dot``."""
    found = renderer()
    if found is None:
        raise GenerationError(
            "render needs the Graphviz 'dot' program or 'graphviz-pure' "
            "(pip install graphviz-pure; Debian/Ubuntu: apt-get install graphviz)"
        )
    result = subprocess.run(
        [str(found.program), f"-T{fmt}"], input=dot.encode(), capture_output=True, check=False
    )
    if result.returncode != 0:
        problem = result.stderr.decode(errors="replace").strip()
        raise GenerationError(f"{found.name} failed: {problem}")
    return stamp_png(result.stdout, dot_hash(dot)) if fmt == "png" else result.stdout


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def stamp_png(png: bytes, digest: str) -> bytes:
    """``png`` with a ``tEXt`` chunk ``lightrocks:dot-sha256`` right after its header."""
    if not png.startswith(PNG_SIGNATURE):
        raise GenerationError("the renderer did not write a PNG")
    header_end = len(PNG_SIGNATURE) + 8 + struct.unpack(">I", png[8:12])[0] + 4
    text = _chunk(b"tEXt", DOT_HASH_KEY + b"\0" + digest.encode())
    return png[:header_end] + text + png[header_end:]


def stamped_hash(png: bytes) -> str | None:
    """The DOT hash a PNG was stamped with, if any."""
    offset = len(PNG_SIGNATURE)
    while offset + 8 <= len(png):
        length = struct.unpack(">I", png[offset : offset + 4])[0]
        kind = png[offset + 4 : offset + 8]
        data = png[offset + 8 : offset + 8 + length]
        if kind == b"tEXt" and data.startswith(DOT_HASH_KEY + b"\0"):
            return data[len(DOT_HASH_KEY) + 1 :].decode()
        offset += 12 + length
    return None
