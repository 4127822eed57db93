"""What every part of the machine shares: the running program, the modal state, the findings.

:class:`MachineBase` holds the state of a run (the variables, the modal state, the facts) and
what every part reports through (findings, alarms, the step budget's verdict); the parts
(:mod:`.calls`, :mod:`.canned_cycles`, :mod:`.motion`) and :class:`.machine.Machine` derive
from it, so the block loop finds every method on one class.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

from ..cancel import CancelToken
from ..config import SYSTEM_A, Config
from ..program.g_code_systems import INCREMENTAL, translated, written
from ..program.index import Program
from ..program.variables import classify
from ..syntax.tree import Compare, Document, Expr, Statement, Var
from ..syntax.walk import subexpressions
from ..translation import joined, tr
from .checkpoints import CtxKey, Resumption, RunRecord
from .compile_lines import (
    INTEGER_ADDRESSES,
    K_IFGOTO,
    K_WHILE,
    CompiledLine,
    CompiledWord,
    ConstantWords,
)
from .compiler import constant_of
from .facts import (
    ALARM_FINDINGS,
    AddressNotInteger,
    AddressOutOfRange,
    DocumentFacts,
    EndlessLoop,
    Facts,
    Finding,
    JumpCount,
    LongLoop,
    PollingLoop,
    Rounding,
    SkipReadBeforeG31,
    ValueSummary,
)
from .machine_setup import Setup
from .toolpath import NOT_MOVES
from .values import AlarmKind, MacroAlarm, Unknown, Value, fmt

if TYPE_CHECKING:
    from .toolpath import Recorder

# The block end position #5001-#5008 (workpiece coordinates, axis = number - 5000).
BLOCK_END_FIRST, BLOCK_END_LAST = 5001, 5008
# The skip position, #5061-#5080: where the skip signal came on in the last G31, per axis
# (0i-MF Custom Macro, "System variables for position information").
SKIP_FIRST, SKIP_LAST = 5061, 5080
# One-shot moves at rapid, whatever the modal motion: recorded under their own code. G27 goes to
# its words; G28 and G30 pass through them to the reference point, and G53 goes to them in
# machine coordinates, neither of which is known in work coordinates (0i-TF "Reference
# position", "Coordinate system").
RAPID_ONE_SHOTS = frozenset({27.0, 28.0, 30.0, 53.0})
LOCAL_COORDINATES = 52.0  # G52: where the tool is in work coordinates changes, not known here
MAX_MOTIONS = 200_000  # motion records kept per analysis
# A stretch's lists of values read and written, by line (see MachineBase._buffers).
Lists = dict[int, list[object]]
Buffers = tuple[Lists, Lists]
# A list of a block's values and their summaries; the runs counted by its length, the line, and
# the writes or the jumps of the facts when the list holds the block's writes or turns too.
Unsummed = tuple[
    tuple["ValueSummary", ...],
    list[object],
    dict[int, int] | None,
    int,
    "dict[int, tuple[int, ValueSummary]] | None",
    "dict[int, JumpCount] | None",
]


@dataclass(eq=False, repr=False)
class ProgramContext:
    uri: str
    doc: Document
    program: Program
    lines: list[CompiledLine]  # indexed by document line
    loop_end: dict[int, int]  # DO line -> END line
    loop_do: dict[int, int]  # END line -> DO line
    facts: DocumentFacts
    is_main: bool  # ends with M30/M02: locals start vacant, unless it reads them first
    name: str = ""  # O3331, for the motion records

    def __post_init__(self) -> None:
        self.name = self.program.display_name


def run_budget(step_budget: int, contexts: Sequence[ProgramContext]) -> int:
    """Blocks one run may execute: the ``step_budget`` setting, or for documents of more than
    half as many blocks (a posted file read whole), every block once and half the setting
    again for what runs more than once, so that a long program is not taken for an endless
    loop. Counted from the documents, so the same input has the same budget on any machine."""
    documents = {id(c.doc): len(c.doc.blocks) for c in contexts}
    return max(step_budget, sum(documents.values()) + step_budget // 2)


class Activation:
    """One running program: its place, its locals and how it returns."""

    __slots__ = (
        "arguments",
        "caller",
        "ctx",
        "locals",
        "loops_turning",
        "machine",
        "macro_level",
        "modal_depth",
        "pc",
        "repeats_left",
        "return_pc",
        "serial",
        "store",
        "undecided_loops",
    )

    def __init__(
        self,
        machine: MachineBase,
        ctx: ProgramContext,
        locals_: list[Value],
        macro_level: int,
        caller: Activation | None,
        return_pc: int,
        repeats_left: int,
    ) -> None:
        self.machine = machine
        self.ctx = ctx
        self.locals = locals_
        self.store = machine.store
        self.macro_level = macro_level
        self.caller = caller
        self.return_pc = return_pc
        self.repeats_left = repeats_left
        self.pc = ctx.program.first_line
        self.undecided_loops: set[int] = set()
        # The WHILE lines whose condition held at their last test: a turn under way, so that
        # a test that fails is the loop's exit, not an entry that runs no turn.
        self.loops_turning: set[int] = set()
        self.arguments: tuple[Value, ...] | None = None
        machine.runs += 1
        self.serial = machine.runs  # tells one call of a program from the next
        # Index in Modal.modal_calls of the G66 macro this program runs for (None: none). A move
        # here calls the macro specified before it, not itself (FANUC: multiple modal calls).
        self.modal_depth: int | None = None if caller is None else caller.modal_depth

    def read_global(self, number: int) -> Value:
        machine = self.machine
        if SKIP_FIRST <= number <= SKIP_LAST:
            machine._skip_read(self, number)
        if BLOCK_END_FIRST <= number <= BLOCK_END_LAST and machine.toolpath is not None:
            # Where the last NC block sent the axis, when the run follows the tool (see
            # run.tracks_positions); the other position variables stay unknown.
            found = machine.toolpath.block_end(number - 5000)
            if found is not None:
                return found
        return machine.unknown_of(number)

    @property
    def signed_atan(self) -> bool:
        return self.machine.config.atan_signed

    @property
    def length_increment(self) -> float:
        # IS-B: 0.001 mm, 0.0001 inch (G20).
        return 0.0001 if self.machine.modal.inch else 0.001

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        machine = self.machine
        found = self.ctx.facts.roundings
        line = machine._line
        seen = found.get(line)
        if seen is None:
            found[line] = Rounding(name, argument, result)
        else:
            seen.count += 1

    def read_indirect(self, index: Value, node: Var) -> Value:
        if isinstance(index, Unknown):
            return index
        # A vacant index refers to #0, and a fractional one is rounded (both unverified).
        n = 0 if index is None else round(index)
        if n == 0:
            return None
        if 1 <= n <= 33:
            return self.locals[n]
        if classify(n).kind == "none":
            raise MacroAlarm(
                "PS0115",
                AlarmKind.NO_SUCH_VARIABLE,
                tr(
                    "#[...] refers to #{number}, which does not exist (VARIABLE NO. OUT OF RANGE)",
                    number=n,
                ),
                float(n),
            )
        v = self.store.get(n, self)
        # Unknown, not read_global: an indirect read of a position is not one the run is
        # known to need when it chooses to follow the tool (run.tracks_positions).
        return self.machine.unknown_of(n) if v is self else v  # type: ignore[return-value]


def g_name(code: float) -> str:
    """A G code's name: G01, G02, G12.1."""
    return f"G{int(code):02d}" if code == int(code) else f"G{code:g}"


