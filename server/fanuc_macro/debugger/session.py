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
import re
import threading
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..config import CONTROLLERS, Config
from ..evaluator.compiler import CondEvaluator, Evaluator, compile_cond, compile_expr
from ..evaluator.facts import Facts
from ..evaluator.machine import (
    K_ASSIGN,
    K_IFGOTO,
    K_IFTHEN,
    K_NC,
    K_OTHER,
    K_WHILE,
    Activation,
    Machine,
    ProgramContext,
    build_contexts,
    compiled,
)
from ..evaluator.run import entry_programs
from ..evaluator.values import MacroAlarm, Unknown, Value
from ..ide import Precision
from ..program.knowledge import code_name, modal_group
from ..program.variables import ARGUMENT_VARIABLES, classify
from ..syntax.parser import default_parser
from ..syntax.tree import Assign, IfGoto, Print, Var
from ..workspace import Workspace, is_program_file

# The exception breakpoints a user can turn on and off (DAP exceptionBreakpointFilters).
ALARM_FILTER = "alarm"  # #3000 and the PS alarms the evaluator raises
MESSAGE_FILTER = "message"  # #3006: the control stops with a message
PROGRAM_STOP_FILTER = "programStop"  # M00, and M01 with the optional stop switch on
EXCEPTION_FILTERS: tuple[tuple[str, str, bool], ...] = (
    (ALARM_FILTER, "Alarms (#3000, PS0112 zero divide, ...)", True),
    (MESSAGE_FILTER, "Stop with message (#3006)", True),
    (PROGRAM_STOP_FILTER, "Program stop (M00, M01)", False),
)

_LETTER_OF = {n: letter for letter, n in ARGUMENT_VARIABLES.items()}
_ARGUMENT_WORD = re.compile(r"\s*(?:#(\d+)|([A-Z]))\s*=?\s*([-+]?(?:\d+\.?\d*|\.\d+))\s*", re.I)
_CALL_WORD = re.compile(r"(?<![A-Z#\d.])(G0*65|G0*66(?:\.1)?|M0*98)(?![\d])", re.I)
_INTERPOLATION = re.compile(r"\{([^{}]*)\}")


class DebugError(Exception):
    """A launch or a request that cannot be done; the message says why, for the user."""


# ---- what the front end gets -----------------------------------------------------------------


@dataclass(frozen=True)
class Stop:
    """The run stopped before a block. ``reason``: entry, step, breakpoint, pause, exception."""

    reason: str
    description: str = ""
    text: str = ""  # an alarm's or a message's text
    breakpoints: tuple[int, ...] = ()
    exception: str = ""  # the filter of an "exception" stop: alarm, message, programStop


@dataclass(frozen=True)
class Output:
    category: str  # "stdout" (DPRNT), "console" (the debugger's notes), "stderr" (alarms)
    text: str
    key: str | None = None  # the file and 0-based line the output comes from
    line: int | None = None


@dataclass(frozen=True)
class Ended:
    """The run is over: why, in a sentence, and whether it ended as the program meant to."""

    message: str
    normal: bool
    blocks: int


class Listener:
    """What the session tells its front end, from the run thread (override each)."""

    def stopped(self, stop: Stop) -> None:
        pass

    def output(self, output: Output) -> None:
        pass

    def ended(self, ended: Ended) -> None:
        pass

    def breakpoint_changed(self, breakpoint: Breakpoint) -> None:
        """A restart read the files again, and the breakpoint now stops elsewhere or not."""


@dataclass(frozen=True)
class Launch:
    """A launch, checked: the file, where to start and what is set before the first block."""

    program: Path
    entry: int | None = None
    preset: Mapping[int, float] = field(default_factory=dict)
    config: Config = field(default_factory=Config)
    stop_on_entry: bool = False
    full_precision: bool = False
    gave_arguments: bool = False


@dataclass
class Breakpoint:
    id: int
    key: str
    line: int  # 0-based, where it was asked for
    verified: bool = False
    actual_line: int | None = None  # the block it stops at
    message: str = ""
    condition: str = ""
    hit_condition: str = ""
    log_message: str = ""
    hits: int = 0
    _cond: CondEvaluator | None = None
    _hit: Callable[[int], bool] | None = None
    _told_unknown: bool = False


