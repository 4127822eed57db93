"""What the evaluator learned: per block runs, values read and written, jumps, motions, findings.

These are the facts the rules, the hover and the inlay hints read. They carry no LSP types.
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, ClassVar, TypeVar, cast

from ..translation import tr
from .values import AlarmKind, Unknown, Value, fmt

if TYPE_CHECKING:
    from .checkpoints import RunRecord
    from .toolpath import Toolpath

K = TypeVar("K")
V = TypeVar("V")


def same_value(a: object, b: object) -> bool:
    """Equal, and the same kind of value: 0.0 and -0.0 differ (they print differently), a
    number and a vacant differ. Containers are compared element by element."""
    if a is b:
        return True
    kind = type(a)
    if kind is not type(b):
        return False
    if kind is float:
        assert isinstance(a, float) and isinstance(b, float)
        return a == b and (a != 0.0 or math.copysign(1.0, a) == math.copysign(1.0, b))
    if kind is tuple or kind is list:
        assert isinstance(a, (tuple, list)) and isinstance(b, (tuple, list))
        return len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b, strict=True))
    if kind is dict:
        assert isinstance(a, dict) and isinstance(b, dict)
        return len(a) == len(b) and all(k in b and same_value(v, b[k]) for k, v in a.items())
    return a == b


_INF = float("inf")  # shared: a summary of no number keeps no floats of its own
_NEG_INF = float("-inf")


class _Spread:
    """What a summary of two or more values keeps besides its first value."""

    __slots__ = ("count", "last", "maximum", "minimum", "unknown", "vacant")

    def __init__(
        self,
        count: int,
        last: Value,
        minimum: float,
        maximum: float,
        vacant: int,
        unknown: Unknown | None,
    ) -> None:
        self.count = count
        self.last = last
        self.minimum = minimum
        self.maximum = maximum
        self.vacant = vacant
        self.unknown = unknown

    def add(self, value: Value) -> None:
        self.count += 1
        self.last = value
        if value is None:
            self.vacant += 1
        elif isinstance(value, Unknown):
            self.unknown = value
        else:
            if value < self.minimum:
                self.minimum = value
            if value > self.maximum:
                self.maximum = value


@dataclass(frozen=True, slots=True)
class _Nothing:
    """The first value of a summary of no values."""


_NOTHING = _Nothing()


class ValueSummary:
    """The values one variable had at one block over every execution.

    Most reads and writes run once: a summary of one value is that value (its count, last,
    smallest, largest, vacant and unknown follow from it), and holds the rest (a ``_Spread``)
    only from its second value on, which keeps the per-block facts of a program without loops
    small: two slots.
    """

    __slots__ = ("_first", "_more")

    def __init__(self) -> None:
        self._first: Value | _Nothing = _NOTHING
        self._more: _Spread | None = None  # None while it holds at most one value

    def add(self, value: Value) -> None:
        more = self._more
        if more is not None:
            more.add(value)
            return
        first = self._first
        if isinstance(first, _Nothing):
            self._first = value
            return
        more = self._more = _Spread(1, first, self.minimum, self.maximum, self.vacant, self.unknown)
        more.add(value)

    def add_all(self, values: list[Value]) -> None:
        """``add`` of each value, in order: the run keeps a block's values of a stretch in a
        list and adds them at once, numbers compared in C."""
        if len(values) > 1:
            numbers = cast("list[float]", values)
            try:
                total = sum(numbers)
            except TypeError:  # a vacant or an unknown among them: one by one
                total = math.nan
            if total == total:  # numbers, no NaN (which add leaves out, and sorting misplaces)
                # A stable sort of floats compares in C, several times faster than min and
                # max: its first is min's (the earliest of equal ones, as ``add`` keeps);
                # its last is the latest of equal ones, which differ for 0.0 and -0.0 only.
                ordered = sorted(numbers)
                low, high = ordered[0], ordered[-1]
                if high == 0.0:
                    high = max(numbers)
                more = self._more
                if more is None:
                    first = self._first
                    if isinstance(first, _Nothing):
                        self._first = values[0]
                        self._more = _Spread(len(values), values[-1], low, high, 0, None)
                        return
                    more = self._more = _Spread(
                        1, first, self.minimum, self.maximum, self.vacant, self.unknown
                    )
                more.count += len(values)
                more.last = values[-1]
                if low < more.minimum:
                    more.minimum = low
                if high > more.maximum:
                    more.maximum = high
                return
        add = self.add
        for value in values:
            add(value)

    @property
    def count(self) -> int:
        more = self._more
        if more is not None:
            return more.count
        return 0 if self._first is _NOTHING else 1

    @property
    def first(self) -> Value:
        first = self._first
        return None if isinstance(first, _Nothing) else first

    @property
    def last(self) -> Value:
        more = self._more
        if more is not None:
            return more.last
        return self.first

    @property
    def minimum(self) -> float:
        more = self._more
        if more is not None:
            return more.minimum
        first = self._first
        if first is None or isinstance(first, _Nothing | Unknown):
            return _INF
        return first if first < _INF else _INF  # as ``add`` compares: NaN stays inf

    @property
    def maximum(self) -> float:
        more = self._more
        if more is not None:
            return more.maximum
        first = self._first
        if first is None or isinstance(first, _Nothing | Unknown):
            return _NEG_INF
        return first if first > _NEG_INF else _NEG_INF

    @property
    def vacant(self) -> int:
        more = self._more
        if more is not None:
            return more.vacant
        return 1 if self._first is None else 0

    @property
    def unknown(self) -> Unknown | None:
        more = self._more
        if more is not None:
            return more.unknown
        first = self._first
        return first if isinstance(first, Unknown) else None

    def then(self, later: ValueSummary) -> ValueSummary:
        """This summary followed by ``later``'s executions, as one summary (a new object)."""
        out = ValueSummary()
        count = self.count + later.count
        out._first = self._first if self._first is not _NOTHING else later._first
        if count > 1:
            later_unknown = later.unknown
            out._more = _Spread(
                count,
                later.last if later.count else self.last,
                min(self.minimum, later.minimum),
                max(self.maximum, later.maximum),
                self.vacant + later.vacant,
                later_unknown if later_unknown is not None else self.unknown,
            )
        return out

    def same_as(self, other: ValueSummary) -> bool:
        return (
            self.count == other.count
            and same_value(self.first, other.first)
            and same_value(self.last, other.last)
            and self.minimum == other.minimum
            and self.maximum == other.maximum
            and self.vacant == other.vacant
            and self.unknown == other.unknown
        )

    @property
    def numeric(self) -> bool:
        return self.minimum <= self.maximum

    @property
    def constant(self) -> bool:
        return self.numeric and self.minimum == self.maximum and self.vacant == 0

    def describe(self, show: Callable[[Value], str] = fmt) -> str:
        """``1.907`` or ``0.092 → 1.887 (88 values, min 0.092, max 1.887)``, each value as
        ``show`` writes it (the control's display by default)."""
        if self.count == 0:
            return tr("never evaluated")
        if self.count == 1 or (self.constant and self.unknown is None):
            return show(self.first)
        if not self.numeric:
            return show(self.last)
        said = {
            "first": show(self.first),
            "last": show(self.last),
            "count": self.count,
            "minimum": show(self.minimum),
            "maximum": show(self.maximum),
        }
        if self.vacant:
            return tr(
                "{first} → {last} ({count} times, min {minimum}, max {maximum}), vacant "
                "{vacant} times",
                vacant=self.vacant,
                **said,
            )
        return tr("{first} → {last} ({count} times, min {minimum}, max {maximum})", **said)


