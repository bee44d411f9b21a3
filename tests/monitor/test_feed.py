"""The feed between the run's thread and the pages: nothing missed or repeated for a page
that connects late, and the oldest records dropped rather than the run kept waiting."""

from __future__ import annotations

from lightrocks.app.monitor.feed import CAPACITY, Feed


def sample(time: float) -> dict:
    return {"time": time, "kind": "sample"}


def enter(state: str) -> dict:
    return {"time": 0.0, "kind": "enter", "state": state}


def test_a_late_page_gets_the_history_then_the_rest_once() -> None:
    feed = Feed()
    for record in (enter("T"), sample(0.1), enter("T/S"), sample(0.2), sample(0.3)):
        feed.publish(record)
    number, history = feed.history()
    assert history == [enter("T"), enter("T/S")]
    number, fresh = feed.since(number)
    assert fresh == [sample(0.2), sample(0.3)]
    feed.publish(enter("T/S/A"))
    assert feed.since(number) == (feed.last, [enter("T/S/A")])
    assert feed.since(feed.last) == (feed.last, [])


def test_the_oldest_records_are_dropped_when_nobody_reads() -> None:
    feed = Feed()
    feed.publish(enter("T"))
    for i in range(CAPACITY + 10):
        feed.publish(sample(i / 100))
    _, kept = feed.since(0)
    assert len(kept) == CAPACITY and kept[-1] == sample((CAPACITY + 9) / 100)
    assert feed.history() == (1, [enter("T")])
