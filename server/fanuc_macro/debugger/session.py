"""Stepping through a run of the evaluator, as a control's single block and macro variable screen
would let a machinist: breakpoints, steps, the macro levels, their variables and the modal
state, Macro B expressions evaluated at a stop. Plain data and a run thread; ``dap/`` speaks the
Debug Adapter Protocol over it.

The run is the evaluator's own (``evaluator.machine.Machine``), with a ``Stepper`` between its
blocks: the same values, calls, alarms and block budget as the diagnostics' runs, so that what
the debugger shows is what the checker concluded from.
"""

from __future__ import annotations

import math
import threading
from pathlib import Path

from ..evaluator.facts import AlarmFinding, Facts
from ..evaluator.machine import K_ASSIGN, Activation, Machine, ProgramContext, build_contexts
from ..evaluator.run import entry_programs
from ..evaluator.toolpath import Recorder
from ..evaluator.values import Value
from ..ide import Precision
from ..program.machine_kind import machine_config
from ..translation import tr, tr_n
from ..workspace import Workspace, is_program_file
from .answers import (
    ALARM_FILTER,
    EXCEPTION_FILTERS,
    Breakpoint,
    DebugError,
    Ended,
    FrameInfo,
    Listener,
    Output,
    ScopeInfo,
    Stop,
    VariableInfo,
)
from .breakpoints import BreakpointTable, verify
from .launch import Launch
from .run_record import RunRecord, block_comment
from .views import StopView


class _Restart(Exception):
    pass


class _Terminate(Exception):
    pass


_IDLE, _RUNNING, _STOPPED, _ENDED = "idle", "running", "stopped", "ended"