@dataclass(init=False)
class Motion:
    """A move the run records: one a block, most of a long program's. The fields few motions
    set (a lathe's threads, G20, G96, drilling) are held together, and only when set."""

    __slots__ = (
        "_rare",
        "code",
        "line",
        "program",
        "program_line",
        "rpm",
        "run",
        "start_line",
        "start_uri",
        "start_x",
        "start_z",
        "uri",
        "words",
        "x",
        "z",
    )
    program: str
    line: int
    code: str
    words: dict[str, float]
    uri: str
    x: float | None  # the diameter the move or cut reaches (G32 Z-only: where it is)
    rpm: float | None  # spindle speed in G97 (None in G96 or unknown)
    program_line: int  # first line of the program the motion belongs to
    z: float | None  # the Z the move or cut ends at
    # Where the tool stood before the block: a cycle's start point, to which it returns.
    start_x: float | None
    start_z: float | None
    start_line: int | None  # the block that put the tool at start_x
    start_uri: str
    run: int  # which execution of its program: every call is a new one
    cycle_pass: int  # G76: the pass number within its cycle (0: not a G76 pass)
    finishing: bool  # G76: a finishing pass at the full thread height
    # The code as a lathe program of G code system B or C writes it ("G78" for code "G92");
    # empty when it is ``code``.
    written: str
    inch: bool  # G20 in force: its lengths are inches (a message says so)
    # A mill's canned drilling cycle (its G76 is fine boring, not a thread).
    drilling: bool
    # G96 in force: its surface speed S (m/min, ft/min in G20); the spindle speed then follows X.
    surface_speed: float | None
    # And the G50 S clamp on the speed then (rpm): inf without one, None when not known.
    speed_clamp: float | None
    # G76: the tool angle a of its first block, along whose flank the passes step.
    tool_angle: float | None
    # The feed mode's G code in force when the run set another than the machine's power-on
    # one (a lathe's G98 per minute, a mill's G95 per revolution: see POWER_ON_FEED_MODE);
    # None: the power-on mode. What the cycle time divides the F by.
    feed_mode: float | None

    def __init__(
        self,
        program: str,
        line: int,
        code: str,
        words: dict[str, float],
        uri: str = "",
        x: float | None = None,
        rpm: float | None = None,
        program_line: int = 0,
        z: float | None = None,
        start_x: float | None = None,
        start_z: float | None = None,
        start_line: int | None = None,
        start_uri: str = "",
        run: int = 0,
        cycle_pass: int = 0,
        finishing: bool = False,
        written: str = "",
        inch: bool = False,
        drilling: bool = False,
        surface_speed: float | None = None,
        speed_clamp: float | None = None,
        tool_angle: float | None = None,
        feed_mode: float | None = None,
    ) -> None:
        self.program = program
        self.line = line
        self.code = code
        self.words = words
        self.uri = uri
        self.x = x
        self.rpm = rpm
        self.program_line = program_line
        self.z = z
        self.start_x = start_x
        self.start_z = start_z
        self.start_line = start_line
        self.start_uri = start_uri
        self.run = run
        self._rare: dict[str, object] | None = None
        if (
            cycle_pass
            or finishing
            or written
            or inch
            or drilling
            or surface_speed is not None
            or speed_clamp is not None
            or tool_angle is not None
            or feed_mode is not None
        ):
            values = (cycle_pass, finishing, written, inch, drilling)
            rare = (*values, surface_speed, speed_clamp, tool_angle, feed_mode)
            for name, value in zip(_RARE, rare, strict=True):
                setattr(self, name, value)

    @property
    def shown(self) -> str:
        """The code as the program writes it: what a message names."""
        return self.written or self.code


