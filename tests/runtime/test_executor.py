"""The executor's semantics on small charts run against the dry-run adapter."""

from __future__ import annotations

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.runtime import Abort, BindingError, Trace, UnknownEvent


def kinds(chart, *wanted: str) -> list[tuple[str, str]]:
    """(kind, state or outcome) of the trace records of the given kinds."""
    return [
        (r["kind"], r.get("state", "") + (f":{r['outcome']}" if "outcome" in r else ""))
        for r in chart.trace
        if r["kind"] in wanted
    ]


SEQ = """package t;

import t.Cell;

<<skill>> statechart Seq {
  parameters {
    Integer n = 0;
  }

  start condition go;
  end condition done;
  end condition failed;

  <<import="Move">> state A(x = 5 mm);
  <<import="Move">> state B;

  go -> A / { n = 1; };
  A -> B [n > 5] reached;
  A -> B [n == 1] reached / { n = 2; };
  A -> failed;
  B -> done reached [n == 2];
}
"""


def test_entry_exit_order_and_guarded_selection(build):
    chart = build({"Seq": SEQ}, "Seq")().start(adapter := DryRunAdapter())
    assert chart.finished and chart.outcome == "done"
    assert kinds(chart, "enter", "exit") == [
        ("enter", "Seq"),
        ("enter", "Seq/A"),
        ("exit", "Seq/A"),
        ("enter", "Seq/B"),
        ("exit", "Seq/B"),
        ("exit", "Seq"),
    ]
    # parameters: bound on import (A), defaults otherwise (B); assigned on transitions
    assert [c[2]["x"] for c in adapter.calls] == [0.005, 0.001]
    assert chart.n == 2
    # the exit action (μ) ran after each command and updated the environment model
    assert chart.env.part.count == 2


def test_stimulus_less_transition_takes_any_declared_outcome_but_not_builtins(build):
    chart = build({"Seq": SEQ}, "Seq")().start(DryRunAdapter(outcomes={"arm.move": ["timeout"]}))
    assert chart.outcome == "error"
    assert "unhandled outcome 'timeout' of Seq/A" in chart.fault.message


def test_postcondition_violation_names_the_model_location(build):
    text = SEQ.replace("/ { n = 2; };", "/ { n = 7; } [n == 2];")
    chart = build({"Seq": text}, "Seq")().start(DryRunAdapter())
    assert chart.outcome == "error"
    assert chart.fault.message == "postcondition violated"
    assert chart.fault.location.endswith("Seq.lr:19:3")


GUARDED = """package t;

import t.Cell;

<<skill>> statechart Guarded {
  start condition go;
  end condition ok;
  end condition late;
  end condition abort [arm.force > 5 N];

  <<import="Move">> state M(x = 2 mm);

  go -> M;
  M -> ok reached;
  M -> late timeout;
}
"""


def test_enclosing_end_condition_preempts_and_holds_the_command(build):
    adapter = DryRunAdapter(duration=0.5, sensors={"arm.force": lambda t: 10.0 if t > 0.05 else 0})
    chart = build({"Guarded": GUARDED}, "Guarded")().start(adapter)
    assert chart.outcome == "abort"
    assert adapter.holds == 1
    assert ("outcome", "Guarded/M:preempted") in kinds(chart, "outcome")
    assert chart.trace[-1]["time"] == pytest.approx(0.06)


def test_abort_stops_the_command_holds_and_ends_preempted(build):
    def stop_in_b(record):
        if record["kind"] == "command" and record["state"] == "Seq/B":
            raise Abort

    trace = Trace()
    trace.listeners.append(stop_in_b)
    chart = build({"Seq": SEQ}, "Seq")().start(adapter := DryRunAdapter(), trace=trace)
    assert chart.finished and chart.outcome == "preempted"
    assert adapter.holds == 1
    assert len(adapter.calls) == 1, "the second command ran"
    assert [r["kind"] for r in chart.trace[-3:]] == ["command", "aborted", "finished"]
    assert chart.trace[-2]["active"] == ["Seq", "Seq/B"]
    assert not kinds(chart, "error")
    assert ("exit", "Seq/B") not in kinds(chart, "exit"), "an exit action ran"


def test_timeout_is_an_outcome_that_can_be_handled(build):
    cls = build({"Guarded": GUARDED}, "Guarded")
    chart = cls().start(DryRunAdapter(duration=5.0))
    assert chart.outcome == "late"
    assert chart.trace[-1]["time"] == pytest.approx(2.0)  # the device's <<timeout="2 s">>