class Session:
    """One program under the debugger. The run goes in a thread of its own; every other method
    is for the front end's thread. Frames, scopes and evaluation need the run stopped."""

    def __init__(self, launch: Launch, listener: Listener) -> None:
        self.launch = launch
        self.listener = listener
        self.workspace = Workspace(launch.config)
        self.key = str(launch.program.resolve())
        self.breakpoints = BreakpointTable()
        self.filters: set[str] = {name for name, _, on in EXCEPTION_FILTERS if on}
        self._lock = threading.Condition()
        self._state = _IDLE
        self._command: str | None = None
        self._pause = False
        self._step: tuple[str, int] | None = None  # ("in" | "over" | "out", depth at the step)
        self._act: Activation | None = None
        self._line = 0
        self._machine: Machine | None = None
        self._thread: threading.Thread | None = None
        self._entry: ProgramContext | None = None
        self._record = RunRecord()  # what the run has seen, for the scopes
        self._reported: dict[str, int] = {}
        self._first = True
        self._control_pending: str | None = None  # a restart or an end asked while running
        self._load()

    # ---- loading ---------------------------------------------------------------------------
    def _load(self) -> None:
        path = self.launch.program.resolve()
        try:
            data = path.read_bytes()
        except OSError as err:
            raise DebugError(f"launch: cannot read {path}: {err.strerror}") from None
        self.workspace.add_bytes(self.key, data)
        not_text = self.workspace.not_text(self.key)
        if not_text:
            raise DebugError(f"launch: {path.name} is not a program text: {not_text}")
        # The other program files of its folder: the sub programs it calls, as on the control's
        # memory.
        for sibling in sorted(path.parent.iterdir()):
            if sibling == path or not sibling.is_file() or not is_program_file(sibling):
                continue
            try:
                self.workspace.add_bytes(str(sibling), sibling.read_bytes())
            except OSError:
                continue
        self._entry = self._entry_context(self._contexts()[1])

    def _contexts(self) -> tuple[Facts, list[ProgramContext], dict[int, ProgramContext]]:
        doc = self.workspace.document(self.key)
        assert doc is not None
        docs = [(self.key, doc, self.workspace.index(self.key)), *self.workspace.others(self.key)]
        facts = Facts()
        programs, every = build_contexts(docs, facts, None, None)
        return facts, every, programs

    def _entry_context(self, every: list[ProgramContext]) -> ProgramContext:
        number = self.launch.entry
        if number is not None:
            for ctx in every:
                if ctx.program.number == number:
                    return ctx
            raise DebugError(f"launch: no O{number} in {self.launch.program.name} or its folder")
        entries = entry_programs(every, self.key)
        if not entries:
            raise DebugError(f"launch: {self.launch.program.name} holds no program")
        return entries[0]

    @property
    def entry_name(self) -> str:
        assert self._entry is not None
        return self._entry.name

    # ---- breakpoints -----------------------------------------------------------------------
    def set_breakpoints(self, key: str, asked: list[tuple[int, str, str, str]]) -> list[Breakpoint]:
        """Replace ``key``'s breakpoints: (0-based line, condition, hit condition, log
        message) each (see :func:`.breakpoints.verify` for where each stops)."""
        resolved, made = self.breakpoints.made(key, asked, self.workspace)
        with self._lock:
            self.breakpoints.by_key[resolved] = made
        return made

    def _reload(self) -> None:
        """Read the files again (a restart runs the program as it is on disk now) and move the
        breakpoints with the text."""
        self.workspace = Workspace(self.launch.config)
        self._load()
        for bp in self.breakpoints:
            before = (bp.verified, bp.actual_line, bp.message)
            verify(bp, self.workspace)
            if (bp.verified, bp.actual_line, bp.message) != before:
                self.listener.breakpoint_changed(bp)

    def set_exception_filters(self, names: list[str]) -> None:
        with self._lock:
            known = {name for name, _, _ in EXCEPTION_FILTERS}
            self.filters = {n for n in names if n in known}

    # ---- running ---------------------------------------------------------------------------
    def start(self) -> None:
        with self._lock:
            if self._thread is not None:
                return
            self._state = _RUNNING
            self._thread = threading.Thread(target=self._run, name="fanuc-macro run", daemon=True)
            self._thread.start()

    def _run(self) -> None:
        while True:
            facts, every, programs = self._contexts()
            entry = self._entry_context(every)
            # The machine of the entry's document (controller 0i-F: as its codes show).
            indexed = self.workspace.indexes().get(entry.uri)
            config = machine_config(
                self.launch.config, entry.doc, None if indexed is None else indexed[1]
            )
            machine = Machine(programs, config, facts, every)
            # The moves and timed blocks, for the cycle time a stop shows.
            timed = frozenset(code for code, _ in config.m_code_seconds)
            recorder = machine.toolpath = Recorder(config.is_lathe, timed_codes=timed)
            facts.toolpath = recorder.toolpath
            machine.stepper = self
            self._machine = machine
            self._record.clear()
            self._reported = {}
            self._first = True
            self.breakpoints.reset_hits()
            preset = dict(self.launch.preset)
            if not self.launch.gave_arguments and not entry.is_main:
                preset = {n: v for n, v in preset.items() if n > 33}
            try:
                why = machine.run(entry, math.inf, preset)
            except _Restart:
                try:
                    self._reload()
                except DebugError as err:
                    self._finish(Ended(f"Cannot restart: {err}", False, machine.steps))
                    return
                self._say("console", f"Restarting {self.entry_name}.")
                continue
            except _Terminate:
                self._finish(Ended("The run was stopped.", True, machine.steps))
                return
            except Exception as err:  # a fault of the evaluator: said, and the session ends
                self._finish(Ended(f"The evaluator failed: {err!r}", False, machine.steps))
                return
            self._report_findings()
            where = ""
            if self._act is not None:
                where = f" at line {self._line + 1} of {self._act.ctx.name}"
            self._finish(_ending(why, entry, machine, where))
            return

    def _finish(self, ended: Ended) -> None:
        with self._lock:
            self._state = _ENDED
            self._act = None
            self._lock.notify_all()
        self.listener.ended(ended)

    def _report_findings(self) -> None:
        """The evaluator's findings since the last look (a non-integer address, a loop that
        does not end, an alarm), as console output at their lines."""
        machine = self._machine
        if machine is None:
            return
        for uri, dfacts in machine.facts.by_uri.items():
            seen = self._reported.get(uri, 0)
            found = dfacts.reported
            for finding in found[seen:]:
                category = "stderr" if isinstance(finding, AlarmFinding) else "console"
                self._say(
                    category,
                    f"{Path(uri).name}:{finding.line + 1}: {finding.message}",
                    uri,
                    finding.line,
                )
            self._reported[uri] = len(found)

    def _say(
        self, category: str, text: str, key: str | None = None, line: int | None = None
    ) -> None:
        self.listener.output(Output(category, text, key, line))

    # The Stepper: called by the machine in the run thread.
    def before(self, act: Activation, line: int) -> None:
        pending = self._control_pending
        if pending is not None:
            self._control_pending = None
            raise _Restart if pending == "restart" else _Terminate
        ctx = act.ctx
        record = self._record
        record.note_level(act)
        if ctx.facts.reported and len(ctx.facts.reported) != self._reported.get(ctx.uri, 0):
            self._report_findings()
        stop = self._stop_before(act, line)
        if stop is not None:
            self._wait(act, line, stop)
        record.note_block(act, ctx.lines[line], line, self._say)

    def _stop_before(self, act: Activation, line: int) -> Stop | None:
        """Why the run stops before ``line``, if it does: the stop the last block asked for, the
        entry, a pause, a breakpoint, the end of a step."""
        stop: Stop | None = None
        record = self._record
        asked, record.pending_stop = record.pending_stop, None
        if asked is not None and asked[0] in self.filters:
            stop = Stop("exception", asked[1], asked[2], exception=asked[0])
        hit = self.breakpoints.hit_at(act, act.ctx.uri, line, self._say, self._show)
        if self._first:
            self._first = False
            if self.launch.stop_on_entry and stop is None:
                stop = Stop("entry", tr("{program} starts", program=act.ctx.name))
        if stop is None and self._pause:
            stop = Stop("pause", tr("Paused"))
        if stop is None and hit:
            stop = Stop("breakpoint", tr("Breakpoint"), breakpoints=tuple(hit))
        if stop is None and self._step is not None:
            how, depth = self._step
            here = _depth(act)
            if how == "in" or (how == "over" and here <= depth) or (how == "out" and here < depth):
                stop = Stop("step", tr("Step"))
        return stop

    def alarm(self, act: Activation, line: int, message: str) -> None:
        self._report_findings()
        cl = act.ctx.lines[line]
        if cl.kind == K_ASSIGN and cl.target_number == 3000:
            # The control shows the block's comment with the alarm number.
            text = block_comment(act, line)
            if text:
                message = f"{message}: {text}"
        if ALARM_FILTER in self.filters:
            self._wait(act, line, Stop("exception", tr("Alarm"), message, exception=ALARM_FILTER))

    def _wait(self, act: Activation, line: int, stop: Stop) -> None:
        with self._lock:
            self._state = _STOPPED
            self._act = act
            self._line = line
            self._command = None
            self._pause = False
            self._step = None
        self.listener.stopped(stop)
        with self._lock:
            while self._command is None:
                self._lock.wait()
            command = self._command
            self._command = None
            self._state = _RUNNING
            if command == "restart":
                raise _Restart
            if command == "terminate":
                raise _Terminate
            if command in ("in", "over", "out"):
                self._step = (command, _depth(act))

    # ---- the front end's commands ----------------------------------------------------------
    def _resume(self, command: str) -> None:
        with self._lock:
            if self._state == _ENDED:
                raise DebugError("the run is over")
            if self._state != _STOPPED:
                raise DebugError("the program is running: pause it first")
            self._command = command
            self._lock.notify_all()

    def continue_(self) -> None:
        self._resume("continue")

    def step_in(self) -> None:
        self._resume("in")

    def step_over(self) -> None:
        self._resume("over")

    def step_out(self) -> None:
        self._resume("out")

    def restart(self) -> None:
        """Run again from the first block, with the breakpoints as they are now."""
        self._control("restart")

    def terminate(self) -> None:
        self._control("terminate")

    def _control(self, command: str) -> None:
        """Restart or end the run, whether it is stopped or running."""
        with self._lock:
            if self._state == _ENDED:
                return
            if self._state == _IDLE:
                if command == "terminate":
                    self._state = _ENDED
                return
            if self._state == _STOPPED:
                self._command = command
                self._lock.notify_all()
            else:
                self._control_pending = command  # the next block does it

    def pause(self) -> None:
        with self._lock:
            if self._state == _RUNNING:
                self._pause = True

    @property
    def started(self) -> bool:
        return self._thread is not None

    @property
    def stopped(self) -> bool:
        return self._state == _STOPPED

    @property
    def ended(self) -> bool:
        return self._state == _ENDED

    def join(self, timeout: float | None = None) -> None:
        thread = self._thread
        if thread is not None:
            thread.join(timeout)

    # ---- what a stop shows (see .views) -------------------------------------------------------
    def _view(self) -> StopView:
        with self._lock:
            if self._state != _STOPPED or self._act is None:
                raise DebugError("the program is running: pause it to see its state")
            levels: list[Activation] = []
            a: Activation | None = self._act
            while a is not None:
                levels.append(a)
                a = a.caller
            return StopView(levels, self._line, self._record, self._show)

    def frames(self) -> list[FrameInfo]:
        return self._view().frames()

    def scopes(self, frame_id: int) -> list[ScopeInfo]:
        return self._view().scopes(frame_id)

    def variables(self, reference: int) -> list[VariableInfo]:
        return self._view().variables(reference)

    def evaluate(self, text: str, frame_id: int | None) -> str:
        """A Macro B expression or condition at a stopped frame (the top one by default), or
        an assignment (``#100=5``) done there."""
        return self._view().evaluate(text, frame_id)

    def set_variable_at(self, reference: int, name: str, text: str) -> str:
        return self._view().set_variable_at(reference, name, text)

    def _show(self, value: Value) -> str:
        machine = self._machine
        inch = machine.modal.inch if machine is not None else False
        return Precision(inch, self.launch.full_precision).show(value)