@dataclass(frozen=True)
class FrameInfo:
    id: int
    name: str
    key: str
    line: int  # 0-based
    column: int  # 0-based


@dataclass(frozen=True)
class ScopeInfo:
    name: str
    reference: int
    count: int
    expensive: bool = False


@dataclass(frozen=True)
class VariableInfo:
    name: str
    value: str
    evaluate_name: str | None = None
    kind: str = ""  # "local", "common", "system", "modal"
    read_only: bool = False


# ---- reading a launch --------------------------------------------------------------------


def read_launch(args: Mapping[str, Any], base: Config | None = None) -> Launch:
    """The launch request's arguments, checked; DebugError names the one that is wrong."""
    program = args.get("program")
    if not isinstance(program, str) or not program.strip():
        raise DebugError("launch: 'program' must be the path of a program file")
    path = Path(program).expanduser()
    if not path.is_file():
        raise DebugError(f"launch: program {program!r} is not a file")
    entry = args.get("entry")
    entry_number: int | None = None
    if entry not in (None, ""):
        text = str(entry).strip().upper().removeprefix("O")
        if not text.isdigit() or not 1 <= int(text) <= 99999999:
            raise DebugError(
                f"launch: 'entry' must be a program number such as 3331, not {entry!r}"
            )
        entry_number = int(text)
    preset: dict[int, float] = {}
    arguments = args.get("arguments")
    gave = bool(arguments)
    preset.update(_arguments(arguments))
    preset.update(_commons(args.get("commons")))
    settings: dict[str, Any] = {}
    if base is None:
        base = Config()
    controller = args.get("controller")
    if controller not in (None, ""):
        if controller not in CONTROLLERS:
            raise DebugError(
                f"launch: 'controller' {controller!r} is not one of {', '.join(CONTROLLERS)}"
            )
        settings["controller"] = controller
    budget = args.get("stepBudget")
    if budget is not None:
        if not isinstance(budget, int) or isinstance(budget, bool) or budget < 1:
            raise DebugError(
                f"launch: 'stepBudget' must be a whole number of blocks, not {budget!r}"
            )
        settings["stepBudget"] = budget
    config = base
    if settings:
        from dataclasses import replace

        config = replace(
            base,
            controller=settings.get("controller", base.controller),
            step_budget=settings.get("stepBudget", base.step_budget),
        )
    return Launch(
        path,
        entry_number,
        preset,
        config,
        stop_on_entry=args.get("stopOnEntry") is True,
        full_precision=args.get("fullPrecision") is True or config.hover_full_precision,
        gave_arguments=gave,
    )


def _arguments(value: object) -> dict[int, float]:
    """G65 words ("A1. F0.3", or {"A": 1, "#9": 0.3}) as local variable numbers."""
    words: list[tuple[str, object]] = []
    if value in (None, "", {}):
        return {}
    if isinstance(value, str):
        at = 0
        text = value.strip()
        while at < len(text):
            found = _ARGUMENT_WORD.match(text, at)
            if found is None or found.end() == at:
                raise DebugError(
                    f"launch: 'arguments' {value!r}: cannot read {text[at:]!r} "
                    "(write G65 words such as 'A1. F0.3' or '#9=0.3')"
                )
            number, letter, num = found.groups()
            words.append((f"#{number}" if number else letter, num))
            at = found.end()
    elif isinstance(value, Mapping):
        words = [(str(k), v) for k, v in value.items()]
    else:
        raise DebugError("launch: 'arguments' must be G65 words or an object of letters and values")
    out: dict[int, float] = {}
    for name, raw in words:
        n = _argument_number(name)
        out[n] = _number_of(f"arguments {name}", raw)
    return out


def _argument_number(name: str) -> int:
    key = name.strip().upper()
    if key.startswith("#") and key[1:].isdigit() and 1 <= int(key[1:]) <= 33:
        return int(key[1:])
    if key in ARGUMENT_VARIABLES:
        return ARGUMENT_VARIABLES[key]
    raise DebugError(
        f"launch: argument {name!r} is not a G65 letter (A-Z but G, L, N, O, P) nor #1-#33"
    )