# The fields few motions set, and their values when not set.
_RARE_DEFAULTS: Mapping[str, object] = MappingProxyType(
    {
        "cycle_pass": 0,
        "finishing": False,
        "written": "",
        "inch": False,
        "drilling": False,
        "surface_speed": None,
        "speed_clamp": None,
        "tool_angle": None,
        "feed_mode": None,
    }
)
_RARE = tuple(_RARE_DEFAULTS)
# The feed mode a machine is in at power on, by lathe or not: a lathe in G99 (feed per
# revolution), a mill in G94 (per minute). FANUC 0i-TF/0i-MF Operator's Manual, "Feed
# functions"; a parameter may choose the other (the lathe's FPM, unverified which number).
POWER_ON_FEED_MODE: Mapping[bool, float] = MappingProxyType({True: 99.0, False: 94.0})


def _rare_field(name: str, default: object) -> property:
    def get(motion: Motion) -> object:
        rare = motion._rare
        return default if rare is None else rare.get(name, default)

    def set_(motion: Motion, value: object) -> None:
        rare = motion._rare
        if rare is None:
            if value is default:
                return
            rare = motion._rare = {}
        rare[name] = value

    return property(get, set_)


def _add_rare_fields() -> None:
    for name, default in _RARE_DEFAULTS.items():
        setattr(Motion, name, _rare_field(name, default))


_add_rare_fields()


@dataclass(slots=True, eq=False, repr=False)
class Rounding:
    """FIX or FUP of a value a hair off a whole number: 7.9999999999 truncated to 7."""

    function: str
    argument: float
    result: float
    count: int = 1


@dataclass(frozen=True, eq=False, repr=False)
class Finding:
    """Something to report at a block: an alarm, a bad address value, a loop that never ends.
    Each kind is a class of its own, which the rules match by type
    (:meth:`fanuc_macro.rules.context.RuleContext.findings`)."""

    KIND: ClassVar[str] = ""

    line: int
    column: int
    end_column: int
    message: str
    uri: str = ""
    related_line: int | None = None
    related_message: str = ""

    @property
    def kind(self) -> str:
        """The finding's name as the trace and the debugger print it (``endless-loop``)."""
        return self.KIND


@dataclass(frozen=True, eq=False, repr=False)
class EndlessLoop(Finding):
    """A loop still running when the step budget ran out, and not getting nearer its end."""

    KIND: ClassVar[str] = "endless-loop"


@dataclass(frozen=True, eq=False, repr=False)
class PollingLoop(Finding):
    """A loop waiting for a variable that only something outside the program changes."""

    KIND: ClassVar[str] = "polling-loop"


@dataclass(frozen=True, eq=False, repr=False)
class LongLoop(Finding):
    """A loop still running when the budget ran out, but nearer its end at every turn."""

    KIND: ClassVar[str] = "long-loop"


@dataclass(frozen=True, eq=False, repr=False)
class ProgramNotFound(Finding):
    """A call of a program the analysis does not have (the call is skipped)."""

    KIND: ClassVar[str] = "program-not-found"

    program: int = field(kw_only=True)  # the number called


