"""The live monitor in headless chromium: the highlighted state follows the run; pause,
step, a breakpoint, resume and abort act on the run and show in its trace; requests without
the token are refused.

chromium and chromedriver are found on PATH or through $CHROMIUM and $CHROMEDRIVER
(Debian: ``apt-get install chromium chromium-driver``). Screenshots are written to the
test's temporary folder and, when $MONITOR_ARTIFACTS names a folder, copied there.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from monitor.browser_page import WAIT, Page, records
from monitor.long_traces import records as long_run

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")
pytest.importorskip("selenium", reason="the browser tests need selenium (the 'dev' extra)")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
SCREWED = ("--script", str(ROOT / "examples" / "screwing" / "screwed.dryrun.json"))
"""The dry run's outcomes of a run that screws the screw home, as MuJoCo gives them."""
HIGHLIGHT = (1.0, 0.953, 0.769)
"""The fill of the innermost active state drawn (#fff3c4 in index.html)."""


def test_the_page_keeps_its_token_out_of_sight_and_within_its_policy(launch, browser) -> None:
    """The token leaves the address bar, the cookie that replaces it is out of the page's
    scripts' reach, and the content security policy blocks nothing the page needs."""
    url, _, _ = launch("run", str(SCREW_TASK), "--adapter", "dryrun", "--paused")
    page = Page(browser, url)
    page.until(lambda: page.text("state") == "paused" and page.active == "ScrewTask")
    assert "token" not in browser.current_url
    assert browser.execute_script("return document.cookie") == ""
    page.press("step")
    page.until(lambda: page.text("state").startswith("paused at ScrewTask/go->"))
    blocked = [
        e["message"] for e in browser.get_log("browser") if "Security Policy" in e["message"]
    ]
    assert not blocked


def test_requests_without_the_token_are_refused(launch) -> None:
    url, _, _ = launch("run", str(SCREW_TASK), "--adapter", "dryrun", "--paused")
    base = url.split("?")[0]
    for path in ("", "task.svg", "control/resume", "control/abort"):
        for query in ("", "?token=wrong"):
            method = "POST" if path.startswith("control") else "GET"
            request = urllib.request.Request(base + path + query, method=method)
            with pytest.raises(urllib.error.HTTPError) as refused:
                urllib.request.urlopen(request, timeout=30)
            assert refused.value.code == 403
    websocket = pytest.importorskip("websockets.sync.client")
    with (
        pytest.raises(Exception, match="403"),
        websocket.connect(base.replace("http", "ws") + "stream") as socket,
    ):
        socket.recv(timeout=30)
    with urllib.request.urlopen(url, timeout=30) as page:
        assert b"LightRocks monitor" in page.read()


@pytest.mark.parametrize("adapter", ["dryrun", pytest.param("mujoco", marks=pytest.mark.slow)])
def test_step_breakpoint_and_abort(adapter: str, launch, browser, tmp_path: Path) -> None:
    script = SCREWED if adapter == "dryrun" else ()
    url, trace, process = launch("run", str(SCREW_TASK), "--adapter", adapter, "--paused", *script)
    page = Page(browser, url)
    page.until(lambda: page.text("state") == "paused" and page.active == "ScrewTask")

    page.press("step")
    page.until(lambda: page.text("state") == "paused at ScrewTask/go->ScrewTask/FindScrew")
    assert page.active == "ScrewTask"
    page.press("step")
    page.until(lambda: page.active == "ScrewTask/FindScrew")
    page.until(lambda: page.text("state") == "paused at ScrewTask/FindScrew")

    drive_in = page.element("ScrewTask/DriveIn")
    page.click(drive_in, "contextmenu")
    page.until(lambda: "breakpoint" in drive_in.get_attribute("class"))
    page.press("resume")
    page.until(lambda: page.text("state") == "paused at ScrewTask/DriveIn")
    assert page.active == "ScrewTask/DriveIn"
    drive_in = page.element("ScrewTask/DriveIn")  # the view followed the run in and out
    assert {"current", "breakpoint"} <= set(drive_in.get_attribute("class").split())
    assert "current" not in page.element("ScrewTask").get_attribute("class")
    assert "active" in page.element("ScrewTask").get_attribute("class")
    assert "active" not in page.element("ScrewTask/FindScrew").get_attribute("class")
    assert_shows_the_run(page.screenshot(tmp_path / f"monitor-{adapter}.png"))
    assert process.poll() is None, "the run ended while paused"

    if adapter == "mujoco":  # a command long enough to pause inside it
        page.press("resume")
        page.until(lambda: page.text("state").startswith("running"))
        page.until(lambda: page.active.startswith("ScrewTask/DriveIn/"))
        page.press("pause")
        page.until(lambda: page.text("state") == "paused")
    page.press("abort")
    page.until(lambda: page.text("summary") == "outcome: preempted")
    assert process.wait(timeout=WAIT) == 1

    run = records(trace)
    paused = [r for r in run if r["kind"] == "paused"]
    places = [r["at"] for r in paused]
    assert places[:4] == [
        "ScrewTask",
        "ScrewTask/go->ScrewTask/FindScrew",
        "ScrewTask/FindScrew",
        "ScrewTask/DriveIn",
    ]
    for record in paused[:-1]:  # the simulated time stands still while paused
        assert run[run.index(record) + 1] == {"time": record["time"], "kind": "resumed"}
    if adapter == "mujoco":
        assert places[4].startswith("ScrewTask/DriveIn/")
    aborted, finished = run[run.index(paused[-1]) + 1 :]
    assert aborted["kind"] == "aborted" and "ScrewTask/DriveIn" in aborted["active"]
    assert aborted["time"] == paused[-1]["time"], "the run went on after Abort"
    assert finished == {"time": aborted["time"], "kind": "finished", "outcome": "preempted"}
    assert not [r for r in run if r["kind"] == "error"], "the arm did not hold"
    assert [r["state"] for r in run if r["kind"] == "enter"].count("ScrewTask/LetGo") == 0