class StopRun(Exception):
    """The run ends here; ``reason`` says why ("budget", "alarm", "end of program"...)."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class Stepper(Protocol):
    """What a debugger puts between the blocks of a run (``Machine.stepper``): it sees each
    block before it runs, and each alarm before the run stops. It may wait there (the run is
    paused) or raise an exception of its own, which ends the run and leaves ``Machine.run``."""

    def before(self, act: Activation, line: int) -> None: ...

    def alarm(self, act: Activation, line: int, message: str) -> None: ...


class Converged(Exception):
    """The resumed run's state, after ``done`` blocks of its run, equals the earlier run's at
    its checkpoint ``index``."""

    def __init__(self, index: int, done: int) -> None:
        super().__init__(index, done)
        self.index = index
        self.done = done


# The spindle's state as the run knows it (Modal.spindle).
SPINDLE_ON = "on"
SPINDLE_OFF = "off"
SPINDLE_TOLD = "told"  # stopped, and a cut with it stopped already reported
SPINDLE_UNKNOWN = "unknown"
# M codes that stop the spindle: M05; M06, the tool change, which orients and stops it for the
# changer (what M06 does is the machine builder's: unverified beyond the machining centres
# whose manuals say so). M19, orientation, stops it too, but for a probe, whose moves feed
# with the spindle still: it leaves the state not known, as other codes do.
SPINDLE_STOPS = frozenset({5.0, 6.0})
SPINDLE_STARTS = frozenset({3.0, 4.0})
# M codes that leave the spindle as it is: the ends and calls, coolant, overrides' on/off.
# Any other (M00 and M01 too, which stop the spindle on some machines, and builders' codes
# such as a live tool's or a sub spindle's) leaves it not known.
SPINDLE_KEEPS = frozenset({2.0, 30.0, 7.0, 8.0, 9.0, 48.0, 49.0, 98.0, 99.0})


@dataclass(eq=False, repr=False)
class Modal:
    motion: float | None = None  # group 01
    feed: Value = None
    speed: Value = None
    constant_surface_speed: bool = False  # G96: S is m/min, not rpm
    # G66/G66.1 in force, in the order specified; G67 cancels the last one. None for a macro
    # the analysis cannot run (not in the analysed files, or its P unknown).
    modal_calls: list[tuple[ProgramContext | None, list[Value], int]] = field(default_factory=list)
    position: dict[str, Value] = field(default_factory=dict)
    # Where each axis was last set: (uri, line), for the verdicts on a cycle's start point.
    position_line: dict[str, tuple[str, int]] = field(default_factory=dict)
    inch: bool = False  # G20
    g76: G76Parameters = field(default_factory=lambda: G76Parameters())
    # G90/G92/G94: the end Z and the taper R in force for a block that repeats the cycle
    # with X alone (0i-TF "Canned cycle for lathe"), as the toolpath draws it.
    cycle: tuple[float | None, float | None] = (None, None)
    # G91 of a lathe in G code system B or C: X and Z are distances, as system A's U and W.
    incremental: bool = False
    # The spindle: SPINDLE_ON, SPINDLE_OFF (stopped by a block of the run), SPINDLE_TOLD
    # (stopped, and a feed move already reported) or SPINDLE_UNKNOWN (at a run's start: a
    # program may be run with the spindle turning); and the block that stopped it.
    spindle: str = "unknown"
    spindle_stop: tuple[str, int, str] | None = None  # uri, line, the M code
    # Z went to the reference point (G28, G30) or to machine zero (G53 Z0): on a mill, the top
    # of its travel, away from the work, until a block moves Z again.
    z_at_top: bool = False
    # The plane, radius compensation, the speed clamp, the tool and its offset, the skip.
    setup: Setup = field(default_factory=Setup)
    # A mill's canned drilling cycle in force (G73, G74, G76, G81-G89: group 09), which a block
    # with an axis word runs instead of the motion of group 01; None after G80 or a code of
    # group 01 (0i-MF "Canned cycle for drilling"); and its Q, the depth of a peck, which stays
    # in force with the cycle's other data (None: not given; NaN: not known).
    drilling: tuple[float, float | None] | None = None


@dataclass(frozen=True)
class G76Parameters:
    """The first block of FANUC's two-block G76, ``G76 P(m)(r)(a) Q(dmin) R(d)``: modal values
    the cutting block uses (FANUC 0i-TF Operator's Manual, "Multiple threading cycle (G76)").
    Without that block the control takes parameters 5142 (m), 5130 (r), 5143 (a), 5140
    (dmin) and 5141 (d); the defaults below stand for them (unverified: machine-dependent)."""

    finishing_passes: int = 1  # m
    chamfer: float = 0.0  # r, in tenths of the lead
    tool_angle: float = 60.0  # a
    min_depth: float = 0.0  # dmin, radius, mm
    finishing_allowance: float = 0.0  # d, radius, mm
    line: int | None = None  # the block that set them


# A system B/C lathe's G codes whose X and Z are not a position to move to, whether in G90 or
# G91 (system A reads them as X and Z too): a dwell's time, data, a setting, machine
# coordinates, a call's arguments.
KEEPS_X_AND_Z = frozenset({4.0, 10.0, 50.0, 50.3, 52.0, 53.0, 65.0, 66.0, 66.1})


def system_a_block(
    values: dict[str, Value], g_codes: Sequence[float], system: str, incremental: bool
) -> tuple[dict[str, Value], Sequence[float], bool]:
    """A block of a system B or C lathe program as system A reads it: its G codes translated
    (program.g_code_systems), in G91 its X and Z as U and W; and whether G91 is in force
    after it. ``values`` is not changed (a constant block's are shared)."""
    g_codes, mode = translated(g_codes, system)
    if mode is not None:
        incremental = mode == INCREMENTAL
    if incremental and KEEPS_X_AND_Z.isdisjoint(g_codes):
        moved = {a: d for a, d in (("X", "U"), ("Z", "W")) if a in values and d not in values}
        if moved:
            values = {moved.get(a, a): v for a, v in values.items()}
    return values, g_codes, incremental


class Appendable(Protocol):
    """What takes the value a block writes or its WHILE's test: a list or a ``RecordNow``."""

    def append(self, value: object, /) -> None: ...


@dataclass(frozen=True, slots=True)
class _Nowhere:
    """What takes the write or turn of a block that has none to record."""

    def append(self, value: object, /) -> None:
        pass


_NOWHERE = _Nowhere()


class RecordNow:
    """What takes the write of a block's first run in a stretch of facts, or its WHILE's
    turn, where later runs' go to its list: the facts themselves."""

    __slots__ = ("facts", "line", "number")

    def __init__(self, facts: DocumentFacts, line: int, number: int | None) -> None:
        self.facts = facts
        self.line = line
        self.number = number  # the variable written; None: a WHILE

    def append(self, value: object, /) -> None:
        if self.number is not None:
            MachineBase._write_now(self.facts, self.line, self.number, value)  # type: ignore[arg-type]
        elif value is True:  # a turn; None: counted by Machine._while
            self.facts.jump_count(self.line).taken += 1


class MachineBase:
    """The state of a run and what its parts report through."""

    def _set_lathe(self, lathe: bool) -> None:
        self.lathe = lathe  # asked at every block
        # The G codes a block with axis words runs instead of the modal motion: no move
        # (NOT_MOVES, G52, the coordinate system setting: G50 on a lathe, G92 on a mill; a
        # lathe's G92 is its threading cycle), or a one-shot move of its own.
        self._own_codes = NOT_MOVES | RAPID_ONE_SHOTS | {LOCAL_COORDINATES, 50.0 if lathe else 92.0}

    def use_machine_of(self, entry: ProgramContext) -> None:
        """Run as the machine of ``entry``'s program: a called program runs on its caller's."""
        if not self._program_lathe:
            return
        lathe = self._program_lathe.get((entry.uri, entry.program.first_line), self.config_lathe)
        if lathe != self.lathe:
            self._set_lathe(lathe)

    def __init__(
        self,
        programs: dict[int, ProgramContext],
        config: Config,
        facts: Facts,
        contexts: Sequence[ProgramContext] = (),
        cancel: CancelToken | None = None,
    ) -> None:
        self.programs = programs
        self.cancel = cancel
        # Every program, by document and first line: what a checkpoint names them by.
        self.contexts: dict[CtxKey, ProgramContext] = {
            (c.uri, c.program.first_line): c for c in contexts
        }
        self.record: RunRecord | None = None  # checkpoints are taken when set
        self.resumption: Resumption | None = None  # the earlier run a resumed one may meet
        self.run_index = 0  # which run of the evaluation is under way
        self._checkpointed = 0  # blocks done in this run at its last checkpoint
        self.config = config
        self.facts = facts
        self.store: dict[int, Value] = {}
        self._unknowns: dict[int, Unknown] = {}
        self._seen_findings: set[tuple[str, str, int, int]] = set()  # kind, uri, line, column
        # What the checkpoints hold of them: the chunks so far, and the keys since the last.
        self._seen_chunks: tuple[frozenset[tuple[str, str, int, int]], ...] = ()
        self._seen_since: list[tuple[str, str, int, int]] = []
        # The lines of cuts without F recorded in this stretch of the run, by document: each
        # stretch lists a line once, and depends on nothing before it but the state.
        self._cuts_seen: dict[str, set[int]] = {}
        self.steps = 0
        self._steps = 0
        self.speculative = False
        self.deadline = 0.0
        self.budget = run_budget(config.step_budget, contexts)
        self.runs = 0  # activations so far: each gets its number
        self.modal = Modal()
        self.value_range = config.value_range
        self._entry_name = ""
        # The machine of each entry program of a file that holds a lathe's and a mill's
        # programs (program.machine_kind); any other runs as the configured one.
        self._program_lathe = {(uri, line): lathe for uri, line, lathe in config.program_machines}
        self.config_lathe = config.is_lathe
        # A lathe's G code system B or C: its blocks are translated to system A's codes.
        self.other_g_code_system = config.g_code_system != SYSTEM_A
        self._set_lathe(config.is_lathe)
        # The message of a move without F, by motion code: the same for every block of a run.
        self._no_feed: dict[float, str] = {}
        # The motions' words made by the run (a block of computed words, an F added), by
        # content: most blocks of a long program move to one of few places, and the motions
        # that go alike share one dict (nothing changes a motion's words once recorded).
        self._words: dict[tuple[object, ...], dict[str, float]] = {}
        # The words of the constant block being run, when made from its motion's words (a
        # plain block keeps no dict of them): _move_words takes its motion's words as they are.
        self._values_of: ConstantWords | None = None
        self._const_values: dict[str, Value] | None = None
        # The toolpath's recorder, when one is asked for (see evaluate) or the programs read
        # the block end position: None costs a run one test per NC block.
        self.toolpath: Recorder | None = None
        # A debugger's hook between blocks (None: no cost but one test per block).
        self.stepper: Stepper | None = None
        # A G70-G73 with P and Q met by _motion, for _nc to follow its profile.
        self._profile_code: float | None = None
        self._profile_blocks = 0  # blocks of profiles read or run in this run
        self._line = 0  # the block being executed, for the facts and findings
        # Values read and written not yet in their summaries (see _buffers).
        self._buffers_of: dict[DocumentFacts, Buffers] = {}
        self._unsummed: list[Unsummed] = []

    def unknown_of(self, number: int) -> Unknown:
        u = self._unknowns.get(number)
        if u is None:
            u = self._unknowns[number] = Unknown(frozenset({number}))
        return u

    def _document_so_far(self, ctx: ProgramContext) -> DocumentFacts:
        """The facts of ``ctx``'s document from every stretch of the evaluation so far."""
        record = self.record
        if record is None:
            return ctx.facts
        merged = ctx.facts.segment()
        merged.take_segments([s[ctx.uri] for s in record.segments if ctx.uri in s])
        return merged

    def _finding(self, ctx: ProgramContext, finding: Finding) -> None:
        """Report ``finding`` of ``ctx``'s document, once per kind and place in the evaluation."""
        key = (finding.kind, finding.uri, finding.line, finding.column)
        seen = self._seen_findings
        if key in seen:
            return
        seen.add(key)
        self._seen_since.append(key)
        ctx.facts.reported.append(finding)

    def _block_finding(
        self, act: Activation, kind: Callable[..., Finding], message: str, **kw: str
    ) -> None:
        """A finding of ``kind`` on the whole of the block being run."""
        ctx = act.ctx
        width = len(ctx.doc.blocks[self._line].text.rstrip())
        self._finding(ctx, kind(self._line, 0, width, message, ctx.uri, **kw))

    def _where(self, act: Activation, at: tuple[str, int]) -> str:
        """A block as a message names it: its line, and its document if not ``act``'s."""
        uri, line = at
        if uri == act.ctx.uri:
            return tr("line {line}", line=line + 1)
        return tr("line {line} of {uri_text}", line=line + 1, uri_text=uri)

    def _shown(self, code: float) -> str:
        """A motion code as the program writes it (a system B or C lathe's own number)."""
        name = g_name(code)
        if self.other_g_code_system and self.lathe:
            return written(name, self.config.g_code_system)
        return name

    def _skip_read(self, act: Activation, number: int) -> None:
        """A read of the skip position before any G31 of the run: it holds the last skip's
        result on the machine, from another program or none."""
        if self.modal.setup.skipped is False:
            self._block_finding(
                act,
                SkipReadBeforeG31,
                tr(
                    "#{number} (the skip position) is read before any G31 of this run: it "
                    "holds where an earlier program's skip stopped, not this program's "
                    "measurement",
                    number=number,
                ),
            )

    @staticmethod
    def _mark_incomplete(act: Activation | None) -> None:
        """Programs on the call stack when a run stops early: their unrun blocks prove nothing."""
        while act is not None:
            act.ctx.facts.incomplete_programs.add(act.ctx.program.first_line)
            act = act.caller

    def _values_read(self, act: Activation, cl: CompiledLine) -> dict[int, Value]:
        """What the block's direct variables hold as it runs (the toolpath's runs only: no
        block of a diagnostics run asks). The block's motion assigns none of them."""
        locals_ = act.locals
        store = self.store
        out: dict[int, Value] = {}
        for n in cl.reads:
            if n <= 33:
                out[n] = locals_[n]
            else:
                v = store.get(n, act)
                out[n] = self.unknown_of(n) if v is act else v  # type: ignore[assignment]
        return out

    # What a block runs again in a stretch of facts (a loop's blocks) is kept in lists, one
    # per block, and added to the summaries at once when the stretch ends, when the run stops
    # and before anything reads them (``_flush_values``): a list's append costs a tenth of a
    # summary's ``add``. A block's first run in the stretch is recorded at once, as before,
    # which makes the facts' keys in their order; later runs go to the lists: the values read
    # and then written (``writes_after_reads``) or the WHILE's test (``turns_after_reads``),
    # the list's length counting the runs of a block that reads variables.

    def _buffers(self, facts: DocumentFacts) -> Buffers:
        """The lists of the values read and written, by line, of ``facts`` (the block loop
        keeps those of the facts it is recording)."""
        found = self._buffers_of.get(facts)
        if found is None:
            found = self._buffers_of[facts] = ({}, {})
        return found

    def _first_reads(
        self, buffers: Buffers, facts: DocumentFacts, line: int, cl: CompiledLine, act: Activation
    ) -> Appendable:
        """The run of a block that reads variables and has no list yet: its first in the
        stretch, recorded at once with its reads, or a later one, which begins its list. What
        takes this run's write or turn (see _buffers): the list, or a ``RecordNow``."""
        runs = facts.runs
        if line in runs:
            found = self._read_buffer(buffers[0], facts, line, cl)
            self._read_into(act, cl, found)
            return found
        runs[line] = 1
        self._add_reads(act, cl, facts, line)
        if cl.writes_after_reads:
            return RecordNow(facts, line, cl.local_target)
        if cl.turns_after_reads:
            return RecordNow(facts, line, None)
        return _NOWHERE

    def _write(
        self, buffers: Buffers, facts: DocumentFacts, line: int, number: int, value: Value
    ) -> None:
        """A write of ``value`` to #``number`` at ``line`` not kept with its reads: to its
        list, or if none yet, at once (its first in the stretch) or to a new list."""
        found = buffers[1].get(line)
        if found is not None:
            found.append(value)
        elif line in facts.writes:
            self._write_buffer(buffers[1], facts, line, number).append(value)
        else:
            self._write_now(facts, line, number, value)

    @staticmethod
    def _write_now(facts: DocumentFacts, line: int, number: int, value: Value) -> None:
        write = facts.writes.get(line)
        if write is None:
            write = facts.writes[line] = (number, ValueSummary())
        write[1].add(value)

    def _read_buffer(
        self, buffers: dict[int, list[object]], facts: DocumentFacts, line: int, cl: CompiledLine
    ) -> list[object]:
        """The list of the values ``cl`` reads at ``line``, each run's in the order of
        ``cl.reads``, and then the value it writes (``cl.writes_after_reads``) or whether its
        test held (``cl.turns_after_reads``: True, None when counted in the jumps already),
        with their summaries; the runs it counts are added to ``facts.runs`` with them."""
        runs = facts.runs
        reads = facts.reads
        summaries: list[ValueSummary] = []
        for n in cl.reads:
            key = (line, n)
            summary = reads.get(key)
            if summary is None:
                summary = reads[key] = ValueSummary()
            summaries.append(summary)
        writes = None
        if cl.writes_after_reads:
            writes = facts.writes
            write = writes.get(line)
            if write is None:
                write = writes[line] = (cl.local_target, ValueSummary())
            summaries.append(write[1])
        jumps = None
        if cl.turns_after_reads:
            jumps = facts.jumps
            if line not in jumps:
                jumps[line] = JumpCount()
        found = buffers[line] = []
        self._unsummed.append((tuple(summaries), found, runs, line, writes, jumps))
        return found

    def _write_buffer(
        self, buffers: dict[int, list[object]], facts: DocumentFacts, line: int, number: int
    ) -> list[object]:
        """The list of the values written at ``line``, with its summary."""
        write = facts.writes.get(line)
        if write is None:
            write = facts.writes[line] = (number, ValueSummary())
        found = buffers[line] = []
        self._unsummed.append(((write[1],), found, None, line, None, None))
        return found

    def _flush_values(self) -> None:
        """Add the values kept in lists to their summaries."""
        unsummed = self._unsummed
        if not unsummed:
            return
        for summaries, values, runs, line, write_facts, jumps in unsummed:
            count = len(summaries)
            stride = count if jumps is None else count + 1
            size = len(values)
            if size <= stride:  # one run: most blocks of a stretch
                if runs is not None:
                    runs[line] += 1
                for summary, value in zip(summaries, values, strict=False):
                    summary.add(value)  # type: ignore[arg-type]
            else:
                if runs is not None:
                    # Each run's values; the last one's write or test is missing when an
                    # alarm stopped the run in its block.
                    runs[line] += (size + stride - 1) // stride
                if stride == 1:
                    summaries[0].add_all(values)  # type: ignore[arg-type]
                else:
                    for i, summary in enumerate(summaries):
                        summary.add_all(values[i::stride])  # type: ignore[arg-type]
            # What a list made for a run that an alarm stopped before its write or test goes
            # (no summary or count of the facts is ever empty).
            if write_facts is not None and not summaries[-1].count:
                del write_facts[line]
            if jumps is not None:
                jc = jumps[line]
                jc.taken += values[count::stride].count(True)
                if not (jc.taken or jc.not_taken or jc.undecided):
                    del jumps[line]
        unsummed.clear()
        for reads, writes in self._buffers_of.values():
            reads.clear()
            writes.clear()

    def _read_into(self, act: Activation, cl: CompiledLine, found: list[object]) -> None:
        """What the block's direct variables hold, added to ``found`` in order."""
        locals_ = act.locals
        store = self.store
        for n in cl.reads:
            if n <= 33:
                found.append(locals_[n])
            else:
                v = store.get(n, act)
                found.append(act.read_global(n) if v is act else v)

    def _record_reads(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> None:
        """The reads of a block counted in ``facts.runs`` already (a profile's), after those
        kept in lists."""
        self._flush_values()
        self._add_reads(act, cl, facts, self._line)

    def _add_reads(
        self, act: Activation, cl: CompiledLine, facts: DocumentFacts, line: int
    ) -> None:
        reads = facts.reads
        locals_ = act.locals
        store = self.store
        for n in cl.reads:
            key = (line, n)
            summary = reads.get(key)
            if summary is None:
                summary = reads[key] = ValueSummary()
            if n <= 33:
                summary.add(locals_[n])
            else:
                v = store.get(n, act)
                summary.add(act.read_global(n) if v is act else v)  # type: ignore[arg-type]

    @staticmethod
    def _label(ctx: ProgramContext, seq: int, from_line: int) -> int | None:
        return ctx.program.label_line(seq, from_line)

    def _check_addresses(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]],
        calls: bool = False,
        d_is_data: bool = False,
    ) -> None:
        # ``calls``: P is a program or sequence number (M98, M99, G65: a whole number); with
        # G04 it is a dwell. ``d_is_data``: D is a cycle's depth, not an offset number; whether
        # FANUC takes a decimal point there is unverified, so it is not checked.
        for address, v, w in order:
            if isinstance(v, Unknown) or v is None or (d_is_data and address == "D"):
                continue
            if (address in INTEGER_ADDRESSES or (address == "P" and calls)) and v != int(v):
                message = tr(
                    "{address} gets {value}: {address} takes a whole number",
                    address=address,
                    value=fmt(v),
                )
                self._finding(
                    act.ctx,
                    AddressNotInteger(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address == "G" and round(v, 1) != v:
                message = tr("G gets {value}: not a G code", value=fmt(v))
                self._finding(
                    act.ctx,
                    AddressNotInteger(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address in ("S", "T", "M", "H", "D", "F") and v < 0:
                message = tr(
                    "{address} gets {value}: {address} cannot be negative",
                    address=address,
                    value=fmt(v),
                )
                self._finding(
                    act.ctx,
                    AddressOutOfRange(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address == "S" and v > self.config.max_spindle_speed:
                message = tr(
                    "S gets {speed} rpm, above the machine's maximum {maximum} rpm",
                    speed=fmt(v),
                    maximum=fmt(self.config.max_spindle_speed),
                )
                self._finding(
                    act.ctx,
                    AddressOutOfRange(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )

    def _alarm(self, act: Activation, cl: CompiledLine, alarm: MacroAlarm) -> str:
        ctx = act.ctx
        block = ctx.doc.blocks[self._line]
        node = alarm.node
        span = getattr(node, "span", None) or getattr(cl.node, "span", None)
        start, end = (span.start, span.end) if span is not None else (0, len(block.text))
        expression: str | None = None
        shown: list[str] = []
        if node is not None:
            args = getattr(node, "args", None) or (getattr(node, "right", None),)
            arg = args[0]
            if arg is not None:
                expression = block.source(arg.span).strip()
                for sub in subexpressions(arg):
                    if isinstance(sub, Var) and sub.number is not None:
                        n = int(sub.number)
                        v = act.locals[n] if 1 <= n <= 33 else self.store.get(n)
                        text = f"#{n}={fmt(v)}"
                        if text not in shown:
                            shown.append(text)
        said: dict[str, object] = {
            "alarm_message": alarm.message,
            "number": alarm.alarm,
            "program": ctx.name,
        }
        if expression is None:
            message = tr("{alarm_message} (alarm {number}) in {program}", **said)
        elif not shown:
            message = tr(
                "{alarm_message} = {expression_text} (alarm {number}) in {program}",
                expression_text=expression,
                **said,
            )
        else:
            message = tr(
                "{alarm_message} = {expression_text} with {values_text} (alarm {number}) in "
                "{program}",
                expression_text=expression,
                values_text=", ".join(shown),
                **said,
            )
        found = ALARM_FINDINGS[alarm.kind]
        self._finding(
            ctx,
            found(self._line, start, end, message, ctx.uri, alarm=alarm.kind, number=alarm.alarm),
        )
        return message

    def _budget_spent(self, act: Activation) -> None:
        self._flush_values()  # the verdict reads the summaries
        ctx = act.ctx
        facts = self._document_so_far(ctx)
        program = ctx.program
        top = max((n for ln, n in facts.runs.items() if program.contains(ln)), default=0)
        hot = sorted(ln for ln, n in facts.runs.items() if program.contains(ln) and n * 2 >= top)
        tests = [ln for ln in hot if ctx.lines[ln].kind in (K_IFGOTO, K_WHILE)]
        loops = program.enclosing_loops(act.pc)
        if loops:
            head = loops[-1].do_line
        elif tests:
            head = tests[0]
        else:  # a GOTO back with no test: the loop begins at its label
            heads = [
                target
                for jump in program.jumps
                if not jump.conditional
                and jump.target is not None
                and jump.line in facts.runs
                and (target := program.label_line(jump.target, jump.line)) is not None
                and target <= act.pc <= jump.line
            ]
            head = min(heads, default=act.pc)
        read = {n for ln in tests for n in ctx.lines[ln].reads}
        written = {ctx.lines[ln].target_number for ln in hot}
        budget = tr("the step budget ({blocks:,} blocks)", blocks=self.budget)
        runs = facts.runs.get(head, 0)
        width = len(ctx.doc.blocks[head].text)
        if read and all(n >= 100 for n in read) and not read & written:
            # Nothing in the loop changes what it tests: it waits for the PMC, a FOCAS client
            # or another path to write a common or system variable.
            names = ", ".join(f"#{n}" for n in sorted(read))
            message = tr(
                "loop waits for {names} to be changed from outside the program (PMC, FOCAS, "
                "another path): nothing in it writes {names}; the analysis stopped after {runs} "
                "turns ({budget})",
                names=names,
                runs=runs,
                budget=budget,
            )
            self._finding(ctx, PollingLoop(head, 0, width, message, ctx.uri))
            return
        cl = ctx.lines[head]
        still = [n for n in cl.reads if (s := facts.reads.get((head, n))) and s.constant]
        approaching = _approaching(cl.node, facts, head)
        if not still and approaching:
            # The test's variables move towards its bound: a long loop, not an endless one.
            message = tr(
                "loop still running after {runs} turns when {budget} ran out: it gets nearer "
                "its end every turn, so it is long rather than endless; values after it are not "
                "analysed",
                runs=runs,
                budget=budget,
            )
            self._finding(ctx, LongLoop(head, 0, width, message, ctx.uri))
            return
        moving = [n for n in cl.reads if n not in still]
        if still:
            why = joined(
                ", ",
                (
                    tr("#{number} stays {value}", number=n, value=fmt(facts.reads[(head, n)].first))
                    for n in still
                ),
            )
        elif moving:
            why = tr(
                "the condition stays true, {names} moving away from its bound",
                names=", ".join(f"#{n}" for n in moving),
            )
        else:
            why = tr("nothing in the condition changes")
        message = tr(
            "loop never ends: the block ran {runs} times before {budget} ran out; {why}",
            runs=runs,
            budget=budget,
            why=why,
        )
        self._finding(ctx, EndlessLoop(head, 0, width, message, ctx.uri))


def _approaching(node: Statement | None, facts: DocumentFacts, line: int) -> bool:
    """Whether a loop test ``#v OP bound`` is nearer its bound at the last turn than the first."""
    cond = getattr(node, "cond", None)
    if not isinstance(cond, Compare) or cond.op in ("EQ", "NE"):
        return False
    distances = []
    for side, other in ((cond.left, cond.right), (cond.right, cond.left)):
        if isinstance(side, Var) and side.number is not None:
            summary = facts.reads.get((line, int(side.number)))
            bound = _fixed(other, facts, line)
            if summary is None or bound is None:
                continue
            first, last = summary.first, summary.last
            if isinstance(first, float) and isinstance(last, float):
                distances.append((abs(first - bound), abs(last - bound)))
    return bool(distances) and all(last < first for first, last in distances)


def _fixed(expr: Expr, facts: DocumentFacts, line: int) -> float | None:
    value = constant_of(expr)
    if value is not None:
        return value
    if isinstance(expr, Var) and expr.number is not None:
        summary = facts.reads.get((line, int(expr.number)))
        if summary is not None and summary.constant:
            return float(summary.minimum)
    return None
