"""The monitor's server: what one run's page is served from (its feed of records, its
execution control, the task's SVG, the summary once over) and its start; the routes are in
:mod:`.routes`. Every request carries the token printed with the URL, as the cookie the
page's first load sets or (tools) as ``Authorization: Bearer``; only that first load takes
it in the URL (see :mod:`lightrocks.app.web.guard`).

uvicorn serves on a daemon thread of its own, so the run's loop never waits for a browser.
"""

from __future__ import annotations

import secrets
import time
from dataclasses import dataclass, field
from typing import Any

from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.feed import Feed
from lightrocks.app.web.guard import Guard
from lightrocks.app.web.serving import serve


def parse_address(text: str) -> tuple[str, int]:
    """``[HOST:]PORT``; the host defaults to the loopback interface."""
    host, _, port = text.rpartition(":")
    if not port.isdigit() or not 0 <= int(port) < 65536:
        raise ValueError(f"--monitor expects [HOST:]PORT, got '{text}'")
    return host or "127.0.0.1", int(port)


@dataclass
class Monitor:
    feed: Feed
    control: RunControl
    svg: str
    title: str
    token: str = field(default_factory=lambda: secrets.token_urlsafe(16))
    summary: dict[str, Any] = field(default_factory=dict)
    """Outcome and measurements once the run is over."""
    replay: list[dict[str, Any]] | None = None
    """A recorded run's records, for a page that replays it instead of watching a run."""
    sent: dict[int, int] = field(default_factory=dict)
    """The number of the last record pushed to each open page (0 until the run is over)."""

    def app(self, guard: Guard) -> Any:
        """The routes (:mod:`.routes`, on starlette, which only a served monitor needs);
        ``guard`` knows the token."""
        from lightrocks.app.monitor.routes import app

        return app(self, guard)

    def status(self) -> dict[str, Any]:
        c = self.control
        return {
            "paused": c.paused,
            "where": c.where,
            "breakpoints": sorted(c.breakpoints),
            **self.summary,
        }

    def drain(self, timeout: float = 15.0) -> None:
        """Give open pages up to ``timeout`` seconds to receive the end of the run and its
        summary, so a run that ends right away still shows its outcome (a busy machine may take
        seconds; a process without open pages ends at once)."""
        deadline = time.monotonic() + timeout
        while any(n < self.feed.last for n in list(self.sent.values())):
            if time.monotonic() > deadline:
                return
            time.sleep(0.02)

    def serve(self, host: str, port: int) -> str:
        """Start serving on a daemon thread; the URL with the token once it listens."""
        return serve(self.app, host, port, self.token, "monitor", url_once=True)