def _commons(value: object) -> dict[int, float]:
    if value in (None, "", {}):
        return {}
    if not isinstance(value, Mapping):
        raise DebugError("launch: 'commons' must be an object such as {\"#100\": 50}")
    out: dict[int, float] = {}
    for name, raw in value.items():
        key = str(name).strip().lstrip("#")
        if not key.isdigit():
            raise DebugError(f"launch: commons {name!r} is not a variable number such as #100")
        n = int(key)
        kind = classify(n)
        if kind.kind in ("none", "null", "local"):
            raise DebugError(
                f"launch: commons #{n} is not a common or system variable (locals go in "
                "'arguments')"
            )
        out[n] = _number_of(f"commons #{n}", raw)
    return out


def _number_of(what: str, raw: object) -> float:
    try:
        number = float(raw)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise DebugError(f"launch: {what} = {raw!r} is not a number") from None
    if not math.isfinite(number):
        raise DebugError(f"launch: {what} = {raw!r} is not a number")
    return number


# ---- expressions typed by the user -------------------------------------------------------


def parse_expression(text: str) -> Evaluator:
    """A Macro B expression (``#4``, ``[#100-2*#9]``, ``SQRT[#4]``) as the evaluator runs it."""
    line = default_parser().parse_line(f"#1=[{text}]")
    statement = line.statement
    if line.problem is not None or not isinstance(statement, Assign):
        raise DebugError(f"{text!r} is not a Macro B expression")
    return compile_expr(statement.value)


def parse_condition(text: str) -> CondEvaluator:
    """A Macro B condition (``#9 GT 1.5``, ``[#1 EQ 2] AND [#2 LT 0]``)."""
    parser = default_parser()
    for code in (f"IF[{text}]GOTO1", f"IF{text}GOTO1"):
        line = parser.parse_line(code)
        if line.problem is None and isinstance(line.statement, IfGoto):
            return compile_cond(line.statement.cond)
    raise DebugError(
        f"{text!r} is not a Macro B condition (write it as in an IF: #9 GT 1.5, "
        "[#1 EQ 2] AND [#2 LT 0])"
    )


def parse_assignment(text: str) -> tuple[Var, Evaluator] | None:
    """``#100=5`` typed in the debug console: its target and value; None if it is not one."""
    if "=" not in text:
        return None
    line = default_parser().parse_line(text)
    statement = line.statement
    if line.problem is not None or not isinstance(statement, Assign):
        return None
    return statement.target, compile_expr(statement.value)


def hit_test(text: str) -> Callable[[int], bool]:
    """A hit condition: ``3`` (from the third hit on), ``>=3``, ``==3``, ``>3``, ``<3``,
    ``<=3``, ``%3`` (every third hit)."""
    found = re.fullmatch(r"\s*(>=|<=|==|=|>|<|%)?\s*(\d+)\s*", text)
    if found is None:
        raise DebugError(f"hit count {text!r}: write a number (3), or >=3, ==3, >3, <3, %3")
    op, count = found.group(1) or ">=", int(found.group(2))
    tests: dict[str, Callable[[int], bool]] = {
        ">=": lambda n: n >= count,
        "<=": lambda n: n <= count,
        "==": lambda n: n == count,
        "=": lambda n: n == count,
        ">": lambda n: n > count,
        "<": lambda n: n < count,
        "%": lambda n: count > 0 and n % count == 0,
    }
    return tests[op]


class _Probe:
    """An activation as an expression typed at a stop reads it: without recording anything
    in the run's facts."""

    def __init__(self, act: Activation) -> None:
        self.act = act
        self.locals = act.locals
        self.store = act.store

    def read_global(self, number: int) -> Value:
        return self.act.read_global(number)

    def read_indirect(self, number: Value, node: Var) -> Value:
        return self.act.read_indirect(number, node)

    @property
    def signed_atan(self) -> bool:
        return self.act.signed_atan

    @property
    def length_increment(self) -> float:
        return self.act.length_increment

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        pass


def read_variable(act: Activation, n: int) -> Value:
    if 1 <= n <= 33:
        return act.locals[n]
    if n == 0:
        return None
    v = act.store.get(n, act)
    return act.read_global(n) if v is act else v  # type: ignore[return-value]


# ---- DPRNT -------------------------------------------------------------------------------