@dataclass(frozen=True, eq=False, repr=False)
class CutSpindleStopped(Finding):
    """The first feed move after the run stopped the spindle (M05, M06): the tool feeds into
    the work without turning."""

    KIND: ClassVar[str] = "feed-spindle-stopped"


@dataclass(frozen=True, eq=False, repr=False)
class LoopNoTurn(Finding):
    """A WHILE entered again that runs no turn, its counter a common variable the loop sets:
    a second call of a macro whose counter was not set back."""

    KIND: ClassVar[str] = "loop-no-turn"


@dataclass(frozen=True, eq=False, repr=False)
class FeedUnit(Finding):
    """A cut at a feed whose size belongs to the other feed mode: per minute set, a feed per
    revolution's value written (or the other way)."""

    KIND: ClassVar[str] = "feed-unit"


@dataclass(frozen=True, eq=False, repr=False)
class SpeedNotClamped(Finding):
    """A lathe's feed move in G96 to a diameter where the surface speed asks for more than
    the machine's maximum (the centre: any), with no G50 S clamp set in the run."""

    KIND: ClassVar[str] = "speed-not-clamped"


@dataclass(frozen=True, eq=False, repr=False)
class LengthOffsetOtherTool(Finding):
    """G43/G44 with an H that is not the tool in the spindle, where the run's earlier tools
    had their H equal to their T."""

    KIND: ClassVar[str] = "length-offset-other-tool"


@dataclass(frozen=True, eq=False, repr=False)
class ToolWithoutLengthOffset(Finding):
    """A cut after a tool change with no tool length offset called, where an earlier tool of
    the run had one."""

    KIND: ClassVar[str] = "tool-without-length-offset"


@dataclass(frozen=True, eq=False, repr=False)
class SkipReadBeforeG31(Finding):
    """A read of the skip position (#5061 and on) before any G31 of the run."""

    KIND: ClassVar[str] = "skip-before-g31"


@dataclass(frozen=True, eq=False, repr=False)
class ArcFault(Finding):
    """A G02/G03 the control cannot cut: an R shorter than half the chord, an end point off
    the circle the I J K centre gives (PS0020), neither R nor I J K (PS0022)."""

    KIND: ClassVar[str] = "arc-fault"

    fault: str = field(kw_only=True)  # "radius", "centre" or "no-centre"


@dataclass(frozen=True, eq=False, repr=False)
class DrillingFault(Finding):
    """A drilling cycle the control stops: a peck cycle without its Q (PS0045), a reference
    return while a cycle is in force (PS0044), a move between M29 and the tapping cycle
    (PS0204)."""

    KIND: ClassVar[str] = "drilling-fault"

    fault: str = field(kw_only=True)  # "peck", "return" or "rigid"


@dataclass(frozen=True, eq=False, repr=False)
class ProfileFault(Finding):
    """A lathe's G70-G73 the control stops at for its profile: P or Q names no block
    (PS0063), a G71/G72 profile that does not keep going one way (PS0064, PS0329)."""

    KIND: ClassVar[str] = "profile-fault"

    fault: str = field(kw_only=True)  # "label" or "monotone"


@dataclass(frozen=True, eq=False, repr=False)
class ThreadCycleFault(Finding):
    """A lathe's G76 the control stops at for its data: a tool angle it does not take
    (PS0315)."""

    KIND: ClassVar[str] = "thread-cycle-fault"

    fault: str = field(kw_only=True)  # "angle"


@dataclass(frozen=True, eq=False, repr=False)
class CornerRefused(Finding):
    """A chamfer or corner R (",C", ",R") on a thread (PS0050) or on the block that starts
    or cancels radius compensation (PS0039)."""

    KIND: ClassVar[str] = "corner-refused"


@dataclass(frozen=True, eq=False, repr=False)
class BlockFault(Finding):
    """A block the control refuses for what its words say together: G30 with a P other than
    2-4 (PS0046), a lathe's T in a G50, G10 or G04 block (PS0245)."""

    KIND: ClassVar[str] = "block-fault"

    fault: str = field(kw_only=True)  # "g30-p" or "t-code"


@dataclass(frozen=True, eq=False, repr=False)
class CompensationFault(Finding):
    """Radius compensation started or cancelled on an arc (PS0034), the plane changed while
    it is on (PS0037), or left on at the end of the program or at a reference return."""

    KIND: ClassVar[str] = "compensation-fault"

    fault: str = field(kw_only=True)  # "arc", "plane" or "left-on"


