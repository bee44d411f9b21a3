"""``lightrocks run --video``: an MP4 with the 'video' extra, else PNG frames and a hint;
either way the run tells where the frames went."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from lightrocks.adapters import video
from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
OPEN = [str(ROOT / "examples" / "screwing" / "actions" / "OpenGripper.lr")]
OPEN += ["--path", str(ROOT / "examples"), "--adapter", "mujoco"]


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


def record(capsys: pytest.CaptureFixture[str], target: Path) -> str:
    status = main(["run", *OPEN, "--video", str(target)])
    captured = capsys.readouterr()
    if "headless rendering failed" in captured.out + captured.err:
        pytest.skip("no headless OpenGL backend on this machine")
    assert status == 0, captured.out + captured.err
    return " ".join(captured.out.split())


def frames_told(out: str) -> int:
    line = next(part for part in out.split("video: ")[1:])
    return int(line.split("(")[1].split()[0]) if "(" in line else int(line.split()[0])


def test_mp4_with_imageio_ffmpeg(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    if importlib.util.find_spec("imageio_ffmpeg") is None:
        pytest.skip("the 'video' extra (imageio, imageio-ffmpeg) is not installed")
    import imageio

    target = tmp_path / "open.mp4"
    out = record(capsys, target)
    count = frames_told(out)
    assert f"video: {target} ({count} frames at 30 fps)" in out
    with imageio.get_reader(target) as reader:
        frames = [frame for frame in reader]
    assert len(frames) == count > 5
    assert frames[-1].shape == (video.HEIGHT, video.WIDTH, 3)
    assert np.asarray(frames[-1]).std() > 5, "a blank frame"


def test_png_frames_and_a_hint_without_the_extra(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    find_spec = importlib.util.find_spec
    monkeypatch.setattr(
        video.importlib.util,
        "find_spec",
        lambda name, *rest: None if name == "imageio_ffmpeg" else find_spec(name, *rest),
    )
    out = record(capsys, tmp_path / "open.mp4")
    folder = tmp_path / "open"
    pngs = sorted(folder.glob("frame_*.png"))
    assert f"video: {len(pngs)} PNG frames in {folder}/" in out
    assert "pip install 'lightrocks[video]'" in out
    assert len(pngs) > 5 and not (tmp_path / "open.mp4").exists()