def dprnt_line(text: str, act: Activation) -> str:
    """What ``DPRNT[...]`` sends: its characters as written (``*`` a space), each ``#n[ab]``
    as a number of ``a`` integer and ``b`` decimal digits (FANUC custom macro, "DPRNT"; the
    sign and the digits' padding, which parameter 6001 PRT sets, are unverified: a leading
    minus, no padding). A vacant variable prints as 0 (unverified)."""
    inner = text[text.find("[") + 1 : text.rfind("]")] if "[" in text else ""
    out: list[str] = []
    at = 0
    pattern = re.compile(r"#(\d+)(?:\[(\d)(\d)\])?")
    while at < len(inner):
        found = pattern.match(inner, at)
        if found is None:
            ch = inner[at]
            out.append(" " if ch == "*" else ch)
            at += 1
            continue
        n = int(found.group(1))
        decimals = int(found.group(3)) if found.group(3) is not None else 0
        value = read_variable(act, n)
        if value is None:
            value = 0.0
        if isinstance(value, Unknown):
            out.append(f"<#{n} {value.describe()}>")
        else:
            out.append(f"{value:.{decimals}f}" if decimals else f"{round(value):d}")
        at = found.end()
    return "".join(out)


# ---- the session ---------------------------------------------------------------------------


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
        self.breakpoints: dict[str, list[Breakpoint]] = {}
        self.filters: set[str] = {name for name, _, on in EXCEPTION_FILTERS if on}
        self._next_id = 0
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
        # What a run has seen, for the scopes: system variables read or written, the modal G
        # codes by group, the T word, and the arguments each macro level was called with.
        self._system_seen: set[int] = set()
        self._groups: dict[str, float] = {}
        self._tool: Value = None
        self._called_with: dict[int, tuple[tuple[int, Value], ...]] = {}
        # A stop the last block asked for (a #3006 message, an M00): filter, description, text.
        self._pending_stop: tuple[str, str, str] | None = None
        self._undecided_seen: set[tuple[str, int]] = set()
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
        message) each. A breakpoint on a line that runs nothing moves to the next block of
        its program that does; outside every program it is not verified, and says why."""
        resolved = str(Path(key).resolve()) if not key.startswith("untitled:") else key
        made: list[Breakpoint] = []
        for line, condition, hit, log in asked:
            self._next_id += 1
            bp = Breakpoint(
                self._next_id,
                resolved,
                line,
                condition=condition,
                hit_condition=hit,
                log_message=log,
            )
            self._verify(bp)
            made.append(bp)
        with self._lock:
            self.breakpoints[resolved] = made
        return made

    def _verify(self, bp: Breakpoint) -> None:
        """Where ``bp`` stops in the text as read now, or why it does not."""
        bp.verified, bp.actual_line, bp.message = False, None, ""
        line = bp.line
        doc = self.workspace.document(bp.key)
        if doc is None:
            bp.message = "this file is not the program under the debugger nor in its folder"
            return
        index = self.workspace.index(bp.key)
        program = next((p for p in index.programs if p.contains(line)), None)
        if program is None:
            # Before a program (a '%', a comment): its first block, if nothing runs between.
            program = next((p for p in index.programs if p.first_line > line), None)
            if program is not None and any(
                _runs(doc.blocks[n].parsed) for n in range(line, program.first_line)
            ):
                program = None
        if program is None:
            bp.message = "no program here (outside O...%): the control runs nothing here"
            return
        target = next(
            (n for n in range(line, program.end_line) if _runs(doc.blocks[n].parsed)), None
        )
        if target is None:
            bp.message = f"no block runs from here to the end of {program.display_name}"
            return
        try:
            bp._cond = parse_condition(bp.condition) if bp.condition.strip() else None
            bp._hit = hit_test(bp.hit_condition) if bp.hit_condition.strip() else None
        except DebugError as err:
            bp.message = str(err)
            return
        bp.verified = True
        bp.actual_line = target

    def _reload(self) -> None:
        """Read the files again (a restart runs the program as it is on disk now) and move the
        breakpoints with the text."""
        self.workspace = Workspace(self.launch.config)
        self._load()
        for bps in self.breakpoints.values():
            for bp in bps:
                before = (bp.verified, bp.actual_line, bp.message)
                self._verify(bp)
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
            machine = Machine(programs, self.launch.config, facts, every)
            machine.stepper = self
            self._machine = machine
            self._system_seen.clear()
            self._groups.clear()
            self._tool = None
            self._called_with.clear()
            self._pending_stop = None
            self._undecided_seen.clear()
            self._reported = {}
            self._first = True
            for bps in self.breakpoints.values():
                for bp in bps:
                    bp.hits = 0
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
            self._finish(self._ending(why, entry, machine))
            return

    def _finish(self, ended: Ended) -> None:
        with self._lock:
            self._state = _ENDED
            self._act = None
            self._lock.notify_all()
        self.listener.ended(ended)

    def _ending(self, why: str, entry: ProgramContext, machine: Machine) -> Ended:
        blocks = machine.steps
        where = ""
        if self._act is not None:
            where = f" at line {self._line + 1} of {self._act.ctx.name}"
        done = f"after {blocks:,} blocks"
        if why == "end of program":
            return Ended(f"{entry.name} ended {done}.", True, blocks)
        if why == "end":
            return Ended(f"{entry.name} ran to its end {done}.", True, blocks)
        if why == "alarm":
            return Ended(f"The run stopped on an alarm {done}.", False, blocks)
        if why == "budget":
            return Ended(
                f"The run stopped {done}: the step budget of {machine.budget:,} blocks "
                "ran out (launch 'stepBudget', setting fanuc-macro.analysis.stepBudget); a "
                "program that goes on this long is likely looping forever.",
                False,
                blocks,
            )
        if why == "unknown jump":
            return Ended(
                f"The run stopped{where}: a GOTO to a number the analysis cannot compute "
                "(it depends on a value set outside the program).",
                False,
                blocks,
            )
        if why == "unread":
            return Ended(
                f"The run stopped {done}: the program goes on past the part of the file "
                "that is read (MB013).",
                False,
                blocks,
            )
        if why == "no END":
            return Ended(f"The run stopped{where}: a WHILE without its END.", False, blocks)
        return Ended(f"The run stopped {done} ({why}).", False, blocks)

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
                category = "stderr" if finding.kind.startswith("alarm") else "console"
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
        cl = ctx.lines[line]
        caller = act.caller
        if (
            caller is not None
            and act.macro_level > caller.macro_level
            and act.serial not in self._called_with
        ):
            # A new macro level's first block: its locals are the arguments it was called with.
            self._called_with[act.serial] = tuple(
                (n, v) for n, v in enumerate(act.locals) if n and v is not None
            )
        if ctx.facts.reported and len(ctx.facts.reported) != self._reported.get(ctx.uri, 0):
            self._report_findings()
        stop: Stop | None = None
        asked, self._pending_stop = self._pending_stop, None
        if asked is not None and asked[0] in self.filters:
            stop = Stop("exception", asked[1], asked[2], exception=asked[0])
        hit = self._breakpoints_at(act, ctx.uri, line)
        if self._first:
            self._first = False
            if self.launch.stop_on_entry and stop is None:
                stop = Stop("entry", f"{ctx.name} starts")
        if stop is None and self._pause:
            stop = Stop("pause", "Paused")
        if stop is None and hit:
            stop = Stop("breakpoint", "Breakpoint", breakpoints=tuple(hit))
        if stop is None and self._step is not None:
            how, depth = self._step
            here = _depth(act)
            if how == "in" or (how == "over" and here <= depth) or (how == "out" and here < depth):
                stop = Stop("step", "Step")
        if stop is not None:
            self._wait(act, line, stop)
        self._note_block(act, cl, line)

    def alarm(self, act: Activation, line: int, message: str) -> None:
        self._report_findings()
        cl = act.ctx.lines[line]
        if cl.kind == K_ASSIGN and cl.target_number == 3000:
            # The control shows the block's comment with the alarm number.
            text = _comment(act, line)
            if text:
                message = f"{message}: {text}"
        if ALARM_FILTER in self.filters:
            self._wait(act, line, Stop("exception", "Alarm", message, exception=ALARM_FILTER))

    def _breakpoints_at(self, act: Activation, key: str, line: int) -> list[int]:
        bps = self.breakpoints.get(key)
        if not bps:
            return []
        hit: list[int] = []
        for bp in bps:
            if not bp.verified or bp.actual_line != line:
                continue
            if bp._cond is not None:
                try:
                    result = bp._cond(_Probe(act))
                except MacroAlarm as alarm:
                    self._say("console", f"breakpoint condition {bp.condition}: {alarm.message}")
                    continue
                if result is not True:
                    if result is not False and not bp._told_unknown:
                        bp._told_unknown = True
                        self._say(
                            "console",
                            f"line {line + 1}: the condition {bp.condition} cannot be "
                            "decided here (it reads a value set outside the program); the "
                            "breakpoint stops only where it is true.",
                            key,
                            line,
                        )
                    continue
            bp.hits += 1
            if bp._hit is not None and not bp._hit(bp.hits):
                continue
            if bp.log_message:
                self._say("console", self._interpolate(bp.log_message, act), key, line)
                continue
            hit.append(bp.id)
        return hit

    def _interpolate(self, text: str, act: Activation) -> str:
        def one(found: re.Match[str]) -> str:
            try:
                return self._show(parse_expression(found.group(1))(_Probe(act)))
            except (DebugError, MacroAlarm) as err:
                return f"<{err}>"

        return _INTERPOLATION.sub(one, text)

    def _note_block(self, act: Activation, cl: Any, line: int) -> None:
        """What the block about to run changes that the scopes show and the machine does not
        keep: the system variables it names, the modal G codes and T, a DPRNT, a #3006."""
        for n in cl.reads:
            if n >= 1000:
                self._system_seen.add(n)
        kind = cl.kind
        if kind == K_ASSIGN:
            n = cl.target_number
            if n is not None and n >= 1000:
                self._system_seen.add(n)
            if n == 3006:
                # The control stops after the block and shows its comment (FANUC custom macro,
                # "#3006 stop with message").
                text = _comment(act, line)
                self._pending_stop = (MESSAGE_FILTER, "Stop with message (#3006)", text or "#3006")
        elif kind in (K_IFGOTO, K_IFTHEN, K_WHILE) and cl.cond is not None:
            self._note_condition(act, cl, line)
        elif kind == K_OTHER and isinstance(cl.node, Print) and cl.node.keyword == "DPRNT":
            self._say("stdout", dprnt_line(cl.node.text, act), act.ctx.uri, line)
        elif kind == K_NC:
            lathe = act.machine.lathe
            const = cl.constant
            if const is not None:
                g_codes: list[float] = list(const.g_codes)
                m_codes: list[float] = list(const.m_codes)
                tool = const.values.get("T")
            else:
                g_codes, m_codes, tool = [], [], None
                for w in cl.words:
                    try:
                        v = w.evaluate(_Probe(act))
                    except MacroAlarm:
                        continue
                    if w.address == "G" and isinstance(v, float):
                        g_codes.append(round(v, 1))
                    elif w.address == "M" and isinstance(v, float):
                        m_codes.append(v)
                    elif w.address == "T" and v is not None:
                        tool = v
            if 0.0 in m_codes or 1.0 in m_codes:
                code = "M00" if 0.0 in m_codes else "M01"
                what = "program stop" if code == "M00" else "optional stop"
                text = _comment(act, line)
                self._pending_stop = (
                    PROGRAM_STOP_FILTER,
                    f"Program stop ({code})",
                    f"{code} {what}" + (f": {text}" if text else ""),
                )
            for g in g_codes:
                group = modal_group(g, lathe)
                if group is not None:
                    self._groups[group] = g
            if tool is not None:
                self._tool = tool

    def _note_condition(self, act: Activation, cl: Any, line: int) -> None:
        """A condition the analysis cannot decide (it reads a probe's result, a PMC signal):
        the run goes on as the checker's does, which the control may not; said once a line."""
        key = (act.ctx.uri, line)
        if key in self._undecided_seen:
            return
        try:
            result = cl.cond(_Probe(act))
        except MacroAlarm:
            return  # the block's own run raises it
        if isinstance(result, bool):
            return
        self._undecided_seen.add(key)
        depends = result.describe() if isinstance(result, Unknown) else "unknown"
        self._say(
            "console",
            f"{Path(act.ctx.uri).name}:{line + 1}: this condition cannot be decided before the "
            f"machine runs ({depends}): the run goes on as the checker's does (an IF falls "
            "through the first time and jumps the next, a WHILE runs its body once), which "
            "the control may not.",
            act.ctx.uri,
            line,
        )

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

    # ---- what a stop shows ------------------------------------------------------------------
    def _levels(self) -> list[Activation]:
        with self._lock:
            if self._state != _STOPPED or self._act is None:
                raise DebugError("the program is running: pause it to see its state")
            out: list[Activation] = []
            a: Activation | None = self._act
            while a is not None:
                out.append(a)
                a = a.caller
            return out

    def frames(self) -> list[FrameInfo]:
        levels = self._levels()
        out: list[FrameInfo] = []
        for i, act in enumerate(levels):
            line = self._line if i == 0 else levels[i - 1].return_pc - 1
            out.append(
                FrameInfo(
                    i + 1, self._frame_name(act, levels[i - 1] if i else None), act.ctx.uri, line, 0
                )
            )
        return out

    def _frame_name(self, act: Activation, _callee: Activation | None) -> str:
        name = act.ctx.name
        caller = act.caller
        if caller is None:
            return name
        call_line = act.return_pc - 1
        text = (
            caller.ctx.doc.blocks[call_line].text
            if 0 <= call_line < len(caller.ctx.doc.blocks)
            else ""
        )
        found = _CALL_WORD.search(text)
        how = code_name(found.group(1)[0], float(found.group(1)[1:])) if found else "G66"
        if how == "M98" and act.macro_level == caller.macro_level:
            return f"{name} (M98 from {caller.ctx.name})"
        args = self._called_with.get(act.serial, ())
        words = " ".join(f"{_LETTER_OF.get(n, f'#{n}=')}{self._show(v)}" for n, v in args)
        return f"{name} ({how} {words})".replace(" )", ")")

    def _level(self, frame_id: int) -> Activation:
        levels = self._levels()
        if not 1 <= frame_id <= len(levels):
            raise DebugError(f"no stack frame {frame_id}")
        return levels[frame_id - 1]

    def scopes(self, frame_id: int) -> list[ScopeInfo]:
        act = self._level(frame_id)
        base = frame_id * 10
        commons = self._common_numbers(act)
        system = self._system_numbers(act)
        shared = ""
        if act.caller is not None and act.macro_level == act.caller.macro_level:
            shared = f", shared with {act.caller.ctx.name} (M98)"
        return [
            ScopeInfo(
                f"Locals #1-#33 ({act.ctx.name}, level {act.macro_level}{shared})", base + 1, 33
            ),
            ScopeInfo("Common variables (set)", base + 2, len(commons)),
            ScopeInfo("System variables (read or written)", base + 3, len(system)),
            ScopeInfo("Modal state", base + 4, len(self._modal(act))),
        ]

    def _common_numbers(self, act: Activation) -> list[int]:
        return sorted(
            n
            for n in act.store
            if n > 33 and classify(n).kind in ("common", "retained", "extended-common")
        )

    def _system_numbers(self, act: Activation) -> list[int]:
        return sorted(
            {n for n in self._system_seen if classify(n).kind == "system"}
            | {n for n in act.store if classify(n).kind == "system"}
        )

    def variables(self, reference: int) -> list[VariableInfo]:
        frame_id, scope = divmod(reference, 10)
        act = self._level(frame_id)
        if scope == 1:
            letters = act.caller is not None and act.macro_level > act.caller.macro_level
            return [
                VariableInfo(
                    f"#{n} ({_LETTER_OF[n]})" if letters and n in _LETTER_OF else f"#{n}",
                    self._show(act.locals[n]),
                    f"#{n}",
                    "local",
                )
                for n in range(1, 34)
            ]
        if scope in (2, 3):
            numbers = self._common_numbers(act) if scope == 2 else self._system_numbers(act)
            out = []
            for n in numbers:
                kind = classify(n)
                name = f"#{n}" if scope == 2 else f"#{n} ({kind.meaning})"
                out.append(
                    VariableInfo(
                        name,
                        self._show(read_variable(act, n)),
                        f"#{n}",
                        "common" if scope == 2 else "system",
                        kind.read_only,
                    )
                )
            return out
        if scope == 4:
            return self._modal(act)
        raise DebugError(f"no variables {reference}")

    def _modal(self, act: Activation) -> list[VariableInfo]:
        modal = act.machine.modal
        out: list[VariableInfo] = []
        for group in sorted(self._groups):
            out.append(
                VariableInfo(
                    f"G group {group}",
                    code_name("G", self._groups[group]),
                    kind="modal",
                    read_only=True,
                )
            )
        if modal.motion is not None and "01" not in self._groups:
            out.append(
                VariableInfo(
                    "G group 01", code_name("G", modal.motion), kind="modal", read_only=True
                )
            )
        out.sort(key=lambda v: v.name)
        out.append(
            VariableInfo(
                "unit", "inch (G20)" if modal.inch else "mm (G21)", kind="modal", read_only=True
            )
        )
        out.append(VariableInfo("F", self._show(modal.feed), kind="modal", read_only=True))
        speed = self._show(modal.speed)
        if modal.constant_surface_speed:
            speed += " m/min (G96)"
        out.append(VariableInfo("S", speed, kind="modal", read_only=True))
        out.append(VariableInfo("T", self._show(self._tool), kind="modal", read_only=True))
        for axis in sorted(modal.position):
            out.append(
                VariableInfo(axis, self._show(modal.position[axis]), kind="modal", read_only=True)
            )
        for callee, _args, _repeat in modal.modal_calls:
            out.append(
                VariableInfo(
                    "G66 in force",
                    callee.name if callee else "a program not in these files",
                    kind="modal",
                    read_only=True,
                )
            )
        return out

    def _show(self, value: Value) -> str:
        machine = self._machine
        inch = machine.modal.inch if machine is not None else False
        return Precision(inch, self.launch.full_precision).show(value)

    def evaluate(self, text: str, frame_id: int | None) -> str:
        """A Macro B expression or condition at a stopped frame (the top one by default), or
        an assignment (``#100=5``) done there."""
        text = text.strip()
        if not text:
            raise DebugError("nothing to evaluate")
        act = self._level(frame_id or 1)
        assignment = parse_assignment(text)
        if assignment is not None:
            target, value = assignment
            if target.number is None:
                raise DebugError("assign to a numbered variable (#100=5), not #[...]")
            return self.set_variable(act, int(target.number), value)
        try:
            evaluator = parse_expression(text)
        except DebugError:
            cond = parse_condition(text)
            result = cond(_Probe(act))
            return {True: "true", False: "false"}.get(result, f"unknown ({result})")  # type: ignore[arg-type]
        try:
            return self._show(evaluator(_Probe(act)))
        except MacroAlarm as alarm:
            raise DebugError(f"{alarm.message} (alarm {alarm.alarm})") from None

    def set_variable_at(self, reference: int, name: str, text: str) -> str:
        frame_id, scope = divmod(reference, 10)
        act = self._level(frame_id)
        if scope == 4:
            raise DebugError("the modal state is what the blocks set: change it in the program")
        found = re.match(r"\s*#(\d+)", name)
        if found is None:
            raise DebugError(f"{name!r} is not a variable")
        return self.set_variable(act, int(found.group(1)), parse_expression(text))

    def set_variable(self, act: Activation, n: int, value: Evaluator) -> str:
        kind = classify(n)
        if kind.kind == "none":
            raise DebugError(f"#{n} does not exist on this control")
        if kind.read_only:
            raise DebugError(f"#{n} is read-only ({kind.meaning})")
        try:
            result = value(_Probe(act))
        except MacroAlarm as alarm:
            raise DebugError(f"{alarm.message} (alarm {alarm.alarm})") from None
        if 1 <= n <= 33:
            act.locals[n] = result
        else:
            act.store[n] = result
        return self._show(result)


def _comment(act: Activation, line: int) -> str:
    parsed = act.ctx.doc.blocks[line].parsed
    return " ".join(c.text for c in parsed.comments).strip()


def _depth(act: Activation) -> int:
    depth = 0
    a: Activation | None = act
    while a is not None:
        depth += 1
        a = a.caller
    return depth


def _runs(parsed: Any) -> bool:
    """Whether the control runs something on this line (a statement, not a comment alone)."""
    return parsed.statement is not None and compiled(parsed).kind not in (0,)


def iter_breakpoints(session: Session) -> Iterator[Breakpoint]:
    for bps in session.breakpoints.values():
        yield from bps
