"""Headless video of a simulated cell: frames at FPS of simulated time from a fixed camera.

``VideoRecorder(path, model)`` renders with ``mujoco.Renderer`` (backend: see adapters/__init__).
A path ending in ``.mp4`` becomes a video if ``imageio`` and ``imageio-ffmpeg`` are installed;
otherwise the frames go as numbered PNGs (``frame_00000.png``, ...) into the folder ``path``
(without a ``.mp4`` suffix), written with the standard library so no dependency is needed.
"""

from __future__ import annotations

import importlib.util
import os
import struct
import zlib
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

FPS = 30.0
WIDTH, HEIGHT = 480, 360
LOOKAT = (0.5, 0.0, 0.15)
"""The camera looks at the workpieces on the table, from the front left and above."""
DISTANCE, AZIMUTH, ELEVATION = 1.5, 135.0, -25.0


def write_png(path: Path, rgb: np.ndarray) -> None:
    """An 8-bit RGB PNG: signature, IHDR, one zlib IDAT (filter 0 per row), IEND."""
    height, width, _ = rgb.shape
    rows = np.hstack((np.zeros((height, 1), np.uint8), rgb.reshape(height, width * 3)))

    def chunk(tag: bytes, data: bytes) -> bytes:
        crc = zlib.crc32(tag + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", crc)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    path.write_bytes(
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(rows.tobytes(), 6))
        + chunk(b"IEND", b"")
    )


def _mp4_writer(path: str) -> Any:
    """An imageio writer for ``path``, or None if imageio/imageio-ffmpeg are missing."""
    if not path.endswith(".mp4"):
        return None
    if importlib.util.find_spec("imageio") is None:
        return None
    if importlib.util.find_spec("imageio_ffmpeg") is None:
        return None
    import imageio

    # H.264 needs even sides only; imageio's default blocks of 16 would stretch 360 to 368
    return imageio.get_writer(path, fps=FPS, macro_block_size=8)


class VideoRecorder:
    """Renders the scene every 1/FPS s of simulated time; the cell calls ``tick`` each tick."""

    def __init__(self, path: str | os.PathLike[str], model: mujoco.MjModel) -> None:
        try:
            self._renderer = mujoco.Renderer(model, HEIGHT, WIDTH)
        except Exception as exc:
            raise RuntimeError(
                f"headless rendering failed with MUJOCO_GL={os.environ.get('MUJOCO_GL')!r} "
                "(EGL, or OSMesa without libEGL, must work, and adapters must be imported "
                f"before mujoco): {exc}"
            ) from exc
        self._camera = mujoco.MjvCamera()
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FREE
        self._camera.lookat[:] = LOOKAT
        self._camera.distance, self._camera.azimuth = DISTANCE, AZIMUTH
        self._camera.elevation = ELEVATION
        path = os.fspath(path)
        self.path = path
        self._writer = _mp4_writer(path)
        self.folder = None if self._writer else Path(path.removesuffix(".mp4"))
        if self.folder is not None:
            self.folder.mkdir(parents=True, exist_ok=True)
        self.frames = 0
        self._next = 0.0

    def tick(self, time: float, plant: Any) -> None:
        """Render a frame if one is due at simulated ``time`` (plant: see devices.Plant)."""
        if time + 1e-9 < self._next:
            return
        self._next += 1.0 / FPS
        plant.sync()
        self._renderer.update_scene(plant.data, self._camera)
        image = self._renderer.render()
        if self._writer is not None:
            self._writer.append_data(image)
        else:
            write_png(self.folder / f"frame_{self.frames:05d}.png", image)
        self.frames += 1

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
        self._renderer.close()

    def written(self) -> str:
        """Where the frames went, for the user; why they are no MP4 when one was asked for."""
        if self.folder is None:
            return f"video: {self.path} ({self.frames} frames at {FPS:g} fps)"
        told = f"video: {self.frames} PNG frames in {self.folder}{os.sep}"
        if self.path.endswith(".mp4"):
            told += " (an MP4 needs imageio and imageio-ffmpeg: pip install 'lightrocks[video]')"
        return told
