"""Running the device commands of action states, the executor's part that talks to the
adapter: an action's stop conditions (its end conditions, the end conditions of enclosing
states, a probe for queued events and the next time event), one ``Adapter.execute`` for an
action or for a round of actions of orthogonal regions, and what becomes of each result."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import Any

from lightrocks.runtime.contract import (
    TIMEOUT,
    Adapter,
    Command,
    CommandResult,
    Snapshot,
    StopCondition,
)
from lightrocks.runtime.environment import SceneObject, object_name
from lightrocks.runtime.faults import DescribedFault, describe
from lightrocks.runtime.safety import not_finite, refusal
from lightrocks.runtime.states import Action, Composite, State, Transition
from lightrocks.runtime.trace import Trace, to_json

EVENT_STOP, TIMER_STOP = "@event", "@timer"

Timer = tuple[State, Transition]  # a time event of an active state, pending


@dataclass(frozen=True)
class Preemption:
    """A running action was stopped for an enclosing end condition or an event."""

    action: Action
    owner: Composite | None = None
    outcome: str = ""
    event: str = ""
    timer: Timer | None = None


Done = tuple[State, str] | Preemption | None
"""What a part of a step leaves to do: complete a state with an outcome, preempt a running
action, or nothing."""


@dataclass
class _Request:
    """An action's command with the stop conditions the executor watches for it."""

    action: Action
    command: Command
    watch: _Watch
    preemptions: dict[str, tuple[Composite, str, Any, str]]


class CommandRunner:
    """The commands of the executor's actions (a base of ``Executor``, whose clock, trace,
    errors, events and time events it uses)."""

    adapter: Adapter | None
    trace: Trace
    events: deque[str]
    _commands: list[Action]
    _queue: deque[Done]
    _timers: dict[Timer, float]

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
            results = self._call([request])
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # any adapter fault, SystemExit too
            return self._failed([request], exc)
        return self._miscounted([request], results) or self._settled(request, results[0])

    def _call(self, requests: list[_Request]) -> list[Any]:
        """Run the commands together; the trace's tick listeners hear their control ticks."""
        commands = [r.command for r in requests]
        return list(self.adapter.execute(commands, on_tick=self.trace.on_tick))

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
        miscounted = self._miscounted(requests, results)
        if miscounted is not None:
            return miscounted
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

    def _miscounted(self, requests: list[_Request], results: list[Any]) -> Done:
        """Not one result per command: the adapter broke the contract."""
        if len(results) == len(requests):
            return None
        self._hold()
        action = requests[0].action
        message = f"adapter broke the contract: {len(results)} results of {len(requests)}"
        return self._error(action, message, action.LOCATION)

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
        """A value outside its safe range, or a number that is not finite: no command is
        sent, the arm holds, ``error``."""
        refused = refusal(action.RANGES, arguments) or not_finite(
            action.DEVICE, action.COMMAND, arguments
        )
        if refused is None:
            return None
        self._hold()
        return self._error(action, refused, action.LOCATION)

    def _request(self, action: Action, arguments: dict[str, Any]) -> _Request:
        """The command of ``action`` with its end conditions, the end conditions of every
        enclosing state, queued events and the next time event as stop conditions."""
        watch = _Watch(partial(self._read_sensors, action) if action.SENSORS else None)
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
        sensors = watch.sensors if watch.sensors is not None else self._sensors(action)
        self._write("stop", state=action.path, outcome=result.outcome, sensors=sensors)
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

    def _sensors(self, action: Action) -> dict[str, Any]:
        """The sensors the action reads, now (after a timeout, no stop condition held)."""
        if not action.SENSORS:
            return {}
        return self._read_sensors(action, self.snapshot())

    @staticmethod
    def _read_sensors(action: Action, snapshot: Snapshot) -> dict[str, Any]:
        return {
            f"{device}.{sensor}": to_json(getattr(getattr(snapshot, device), sensor))
            for device, sensor in action.SENSORS
        }


def _bound(holds: Any, owner: State) -> Any:
    return lambda s: bool(holds(owner, s))


class _Watch:
    """Wraps stop predicates: the first one that raises stops the command (it holds) and
    keeps its fault, which the executor reports after the adapter returned. The first one
    that holds reads the action's sensors (``read``) on the snapshot it held on: the stop
    record tells what the condition saw, not what the adapter shows once it holds the arm."""

    def __init__(self, read: Callable[[Snapshot], dict[str, Any]] | None = None) -> None:
        self.fault: DescribedFault | None = None
        self.read = read
        self.sensors: dict[str, Any] | None = None

    def __call__(self, holds: Any, location: str) -> Any:
        def watched(s: Snapshot) -> bool:
            if self.fault is not None:
                return True
            try:
                held = bool(holds(s))
                if held and self.sensors is None and self.read is not None:
                    self.sensors = self.read(s)
                return held
            except KeyboardInterrupt:
                raise
            except BaseException as exc:  # reported as the action's error
                self.fault = DescribedFault(describe(exc), location)
                return True

        return watched
