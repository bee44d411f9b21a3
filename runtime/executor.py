"""The executor: run-to-completion steps over the state tree, one thread, adapter time.

A step starts with ``start()`` or ``send(event)`` and ends when every active state rests:
in a simple state waiting for an event, or with the top state finished. Entering an action
state runs its device command to its outcome inside the step (the adapter blocks), so a
LightRocks task runs to its end within ``start()``. No fault escapes a step: each becomes
one ``error`` outcome, and a run always ends with a ``finished`` or ``interrupted`` record.

Orthogonal regions react in declaration order within one step; the completions they cause
wait in a queue and are handled one after the other. Actions entered inside regions do not
block: their commands are collected and run together (one ``execute``) once the step has
nothing else to do, and a command stopped for an event or a time event of another region
starts again if its action is still active after the reaction.
"""

from __future__ import annotations

from collections import deque
from contextlib import suppress
from functools import partial
from types import SimpleNamespace
from typing import Any

from lightrocks.runtime.commands import CommandRunner, Done, Preemption, Timer
from lightrocks.runtime.contract import TIMEOUT, Adapter, Snapshot
from lightrocks.runtime.environment import Environment
from lightrocks.runtime.faults import (
    ERROR,
    INTERRUPTED,
    PREEMPTED,
    Abort,
    DescribedFault,
    Fault,
    UnknownEvent,
    describe,
)
from lightrocks.runtime.states import (
    Action,
    Choice,
    Composite,
    Condition,
    Parallel,
    State,
    Transition,
)
from lightrocks.runtime.trace import Trace
from lightrocks.runtime.tree import (
    BUDGET_SPENT,
    active_children,
    known_events,
    matches,
    owners,
    reactions,
    states_below,
    timed_events,
)


