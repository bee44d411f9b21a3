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
from dataclasses import dataclass, field
from functools import partial
from types import SimpleNamespace
from typing import Any

from lightrocks.runtime.contract import (
    TIMEOUT,
    Adapter,
    Command,
    CommandResult,
    Snapshot,
    StopCondition,
)
from lightrocks.runtime.environment import Environment, SceneObject, object_name
from lightrocks.runtime.safety import refusal
from lightrocks.runtime.states import Action, Choice, Composite, Parallel, State, Transition
from lightrocks.runtime.trace import Trace, to_json

ERROR, PREEMPTED, INTERRUPTED = "error", "preempted", "interrupted"
EVENT_STOP, TIMER_STOP = "@event", "@timer"

Timer = tuple[State, Transition]  # a time event of an active state, pending


class Abort(KeyboardInterrupt):
    """Raised on the run's thread (by a stop condition or a trace listener) to stop the run
    safely from outside: the arm holds, no exit action runs, the outcome is ``preempted``.
    A kind of Ctrl-C, so that every handler lets it through as it does Ctrl-C."""


class UnknownEvent(ValueError):
    """An event that no transition of the statechart names and no declaration lists."""


class _Fault(Exception):
    """A fault already described (message and model location) on its way to ``_guarded``."""

    def __init__(self, message: str, location: str) -> None:
        super().__init__(message)
        self.message, self.location = message, location


def describe(exc: BaseException) -> str:
    """What a Python error in model code, an adapter or a sensor read says about itself."""
    return f"{type(exc).__name__} in model code: {exc}"


@dataclass
class Fault:
    """Why a state ended with ``error``, and the states the error passed through."""

    message: str
    location: str
    origin: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Preemption:
    """A running action was stopped for an enclosing end condition or an event."""

    action: Action
    owner: Composite | None = None
    outcome: str = ""
    event: str = ""
    timer: Timer | None = None


Done = tuple[State, str] | Preemption | None


@dataclass
class _Request:
    """An action's command with the stop conditions the executor watches for it."""

    action: Action
    command: Command
    watch: _Watch
    preemptions: dict[str, tuple[Composite, str, Any, str]]