def test_adapter_fault_becomes_error_with_its_origin(build):
    chart = build({"Guarded": GUARDED}, "Guarded")()
    chart.start(DryRunAdapter(outcomes={"arm.move": ["error"]}))
    assert chart.outcome == "error"
    assert "adapter fault in arm.move" in chart.fault.message
    assert chart.fault.origin == ["Guarded/M", "Guarded"]


def test_extension_overrides_a_parameter_and_a_transition(build):
    derived = """package t;

import t.Cell;

<<skill, extends="Guarded">> statechart Careful {
  end condition other;

  <<import="Slow">> state M;

  M -> other reached;
}
"""
    slow = """package t;

<<action, extends="Move", timeout="500 ms">> statechart Slow {
  parameters {
    Length x = 3 mm;
  }
}
"""
    cls = build({"Guarded": GUARDED, "Careful": derived, "Slow": slow}, "Careful")
    assert cls.__mro__[1].__name__ == "Guarded"
    adapter = DryRunAdapter()
    chart = cls().start(adapter)
    assert chart.outcome == "other"
    assert adapter.calls[0][2] == {"x": 0.003}
    assert type(chart.children["M"]).BUDGET == 0.5


def test_binding_names_every_missing_device_and_sensor(build):
    class Empty(DryRunAdapter):
        def emulate(self, devices):
            """Offers nothing."""

    with pytest.raises(BindingError, match="missing device 'arm'"):
        build({"Guarded": GUARDED}, "Guarded")().start(Empty())


PLAIN = """package t;

statechart Counter {
  parameters {
    Integer count = 0;
  }

  initial state Idle;
  state Busy [count < 3] {
    initial state One;
    state Two;
    One -> Two step;
    Two -> One step / { count = count + 1; };
  }
  final state Done;

  Idle -> Busy start;
  Busy -> Done stop;
}
"""


def test_plain_statechart_with_events(build):
    chart = build({"Counter": PLAIN}, "Counter")().start()
    assert chart.active_configuration == ("Counter", "Idle")
    assert chart.send("start")
    assert chart.active_configuration == ("Counter", "Busy", "One")
    with pytest.raises(UnknownEvent, match="unknown event 'nothing'; Counter accepts: start, step"):
        chart.send("nothing")
    for _ in range(4):
        chart.send("step")
    assert chart.count == 2 and chart.active_configuration[-1] == "One"
    chart.send("stop")
    assert chart.finished and chart.outcome == "Done"


def test_invariant_violation_is_an_error_at_its_location(build):
    chart = build({"Counter": PLAIN}, "Counter")().start()
    chart.send("start")
    for _ in range(6):
        chart.send("step")
    assert chart.outcome == "error"
    assert chart.fault.message == "invariant violated"
    assert chart.fault.location.endswith("Counter.lr:9:3")


DIVIDE = """package t;

statechart Divide {
  parameters {
    Integer n = 0;
  }

  initial state Idle;
  state Busy;

  Idle -> Busy [1 / n > 0] go;
}
"""


def test_python_error_in_a_guard_becomes_error_not_a_crash(build):
    chart = build({"Divide": DIVIDE}, "Divide")().start()
    chart.send("go")
    assert chart.finished and chart.outcome == "error"
    assert "ZeroDivisionError in model code" in chart.fault.message


OUTCOME_AS_EVENT = """package t;

statechart Q {
  initial state Idle;
  state Job {
    end condition out;
    initial state Load;
    final state Ok;
    Load -> Ok load;
    Load -> out bail;
  }
  state Other;

  Idle -> Job go;
  Job -> Idle Ok;
  Job -> Other out;
  Other -> Idle back;
}
"""


def test_an_outcome_is_never_taken_as_an_external_event(build):
    chart = build({"Q": OUTCOME_AS_EVENT}, "Q")().start()
    chart.send("go")
    for outcome in ("Ok", "out", "error"):
        with pytest.raises(UnknownEvent):
            chart.send(outcome)
    assert chart.active_configuration == ("Q", "Job", "Load")
    assert chart.send("load")
    assert chart.active_configuration == ("Q", "Idle")


def test_a_disabled_trace_keeps_nothing_and_changes_nothing(build):
    cls = build({"Seq": SEQ}, "Seq")
    kept = cls().start(kept_adapter := DryRunAdapter())
    silent = cls().start(silent_adapter := DryRunAdapter(), trace=Trace(keep=False))
    assert silent.trace == []
    assert (silent.outcome, silent.n, silent.env.part.count) == ("done", 2, 2)
    assert silent_adapter.calls == kept_adapter.calls
    heard = []
    trace = Trace(keep=False)
    trace.listeners.append(heard.append)
    cls().start(DryRunAdapter(), trace=trace)
    assert trace.records == []
    assert heard == kept.trace, "a listener enables the trace"