class Executor(CommandRunner):
    """Runs a state tree: run-to-completion steps, their faults, events and time events."""

    def __init__(self, top: State, adapter: Adapter | None, trace: Trace, env: Environment):
        self.top = top
        self.adapter = adapter
        self.trace = trace
        self.env = env
        self.fault: Fault | None = None
        self.finished = False
        self.outcome: str | None = None
        self.events: deque[str] = deque()
        self.known_events = known_events(top)
        self._timers: dict[Timer, float] = {}  # deadline of each pending time event
        self._queue: deque[Done] = deque()  # completions of further regions, in order
        self._commands: list[Action] = []  # actions entered in regions, not yet run
        self._busy = False
        self._clock = 0.0
        self._idle = SimpleNamespace(time=0.0)
        self._sent = ""  # the event of the running send(), and whether a transition took it
        self._handled = True
        tree = states_below(top)
        self._reactions = {state: reactions(state) for state in tree}
        self._timed = {state: timed_events(state) for state in tree}
        self._depth = {state: len(owners(state)) for state in tree}
        self._invariants = any(state.INVARIANTS for state in tree)
        self._checks = self._invariants or adapter is not None  # adapter snapshots each step
        self._tracing = trace.enabled  # looked at again at the start of every step

    # -- clock and sensors ----------------------------------------------------------------

    @property
    def time(self) -> float:
        if self.adapter is None:
            return self._clock  # the virtual clock, moved by advance()
        return self._ask("time", lambda: self.adapter.time)

    def snapshot(self) -> Snapshot:
        if self.adapter is None:
            return self._idle
        return self._ask("snapshot()", self.adapter.snapshot)

    @staticmethod
    def _ask(what: str, read: Any) -> Any:
        """Read the adapter; a failure is an adapter fault, not one of the model's code."""
        try:
            return read()
        except KeyboardInterrupt:
            raise
        except BaseException as exc:
            raise DescribedFault(f"adapter fault in {what}: {exc!r}", "") from None

    def _write(self, kind: str, **fields: Any) -> None:
        """One trace record now; nothing at all while the trace is disabled."""
        if not self._tracing:
            return
        if self.adapter is not None:
            self._clock = self.time
        self.trace.record(self._clock, kind, fields)

    # -- public steps ---------------------------------------------------------------------

    def start(self) -> None:
        self._step(lambda: self._enter(self.top, self.snapshot()))

    def send(self, event: str) -> bool:
        """Dispatch one event; while a command runs it is queued and may preempt it. A
        finished run takes no event."""
        if self.finished:
            return False
        if event not in self.known_events:
            known = ", ".join(sorted(self.known_events)) or "none"
            raise UnknownEvent(f"unknown event '{event}'; {self.top.NAME} accepts: {known}")
        if self._busy:
            self.events.append(event)
            return True
        self._sent, self._handled = event, True  # no answer: the event ended in an error
        self._step(self._dispatch_sent)
        return self._handled

    def _dispatch_sent(self) -> Done:
        event = self._sent
        self._write("event", name=event)
        done = self._dispatch(event, self.snapshot())
        self._handled = done is not False
        if done is False:
            self._write("discarded", name=event)
            return None
        return done

    def advance(self, seconds: float) -> None:
        """Move the virtual clock of a run without adapter; due time events fire on the way,
        each at its own deadline."""
        if self.adapter is not None:
            raise RuntimeError("the adapter's clock drives this run; it cannot be advanced")
        if seconds < 0:
            raise ValueError(f"time cannot go back: advance({seconds})")
        until = self._clock + seconds
        while not self.finished and (due := self._due(until)) is not None:
            self._clock = max(self._clock, self._timers[due])
            self._step(partial(self._fire, due))
        self._clock = until

    def active(self) -> list[State]:
        """The active states from the top down, each region's states after its own."""
        if self.finished:
            return []
        found: list[State] = []
        pending = [self.top]
        while pending:
            state = pending.pop()
            found.append(state)
            pending += reversed(active_children(state))
        return found

    def _is_active(self, state: State) -> bool:
        while state.parent is not None:
            if state not in active_children(state.parent):
                return False
            state = state.parent
        return state is self.top and not self.finished

    # -- run to completion ----------------------------------------------------------------

    def _step(self, begin: Any) -> None:
        self._busy = True
        self._tracing = self.trace.enabled
        try:
            done = self._guarded(begin)
            while True:
                while done is not None:
                    if isinstance(done, Preemption):
                        done = self._guarded(partial(self._preempt, done))
                    else:
                        state, outcome = done
                        complete = partial(self._complete, state, outcome)
                        done = self._guarded(complete, handling_error=outcome == ERROR)
                if self._queue:  # a completion of another region, unless it was left since
                    done = self._queue.popleft()
                    source = done.action if isinstance(done, Preemption) else done[0]
                    done = done if self._is_active(source) else None
                    continue
                if self._checks:
                    done = self._guarded(self._check_invariants)
                if done is None and self.events and not self.finished:
                    event = self.events.popleft()
                    self._write("event", name=event)
                    done = self._guarded(partial(self._dispatch_now, event))
                if done is None and not self.finished:
                    due = self._due(self.time)
                    if due is not None:
                        done = self._guarded(partial(self._fire, due))
                        continue
                if done is None and self._commands and not self.finished:
                    done = self._guarded(self._run_commands)
                    continue
                if done is None:
                    return
        except Abort:
            self._stop_safely()
        except KeyboardInterrupt:
            self._interrupt()
            raise
        finally:
            self._busy = False

    def _guarded(self, step: Any, handling_error: bool = False) -> Done:
        """Run a part of a step. Whatever it raises (but Ctrl-C) becomes the outcome ``error``
        of the innermost active state, once; a fault while an ``error`` is being handled, or
        after the top state was left, ends the run with ``error`` at once."""
        try:
            return step()
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # any fault of model or adapter code
            message, location = (
                (exc.message, exc.location)
                if isinstance(exc, DescribedFault)
                else (describe(exc), "")
            )
            active = self.active()
            if handling_error or not active:
                self._abort(message, location)
                return None
            state = active[-1]
            return self._error(state, message, location or state.LOCATION)

    def _abort(self, message: str, location: str) -> None:
        """End the run with ``error`` now: no exit action runs, the arm holds, the trace ends
        with ``finished``. Safe against a trace or a clock that fails as well."""
        origin = [state.path for state in reversed(self.active())] or [self.top.path]
        self.fault = Fault(message, location, origin)
        self.finished, self.outcome = True, ERROR
        self._hold()
        self._record("error", state=origin[0], message=message, location=location)
        self._record("finished", outcome=ERROR)

    def _interrupt(self) -> None:
        """Ctrl-C: the arm holds and the trace ends with an ``interrupted`` record."""
        active = [state.path for state in self.active()]
        self.finished, self.outcome = True, INTERRUPTED
        self._hold()
        self._record(INTERRUPTED, active=active)

    def _stop_safely(self) -> None:
        """An ``Abort``: the arm holds; the trace ends with ``aborted`` (the states that were
        active) and ``finished`` with ``preempted``."""
        active = [state.path for state in self.active()]
        self.finished, self.outcome = True, PREEMPTED
        self._hold()
        self._record("aborted", active=active)
        self._record("finished", outcome=PREEMPTED)

    def _record(self, kind: str, **fields: Any) -> None:
        """Write a closing record even when the adapter's clock fails (last known time)."""
        try:
            time = self.time
        except KeyboardInterrupt:
            raise
        except BaseException:  # the run is ending; the record matters more
            time = self._clock
        with suppress(Exception):  # nothing is left to report a failing trace to
            self.trace.write(time, kind, **fields)

    def _enter(self, state: State, s: Snapshot, history: str = "") -> Done:
        """Enter ``state`` and descend until something rests or completes; through a
        ``history`` the last active child is entered instead of the initial one (and, for
        ``deep`` history, so on below)."""
        while True:
            parent = state.parent
            if isinstance(state, Choice):
                return self._choose(state, s)
            if isinstance(parent, Parallel):
                parent.running.add(state.name)
            elif parent is not None:
                parent.current = state
            if parent is not None and state.name in parent.BINDINGS:  # <<import>>: arguments
                state.given = parent.BINDINGS[state.name](parent, s)
            self._write("enter", state=state.path, layer=state.LAYER)
            initialize = getattr(state, "initialize", None)
            if initialize is not None:
                initialize(s)
            try:
                state.on_entry(s)
            except Exception as exc:  # reported where the entry action is written
                raise _located(exc, state.ENTRY_LOCATION) from None
            if self._timed[state]:
                self._arm(state, s)
            if state.INVARIANTS:
                violated = self._violated(state, s)
                if violated is not None:
                    return violated
            if state.FINAL:
                return (state.parent, state.name) if state.parent is not None else (state, "")
            if isinstance(state, Action):
                if any(isinstance(owner, Parallel) for owner in owners(state)):
                    self._commands.append(state)  # runs with the commands of other regions
                    return None
                return self._execute(state, s)
            if isinstance(state, Parallel):
                return self._enter_regions(state, s, history)
            if not isinstance(state, Composite):
                return None
            remembered = state.last if history else None
            if remembered is not None and not remembered.FINAL:
                first: State | Done = remembered
                history = "deep" if history == "deep" else ""
            else:
                first, history = self._first_child(state, s), ""
            if not isinstance(first, State):
                return first
            state = first

    def _enter_regions(self, state: Parallel, s: Snapshot, history: str) -> Done:
        """Enter every region in declaration order (through deep history when it is given);
        the first completion is returned, the others wait in the queue. An error stops the
        entry of further regions."""
        dones = []
        for region in state.children.values():
            done = self._enter(region, s, "deep" if history == "deep" else "")
            if done is not None:
                dones.append(done)
                if not isinstance(done, Preemption) and done[1] == ERROR:
                    return done
        self._queue.extend(dones[1:])
        return dones[0] if dones else None

    def _choose(self, choice: Choice, s: Snapshot) -> Done:
        """Leave a choice pseudostate at once by its first branch whose guard holds."""
        parent = choice.parent
        for transition in parent.transitions_from(choice.name):
            if _guard_holds(transition, parent, s):
                return self._take(parent, transition, s)
        return self._error(parent, f"no branch of choice '{choice.name}' holds", choice.LOCATION)

    def _first_child(self, state: Composite, s: Snapshot) -> State | Done:
        """The child a composite starts in: through the first start condition that holds."""
        if state.STARTS:
            for condition in state.STARTS:
                if _condition_holds(condition, state, s):
                    for transition in state.transitions_from(condition.name):
                        if _guard_holds(transition, state, s):
                            return self._take(state, transition, s, enter=False)
            return self._error(state, "no start condition holds", state.LOCATION)
        if state.INITIAL is not None:
            return state.children[state.INITIAL]
        return self._error(state, "no start condition and no initial state", state.LOCATION)

    def _take(self, owner: Composite, t: Transition, s: Snapshot, enter: bool = True) -> Any:
        """Fire a transition whose source has been left: action, postcondition, target."""
        self._write("transition", state=owner.path, source=t.source, target=t.target,
                    stimulus=t.stimulus)  # fmt: skip
        if t.action is not None:
            _located_call(t.action, owner, s, t.location)
        if t.post is not None and not _located_call(t.post, owner, s, t.location):
            return self._error(owner, "postcondition violated", t.location)
        if t.target in owner.end_names:  # ended like in a final state: nothing to remember
            owner.last = None
            return (owner, t.target)
        target = owner.children[t.target]
        return self._enter(target, s, t.history) if enter else target

    def _complete(self, state: State, outcome: str) -> Done:
        """``state`` ended with ``outcome``: leave it and let its parent react."""
        fields: dict[str, Any] = {"state": state.path, "outcome": outcome}
        if outcome == ERROR and self.fault is not None:
            fields["origin"] = list(self.fault.origin)
        self._write("outcome", **fields)
        s = self.snapshot()
        parent = state.parent
        if parent is None:
            self.finished, self.outcome = True, outcome
            self._exit(state, s)
            self._write("finished", outcome=outcome)
            return None
        if isinstance(parent, Parallel) and outcome != ERROR:
            return self._join(parent)
        self._exit(state, s)
        for transition in parent.transitions_from(state.name):
            if matches(transition, outcome, state) and _guard_holds(transition, parent, s):
                if outcome == ERROR:
                    self.fault = None
                return self._take(parent, transition, s)
        if outcome == ERROR and self.fault is not None:
            self.fault.origin.append(parent.path)
            return (parent, ERROR)
        message = f"unhandled outcome '{outcome}' of {state.path}"
        return self._error(parent, message, state.LOCATION)

    @staticmethod
    def _join(state: Parallel) -> Done:
        """A region rests in a final state: once every region does, ``state`` completes
        with the final state of its first region."""
        finals = [region.current for region in state.children.values()]
        if all(final is not None and final.FINAL for final in finals):
            return (state, finals[0].name)
        return None

    def _exit(self, state: State, s: Snapshot) -> None:
        """Leave ``state`` and its active descendants, innermost first (regions in reverse
        declaration order)."""
        if isinstance(state, Parallel):
            for region in reversed(state.regions()):
                self._exit(region, s)
        elif isinstance(state, Composite) and state.current is not None:
            self._exit(state.current, s)
        try:
            state.on_exit(s)
        except Exception as exc:  # reported where the exit action is written
            raise _located(exc, state.EXIT_LOCATION) from None
        finally:  # left even when its exit action fails: the error belongs to the parent
            self._write("exit", state=state.path)
            if self._timers:
                for timer in [t for t in self._timers if t[0] is state]:
                    del self._timers[timer]
            parent = state.parent
            if isinstance(parent, Parallel):
                parent.running.discard(state.name)
            elif parent is not None:
                parent.last = state
                parent.current = None

    def _error(self, state: State, message: str, location: str) -> tuple[State, str]:
        self.fault = Fault(message, location, [state.path])
        self._record("error", state=state.path, message=message, location=location)
        return (state, ERROR)

    # -- events ---------------------------------------------------------------------------

    def _find(self, event: str, s: Snapshot) -> list[tuple[State, Transition]]:
        """The enabled transitions for ``event``: in each active region the innermost state
        that has one (its internal transitions before those that leave it), regions in
        declaration order; an enclosing state only when no state inside it has one."""
        return [] if self.finished else self._select(self.top, event, s)

    def _select(self, state: State, event: str, s: Snapshot) -> list[tuple[State, Transition]]:
        if isinstance(state, Parallel):
            inner = [found for region in state.regions() for found in
                     self._select(region, event, s)]  # fmt: skip
            if inner:
                return inner
        elif isinstance(state, Composite) and state.current is not None:
            inner = self._select(state.current, event, s)
            if inner:
                return inner
        for owner, transition in self._reactions[state].get(event, ()):
            if transition.guard is None or _guard_holds(transition, owner, s):
                return [(state, transition)]
        return []

    def _dispatch_now(self, event: str) -> Done:
        return self._dispatch(event, self.snapshot()) or None

    def _dispatch(self, event: str, s: Snapshot) -> Done | bool:
        """Take every enabled transition for ``event``, one region after the other; the
        first completion is returned, the others wait in the queue."""
        found = self._find(event, s)
        if not found:
            return False
        if len(found) == 1:  # found among the active states just now: still active
            state, transition = found[0]
            return self._react(state, transition, s)
        dones = [self._react(state, t, s) for state, t in found if self._is_active(state)]
        dones = [done for done in dones if done is not None]
        self._queue.extend(dones[1:])
        return dones[0] if dones else None

    def _react(self, state: State, transition: Transition, s: Snapshot) -> Done:
        """Take an enabled transition of an active state: an internal one stays in it."""
        if transition.target:
            self._exit(state, s)
            return self._take(state.parent, transition, s)
        self._write("transition", state=state.path, source=state.name, target="",
                    stimulus=transition.stimulus)  # fmt: skip
        if transition.action is not None:
            _located_call(transition.action, state, s, transition.location)
        return None

    # -- time events ----------------------------------------------------------------------

    def _arm(self, state: State, s: Snapshot) -> None:
        """Start the time events of a state just entered: its own and those leaving it."""
        for owner, transition in self._timed[state]:
            delay = _located_call(transition.delay, owner, s, transition.location)
            self._timers[(state, transition)] = self.time + delay

    def _due(self, now: float) -> Timer | None:
        """The pending time event with the earliest deadline not after ``now``; of several at
        one deadline the innermost state's first, as for an event, then in arming order."""
        if not self._timers:
            return None
        due = [(deadline, timer) for timer, deadline in self._timers.items() if deadline <= now]
        return min(due, key=lambda item: (item[0], -self._depth[item[1][0]]))[1] if due else None

    def _fire(self, timer: Timer) -> Done:
        """A time event occurs once: taken when its guard holds, else dropped."""
        del self._timers[timer]
        state, transition = timer
        s = self.snapshot()
        owner = state if not transition.target else state.parent
        self._write("event", name=transition.stimulus, state=state.path)
        if not _guard_holds(transition, owner, s):
            return None
        if transition is BUDGET_SPENT:
            return (state, TIMEOUT)
        return self._react(state, transition, s)

    def _preempt(self, preemption: Preemption) -> Done:
        action = preemption.action
        self._write("outcome", state=action.path, outcome=PREEMPTED)
        if preemption.owner is not None:
            return (preemption.owner, preemption.outcome)
        if preemption.timer is not None:
            return self._fire(preemption.timer)
        self._write("event", name=preemption.event)
        s = self.snapshot()
        return self._dispatch(preemption.event, s) or None

    def _hold(self) -> None:
        if self.adapter is None:
            return
        try:
            self.adapter.hold()
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # holding is best effort, reported anyway
            self._record("error", state=self.top.path, message=f"hold failed: {exc!r}", location="")

    # -- contracts ------------------------------------------------------------------------

    def _violated(self, state: State, s: Snapshot) -> tuple[State, str] | None:
        for invariant in state.INVARIANTS:
            if not _located_call(invariant.holds, state, s, invariant.location):
                return self._error(state, "invariant violated", invariant.location)
        return None

    def _check_invariants(self) -> Done:
        if self.finished:
            return None
        s = self.snapshot()
        if not self._invariants:
            return None
        for state in self.active():
            violated = self._violated(state, s)
            if violated is not None:
                return violated
        return None


def _guard_holds(transition: Transition, owner: State, s: Snapshot) -> bool:
    """The transition's guard holds (or it has none); a fault of the guard is reported
    where the transition is written."""
    guard = transition.guard
    return guard is None or bool(_located_call(guard, owner, s, transition.location))


def _condition_holds(condition: Condition, owner: State, s: Snapshot) -> bool:
    """A start or end condition holds (or is a pure entry or exit point); a fault of its
    expression is reported where the condition is written."""
    holds = condition.holds
    return holds is None or bool(_located_call(holds, owner, s, condition.location))


def _located_call(code: Any, owner: State, s: Snapshot, location: str) -> Any:
    """``code(owner, s)`` of a table of the model (an action, a delay, a postcondition, an
    invariant); a fault of it is reported at ``location``, where it is written."""
    try:
        return code(owner, s)
    except Exception as exc:
        raise _located(exc, location) from None


def _located(exc: Exception, location: str) -> Exception:
    """A fault of model code with the place of that code (unless it has one already)."""
    if isinstance(exc, DescribedFault) or not location:
        return exc
    return DescribedFault(describe(exc), location)