def _ending(why: str, entry: ProgramContext, machine: Machine, where: str) -> Ended:
    """The run's end in a sentence, from the machine's reason; ``where`` the block it stopped
    at (" at line 12 of O1000"), or ""."""
    blocks = machine.steps
    done = tr_n("after {count:,} block", "after {count:,} blocks", blocks)
    name = entry.name
    if why == "end of program":
        return Ended(tr("{program} ended {done}.", program=name, done=done), True, blocks)
    if why == "end":
        return Ended(tr("{program} ran to its end {done}.", program=name, done=done), True, blocks)
    if why == "alarm":
        return Ended(tr("The run stopped on an alarm {done}.", done=done), False, blocks)
    if why == "budget":
        budget = tr(
            "The run stopped {done}: the step budget of {budget:,} blocks ran out (launch "
            "'stepBudget', setting fanuc-macro.analysis.stepBudget); a program that goes on "
            "this long is likely looping forever.",
            done=done,
            budget=machine.budget,
        )
        return Ended(budget, False, blocks)
    if why == "unknown jump":
        jump = tr(
            "The run stopped{where}: a GOTO to a number the analysis cannot compute (it "
            "depends on a value set outside the program).",
            where=where,
        )
        return Ended(jump, False, blocks)
    if why == "unread":
        unread = tr(
            "The run stopped {done}: the program goes on past the part of the file that is "
            "read (MB013).",
            done=done,
        )
        return Ended(unread, False, blocks)
    if why == "no END":
        return Ended(
            tr("The run stopped{where}: a WHILE without its END.", where=where), False, blocks
        )
    return Ended(tr("The run stopped {done} ({why}).", done=done, why=why), False, blocks)


def _depth(act: Activation) -> int:
    depth = 0
    a: Activation | None = act
    while a is not None:
        depth += 1
        a = a.caller
    return depth
