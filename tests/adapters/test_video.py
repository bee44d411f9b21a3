"""video=PATH renders frames of the scene headless (MUJOCO_GL=egl, else osmesa)."""

import struct
import zlib

import numpy as np
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.video import FPS, HEIGHT, WIDTH
from lightrocks.runtime.contract import Command


def read_png(data: bytes) -> np.ndarray:
    """Decode the 8-bit RGB, filter-0 PNGs that adapters.video writes (and check the CRCs)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    chunks, at = {}, 8
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        tag, body = data[at + 4 : at + 8], data[at + 8 : at + 8 + length]
        (crc,) = struct.unpack(">I", data[at + 8 + length : at + 12 + length])
        assert zlib.crc32(tag + body) & 0xFFFFFFFF == crc
        chunks[tag] = chunks.get(tag, b"") + body
        at += 12 + length
    width, height, depth, colour = struct.unpack(">IIBB", chunks[b"IHDR"][:10])
    assert (depth, colour) == (8, 2) and b"IEND" in chunks
    rows = np.frombuffer(zlib.decompress(chunks[b"IDAT"]), np.uint8).reshape(height, -1)
    assert not rows[:, 0].any()
    return rows[:, 1:].reshape(height, width, 3)


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_video_writes_png_frames_of_the_scene(kind, tmp_path):
    folder = tmp_path / "frames"
    try:
        adapter = kind(video=str(folder))
    except RuntimeError as exc:
        pytest.skip(f"no headless OpenGL backend on this machine: {exc}")
    adapter.execute([Command("gripper", "close", {}, [], 0.2)])
    adapter.close()
    frames = sorted(folder.glob("frame_*.png"))
    assert len(frames) == round((0.3 + 0.2) * FPS) + 1
    for frame in (frames[0], frames[-1]):
        image = read_png(frame.read_bytes())
        assert image.shape == (HEIGHT, WIDTH, 3)
        assert len(np.unique(image.reshape(-1, 3), axis=0)) > 10