class Executor:
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
        tree = _states(top)
        self._reactions = {state: _reactions(state) for state in tree}
        self._timed = {state: _timed(state) for state in tree}
        self._depth = {state: len(_owners(state)) for state in tree}
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
            raise _Fault(f"adapter fault in {what}: {exc!r}", "") from None

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
            pending += reversed(_active_children(state))
        return found

    def _is_active(self, state: State) -> bool:
        while state.parent is not None:
            if state not in _active_children(state.parent):
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
                (exc.message, exc.location) if isinstance(exc, _Fault) else (describe(exc), "")
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
            state.on_entry(s)
            if self._timed[state]:
                self._arm(state, s)
            if state.INVARIANTS:
                violated = self._violated(state, s)
                if violated is not None:
                    return violated
            if state.FINAL:
                return (state.parent, state.name) if state.parent is not None else (state, "")
            if isinstance(state, Action):
                if any(isinstance(owner, Parallel) for owner in _owners(state)):
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
            if transition.guard is None or transition.guard(parent, s):
                return self._take(parent, transition, s)
        return self._error(parent, f"no branch of choice '{choice.name}' holds", choice.LOCATION)

    def _first_child(self, state: Composite, s: Snapshot) -> State | Done:
        """The child a composite starts in: through the first start condition that holds."""
        if state.STARTS:
            for condition in state.STARTS:
                if condition.holds is None or condition.holds(state, s):
                    for transition in state.transitions_from(condition.name):
                        if transition.guard is None or transition.guard(state, s):
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
            t.action(owner, s)
        if t.post is not None and not t.post(owner, s):
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
            if _matches(transition, outcome, state) and (
                transition.guard is None or transition.guard(parent, s)
            ):
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
            if transition.guard is None or transition.guard(owner, s):
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
            transition.action(state, s)
        return None

    # -- time events ----------------------------------------------------------------------

    def _arm(self, state: State, s: Snapshot) -> None:
        """Start the time events of a state just entered: its own and those leaving it."""
        for owner, transition in self._timed[state]:
            self._timers[(state, transition)] = self.time + transition.delay(owner, s)

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
        if transition.guard is not None and not transition.guard(owner, s):
            return None
        return self._react(state, transition, s)

    # -- actions --------------------------------------------------------------------------

    def _execute(self, action: Action, s: Snapshot) -> Done:
        """Run the device command until an end condition, a preemption or the budget."""
        if self.adapter is None:
            return self._error(action, "no adapter bound to run a device command", action.LOCATION)
        arguments = self._arguments(action, s)
        refused = self._refused(action, arguments)
        if refused is not None:
            return refused
        request = self._request(action, arguments)
        try:
            (result,) = self._call([request])
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # any adapter fault, SystemExit too
            return self._failed([request], exc)
        return self._settled(request, result)

    def _call(self, requests: list[_Request]) -> list[Any]:
        """Run the commands together; the trace's tick listeners hear their control ticks."""
        on_tick = self.trace.tick if self.trace.tick_listeners else None
        return list(self.adapter.execute([r.command for r in requests], on_tick=on_tick))

    def _run_commands(self) -> Done:
        """Run the commands of the actions entered in regions together, one per device."""
        actions = [action for action in self._commands if self._is_active(action)]
        self._commands.clear()
        if not actions:
            return None
        if self.adapter is None:
            return self._error(
                actions[0], "no adapter bound to run a device command", actions[0].LOCATION
            )
        s = self.snapshot()
        given = [self._arguments(action, s) for action in actions]
        for action, arguments in zip(actions, given, strict=True):
            refused = self._refused(action, arguments)
            if refused is not None:
                return refused
        requests = [
            self._request(a, arguments) for a, arguments in zip(actions, given, strict=True)
        ]
        try:
            results = self._call(requests)
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # any adapter fault, SystemExit too
            return self._failed(requests, exc)
        if len(results) != len(requests):
            self._hold()
            message = f"adapter broke the contract: {len(results)} results of {len(requests)}"
            return self._error(actions[0], message, actions[0].LOCATION)
        dones: list[Done] = []
        for request, result in zip(requests, results, strict=True):
            if self._interrupted(result):
                self._write("stop", state=request.action.path, outcome=result.outcome,
                            sensors={})  # fmt: skip
                self._commands.append(request.action)  # again after the reaction, if active
            else:
                dones.append(self._settled(request, result))
        self._queue.extend(dones[1:])
        return dones[0] if dones else None

    def _interrupted(self, result: Any) -> bool:
        """The command was stopped for an event or a time event that is really due."""
        if not isinstance(result, CommandResult):
            return False
        if result.outcome == EVENT_STOP:
            return bool(self.events)
        return result.outcome == TIMER_STOP and self._due(self.time) is not None

    @staticmethod
    def _arguments(action: Action, s: Snapshot) -> dict[str, Any]:
        """The command's arguments, scene objects by name."""
        return {
            k: object_name(v) if isinstance(v, SceneObject) else v
            for k, v in action.arguments(s).items()
        }

    def _refused(self, action: Action, arguments: dict[str, Any]) -> Done:
        """A value outside its safe range: no command is sent, the arm holds, ``error``."""
        refused = refusal(action.RANGES, arguments)
        if refused is None:
            return None
        self._hold()
        return self._error(action, refused, action.LOCATION)

    def _request(self, action: Action, arguments: dict[str, Any]) -> _Request:
        """The command of ``action`` with its end conditions, the end conditions of every
        enclosing state, queued events and the next time event as stop conditions."""
        watch = _Watch()
        stops = [
            StopCondition(c.name, watch(_bound(c.holds, action), c.location or action.LOCATION))
            for c in action.ENDS
        ]
        preemptions = self._preemptions(action)
        stops += [
            StopCondition(key, watch(holds, location))
            for key, (_, _, holds, location) in preemptions.items()
        ]
        stops.append(StopCondition(EVENT_STOP, watch(self._find_queued, action.LOCATION)))
        if self._timers:
            deadline = min(self._timers.values())
            stops.append(StopCondition(TIMER_STOP, lambda _: self.time >= deadline))
        self._write("command", state=action.path, device=action.DEVICE, command=action.COMMAND,
                    budget=action.BUDGET)  # fmt: skip
        command = Command(action.DEVICE, action.COMMAND, arguments, stops, action.BUDGET)
        return _Request(action, command, watch, preemptions)

    def _failed(self, requests: list[_Request], exc: BaseException) -> Done:
        """The adapter raised while running these commands: the first action's error."""
        self._hold()
        for request in requests:
            if request.watch.fault is not None:  # the adapter passed a predicate's fault on
                raise request.watch.fault from None
        action = requests[0].action
        where = ", ".join(f"{r.action.DEVICE}.{r.action.COMMAND}" for r in requests)
        return self._error(action, f"adapter fault in {where}: {exc!r}", action.LOCATION)

    def _settled(self, request: _Request, result: Any) -> Done:
        """What the executor does with the result of one command."""
        action, watch, preemptions = request.action, request.watch, request.preemptions
        if watch.fault is not None:
            self._hold()
            raise watch.fault
        names = {c.name for c in action.ENDS}
        if not isinstance(result, CommandResult) or (
            result.outcome not in names | set(preemptions) | {TIMEOUT, EVENT_STOP, TIMER_STOP}
        ):
            self._hold()
            message = f"adapter broke the contract: {result!r} is no outcome of this command"
            return self._error(action, message, action.LOCATION)
        self._write("stop", state=action.path, outcome=result.outcome,
                    sensors=self._sensors(action))  # fmt: skip
        if result.outcome in preemptions:
            self._hold()
            owner, outcome, _, _ = preemptions[result.outcome]
            return Preemption(action, owner, outcome)
        if result.outcome == EVENT_STOP:
            self._hold()
            return Preemption(action, event=self.events.popleft())
        if result.outcome == TIMER_STOP:
            self._hold()
            return Preemption(action, timer=self._due(self.time))
        if result.outcome == TIMEOUT:
            self._hold()
        elif result.value is not None:
            action.store(result.value)
        return (action, result.outcome)

    def _preemptions(self, action: Action) -> dict[str, tuple[Composite, str, Any, str]]:
        """Stop predicates for the end-condition expressions of every enclosing state."""
        found = {}
        owner = action.parent
        while owner is not None:
            for condition in owner.ENDS:
                if condition.holds is not None:
                    key = f"{owner.path}#{condition.name}"
                    holds = _bound(condition.holds, owner)
                    found[key] = (owner, condition.name, holds, condition.location)
            owner = owner.parent
        return found

    def _find_queued(self, s: Snapshot) -> bool:
        while self.events:
            if self._find(self.events[0], s):
                return True
            self._write("discarded", name=self.events.popleft())
        return False

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

    def _sensors(self, action: Action) -> dict[str, Any]:
        if not action.SENSORS:
            return {}
        snapshot = self.snapshot()
        return {
            f"{device}.{sensor}": to_json(getattr(getattr(snapshot, device), sensor))
            for device, sensor in action.SENSORS
        }

    # -- contracts ------------------------------------------------------------------------

    def _violated(self, state: State, s: Snapshot) -> tuple[State, str] | None:
        for invariant in state.INVARIANTS:
            if not invariant.holds(state, s):
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