def test_breakpoint_from_the_command_line_and_resume_to_the_end(launch, browser) -> None:
    url, trace, process = launch(
        "run", str(SCREW_TASK), "--adapter", "dryrun", *SCREWED, "--break", "ScrewTask.Carry"
    )
    page = Page(browser, url)
    page.until(lambda: page.text("state") == "paused at ScrewTask/Carry")
    assert page.active == "ScrewTask/Carry"
    page.press("resume")
    page.until(lambda: page.text("summary") == "outcome: screwed")
    page.until(lambda: page.text("state") == "run over")
    assert process.wait(timeout=WAIT) == 0
    run = records(trace)
    assert [r.get("at") for r in run if r["kind"] == "paused"] == ["ScrewTask/Carry"]
    assert run[-1]["kind"] == "finished" and run[-1]["outcome"] == "screwed"


def assert_shows_the_run(png: Path) -> None:
    """A screenshot of the page is not blank and shows the innermost active state filled,
    on a small part of the picture only (not the whole task)."""
    from matplotlib.image import imread

    pixels = imread(png)[..., :3]
    assert pixels.shape[0] > 600 and pixels.shape[1] > 1000
    assert pixels.std() > 0.05, "the screenshot is blank"
    highlighted = (abs(pixels - HIGHLIGHT).max(axis=2) < 0.03).sum()
    assert highlighted > 100, "no highlighted state in the screenshot"
    assert highlighted < 0.15 * pixels.shape[0] * pixels.shape[1], "more than one state filled"


def active_at(run: list[dict], time: float) -> str:
    """The innermost state a run was in at ``time``, from its trace."""
    active: list[str] = []
    for record in run:
        if record["time"] > time:
            break
        if record["kind"] == "enter":
            active.append(record["state"])
        elif record["kind"] == "exit":
            active.remove(record["state"])
    return active[-1]


def test_replay_with_the_time_slider(launch, browser, tmp_path: Path) -> None:
    trace = tmp_path / "recorded.jsonl"
    command = [sys.executable, "-m", "lightrocks.app.cli", "run", str(SCREW_TASK)]
    command += ["--adapter", "dryrun", *SCREWED, "--trace", str(trace)]
    subprocess.run(command, check=True, capture_output=True)
    run = records(trace)
    url, _, _ = launch("replay", str(trace))
    page = Page(browser, url)
    page.until(lambda: page.text("summary") == "outcome: screwed")
    slider = browser.find_element("id", "slider")
    assert float(slider.get_attribute("max")) == run[-1]["time"]
    assert not browser.find_element("id", "pause").is_displayed()

    def move_to(time: float) -> None:
        browser.execute_script(
            "arguments[0].value = arguments[1];arguments[0].dispatchEvent(new Event('input'))",
            slider,
            time,
        )

    drive_in = next(r["time"] for r in run if r.get("state") == "ScrewTask/DriveIn")
    for moment in (0.0, drive_in + 0.05, drive_in - 0.05):
        move_to(moment)
        page.until(lambda moment=moment: page.active == active_at(run, moment))
        assert page.text("summary") == "running"
        shown = [r for r in run if r["time"] <= moment and r["kind"] != "sample"]
        assert len(page.text("log").splitlines()) == len(shown)
    move_to(drive_in + 0.05)
    page.until(lambda: page.active.startswith("ScrewTask/DriveIn"))
    assert_shows_the_run(page.screenshot(tmp_path / "replay.png"))
    base, _, token = url.partition("?token=")
    bearer = {"Authorization": f"Bearer {token}"}
    refused = urllib.request.Request(base + "control/resume", method="POST", headers=bearer)
    with pytest.raises(urllib.error.HTTPError) as error:
        urllib.request.urlopen(refused, timeout=30)
    assert error.value.code == 409


def test_a_long_replay_plays_in_time(launch, browser, tmp_path: Path) -> None:
    """Moving the slider on applies only the records it passes, and the log is laid out
    once per move: 20,000 skill spans replay from start to end well within the limit."""
    trace = tmp_path / "long.jsonl"
    trace.write_text("".join(json.dumps(r) + "\n" for r in long_run(20_000)), encoding="utf-8")
    url, _, _ = launch("replay", str(trace))
    started = time.monotonic()
    page = Page(browser, url)
    page.until(lambda: page.text("summary") == "outcome: screwed")
    slider = browser.find_element("id", "slider")
    for moment in (0.0, *(i * 20.0 for i in range(1, 11))):
        browser.execute_script(
            "arguments[0].value = arguments[1];arguments[0].dispatchEvent(new Event('input'))",
            slider,
            moment,
        )
    page.until(lambda: page.text("summary") == "outcome: screwed")
    assert time.monotonic() - started < 120.0
