"""What the evaluator learned: per block runs, values read and written, jumps, motions, findings.

These are the facts the rules, the hover and the inlay hints read. They carry no LSP types.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .values import Unknown, Value, fmt


class ValueSummary:
    """The values one variable had at one block over every execution."""

    __slots__ = ("count", "first", "last", "maximum", "minimum", "unknown", "vacant")

    def __init__(self) -> None:
        self.count = 0
        self.first: Value = None
        self.last: Value = None
        self.minimum = float("inf")
        self.maximum = float("-inf")
        self.vacant = 0
        self.unknown: Unknown | None = None

    def add(self, value: Value) -> None:
        if self.count == 0:
            self.first = value
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

    @property
    def numeric(self) -> bool:
        return self.minimum <= self.maximum

    @property
    def constant(self) -> bool:
        return self.numeric and self.minimum == self.maximum and self.vacant == 0

    def describe(self) -> str:
        """``1.907`` or ``0.092 → 1.887 (88 values, min 0.092, max 1.887)``."""
        if self.count == 0:
            return "never evaluated"
        if self.count == 1 or (self.constant and self.unknown is None):
            return fmt(self.first)
        if not self.numeric:
            return fmt(self.last)
        text = (
            f"{fmt(self.first)} → {fmt(self.last)} ({self.count} times, min "
            f"{fmt(self.minimum)}, max {fmt(self.maximum)})"
        )
        if self.vacant:
            text += f", vacant {self.vacant} times"
        return text


@dataclass(slots=True)
class Motion:
    program: str
    line: int
    code: str
    words: dict[str, float]
    uri: str = ""
    x: float | None = None  # the diameter the move or cut reaches (G32 Z-only: where it is)
    rpm: float | None = None  # spindle speed in G97 (None in G96 or unknown)
    program_line: int = 0  # first line of the program the motion belongs to
    z: float | None = None  # the Z the move or cut ends at
    # Where the tool stood before the block: a cycle's start point, to which it returns.
    start_x: float | None = None
    start_z: float | None = None
    start_line: int | None = None  # the block that put the tool at start_x
    start_uri: str = ""
    run: int = 0  # which execution of its program: every call is a new one
    cycle_pass: int = 0  # G76: the pass number within its cycle (0: not a G76 pass)
    finishing: bool = False  # G76: a finishing pass at the full thread height


@dataclass(slots=True)
class Rounding:
    """FIX or FUP of a value a hair off a whole number: 7.9999999999 truncated to 7."""

    function: str
    argument: float
    result: float
    count: int = 1


@dataclass
class Finding:
    """Something to report at a block: an alarm, a bad address value, a loop that never ends."""

    kind: str
    line: int
    column: int
    end_column: int
    message: str
    uri: str = ""
    related_line: int | None = None
    related_message: str = ""


@dataclass(slots=True)
class JumpCount:
    taken: int = 0
    not_taken: int = 0
    undecided: int = 0
    guessed: int = 0  # decided, but on a path that went through an undecided condition


@dataclass
class DocumentFacts:
    """Facts about one document's blocks, across every run that reached them."""

    runs: dict[int, int] = field(default_factory=dict)
    reads: dict[tuple[int, int], ValueSummary] = field(default_factory=dict)
    writes: dict[int, tuple[int, ValueSummary]] = field(default_factory=dict)
    jumps: dict[int, JumpCount] = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)
    analysed_programs: set[int] = field(default_factory=set)  # first lines of programs run
    incomplete_programs: set[int] = field(default_factory=set)  # runs that stopped early
    roundings: dict[int, Rounding] = field(default_factory=dict)  # line -> the first such
    # first line of a program -> its first block with M30 or M02 (block skip or not)
    program_ends: dict[int, int] = field(default_factory=dict)
    # Programs ending with M30 run on their own with unknown arguments, because they read
    # locals before setting them: first line -> (local, line of its first read), in text order.
    assumed_arguments: dict[int, tuple[tuple[int, int], ...]] = field(default_factory=dict)

    def jump_count(self, line: int) -> JumpCount:
        count = self.jumps.get(line)
        if count is None:
            count = self.jumps[line] = JumpCount()
        return count

    def read_summary(self, line: int, number: int) -> ValueSummary | None:
        return self.reads.get((line, number))

    def write_summary(self, line: int) -> tuple[int, ValueSummary] | None:
        return self.writes.get(line)


@dataclass(frozen=True, slots=True)
class RunValues:
    """The variables of one execution of a program when it began to cut a thread: what the
    threading rules read a module's inputs from when it is called more than once."""

    locals: tuple[Value, ...]  # #0-#33
    globals: dict[int, Value]

    def value(self, number: int) -> float | None:
        v = self.locals[number] if number <= 33 else self.globals.get(number)
        return v if isinstance(v, float) else None


@dataclass
class Facts:
    by_uri: dict[str, DocumentFacts] = field(default_factory=dict)
    motions: list[Motion] = field(default_factory=list)
    steps: int = 0
    # Why a run stopped early: "budget" (the step budget), "time" (the safety net), or None.
    stopped: str | None = None
    time_limit: float = 0.0  # the safety net's seconds, when it stopped a run
    run_values: dict[int, RunValues] = field(default_factory=dict)  # run -> at its first cut

    def stop_message(self) -> str | None:
        """What a user is told when the safety net stopped the analysis (None otherwise)."""
        if self.stopped != "time":
            return None
        return (
            f"analysis stopped after {self.time_limit:g} s, before its step budget (the "
            "machine running the analysis is slow or busy): the runs are incomplete, so no "
            "verdict that needs a whole run is given (endless or long loop, blocks never "
            "executed, conditions always true or false)"
        )

    def document(self, uri: str) -> DocumentFacts:
        facts = self.by_uri.get(uri)
        if facts is None:
            facts = self.by_uri[uri] = DocumentFacts()
        return facts