def known_events(top: State) -> frozenset[str]:
    """Every event the state tree can take: declared ones and the stimuli that are no
    outcome of their source."""
    found: set[str] = set(getattr(top, "EVENTS", None) or ())
    internal = [t.stimulus for t in top.INTERNAL if t.delay is None]
    found.update(internal)
    if isinstance(top, Composite):
        for transition in top.TRANSITIONS:
            source = top.children.get(transition.source)
            if source is None or transition.delay is not None or not transition.stimulus:
                continue
            if transition.stimulus not in _completions(source):
                found.add(transition.stimulus)
        for child in top.children.values():
            found |= known_events(child)
    return frozenset(found)


def _states(top: State) -> list[State]:
    """Every state of the tree below ``top``, ``top`` first."""
    found, pending = [], [top]
    while pending:
        state = pending.pop()
        found.append(state)
        pending += getattr(state, "children", {}).values()
    return found


def _reactions(state: State) -> dict[str, tuple[tuple[State, Transition], ...]]:
    """The transitions an event may take from ``state``, by event, each with the state its
    guard belongs to: its internal transitions, then those leaving it (unless the event is
    one of its completions, which only its completion fires)."""
    found: dict[str, list[tuple[State, Transition]]] = {}
    for transition in state.INTERNAL:
        found.setdefault(transition.stimulus, []).append((state, transition))
    parent = state.parent
    if parent is not None:
        completions = _completions(state)
        for transition in parent.transitions_from(state.name):
            if transition.stimulus not in completions:
                found.setdefault(transition.stimulus, []).append((parent, transition))
    return {event: tuple(candidates) for event, candidates in found.items()}


def _timed(state: State) -> tuple[tuple[State, Transition], ...]:
    """The time events armed on entering ``state``: its own, then those leaving it (the order
    in which they fire at one deadline); each with the state its delay belongs to."""
    parent = state.parent
    leaving = parent.transitions_from(state.name) if parent is not None else ()
    return tuple(
        [(state, t) for t in state.INTERNAL if t.delay is not None]
        + [(parent, t) for t in leaving if t.delay is not None]
    )


def _active_children(state: State) -> list[State]:
    """The active children of ``state``. ``_select`` and ``_exit``, on the path of every
    event, test the two cases in place: a list per call made dispatch 20 % slower."""
    if isinstance(state, Parallel):
        return state.regions()
    if isinstance(state, Composite) and state.current is not None:
        return [state.current]
    return []


def _owners(state: State) -> list[State]:
    found = []
    while state.parent is not None:
        state = state.parent
        found.append(state)
    return found


def _completions(state: State) -> tuple[str, ...]:
    """Outcomes ``state`` ends with: they fire only on completion, never as external events."""
    if isinstance(state, Action | Composite):
        return (*state.OUTCOMES, ERROR, TIMEOUT, PREEMPTED)
    return (ERROR,)  # a violated invariant ends even a simple state


def _matches(transition: Transition, outcome: str, child: State) -> bool:
    """The stimulus names the outcome, or is empty and the outcome is a declared one."""
    stimulus = transition.stimulus
    return stimulus == outcome or (not stimulus and outcome in child.OUTCOMES)


def _bound(holds: Any, owner: State) -> Any:
    return lambda s: bool(holds(owner, s))


class _Watch:
    """Wraps stop predicates: the first one that raises stops the command (it holds) and
    keeps its fault, which the executor reports after the adapter returned."""

    def __init__(self) -> None:
        self.fault: _Fault | None = None

    def __call__(self, holds: Any, location: str) -> Any:
        def watched(s: Snapshot) -> bool:
            if self.fault is not None:
                return True
            try:
                return bool(holds(s))
            except KeyboardInterrupt:
                raise
            except BaseException as exc:  # reported as the action's error
                self.fault = _Fault(describe(exc), location)
                return True

        return watched