@dataclass(frozen=True, eq=False, repr=False)
class AddressFinding(Finding):
    """A word whose value its address cannot take."""

    address: str = field(kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class AddressNotInteger(AddressFinding):
    """A fraction where the address takes a whole number (or not a G code)."""

    KIND: ClassVar[str] = "address-non-integer"


@dataclass(frozen=True, eq=False, repr=False)
class AddressOutOfRange(AddressFinding):
    """A negative value, or a spindle speed above the machine's maximum."""

    KIND: ClassVar[str] = "address-range"


@dataclass(frozen=True, eq=False, repr=False)
class FeedNotSet(Finding):
    """A cut with no F commanded before it (kept by line: see :class:`CutsWithoutFeed`)."""

    KIND: ClassVar[str] = "feed-not-set"


@dataclass(frozen=True, eq=False, repr=False)
class AlarmFinding(Finding):
    """An alarm the control raises at the block: the run stops there."""

    alarm: AlarmKind = field(kw_only=True)
    number: str = field(kw_only=True)  # the alarm's number: "PS0112", "3000"

    @property
    def kind(self) -> str:
        return f"alarm:{self.alarm.value}"


@dataclass(frozen=True, eq=False, repr=False)
class ArithmeticAlarm(AlarmFinding):
    """ZERO DIVIDE, CALCULATED DATA OVERFLOW, or a function's argument outside its domain."""


@dataclass(frozen=True, eq=False, repr=False)
class UserAlarm(AlarmFinding):
    """The program's own macro alarm: a number written to #3000."""


@dataclass(frozen=True, eq=False, repr=False)
class GotoAlarm(AlarmFinding):
    """A GOTO to no sequence number, or to one the program does not have."""


@dataclass(frozen=True, eq=False, repr=False)
class ReturnMissing(AlarmFinding):
    """An M99 P to a sequence number the caller does not have."""


@dataclass(frozen=True, eq=False, repr=False)
class NestingAlarm(AlarmFinding):
    """Calls nested deeper than the control allows."""


@dataclass(frozen=True, eq=False, repr=False)
class ReadOnlyWrite(AlarmFinding):
    """A write of #0 or of a read-only system variable."""


@dataclass(frozen=True, eq=False, repr=False)
class NoSuchVariable(AlarmFinding):
    """A variable number the control does not have."""


@dataclass(frozen=True, eq=False, repr=False)
class FeedZero(AlarmFinding):
    """A cut or thread run with F = 0 (PS0011 FEED ZERO)."""

    @property
    def lead(self) -> bool:
        """F is a thread's lead, not a feed."""
        return self.alarm is AlarmKind.LEAD_ZERO


# The finding each kind of alarm makes.
ALARM_FINDINGS: Mapping[AlarmKind, type[AlarmFinding]] = MappingProxyType(
    {
        AlarmKind.ZERO_DIVIDE: ArithmeticAlarm,
        AlarmKind.OVERFLOW: ArithmeticAlarm,
        AlarmKind.SQRT_NEGATIVE: ArithmeticAlarm,
        AlarmKind.ASIN_RANGE: ArithmeticAlarm,
        AlarmKind.ACOS_RANGE: ArithmeticAlarm,
        AlarmKind.LN_DOMAIN: ArithmeticAlarm,
        AlarmKind.BIN_RANGE: ArithmeticAlarm,
        AlarmKind.BCD_RANGE: ArithmeticAlarm,
        AlarmKind.POW_RANGE: ArithmeticAlarm,
        AlarmKind.ATAN_ZERO: ArithmeticAlarm,
        AlarmKind.MACRO_ALARM: UserAlarm,
        AlarmKind.GOTO_TARGET: GotoAlarm,
        AlarmKind.GOTO_MISSING: GotoAlarm,
        AlarmKind.RETURN_MISSING: ReturnMissing,
        AlarmKind.NESTING: NestingAlarm,
        AlarmKind.WRITE_READ_ONLY: ReadOnlyWrite,
        AlarmKind.NO_SUCH_VARIABLE: NoSuchVariable,
        AlarmKind.FEED_ZERO: FeedZero,
        AlarmKind.LEAD_ZERO: FeedZero,
    }
)


@dataclass(slots=True, eq=False, repr=False)
class CutsWithoutFeed:
    """Cuts with no F commanded before them (MB603), found one after another in one program
    with no other finding of the document between them: kept as their lines, not as a
    :class:`Finding` each (a CAM file without F has one per block). A stretch of the run
    lists each line once; the document's facts keep the first record of a line."""

    uri: str
    program: int  # the first line of the program that ran them
    message: str
    after: int  # how many of the document's other findings came before them
    lines: array[int]
    ascending: bool = True  # each line after the one before (a run without jumps back)


@dataclass(slots=True, eq=False, repr=False)
class FeedlessProgram:
    """MB603 of one program: the first cut without F, its message, the count of such cuts
    (each line once), and the first ``SHOWN_CUTS`` of them in the order the run reached them."""

    message: str
    count: int
    lines: list[int]


SHOWN_CUTS = 20


class Stretch:
    """The identity of one stretch of a run's facts: equal only to itself, so that no two
    stretches of any evaluations are taken for one another."""

    __slots__ = ()


@dataclass(slots=True, eq=False, repr=False)
class JumpCount:
    taken: int = 0
    not_taken: int = 0
    undecided: int = 0
    guessed: int = 0  # decided, but on a path that went through an undecided condition


@dataclass(eq=False, repr=False)
class DocumentFacts:
    """Facts about one document's blocks, across every run that reached them."""

    runs: dict[int, int] = field(default_factory=dict)
    reads: dict[tuple[int, int], ValueSummary] = field(default_factory=dict)
    writes: dict[int, tuple[int, ValueSummary]] = field(default_factory=dict)
    jumps: dict[int, JumpCount] = field(default_factory=dict)
    # The findings but the cuts without F, in the order the run found them: see ``findings``.
    reported: list[Finding] = field(default_factory=list)
    cuts: list[CutsWithoutFeed] = field(default_factory=list)  # this stretch's, or all
    analysed_programs: set[int] = field(default_factory=set)  # first lines of programs run
    incomplete_programs: set[int] = field(default_factory=set)  # runs that stopped early
    roundings: dict[int, Rounding] = field(default_factory=dict)  # line -> the first such
    # first line of a program -> its first block with M30 or M02 (block skip or not)
    program_ends: dict[int, int] = field(default_factory=dict)
    # Programs ending with M30 run on their own with unknown arguments, because they read
    # locals before setting them: first line -> (local, line of its first read), in text order.
    assumed_arguments: dict[int, tuple[tuple[int, int], ...]] = field(default_factory=dict)
    _feedless: dict[int, FeedlessProgram] | None = field(
        default=None, init=False, repr=False, compare=False
    )
    # Which stretch of a run these facts are (0: a document's whole facts): a stretch
    # renumbered after an edit of lines keeps it, so that the rules can tell the stretches an
    # evaluation took from the earlier one (:func:`.checkpoints.lines_with_other_facts`).
    stretch: Stretch | int = field(default=0, repr=False, compare=False)

    @property
    def findings(self) -> list[Finding]:
        """Every finding in the order the run found them, one per cut without F too (a new
        list: the rules read :attr:`reported` and :meth:`feedless`)."""
        if not self.cuts:
            return list(self.reported)
        reported = self.reported
        out: list[Finding] = []
        seen: set[int] = set()
        taken = 0
        for cuts in self.cuts:
            if cuts.after > taken:
                out.extend(reported[taken : cuts.after])
                taken = cuts.after
            for line in cuts.lines:
                if line not in seen:
                    seen.add(line)
                    out.append(FeedNotSet(line, 0, 0, cuts.message, cuts.uri))
        out.extend(reported[taken:])
        return out

    def feedless(self) -> dict[int, FeedlessProgram]:
        """The cuts without F by program (its first line), programs in the order the run
        reached their first such cut: computed once, from the records of every stretch."""
        found = self._feedless
        if found is None:
            found = self._feedless = _feedless(self.cuts)
        return found

    def segment(self) -> DocumentFacts:
        """Facts of the same document for a later stretch of the run: the counts and summaries
        start empty, the findings and the programs run are shared with this one."""
        return DocumentFacts(
            reported=self.reported,
            analysed_programs=self.analysed_programs,
            program_ends=self.program_ends,
            assumed_arguments=self.assumed_arguments,
            stretch=Stretch(),
        )

    def take_segments(self, segments: Sequence[DocumentFacts]) -> None:
        """Set the counts and summaries to those of ``segments``, stretches of one run in
        order. A key in one segment only keeps that segment's object (nothing mutates a
        segment after its stretch of the run), so a run without loops merges at the speed of
        ``dict.update``."""
        self.runs = _merged([s.runs for s in segments], _add)
        self.reads = _merged([s.reads for s in segments], ValueSummary.then)
        self.writes = _merged([s.writes for s in segments], _then_write)
        self.jumps = _merged([s.jumps for s in segments], _add_jumps)
        self.roundings = _merged([s.roundings for s in segments], _add_roundings)
        self.cuts = [cuts for s in segments for cuts in s.cuts]
        self._feedless = None
        incomplete: set[int] = set()
        for s in segments:
            incomplete |= s.incomplete_programs
        self.incomplete_programs = incomplete

    def jump_count(self, line: int) -> JumpCount:
        count = self.jumps.get(line)
        if count is None:
            count = self.jumps[line] = JumpCount()
        return count

    def read_summary(self, line: int, number: int) -> ValueSummary | None:
        return self.reads.get((line, number))

    def write_summary(self, line: int) -> tuple[int, ValueSummary] | None:
        return self.writes.get(line)


@dataclass(frozen=True, eq=False, repr=False)
class RunValues:
    """The variables of one execution of a program when it began to cut a thread: what the
    threading rules read a module's inputs from when it is called more than once."""

    locals: tuple[Value, ...]  # #0-#33
    globals: dict[int, Value]

    def value(self, number: int) -> float | None:
        v = self.locals[number] if number <= 33 else self.globals.get(number)
        return v if isinstance(v, float) else None


@dataclass(eq=False, repr=False)
class Facts:
    by_uri: dict[str, DocumentFacts] = field(default_factory=dict)
    motions: list[Motion] = field(default_factory=list)
    steps: int = 0
    # Why a run stopped early: "budget" (the step budget), "time" (the safety net), or None.
    stopped: str | None = None
    time_limit: float = 0.0  # the safety net's seconds, when it stopped a run
    run_values: dict[int, RunValues] = field(default_factory=dict)  # run -> at its first cut
    # The run's checkpoints and facts by stretch, from which the next analysis resumes.
    record: RunRecord | None = field(default=None, repr=False, compare=False)
    toolpath: Toolpath | None = None  # the moves, when the evaluation was asked for them
    # The runs with the block-delete switch off and on, when the programs run have a block
    # that begins with '/': these facts are the two merged (see :func:`both_ways`), and the
    # next evaluation resumes each from its own.
    ways: tuple[Facts, Facts] | None = field(default=None, repr=False, compare=False)

    def stop_message(self) -> str | None:
        """What a user is told when the safety net stopped the analysis (None otherwise)."""
        if self.stopped != "time":
            return None
        return tr(
            "analysis stopped after {seconds:g} s, before its step budget (the "
            "machine running the analysis is slow or busy): the runs are incomplete, so no "
            "verdict that needs a whole run is given (endless or long loop, blocks never "
            "executed, conditions always true or false)",
            seconds=self.time_limit,
        )

    def document(self, uri: str) -> DocumentFacts:
        facts = self.by_uri.get(uri)
        if facts is None:
            facts = self.by_uri[uri] = DocumentFacts()
        return facts


def _feedless(records: Sequence[CutsWithoutFeed]) -> dict[int, FeedlessProgram]:
    out: dict[int, FeedlessProgram] = {}
    # Records that only go on down the text hold no line seen before: the set of lines seen
    # is made only once a record goes back (a loop, a call).
    high = -1
    seen: set[int] | None = None
    for i, cuts in enumerate(records):
        lines = cuts.lines
        new: Sequence[int]
        if seen is None and cuts.ascending and lines[0] > high:
            new = lines
            high = lines[-1]
        else:
            if seen is None:
                seen = set()
                for earlier in records[:i]:
                    seen.update(earlier.lines)
            if seen.isdisjoint(lines):  # done in C
                seen.update(lines)
                new = lines
            else:
                new = _unseen(lines, seen)
        if not new:
            continue
        program = out.get(cuts.program)
        if program is None:
            program = out[cuts.program] = FeedlessProgram(cuts.message, 0, [])
        program.count += len(new)
        wanted = SHOWN_CUTS - len(program.lines)
        if wanted > 0:
            program.lines.extend(new[:wanted])
    return out


def _unseen(lines: Sequence[int], seen: set[int]) -> list[int]:
    fresh: list[int] = []
    for line in lines:
        if line not in seen:
            seen.add(line)
            fresh.append(line)
    return fresh


def _merged(parts: list[dict[K, V]], combine: Callable[[V, V], V]) -> dict[K, V]:
    """One dict of ``parts`` in order: a key in several is ``combine``d, earlier first."""
    nonempty = [p for p in parts if p]
    if not nonempty:
        return {}
    if len(nonempty) == 1:
        return nonempty[0]
    out = dict(nonempty[0])
    for part in nonempty[1:]:
        if out.keys().isdisjoint(part.keys()):  # most stretches: no allocation, in C
            out.update(part)
            continue
        common = out.keys() & part.keys()
        earlier = {k: out[k] for k in common}
        out.update(part)
        for k in common:
            out[k] = combine(earlier[k], part[k])
    return out


def _add(a: int, b: int) -> int:
    return a + b


Write = tuple[int, ValueSummary]


def _then_write(a: Write, b: Write) -> Write:
    return (a[0], a[1].then(b[1]))  # the variable of the first write, as a single run keeps


def _add_jumps(a: JumpCount, b: JumpCount) -> JumpCount:
    return JumpCount(
        a.taken + b.taken,
        a.not_taken + b.not_taken,
        a.undecided + b.undecided,
        a.guessed + b.guessed,
    )


def _add_roundings(a: Rounding, b: Rounding) -> Rounding:
    return Rounding(a.function, a.argument, a.result, a.count + b.count)


# The clause a verdict found with the block-delete switch in one position only ends with.
SWITCH_OFF = " (with the block-delete switch off)"
SWITCH_ON = " (with the block-delete switch on)"


def both_ways(off: Facts, on: Facts) -> Facts:
    """The facts of a run with the block-delete switch off (``off``, every '/' block runs)
    and on (``on``, they are skipped), as one: what the rules, the hover and the inlay hints
    read.

    - A block ran if either run reached it, so a verdict that a block never runs (MB702)
      holds both ways. Its count, values read and written and roundings are the switch-off
      run's, or the switch-on run's at a block only that run reached.
    - The outcomes of a jump or loop condition are added: a condition is constant (MB701)
      only when it is so both ways.
    - A finding of one class at one place in both runs is reported once, with the switch-off
      run's message; a finding of one run only ends with the clause saying which
      (:data:`SWITCH_OFF`, :data:`SWITCH_ON`). So do cuts without F.
    - A program is incomplete if either run stopped in it; the motions, the values at the
      first cut of each run and the toolpath are the switch-off run's.
    """
    out = Facts(
        motions=off.motions,
        steps=off.steps + on.steps,
        run_values=off.run_values,
        record=off.record,
        ways=(off, on),
    )
    reasons = (off.stopped, on.stopped)
    out.stopped = "time" if "time" in reasons else "budget" if "budget" in reasons else None
    out.time_limit = max(off.time_limit, on.time_limit)
    for uri in [*off.by_uri, *(u for u in on.by_uri if u not in off.by_uri)]:
        a = off.by_uri.get(uri) or DocumentFacts()
        b = on.by_uri.get(uri) or DocumentFacts()
        out.by_uri[uri] = _document_both_ways(a, b)
    return out


def _document_both_ways(a: DocumentFacts, b: DocumentFacts) -> DocumentFacts:
    reported = _findings_both_ways(a.reported, b.reported)
    return DocumentFacts(
        runs={**b.runs, **a.runs},
        reads={**b.reads, **a.reads},
        writes={**b.writes, **a.writes},
        jumps=_merged([a.jumps, b.jumps], _add_jumps),
        reported=reported,
        cuts=_cuts_both_ways(a.cuts, b.cuts, len(reported)),
        analysed_programs=a.analysed_programs | b.analysed_programs,
        incomplete_programs=a.incomplete_programs | b.incomplete_programs,
        roundings={**b.roundings, **a.roundings},
        program_ends=a.program_ends or b.program_ends,
        assumed_arguments={**b.assumed_arguments, **a.assumed_arguments},
    )


def _place(f: Finding) -> tuple[object, ...]:
    return (type(f), f.uri, f.line, f.column, f.end_column)


def _findings_both_ways(a: list[Finding], b: list[Finding]) -> list[Finding]:
    """``a``'s findings (switch off) in their order, then those of ``b`` only (switch on)."""
    unmatched: dict[tuple[object, ...], int] = {}
    for f in b:
        key = _place(f)
        unmatched[key] = unmatched.get(key, 0) + 1
    out: list[Finding] = []
    matched: dict[tuple[object, ...], int] = {}
    for f in a:
        key = _place(f)
        left = unmatched.get(key, 0)
        if left:
            unmatched[key] = left - 1
            matched[key] = matched.get(key, 0) + 1
            out.append(f)
        else:
            out.append(
                replace(
                    f, message=tr("{message} (with the block-delete switch off)", message=f.message)
                )
            )
    for f in b:
        key = _place(f)
        taken = matched.get(key, 0)
        if taken:
            matched[key] = taken - 1
        else:
            out.append(
                replace(
                    f, message=tr("{message} (with the block-delete switch on)", message=f.message)
                )
            )
    return out


def _cuts_both_ways(
    a: list[CutsWithoutFeed], b: list[CutsWithoutFeed], findings: int
) -> list[CutsWithoutFeed]:
    """``a``'s records (switch off), each split into the lines ``b`` has too and those it has
    not (their message ends with the clause), then ``b``'s lines of its own (after every
    finding: ``findings`` of them)."""
    if not a and not b:
        return []
    in_a = {line for cuts in a for line in cuts.lines}
    in_b = {line for cuts in b for line in cuts.lines}
    out: list[CutsWithoutFeed] = []
    for cuts in a:
        both = array("i", [line for line in cuts.lines if line in in_b])
        only = array("i", [line for line in cuts.lines if line not in in_b])
        if both:
            out.append(replace(cuts, lines=both))
        if only:
            out.append(
                replace(
                    cuts,
                    lines=only,
                    message=tr(
                        "{message} (with the block-delete switch off)", message=cuts.message
                    ),
                )
            )
    for cuts in b:
        only = array("i", [line for line in cuts.lines if line not in in_a])
        if only:
            out.append(
                replace(
                    cuts,
                    lines=only,
                    message=tr("{message} (with the block-delete switch on)", message=cuts.message),
                    after=findings,
                )
            )
    return out
