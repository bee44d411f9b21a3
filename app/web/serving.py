"""A page's server started on a daemon thread, behind its guard: the monitor and the studio
start alike, so that neither the run's loop nor the command ever waits for a browser."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from lightrocks.app.web.guard import Guard, Guarded


def serve(
    make_app: Callable[[Guard], Any], host: str, port: int, token: str, name: str,
    url_once: bool = False,
) -> str:  # fmt: skip
    """Serve ``make_app(guard)`` behind its guard on a daemon thread named ``name``; the URL
    with the token once it listens (``url_once``: see :attr:`Guard.url_once`)."""
    import uvicorn

    guard = Guard(host, token, url_once=url_once)
    bind = host.strip("[]")
    config = uvicorn.Config(Guarded(make_app(guard), guard), host=bind, port=port,
                            log_level="warning")  # fmt: skip
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, name=name, daemon=True)
    thread.start()
    while not server.started:
        if not thread.is_alive():
            raise OSError(f"the {name} cannot listen on {host}:{port}")
        time.sleep(0.02)
    bound = server.servers[0].sockets[0].getsockname()[1]
    shown = f"[{bind}]" if ":" in bind else bind
    return f"http://{shown}:{bound}/?token={token}"
