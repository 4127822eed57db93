"""What the debugger's session gives its front end: stops, output, the run's end, breakpoints,
and the frames, scopes and variables of a stop. Plain data, no protocol."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..evaluator.compiler import CondEvaluator
from ..translation import tr

# The exception breakpoints a user can turn on and off (DAP exceptionBreakpointFilters).
ALARM_FILTER = "alarm"  # #3000 and the PS alarms the evaluator raises
MESSAGE_FILTER = "message"  # #3006: the control stops with a message
PROGRAM_STOP_FILTER = "programStop"  # M00, and M01 with the optional stop switch on
EXCEPTION_FILTERS: tuple[tuple[str, str, bool], ...] = (
    (ALARM_FILTER, tr("Alarms (#3000, PS0112 zero divide, ...)"), True),
    (MESSAGE_FILTER, tr("Stop with message (#3006)"), True),
    (PROGRAM_STOP_FILTER, tr("Program stop (M00, M01)"), False),
)


class DebugError(Exception):
    """A launch or a request that cannot be done; the message says why, for the user."""


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
