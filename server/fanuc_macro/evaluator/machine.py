"""Running programs as the control would: blocks, jumps, loops, calls, modal state.

The run starts from each entry program (one nothing calls; a file's first) with a step and a
time budget, and records facts (:mod:`.facts`) as it goes. Values the analysis cannot know are
:class:`Unknown`; a branch on an unknown condition takes the fall-through path (and a WHILE on
an unknown condition runs its body once), so a program analysed alone still gets its values.
"""

from __future__ import annotations

import math
import re
import sys
import time
import zlib
from array import array
from bisect import bisect_left
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

from ..cancel import RUNNING, CancelToken
from ..config import Config
from ..line_maps import LineMap
from ..program.index import Program, ProgramIndex
from ..program.variables import ARGUMENT_VARIABLES, classify
from ..syntax.marks import constant_value
from ..syntax.tree import (
    Assign,
    Bracket,
    Compare,
    Document,
    End,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    Mixed,
    NcStatement,
    Num,
    ParsedLine,
    PlainNc,
    ProgramStart,
    Statement,
    Unary,
    Var,
    While,
)
from ..syntax.walk import subexpressions, top_expressions
from .checkpoints import CtxKey, LevelState, MachineState, ModalState, Resumption, RunRecord
from .compiler import CondEvaluator, Evaluator, compile_cond, compile_expr, constant_of, kept
from .cycles import g76_depths
from .facts import (
    ALARM_FINDINGS,
    AddressNotInteger,
    AddressOutOfRange,
    CutsWithoutFeed,
    DocumentFacts,
    EndlessLoop,
    Facts,
    Finding,
    LongLoop,
    Motion,
    PollingLoop,
    ProgramNotFound,
    Rounding,
    RunValues,
    ValueSummary,
)
from .toolpath import NOT_MOVES, ProfileBlock, Recorder
from .values import UNKNOWN, AlarmKind, MacroAlarm, Unknown, Value, fmt

# Block kinds of the compiled program.
K_EMPTY, K_ASSIGN, K_GOTO, K_IFGOTO, K_IFTHEN, K_WHILE, K_END, K_NC, K_HEADER, K_OTHER = range(10)

MOTION_GROUP = {0.0, 1.0, 2.0, 3.0, 32.0, 33.0, 34.0}
LATHE_CYCLES = {90.0, 92.0, 94.0}  # G-code system A: modal canned cycles of group 01
ONE_SHOT_CYCLES = {70.0, 71.0, 72.0, 73.0, 74.0, 75.0, 76.0}  # group 00: they do not repeat
# The lathe's cycles that name a profile N(ns)..N(nf) by P and Q: G71-G73 read it, G70 runs it.
PROFILE_CYCLES = frozenset({70.0, 71.0, 72.0, 73.0})
# What a block of the profile may not hold for the evaluator to follow it: calls, returns, ends,
# the cycles themselves (FANUC forbids M98/M99 and the one-shot cycles in a profile: 0i-TF
# "Multiple repetitive cycle", limitations).
NOT_IN_PROFILE_G = frozenset({65.0, 66.0, 66.1, 70.0, 71.0, 72.0, 73.0, 74.0, 75.0, 76.0})
NOT_IN_PROFILE_M = frozenset({2.0, 30.0, 98.0, 99.0, 198.0})
# The block end position #5001-#5008 (workpiece coordinates, axis = number - 5000).
BLOCK_END_FIRST, BLOCK_END_LAST = 5001, 5008
AXES = frozenset("XYZUVWABC")
# Addresses whose values are lengths or angles in the least input increment (ROUND in them
# rounds to that increment); the others take whole numbers.
LENGTH_ADDRESSES = frozenset("XYZUVWABCIJKRQF")
FEED_MOTIONS = {1.0, 2.0, 3.0}  # cutting moves at the modal F (G32 and the cycles take F as lead)
# One-shot moves at rapid, whatever the modal motion: recorded under their own code. G27 goes to
# its words; G28 and G30 pass through them to the reference point, and G53 goes to them in
# machine coordinates, neither of which is known in work coordinates (0i-TF "Reference
# position", "Coordinate system").
RAPID_ONE_SHOTS = frozenset({27.0, 28.0, 30.0, 53.0})
LEFT_UNKNOWN = frozenset({28.0, 30.0, 53.0})
LOCAL_COORDINATES = 52.0  # G52: where the tool is in work coordinates changes, not known here
INTEGER_ADDRESSES = frozenset("MSTLHD")  # P too, when it names a program (M98, G65, M99)
MAX_MACRO_LEVEL = 5  # G65/G66 levels (0i-D/30i); 16i has 4
MAX_NESTING = 10
MAX_MOTIONS = 200_000  # motion records kept per analysis
MAX_SHARED_WORDS = 4096  # distinct motion words a run looks up to share (Machine._words)
THREADING_CODES = frozenset({32.0, 33.0, 34.0, 76.0, 92.0})
# The lathe's moves that cut at F besides G01-G03: threads (F the lead), turning and facing.
LATHE_FED = frozenset({32.0, 33.0, 34.0, 76.0, 90.0, 92.0, 94.0})
MAX_REMEMBERED_RUNS = 1000  # executions whose variables are kept when they start a thread
CHECK_EVERY = 1024  # blocks between two looks at the budgets and a newer edit
# Blocks between two checkpoints (at the next boundary line): a resumed run re-runs about
# this many blocks before an edit and after it, and each checkpoint costs a capture of the
# state and a stretch of facts.
CHECKPOINT_EVERY = 256


@dataclass(slots=True, eq=False, repr=False)
class CompiledWord:
    address: str
    evaluate: Evaluator
    start: int
    end: int
    decimal_point: bool = False  # written as a number with a decimal point (``Q0.4``)


@dataclass(slots=True)
class CompiledLine:
    kind: int
    reads: tuple[int, ...] = ()  # direct variables the block reads (for the facts)
    target: Evaluator | None = None  # assignment target index (indirect) or GOTO target
    target_number: int | None = None  # direct assignment target
    value: Evaluator | None = None
    cond: CondEvaluator | None = None
    words: tuple[CompiledWord, ...] = ()
    nc: NcStatement | None = None
    node: Statement | None = None
    second: CompiledLine | None = None  # the macro part of a mixed block
    constant: ConstantWords | None = None  # an NC block whose words are all constants
    ends_program: bool = False  # M02/M30: the program is a main program
    # One line in eight, by its text: where the run may take a checkpoint (see Machine._loop).
    boundary: bool = False


@dataclass(slots=True)
class ConstantWords:
    """What an NC block of constant words evaluates to, worked out once at compile time.
    Most blocks of a long program are such; nothing here is mutated by a run."""

    values: dict[str, Value]
    g_codes: tuple[float, ...]
    m_codes: tuple[float, ...]
    nc: NcStatement
    # The words' values, in the order of the block; None when each is its Num's value.
    constants: tuple[float, ...] | None
    words: dict[str, float]  # the motion record's words
    has_axis: bool
    # No word can get an address finding (MB5xx: whole numbers, G codes, signs, the spindle's
    # maximum), whatever the settings: the run need not look at them.
    quiet: bool = False
    _order: list[tuple[str, Value, CompiledWord]] | None = field(default=None, compare=False)

    @property
    def order(self) -> list[tuple[str, Value, CompiledWord]]:
        """Each word: its address, value and compiled word. Made when a run first asks (a
        block with a call, a G76, a word to check): most blocks never need it."""
        order = self._order
        if order is None:
            words = self.nc.words
            constants = self.constants
            values = [w.value.value for w in words] if constants is None else constants  # type: ignore[union-attr]
            order = self._order = [
                (
                    w.address,
                    v,
                    _folded_word(
                        w.address, w.span.start, w.span.end, _written_with_decimal_point(w.value)
                    ),
                )
                for w, v in zip(words, values, strict=True)
            ]
        return order


def _direct_reads(statement: Statement) -> tuple[int, ...]:
    numbers: list[int] = []
    skip_target: Var | None = None
    if isinstance(statement, Assign):
        skip_target = statement.target
    elif isinstance(statement, IfThen):
        skip_target = statement.then.target
    for top in top_expressions(statement):
        for node in subexpressions(top):
            if node is skip_target:
                continue
            if (
                isinstance(node, Var)
                and node.number is not None
                and node.number == int(node.number)
            ):
                n = int(node.number)
                if n and n not in numbers:
                    numbers.append(n)
    return tuple(numbers)


def _compile_assign(kind: int, assign: Assign, text: str | None) -> CompiledLine:
    target = assign.target
    compiled = CompiledLine(kind, value=_compile_word(assign.value, False, text), node=assign)
    if target.number is not None:
        compiled.target_number = int(target.number) if target.number == int(target.number) else -1
    else:
        assert target.index is not None
        compiled.target = compile_expr(target.index)
    return compiled


def compile_statement(statement: Statement | None, text: str | None = None) -> CompiledLine:
    """The closures of one statement; they do not depend on where the line stands. With the
    line's ``text``, expressions are shared with other lines' (see ``_compile_word``)."""
    if statement is None:
        return CompiledLine(K_EMPTY)
    if type(statement) is PlainNc:
        return _compile_plain_code(statement)
    if type(statement) is NcStatement:
        plain = _compile_plain_nc(statement)
        if plain is not None:
            return plain
    reads = _direct_reads(statement)
    if isinstance(statement, Mixed):
        first = compile_statement(statement.nc, text)
        first.second = compile_statement(statement.macro, text)
        first.reads = reads
        return first
    if isinstance(statement, Assign):
        c = _compile_assign(K_ASSIGN, statement, text)
    elif isinstance(statement, IfThen):
        c = _compile_assign(K_IFTHEN, statement.then, text)
        c.cond = compile_cond(statement.cond)
        c.node = statement
    elif isinstance(statement, Goto):
        c = CompiledLine(K_GOTO, target=compile_expr(statement.target), node=statement)
    elif isinstance(statement, IfGoto):
        c = CompiledLine(
            K_IFGOTO,
            target=compile_expr(statement.goto.target),
            cond=compile_cond(statement.cond),
            node=statement,
        )
    elif isinstance(statement, While):
        cond = compile_cond(statement.cond) if statement.cond is not None else None
        c = CompiledLine(K_WHILE, cond=cond, node=statement)
    elif isinstance(statement, End):
        c = CompiledLine(K_END, node=statement)
    elif isinstance(statement, NcStatement):
        c = _compile_nc(statement, text)
    elif isinstance(statement, IfNc):
        c = _compile_nc(statement.words, text)
        c.cond = compile_cond(statement.cond)
    elif isinstance(statement, ProgramStart):
        c = CompiledLine(K_HEADER, node=statement)
    else:
        c = CompiledLine(K_OTHER, node=statement)
    c.reads = reads
    c.ends_program = _ends_program(statement)
    return c


def _folded(_: object) -> Value:
    raise AssertionError("a block of constant words is run from its ConstantWords")


def _compile_nc(nc: NcStatement, text: str | None = None) -> CompiledLine:
    constants = [constant_of(w.value, w.address in LENGTH_ADDRESSES) for w in nc.words]
    folded = all(c is not None for c in constants)
    if not folded:
        words = tuple(
            CompiledWord(
                w.address,
                _compile_word(w.value, w.address in LENGTH_ADDRESSES, text),
                w.span.start,
                w.span.end,
                _written_with_decimal_point(w.value),
            )
            for w in nc.words
        )
        return CompiledLine(K_NC, words=words, nc=nc, node=nc)
    # A block of constant words is run from its ConstantWords: its words need no closures.
    compiled = CompiledLine(K_NC, nc=nc, node=nc)
    values: dict[str, Value] = {}
    pairs = [(w.address, c) for w, c in zip(nc.words, constants, strict=True)]
    for a, c in pairs:
        values.setdefault(a, c)
    compiled.constant = ConstantWords(
        values,
        _shared_codes(round(v, 1) for a, v in pairs if a == "G" and isinstance(v, float)),
        _shared_codes(v for a, v in pairs if a == "M" and isinstance(v, float)),
        nc,
        tuple(c for c in constants if c is not None),
        _motion_words(values),
        any(a in AXES for a in values),
    )
    return compiled


def _compile_plain_nc(nc: NcStatement) -> CompiledLine | None:
    """``_compile_nc`` of a block whose words are all numbers (the fast parse's blocks, most of
    a program), in one pass over its words; None for any other block. The result is the one
    ``compile_statement`` gives: no variable read, a ConstantWords, M02/M30 an end."""
    words: list[tuple[str, str, float]] = []
    for w in nc.words:
        num = w.value
        if type(num) is not Num or type(num.value) is not float:
            return None
        words.append((w.address, num.text, num.value))
    return _compile_words(nc, words)


# Address letters as written to the address (upper case, one string each).
_ADDRESS_OF = {ch: ch.upper() for ch in "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"}


# A number with more than three decimals: its motion word is rounded (see _compile_words).
_FOUR_DECIMALS = re.compile(r"\.[0-9]{4}")


def _compile_plain_code(nc: PlainNc) -> CompiledLine:
    """``_compile_words`` of a plain block, read from its code: each address once, no number
    with more than three decimals (a CAM block), with its G and M codes as the parser read
    them; otherwise word by word."""
    span = nc.span
    words = nc.code[span.start : span.end]  # nc.text()
    values: dict[str, float] | None = None
    if "E" not in words and "e" not in words:
        # Spaces part the words (CAM output): each token is a letter and its number. A token
        # of two words holds a letter after its first, which float() refuses (E aside).
        tokens = words.split()
        try:
            values = {_ADDRESS_OF[t[0]]: float(t[1:]) for t in tokens}
        except ValueError:
            values = None
        count = len(tokens)
    if values is None:
        pairs = nc.pairs()
        values = {_ADDRESS_OF[letter]: float(number) for letter, number in pairs}
        count = len(pairs)
    if len(values) < count or _FOUR_DECIMALS.search(words):
        return _compile_words(
            nc, [(_ADDRESS_OF[letter], number, float(number)) for letter, number in nc.pairs()]
        )
    written = nc.codes
    codes = _codes_compiled.get(written)
    if codes is None:
        codes = _compile_codes(written)
    g_codes, m_codes, quiet, ends_program = codes
    motion_words = values
    if written:  # G or M words (the words hold no N): the motion's are the others
        motion_words = values.copy()  # in the same order
        if g_codes:
            del motion_words["G"]
        if m_codes:
            del motion_words["M"]
    if quiet and not _CHECKED_ADDRESSES.isdisjoint(values):
        for address in _CHECKED_ADDRESSES.intersection(values):
            v = values[address]
            if address == "S" or v < 0 or (address in _WHOLE_ADDRESSES and v != int(v)):
                quiet = False
                break
    constant = ConstantWords(
        values,  # type: ignore[arg-type]  # of floats only
        g_codes,
        m_codes,
        nc,
        None,
        motion_words,
        not AXES.isdisjoint(values),
        quiet,
    )
    # CompiledLine(K_NC, nc=nc, node=nc, constant=constant, ends_program=ends_program), its
    # arguments by position (faster by a third).
    return CompiledLine(K_NC, (), None, None, None, None, (), nc, nc, None, constant, ends_program)


# What a plain block's G and M codes (shared by the parser) compile to: the G codes at their
# least increment, the M codes, whether the G codes need no rounding, whether M02/M30 ends.
_codes_compiled: dict[
    tuple[tuple[str, float], ...], tuple[tuple[float, ...], tuple[float, ...], bool, bool]
] = {}


def _compile_codes(
    codes: tuple[tuple[str, float], ...],
) -> tuple[tuple[float, ...], tuple[float, ...], bool, bool]:
    g_codes: list[float] = []
    m_codes: list[float] = []
    quiet = True
    for address, v in codes:
        if address == "G":
            code = round(v, 1)  # v itself when written with at most one decimal
            g_codes.append(code)
            quiet = quiet and code == v
        else:
            m_codes.append(v)
    found = (
        _shared_codes(g_codes) if g_codes else (),
        _shared_codes(m_codes) if m_codes else (),
        quiet,
        2.0 in m_codes or 30.0 in m_codes,
    )
    if len(_codes_compiled) >= MAX_SHARED_CODES:
        _codes_compiled.clear()
    _codes_compiled[codes] = found
    return found


def _compile_words(nc: NcStatement, words: list[tuple[str, str, float]]) -> CompiledLine:
    """``_compile_plain_nc`` of the words' addresses, number texts and values, in order."""
    values: dict[str, Value] = {}
    g_codes: list[float] = []
    m_codes: list[float] = []
    motion_words: dict[str, float] = {}
    quiet = True
    rounded_any = False
    for address, text, v in words:
        point = text.find(".")
        # Digits after the point: a number read from at most n decimals is its own round(v, n)
        # (float() and round() both give the double nearest the decimal), so most words need
        # no rounding (which costs more than the rest of the word).
        decimals = 0 if point < 0 else len(text) - point - 1
        if address not in values:
            values[address] = v
            if address not in ("G", "M", "N"):
                if decimals <= 3:
                    motion_words[address] = v
                else:
                    rounded = round(v, 3)  # the least input increment (IS-B)
                    motion_words[address] = v if rounded == v else rounded
                    rounded_any = rounded_any or rounded != v
        if address == "G":
            code = v if decimals <= 1 else round(v, 1)
            g_codes.append(code)
            quiet = quiet and code == v
        elif address == "M":
            m_codes.append(v)
        if quiet and address in _CHECKED_ADDRESSES:
            # What _check_addresses looks at: S against a setting, the others' signs and
            # whole numbers.
            quiet = address != "S" and v >= 0 and (address not in _WHOLE_ADDRESSES or v == int(v))
    if len(motion_words) == len(values) and not rounded_any:
        # No G, M or N, nothing rounded ("X1.5 Y2.", a modal CAM block): the same words, in
        # the same order. Neither dict is changed after this.
        motion_words = values  # type: ignore[assignment]
    compiled = CompiledLine(K_NC, nc=nc, node=nc)
    compiled.constant = ConstantWords(
        values,
        _shared_codes(g_codes) if g_codes else (),
        _shared_codes(m_codes) if m_codes else (),
        nc,
        None,
        motion_words,
        not AXES.isdisjoint(values),
        quiet,
    )
    compiled.ends_program = 2.0 in m_codes or 30.0 in m_codes
    return compiled


_WHOLE_ADDRESSES = INTEGER_ADDRESSES | {"P"}  # P when it names a program
_CHECKED_ADDRESSES = _WHOLE_ADDRESSES | {"F"}


# The words of constant blocks, by address, columns and decimal point: they hold no closure,
# so every block with a word at the same place shares it.
_folded_words: dict[tuple[str, int, int, bool], CompiledWord] = {}
# The G and M codes of constant blocks: a few combinations recur in every program.
_code_tuples: dict[tuple[float, ...], tuple[float, ...]] = {}
MAX_SHARED_CODES = 10_000  # entries of each: emptied when full


def _folded_word(address: str, start: int, end: int, decimal_point: bool) -> CompiledWord:
    key = (address, start, end, decimal_point)
    word = _folded_words.get(key)
    if word is None:
        if len(_folded_words) >= MAX_SHARED_CODES:
            _folded_words.clear()
        word = _folded_words[key] = CompiledWord(address, _folded, start, end, decimal_point)
    return word


def _shared_codes(codes: Iterable[float]) -> tuple[float, ...]:
    found = tuple(codes)
    shared = _code_tuples.get(found)
    if shared is None:
        if len(_code_tuples) >= MAX_SHARED_CODES:
            _code_tuples.clear()
        shared = _code_tuples[found] = found
    return shared


# Compiled expressions by their place and text in a line: the same text at the same column
# compiles to the same closures (spans included, which alarms report), so lines that repeat an
# expression (X[#100+2.] in every pass) share them. Emptied when it reaches its bound.
_shared_expressions: dict[tuple[int, int, str, bool], Evaluator] = {}
MAX_SHARED_EXPRESSIONS = 100_000


def _compile_word(expr: Expr, in_address: bool, text: str | None) -> Evaluator:
    """``compile_expr``, shared between lines with the same expression at the same place when
    the line's ``text`` is given."""
    if text is None or isinstance(expr, Num):
        return compile_expr(expr, in_address)
    span = expr.span
    key = (span.start, span.end, text[span.start : span.end], in_address)
    evaluator = _shared_expressions.get(key)
    if evaluator is None:
        made = compile_expr(expr, in_address)
        evaluator = kept(_shared_expressions, key, made, MAX_SHARED_EXPRESSIONS)
    return evaluator


def _written_with_decimal_point(expr: Expr) -> bool:
    while isinstance(expr, Unary | Bracket):
        expr = expr.operand if isinstance(expr, Unary) else expr.inner
    return isinstance(expr, Num) and expr.has_decimal_point


def _motion_words(values: dict[str, Value]) -> dict[str, float]:
    words: dict[str, float] = {}
    for address, v in values.items():
        if address in ("G", "M", "N") or not isinstance(v, float):
            continue
        rounded = round(v, 3)  # the least input increment (IS-B)
        words[address] = v if rounded == v else rounded  # the same value, no second float
    return words


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


class Activation:
    """One running program: its place, its locals and how it returns."""

    __slots__ = (
        "arguments",
        "caller",
        "ctx",
        "locals",
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
        machine: Machine,
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
        self.arguments: tuple[Value, ...] | None = None
        machine.runs += 1
        self.serial = machine.runs  # tells one call of a program from the next
        # Index in Modal.modal_calls of the G66 macro this program runs for (None: none). A move
        # here calls the macro specified before it, not itself (FANUC: multiple modal calls).
        self.modal_depth: int | None = None if caller is None else caller.modal_depth

    def read_global(self, number: int) -> Value:
        machine = self.machine
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
                f"#[...] refers to #{n}, which does not exist (VARIABLE NO. OUT OF RANGE)",
                float(n),
            )
        v = self.store.get(n, self)
        # Unknown, not read_global: an indirect read of a position is not one the run is
        # known to need when it chooses to follow the tool (run.tracks_positions).
        return self.machine.unknown_of(n) if v is self else v  # type: ignore[return-value]


class _Stop(Exception):
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


class Machine:
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
        self.budget = config.step_budget
        self.runs = 0  # activations so far: each gets its number
        self.modal = Modal()
        self.value_range = config.value_range
        self._entry_name = ""
        self.lathe = config.is_lathe  # asked at every block
        # The G codes a block with axis words runs instead of the modal motion: no move
        # (NOT_MOVES, G52, the coordinate system setting: G50 on a lathe, G92 on a mill; a
        # lathe's G92 is its threading cycle), or a one-shot move of its own.
        self._own_codes = (
            NOT_MOVES | RAPID_ONE_SHOTS | {LOCAL_COORDINATES, 50.0 if self.lathe else 92.0}
        )
        # The message of a move without F, by motion code: the same for every block of a run.
        self._no_feed: dict[float, str] = {}
        # The motions' words made by the run (a block of computed words, an F added), by
        # content: most blocks of a long program move to one of few places, and the motions
        # that go alike share one dict (nothing changes a motion's words once recorded).
        self._words: dict[tuple[object, ...], dict[str, float]] = {}
        # The toolpath's recorder, when one is asked for (see evaluate) or the programs read
        # the block end position: None costs a run one test per NC block.
        self.toolpath: Recorder | None = None
        # A debugger's hook between blocks (None: no cost but one test per block).
        self.stepper: Stepper | None = None
        # A G70-G73 with P and Q met by _motion, for _nc to follow its profile.
        self._profile_code: float | None = None
        self._profile_blocks = 0  # blocks of profiles read or run in this run

    def unknown_of(self, number: int) -> Unknown:
        u = self._unknowns.get(number)
        if u is None:
            u = self._unknowns[number] = Unknown(frozenset({number}))
        return u

    # ---- the run ---------------------------------------------------------------------------
    def run(
        self, entry: ProgramContext, deadline: float, preset: Mapping[int, Value] | None = None
    ) -> str:
        """Run from ``entry``; returns why the run ended. ``preset``: variables set before the
        first block (a debugger's launch: the entry's arguments #1-#33, with the locals not
        given vacant, as after a G65 with those words; commons and system variables)."""
        self.store = {}
        self.speculative = False  # the path went through a condition that was not decided
        self.deadline = deadline
        self.modal = Modal()
        self._entry_name = entry.name
        self._no_feed = {}
        locals_: list[Value] = [None] * 34
        # A program that reads #1-#33 before it sets them receives arguments: a G65 from a
        # program outside the analysed files calls it, even if it ends with M30.
        read_first = locals_read_first(entry) if entry.is_main else ()
        if self.record is not None and entry.is_main:
            self.record.read_first[(entry.uri, entry.program.first_line)] = read_first
        if not entry.is_main or read_first:
            self.modal.feed = Unknown(frozenset())  # the caller's F, which a lone run cannot know
            # A macro analysed alone: its arguments are unknown, not vacant.
            for n in range(1, 34):
                locals_[n] = self.unknown_of(n)
        if read_first:
            entry.facts.assumed_arguments[entry.program.first_line] = read_first
        if preset:
            if any(1 <= n <= 33 for n in preset):
                locals_ = [None] * 34
            for n, value in preset.items():
                if 1 <= n <= 33:
                    locals_[n] = value
                elif n > 33:
                    self.store[n] = value
        act = Activation(self, entry, locals_, 0, None, 0, 0)
        entry.facts.analysed_programs.add(entry.program.first_line)
        if self.toolpath is not None:
            self.toolpath.begin_run(len(self.facts.motions))
        self._steps = 0
        self._profile_blocks = 0
        self._checkpoint(act, 0)
        return self._run_loop(act, 0)

    def resume(self, state: MachineState, deadline: float) -> str:
        """Go on with a run from a checkpoint of an earlier evaluation (its facts so far are
        the caller's to restore); returns why the run ended."""
        self.deadline = deadline
        act = self._restore(state)
        self._begin_segment(state)
        return self._run_loop(act, state.done)

    def _run_loop(self, act: Activation, done: int) -> str:
        try:
            self._loop(act, done)
        except _Stop as stop:
            return stop.reason
        finally:
            self.steps = self._steps
        return "end"

    # ---- checkpoints -----------------------------------------------------------------------
    def _checkpoint(self, act: Activation, done: int) -> None:
        """Record the state before the next block and begin a new stretch of facts; in a
        resumed run, stop when the state is the earlier run's (see :mod:`.checkpoints`)."""
        if self.record is None:
            return
        state = self.capture(act, done)
        resumption = self.resumption
        if resumption is not None:
            for index in resumption.convergeable.get(state.meeting_key(), ()):
                old = resumption.record.checkpoints[index]
                if not state.same_as(old, counted=False):
                    continue
                # Met, perhaps with more or fewer blocks done: the rest of the run then ends
                # as many blocks later or sooner, and must stay within the budget; with more
                # or fewer motions, neither run may reach the records kept (a full run keeps
                # the first MAX_MOTIONS).
                total = resumption.record.results[state.run][2] + done - old.done
                recorded = len(resumption.previous.motions)
                moved = state.motions - old.motions
                if total <= self.budget and (
                    not moved or max(recorded, recorded + moved) < MAX_MOTIONS
                ):
                    raise Converged(index, done)
        self._begin_segment(state)

    def _begin_segment(self, state: MachineState) -> None:
        record = self.record
        assert record is not None
        self._checkpointed = state.done
        self._cuts_seen = {}
        record.checkpoints.append(state)
        segment = {uri: base.segment() for uri, base in self.facts.by_uri.items()}
        record.segments.append(segment)
        for ctx in self.contexts.values():
            ctx.facts = segment[ctx.uri]

    def capture(self, act: Activation, done: int) -> MachineState:
        chain: list[Activation] = []
        a: Activation | None = act
        while a is not None:
            chain.append(a)
            a = a.caller
        chain.reverse()
        levels = tuple(
            LevelState(
                (a.ctx.uri, a.ctx.program.first_line),
                tuple(a.locals),
                i > 0 and a.locals is chain[i - 1].locals,
                a.pc,
                a.macro_level,
                a.return_pc,
                a.repeats_left,
                a.serial,
                a.arguments,
                frozenset(a.undecided_loops),
                a.modal_depth,
            )
            for i, a in enumerate(chain)
        )
        m = self.modal
        modal = ModalState(
            m.motion,
            m.feed,
            m.speed,
            m.constant_surface_speed,
            tuple(
                (None if c is None else (c.uri, c.program.first_line), tuple(args), repeat)
                for c, args, repeat in m.modal_calls
            ),
            tuple(m.position.items()),
            tuple(m.position_line.items()),
            m.inch,
            m.g76,
            m.cycle,
        )
        if self._seen_since:
            self._seen_chunks = (*self._seen_chunks, frozenset(self._seen_since))
            self._seen_since = []
        facts = self.facts
        bases = facts.by_uri
        return MachineState(
            self.run_index,
            done,
            levels,
            dict(self.store),
            modal,
            self.speculative,
            self.runs,
            self._seen_chunks,
            len(facts.motions),
            tuple(facts.run_values),
            tuple((uri, len(b.reported)) for uri, b in bases.items()),
            tuple((uri, frozenset(b.analysed_programs)) for uri, b in bases.items()),
            tuple((uri, tuple(b.assumed_arguments.items())) for uri, b in bases.items()),
            self._profile_blocks,
        )

    def _restore(self, state: MachineState) -> Activation:
        """The machine as it was at ``state``, on the programs of this evaluation."""
        self.run_index = state.run
        self.store = store = dict(state.store)
        self.speculative = state.speculative
        self.runs = state.activations
        self._seen_chunks = state.seen_findings
        self._seen_since = []
        self._seen_findings = set().union(*state.seen_findings)
        self._steps = state.done
        self._profile_blocks = state.profile_blocks
        contexts = self.contexts
        ms = state.modal
        assert isinstance(ms.g76, G76Parameters)
        self.modal = Modal(
            ms.motion,
            ms.feed,
            ms.speed,
            ms.constant_surface_speed,
            [
                (None if key is None else contexts[key], list(args), repeat)
                for key, args, repeat in ms.modal_calls
            ],
            dict(ms.position),
            dict(ms.position_line),
            ms.inch,
            ms.g76,
            ms.cycle,
        )
        caller: Activation | None = None
        for level in state.levels:
            a = Activation.__new__(Activation)
            a.machine = self
            a.ctx = contexts[level.ctx]
            a.locals = (
                caller.locals
                if caller is not None and level.shares_locals_with_caller
                else list(level.locals)
            )
            a.store = store
            a.macro_level = level.macro_level
            a.caller = caller
            a.return_pc = level.return_pc
            a.repeats_left = level.repeats_left
            a.pc = level.pc
            a.undecided_loops = set(level.undecided_loops)
            a.arguments = level.arguments
            a.serial = level.serial
            a.modal_depth = level.modal_depth
            caller = a
        assert caller is not None
        self._entry_name = contexts[state.levels[0].ctx].name
        self._no_feed = {}
        return caller

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

    def _cut_without_feed(self, ctx: ProgramContext, message: str) -> None:
        """MB603's finding at the block being run, recorded by line (see CutsWithoutFeed)."""
        line = self._line
        uri = ctx.uri
        seen = self._cuts_seen.get(uri)
        if seen is None:
            seen = self._cuts_seen[uri] = set()
        elif line in seen:
            return
        seen.add(line)
        facts = ctx.facts
        records = facts.cuts
        after = len(facts.reported)
        program = ctx.program.first_line
        last = records[-1] if records else None
        if (
            last is None
            or last.after != after
            or last.program != program
            or last.message != message
        ):
            records.append(CutsWithoutFeed(uri, program, message, after, array("i", (line,))))
        else:
            if line <= last.lines[-1]:
                last.ascending = False
            last.lines.append(line)

    def _loop(self, act: Activation, done: int = 0) -> None:
        steps = self._steps = done
        budget = self.budget
        cancel = self.cancel
        # Block budget + 1: the budget's last block still runs, and the run stops before the
        # next, at the same block on any machine.
        next_check = min((done + 1) // CHECK_EVERY * CHECK_EVERY + CHECK_EVERY, budget + 1)
        recording = self.record is not None
        # A checkpoint is taken at the first block of a boundary line (see CompiledLine) once
        # CHECKPOINT_EVERY blocks have run since the last one: chosen by the text, not by the
        # count, so that a run with more or fewer blocks before (an edit added or removed
        # some) takes its checkpoints at the same blocks as the earlier run after the edit.
        wanted = False
        next_due = self._checkpointed + CHECKPOINT_EVERY + 1 if recording else budget + 1
        next_event = min(next_check, next_due)
        stepper = self.stepper
        while True:
            ctx = act.ctx
            pc = act.pc
            if pc >= ctx.program.end_line:
                unread = ctx.doc.unread_from
                if unread is not None and ctx.program.end_line >= unread:
                    # The program goes on in the part of the file the analysis does not read
                    # (MB013): its run is not over.
                    self._mark_incomplete(act)
                    raise _Stop("unread")
                act = self._return(act, None, ctx.program.end_line - 1)
                continue
            cl = ctx.lines[pc]
            kind = cl.kind
            self._line = pc  # the block being executed, for the facts and findings
            steps += 1
            self._steps = steps
            if steps >= next_event:
                self._steps = steps - 1  # this block has not run yet
                if steps >= next_check:
                    if steps > budget:  # nor does it run
                        self._budget_spent(act)
                        self._mark_incomplete(act)
                        raise _Stop("budget")
                    if time.monotonic() > self.deadline:
                        # The safety net: how far a run gets in seconds depends on the machine
                        # and its load, so nothing is concluded from where it stopped.
                        self._mark_incomplete(act)
                        raise _Stop("time")
                    if cancel is not None:
                        cancel.reached(RUNNING, steps - 1, budget)
                    next_check = min(steps + CHECK_EVERY, budget + 1)
                if recording:
                    since = steps - 1 - self._checkpointed
                    # No boundary line in four intervals (a loop without one): take it here.
                    if since >= 4 * CHECKPOINT_EVERY or (since >= CHECKPOINT_EVERY and cl.boundary):
                        wanted = False
                        self._checkpoint(act, steps - 1)
                        next_due = steps + CHECKPOINT_EVERY
                    elif since >= CHECKPOINT_EVERY:
                        wanted = True
                        next_due = self._checkpointed + 4 * CHECKPOINT_EVERY + 1
                    else:  # a checkpoint taken since (a program began)
                        next_due = self._checkpointed + CHECKPOINT_EVERY + 1
                self._steps = steps
                next_event = min(next_check, next_due)
            elif wanted and cl.boundary:
                wanted = False
                self._steps = steps - 1
                self._checkpoint(act, steps - 1)
                self._steps = steps
                next_due = steps + CHECKPOINT_EVERY
                next_event = min(next_check, next_due)
            if stepper is not None:
                stepper.before(act, pc)
            facts = ctx.facts
            runs = facts.runs
            runs[pc] = runs.get(pc, 0) + 1
            if cl.reads:
                self._record_reads(act, cl, facts)
            try:
                if kind == K_NC:  # most blocks: first
                    act = self._nc(act, cl)
                    if cl.second is not None and act.ctx is ctx and act.pc == pc + 1:
                        act.pc = pc
                        self._run_second(act, cl.second, facts)
                elif kind in (K_EMPTY, K_OTHER):
                    act.pc = pc + 1
                elif kind == K_ASSIGN:
                    self._assign(act, cl, facts)
                    act.pc = pc + 1
                elif kind == K_IFGOTO:
                    assert cl.cond is not None
                    result = cl.cond(act)
                    jc = facts.jump_count(pc)
                    if result is True:
                        jc.taken += 1
                        jc.guessed += self.speculative
                        act.pc = self._goto(act, cl)
                    elif result is False:
                        jc.not_taken += 1
                        jc.guessed += self.speculative
                        act.pc = pc + 1
                    else:
                        jc.undecided += 1
                        self.speculative = True
                        # Unknown: fall through the first time; if the path comes back here,
                        # it is a loop whose exit is unknown, so take the jump to leave it.
                        seen = act.undecided_loops
                        if pc in seen:
                            seen.discard(pc)
                            act.pc = self._goto(act, cl)
                        else:
                            seen.add(pc)
                            act.pc = pc + 1
                elif kind == K_GOTO:
                    act.pc = self._goto(act, cl)
                elif kind == K_IFTHEN:
                    assert cl.cond is not None
                    result = cl.cond(act)
                    jc = facts.jump_count(pc)
                    if result is True:
                        jc.taken += 1
                        jc.guessed += self.speculative
                        self._assign(act, cl, facts)
                    elif result is False:
                        jc.not_taken += 1
                        jc.guessed += self.speculative
                    else:
                        jc.undecided += 1
                        self.speculative = True
                        self._assign(act, cl, facts, unknown=result)
                    act.pc = pc + 1
                elif kind == K_WHILE:
                    act.pc = self._while(act, cl, facts)
                elif kind == K_END:
                    do_line = ctx.loop_do.get(pc)
                    act.pc = pc + 1 if do_line is None else do_line
                elif kind == K_HEADER:
                    act.pc = pc + 1
            except MacroAlarm as alarm:
                self.steps = steps
                message = self._alarm(act, cl, alarm)
                if stepper is not None:
                    stepper.alarm(act, pc, message)
                self._mark_incomplete(act)
                raise _Stop("alarm") from None
            except _Stop as stop:
                if stop.reason != "end of program":
                    self._mark_incomplete(act)
                raise

    @staticmethod
    def _mark_incomplete(act: Activation | None) -> None:
        """Programs on the call stack when a run stops early: their unrun blocks prove nothing."""
        while act is not None:
            act.ctx.facts.incomplete_programs.add(act.ctx.program.first_line)
            act = act.caller

    def _run_second(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> None:
        if cl.kind == K_ASSIGN:
            self._assign(act, cl, facts)
            act.pc = self._line + 1
        elif cl.kind == K_GOTO:
            act.pc = self._goto(act, cl)
        else:
            act.pc = self._line + 1

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

    def _record_reads(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> None:
        reads = facts.reads
        line = self._line
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

    def _assign(
        self,
        act: Activation,
        cl: CompiledLine,
        facts: DocumentFacts,
        unknown: Unknown | None = None,
    ) -> None:
        assert cl.value is not None
        value = cl.value(act)
        if value.__class__ is float:
            smallest, largest = self.value_range
            if not -largest <= value <= largest:  # NaN fails both comparisons
                raise MacroAlarm(
                    "PS0111",
                    AlarmKind.OVERFLOW,
                    f"the result {fmt(value)} is beyond the control's range "
                    f"±{largest:.3g} (CALCULATED DATA OVERFLOW)",
                )
            if -smallest < value < smallest:
                value = 0.0  # below the smallest magnitude the control holds (unverified)
        if unknown is not None:
            # IF [unknown] THEN #n=...: afterwards #n may or may not have changed.
            deps = set(unknown.deps)
            if isinstance(value, Unknown):
                deps |= value.deps
            value = Unknown(frozenset(deps))
        n = cl.target_number
        if n is None:
            assert cl.target is not None
            index = cl.target(act)
            if isinstance(index, Unknown):
                return
            n = 0 if index is None else round(index)
            kind = classify(n)
            if kind.kind == "none":
                raise MacroAlarm(
                    "PS0115",
                    AlarmKind.NO_SUCH_VARIABLE,
                    f"#[...] = ... writes #{n}, which does not exist (VARIABLE NO. OUT OF RANGE)",
                    float(n),
                )
            if kind.read_only:
                raise MacroAlarm(
                    "PS0116",
                    AlarmKind.WRITE_READ_ONLY,
                    f"#[...] = ... writes #{n}, which is read-only ({kind.meaning})",
                    float(n),
                )
        if n < 0:
            return  # #30001.116 and the like: not FANUC, reported by MB002
        if 1 <= n <= 33:
            act.locals[n] = value
        elif n == 0:
            raise MacroAlarm("PS0116", AlarmKind.WRITE_READ_ONLY, "#0 is read-only", 0.0)
        else:
            if n == 3000 and self.speculative:
                # Reached through a condition the analysis could not decide (an argument
                # check, typically): the control may never come here.
                pass
            elif n == 3000 and value is not None and not isinstance(value, Unknown):
                raise MacroAlarm(
                    "3000",
                    AlarmKind.MACRO_ALARM,
                    f"#3000 = {fmt(value)}: the program raises macro alarm {3000 + int(value)}",
                    value,
                )
            if not _volatile(n):
                self.store[n] = value
        write = facts.writes.get(self._line)
        if write is None:
            write = facts.writes[self._line] = (n, ValueSummary())
        write[1].add(value)

    def _shared_words(self, words: dict[str, float]) -> dict[str, float]:
        """``words``, or an equal dict an earlier motion of the run holds."""
        key: tuple[object, ...] = tuple(words.items())
        if 0.0 in words.values():  # 0.0 and -0.0 are equal but print differently
            key += tuple(math.copysign(1.0, v) for v in words.values())
        table = self._words
        shared = table.get(key)
        if shared is not None:
            return shared
        if len(table) < MAX_SHARED_WORDS:  # a run of all different moves keeps no more
            table[key] = words
        return words

    def _goto(self, act: Activation, cl: CompiledLine) -> int:
        assert cl.target is not None
        target = cl.target(act)
        ctx = act.ctx
        if isinstance(target, Unknown):
            raise _Stop("unknown jump")
        if target is None or target != int(target) or not 1 <= target <= 99999:
            raise MacroAlarm(
                "PS0128",
                AlarmKind.GOTO_TARGET,
                f"GOTO {fmt(target)}: not a sequence number 1-99999 (ILLEGAL MACRO "
                "SEQUENCE NUMBER)",
                target if target is not None else 0.0,
            )
        line = self._label(ctx, int(target), self._line)
        if line is None:
            raise MacroAlarm(
                "PS0128",
                AlarmKind.GOTO_MISSING,
                f"GOTO {int(target)}: no N{int(target)} in {ctx.name} (ILLEGAL MACRO "
                "SEQUENCE NUMBER)",
                target,
            )
        return line

    @staticmethod
    def _label(ctx: ProgramContext, seq: int, from_line: int) -> int | None:
        return ctx.program.label_line(seq, from_line)

    def _while(self, act: Activation, cl: CompiledLine, facts: DocumentFacts) -> int:
        pc = self._line
        end = act.ctx.loop_end.get(pc)
        result: object = True if cl.cond is None else cl.cond(act)
        jc = facts.jump_count(pc)
        if result is True:
            jc.taken += 1
            jc.guessed += self.speculative
            return pc + 1
        if result is False:
            jc.not_taken += 1
            jc.guessed += self.speculative
        else:
            jc.undecided += 1
            self.speculative = True  # the control may never run the body, nor what follows
            if pc not in act.undecided_loops:
                act.undecided_loops.add(pc)  # run the body once to learn its values
                return pc + 1
        act.undecided_loops.discard(pc)
        if end is None:
            raise _Stop("no END")
        return end + 1

    # ---- NC blocks -------------------------------------------------------------------------
    def _nc(self, act: Activation, cl: CompiledLine) -> Activation:
        if cl.cond is not None:  # Haas IF [c] <words>
            result = cl.cond(act)
            if result is not True:
                act.pc = self._line + 1
                return act
        const = cl.constant
        g_codes: Sequence[float]
        m_codes: Sequence[float]
        # A constant block's words in order: made only when something below needs them.
        order: list[tuple[str, Value, CompiledWord]] | None = None
        if const is not None:
            values, g_codes, m_codes = const.values, const.g_codes, const.m_codes
        else:
            values = {}
            g_codes = g_list = []
            m_codes = m_list = []
            order = []
            for w in cl.words:
                v = w.evaluate(act)
                if v is None:
                    continue  # a vacant variable omits the word
                order.append((w.address, v, w))
                if w.address == "G" and not isinstance(v, Unknown):
                    g_list.append(round(v, 1))
                elif w.address == "M" and not isinstance(v, Unknown):
                    m_list.append(v)
                if w.address not in values:
                    values[w.address] = v
        modal = self.modal
        call_kind: str | None = None
        for g in g_codes:
            if g in MOTION_GROUP or (self.lathe and g in LATHE_CYCLES):
                modal.motion = g
                if g not in LATHE_CYCLES:
                    modal.cycle = (None, None)
            elif g == 65.0:
                call_kind = "G65"
            elif g in (66.0, 66.1):
                call_kind = "G66"
            elif g == 67.0 and modal.modal_calls:
                modal.modal_calls.pop()
            elif g == 96.0:
                modal.constant_surface_speed = True
            elif g == 97.0:
                modal.constant_surface_speed = False
            elif g == 20.0:
                modal.inch = True
            elif g == 21.0:
                modal.inch = False
        if const is not None and const.quiet:
            pass  # no word of it can get a finding
        else:
            if order is None:
                assert const is not None
                order = const.order
            if call_kind is None:
                self._check_addresses(act, cl, order, 98.0 in m_codes or 99.0 in m_codes)
            else:  # after G65/G66 the words are arguments (#1-#26): only P names a program
                self._check_addresses(act, cl, [w for w in order if w[0] == "P"], calls=True)
        if "F" in values and call_kind is None:
            modal.feed = values["F"]
        if "S" in values and call_kind is None:
            modal.speed = values["S"]
        if call_kind is not None and order is None:
            assert const is not None
            order = const.order
        if call_kind == "G65":
            assert order is not None
            return self._macro_call(act, cl, order, modal_call=False)
        if call_kind == "G66":
            assert order is not None
            self._macro_call(act, cl, order, modal_call=True)
            act.pc = self._line + 1
            return act
        moved = self._motion(act, cl, values, g_codes, order)
        next_pc = self._line + 1
        profile: list[ProfileBlock] | str | None = None
        finishing: tuple[int, int] | None = None
        if self._profile_code is not None:
            profile, next_pc, finishing = self._profile(act, values, self._profile_code)
            self._profile_code = None
        if self.toolpath is not None:
            ctx = act.ctx
            read = self._values_read(act, cl) if cl.reads else None
            self.toolpath.block(
                ctx.name, ctx.uri, self._line, values, g_codes, self.facts.motions, profile, read
            )
        if finishing is not None:
            self._run_profile(act, *finishing)
        for m in m_codes:
            if m == 98.0:
                return self._sub_call(act, cl, values)
            if m == 99.0:
                return self._return(act, values.get("P"), self._line)
            if m in (2.0, 30.0):
                raise _Stop("end of program")
        act.pc = next_pc
        if moved and modal.modal_calls:
            # FANUC calls the macro after each move; a move in a modal macro calls the one
            # specified before it, and none in the first. Source: a FANUC operator's manual page,
            # custom macro "multiple modal call" (photo shipped with NCVC's G66 sample; series
            # not named on it).
            target = len(modal.modal_calls) - 1 if act.modal_depth is None else act.modal_depth - 1
            if target >= 0:
                callee, args, _ = modal.modal_calls[target]
                if callee is None:
                    self._call_unknown(act, shares_locals=False)
                    return act
                new = self._enter(act, callee, list(args), True, self._line + 1, 1)
                new.modal_depth = target
                return new
        return act

    # ---- the profile of G70-G73 -----------------------------------------------------------
    def _profile(
        self, act: Activation, values: dict[str, Value], code: float
    ) -> tuple[list[ProfileBlock] | str, int, tuple[int, int] | None]:
        """A G70-G73 that names its profile ``P(ns) Q(nf)``: what the toolpath gets of the
        profile (its blocks' words, or why it cannot be followed), the block to run next, and
        for G70 the profile's lines to run now.

        FANUC Series 0i-TF / 0i-TD Operator's Manual, "Multiple repetitive cycle (G70-G76)":
        G71, G72 and G73 read the blocks N(ns) to N(nf) to work out their passes and, done,
        go on with the block after N(nf); G70 runs them and goes on with the block after the
        G70, back at its start point. A profile the evaluator cannot follow (its N not in the
        program, a call, a jump or an assignment in it) is run as before: the block after the
        cycle comes next."""
        line = self._line
        ctx = act.ctx
        p, q = values.get("P"), values.get("Q")
        if not isinstance(p, float) or not isinstance(q, float):
            return "its P or Q is not known", line + 1, None
        first = self._label(ctx, int(p), line)
        if first is None:
            return f"no N{int(p)} (its P) in {ctx.name}", line + 1, None
        last = self._label(ctx, int(q), first - 1)
        if last is None or last < first:
            return f"no N{int(q)} (its Q) after N{int(p)} in {ctx.name}", line + 1, None
        lines = ctx.lines
        for n in range(first, last + 1):
            if not _plain_profile_line(lines[n]):
                return (
                    f"the profile N{int(p)}-N{int(q)} holds a block the analysis does not "
                    f"follow in a profile (line {n + 1})",
                    line + 1,
                    None,
                )
        if self.modal.modal_calls:
            return "a G66 modal call is in force", line + 1, None
        self._profile_budget(act, last + 1 - first)
        if code == 70.0:
            return [], line + 1, (first, last)
        return self._read_profile(act, first, last), last + 1, None

    def _profile_budget(self, act: Activation, blocks: int) -> None:
        """The profiles' blocks run within the G70-G73 block that names them, which the step
        budget counts once: they have a budget of their own, as many blocks, so that a loop
        around a G70 ends as soon."""
        self._profile_blocks += blocks
        if self._profile_blocks > self.budget:
            self._budget_spent(act)
            self._mark_incomplete(act)
            raise _Stop("budget")

    def _read_profile(self, act: Activation, first: int, last: int) -> list[ProfileBlock]:
        """The blocks of a G71-G73's profile as the control reads them: their words evaluated
        now (with the variables' values now) and checked, each block counted as reached, none
        run (no motion, no modal change)."""
        line = self._line
        blocks: list[ProfileBlock] = []
        for n in range(first, last + 1):
            pcl = self._profile_line(act, n)
            if pcl.kind != K_NC:
                continue
            try:
                values, g_codes, order = self._words_of(act, pcl)
                if order is not None:
                    self._check_addresses(act, pcl, order)
            except MacroAlarm as alarm:
                self._profile_alarm(act, pcl, alarm)
            blocks.append((values, g_codes))
        self._line = line
        return blocks

    def _profile_alarm(self, act: Activation, pcl: CompiledLine, alarm: MacroAlarm) -> None:
        """An alarm in a block of a profile (the run is at that block): the run stops."""
        message = self._alarm(act, pcl, alarm)
        if self.stepper is not None:
            self.stepper.alarm(act, self._line, message)
        self._mark_incomplete(act)
        raise _Stop("alarm") from None

    def _profile_line(self, act: Activation, n: int) -> CompiledLine:
        """Line ``n`` of a profile, counted as reached and its reads recorded: the block the
        evaluator is at from now on."""
        pcl = act.ctx.lines[n]
        self._line = n
        facts = act.ctx.facts
        facts.runs[n] = facts.runs.get(n, 0) + 1
        if pcl.reads:
            self._record_reads(act, pcl, facts)
        return pcl

    def _run_profile(self, act: Activation, first: int, last: int) -> None:
        """G70: the blocks N(ns) to N(nf) run as blocks of the G70 (the step budget counts the
        G70 once), then the tool is back at the G70's start point."""
        line = self._line
        modal = self.modal
        start, start_lines = dict(modal.position), dict(modal.position_line)
        for n in range(first, last + 1):
            pcl = self._profile_line(act, n)
            if pcl.kind != K_NC:
                continue
            try:
                self._nc(act, pcl)
            except MacroAlarm as alarm:
                self._profile_alarm(act, pcl, alarm)
        self._line = line
        modal.position = start
        modal.position_line = start_lines
        if self.toolpath is not None:
            self.toolpath.end_profile()

    def _words_of(
        self, act: Activation, cl: CompiledLine
    ) -> tuple[dict[str, Value], Sequence[float], list[tuple[str, Value, CompiledWord]] | None]:
        """An NC block's words evaluated: by address (the first of each), its G codes, and
        the words in order when a check may find something in them (None: it cannot)."""
        const = cl.constant
        if const is not None:
            return const.values, const.g_codes, None if const.quiet else const.order
        values: dict[str, Value] = {}
        g_codes: list[float] = []
        order: list[tuple[str, Value, CompiledWord]] = []
        for w in cl.words:
            v = w.evaluate(act)
            if v is None:
                continue
            order.append((w.address, v, w))
            if w.address == "G" and not isinstance(v, Unknown):
                g_codes.append(round(v, 1))
            if w.address not in values:
                values[w.address] = v
        return values, g_codes, order

    def _axis(self, values: dict[str, Value], absolute: str, incremental: str) -> float | None:
        """Where a block sends an axis: its absolute word, else where it is plus the
        incremental word (U, W on a lathe in G-code system A), else where it is."""
        v = values.get(absolute)
        if isinstance(v, float):
            return v
        here = self.modal.position.get(absolute)
        if not isinstance(here, float):
            return None
        step = values.get(incremental)
        if step is None:
            return here
        return here + step if isinstance(step, float) else None

    def _motion(
        self,
        act: Activation,
        cl: CompiledLine,
        values: dict[str, Value],
        g_codes: Sequence[float],
        order: list[tuple[str, Value, CompiledWord]] | None,  # None: the constant block's
    ) -> bool:
        # G70-G76 are the lathe's multiple repetitive cycles; on a mill G73-G76 are canned
        # drilling and boring cycles (G76 fine boring), which the analysis does not run.
        lathe = self.lathe
        one_shot = (
            next((g for g in g_codes if g in ONE_SHOT_CYCLES), None)
            if lathe and g_codes and not ONE_SHOT_CYCLES.isdisjoint(g_codes)
            else None
        )
        const = cl.constant
        has_axis = const.has_axis if const is not None else not AXES.isdisjoint(values)
        modal = self.modal
        own = (
            next((g for g in g_codes if g in self._own_codes), None)
            if has_axis and g_codes and not self._own_codes.isdisjoint(g_codes)
            else None
        )
        if one_shot is not None:
            code = one_shot
            if code in PROFILE_CYCLES and "P" in values and "Q" in values:
                self._profile_code = code
        elif own is not None:
            if own not in RAPID_ONE_SHOTS:  # no move: a dwell, a setting
                if own not in NOT_MOVES:
                    self._coordinates_set(act, values, own)
                return False
            code = own
        elif has_axis and modal.motion is not None:
            code = modal.motion
        else:
            return False
        if code == 76.0:
            if order is None:
                assert const is not None
                order = const.order
        else:
            order = None  # not needed below
        if code == 76.0 and not any(a in values for a in "XUZW"):
            assert order is not None
            self._g76_parameters(values, order)  # the first block of G76 sets, it does not cut
            return False
        words = const.words if const is not None else _motion_words(values)
        if (
            "F" not in words
            and isinstance(modal.feed, float)
            and code != 0.0
            and code not in RAPID_ONE_SHOTS
        ):
            words = {**words, "F": modal.feed}
        lathe_cycle = lathe and code in LATHE_CYCLES
        if lathe_cycle:
            taper = values.get("R") if "R" in values else modal.cycle[1]
            if "R" not in words and isinstance(taper, float) and taper != 0.0:
                words = {**words, "R": taper}  # a repeat of a taper cycle: the cone in force
        if words.get("F") == 0.0 and (code in FEED_MOTIONS or (lathe and code in LATHE_FED)):
            # PS0011 FEED ZERO (COMMAND), 0i-TF/0i-MF alarm lists: the control stops here.
            # (For a threading lead of 0 the alarm number is unverified.)
            if code in THREADING_CODES:
                raise MacroAlarm(
                    "PS0011", AlarmKind.LEAD_ZERO, f"{_g_name(code)} runs with the lead F = 0"
                )
            raise MacroAlarm(
                "PS0011", AlarmKind.FEED_ZERO, f"{_g_name(code)} runs with the feed F = 0"
            )
        if const is None or words is not const.words:
            words = self._shared_words(words)
        if code in FEED_MOTIONS and modal.feed is None:
            message = self._no_feed.get(code)
            if message is None:
                # One string for the many blocks that give it (a CAM file: every block).
                message = self._no_feed[code] = sys.intern(
                    f"G{code:02g} cuts with no F commanded before it"
                    f" since {self._entry_name} started"
                )
            self._cut_without_feed(act.ctx, message)
        position = modal.position
        # An axis's absolute word (most blocks) is where it goes, without _axis.
        x = values.get("X")
        if type(x) is not float:
            x = self._axis(values, "X", "U")
        z = values.get("Z")
        if type(z) is not float:
            z = self._axis(values, "Z", "W") if lathe else None
        if lathe_cycle:
            if "Z" not in values and "W" not in values:
                z = modal.cycle[0]  # the cycle repeated: its end Z stays
            r = words.get("R")
            modal.cycle = (z, r if isinstance(r, float) else None)
        elif code in LEFT_UNKNOWN:  # the axes named end where the analysis does not know
            if "X" in values or "U" in values:
                x = None
            if "Z" in values or "W" in values:
                z = None
        start_x = position.get("X")
        start_z = position.get("Z")
        ctx = act.ctx
        where = modal.position_line.get("X")
        motion = Motion(
            ctx.name,
            self._line,
            _g_name(code),
            words,
            ctx.uri,
            x,
            None
            if modal.constant_surface_speed or not isinstance(modal.speed, float)
            else modal.speed,
            ctx.program.first_line,
            z,
            start_x if isinstance(start_x, float) else None,
            start_z if isinstance(start_z, float) else None,
            None if where is None else where[1],
            "" if where is None else where[0],
            act.serial,
        )
        motions = self.facts.motions
        if code in THREADING_CODES and act.serial not in self.facts.run_values:
            self._remember_run(act)
        if code == 76.0:
            assert order is not None
            self._g76_passes(motion, values, order)
        elif len(motions) < MAX_MOTIONS:
            motions.append(motion)
        if code not in LATHE_CYCLES and code not in ONE_SHOT_CYCLES:  # cycles end where they began
            here = (ctx.uri, self._line)
            if x is not None or "X" in values or "U" in values:
                position["X"] = x
                modal.position_line["X"] = here
            if z is not None or "Z" in values or "W" in values:
                position["Z"] = z
                modal.position_line["Z"] = here
            if "Y" in values:
                position["Y"] = None if code in LEFT_UNKNOWN else values["Y"]
        return True

    def _coordinates_set(self, act: Activation, values: dict[str, Value], code: float) -> None:
        """G52 and the coordinate system setting (G50 on a lathe, G92 on a mill) move nothing,
        but where the tool is in work coordinates changes: to the words' values after a
        setting (0i-TF "Setting a workpiece coordinate system"), to a place not known here
        after G52 (its offset is added to every work coordinate system, 0i-TF "Local
        coordinate system"; unverified against the manual's text)."""
        modal = self.modal
        here = (act.ctx.uri, self._line)
        for axis, incremental in (("X", "U"), ("Z", "W")):
            if axis in values or incremental in values:
                v = values.get(axis)
                modal.position[axis] = v if code != LOCAL_COORDINATES and type(v) is float else None
                modal.position_line[axis] = here
        if "Y" in values:
            v = values["Y"]
            modal.position["Y"] = v if code != LOCAL_COORDINATES and type(v) is float else None

    def _remember_run(self, act: Activation) -> None:
        runs = self.facts.run_values
        if len(runs) < MAX_REMEMBERED_RUNS:
            runs[act.serial] = RunValues(tuple(act.locals), dict(self.store))

    def _least_increments(self, value: Value, word: CompiledWord | None) -> float | None:
        """A G76 word given in least input increments (P, Q: no decimal point, 0.001 mm); one
        written with a decimal point is taken in mm (unverified: FANUC may reject it)."""
        if not isinstance(value, float):
            return None
        if word is not None and word.decimal_point:
            return value
        return value * (0.0001 if self.modal.inch else 0.001)

    @staticmethod
    def _word(order: list[tuple[str, Value, CompiledWord]], address: str) -> CompiledWord | None:
        return next((w for a, _v, w in order if a == address), None)

    def _g76_parameters(
        self, values: dict[str, Value], order: list[tuple[str, Value, CompiledWord]]
    ) -> None:
        old = self.modal.g76
        m, chamfer, angle = old.finishing_passes, old.chamfer, old.tool_angle
        p = values.get("P")
        if isinstance(p, float):  # P mmrraa: finishing passes, chamfer, tool angle
            digits = round(p)
            m, chamfer, angle = digits // 10000, float(digits // 100 % 100), float(digits % 100)
        q = self._least_increments(values.get("Q"), self._word(order, "Q"))
        r = self._least_increments(values.get("R"), self._word(order, "R"))
        self.modal.g76 = G76Parameters(
            m,
            chamfer,
            angle,
            old.min_depth if q is None else q,
            old.finishing_allowance if r is None else r,
            self._line,
        )

    def _g76_passes(
        self, cut: Motion, values: dict[str, Value], order: list[tuple[str, Value, CompiledWord]]
    ) -> None:
        """The passes of G76's cutting block ``G76 X Z R(i) P(k) Q(Δd) F(L)``: X is the root,
        k the thread height and Δd the first depth, both radius values in least increments."""
        motions = self.facts.motions
        height = self._least_increments(values.get("P"), self._word(order, "P"))
        first = self._least_increments(values.get("Q"), self._word(order, "Q"))
        if cut.x is None or cut.start_x is None or height is None or first is None:
            if len(motions) < MAX_MOTIONS:
                motions.append(cut)  # what the control would cut cannot be known: one record
            return
        params = self.modal.g76
        outward = cut.x > cut.start_x  # an internal thread: the cuts go away from the axis
        sign = -1.0 if outward else 1.0
        depths = g76_depths(
            height, first, params.min_depth, params.finishing_allowance, params.finishing_passes
        )
        for n, (depth, finishing) in enumerate(depths, 1):
            if len(motions) >= MAX_MOTIONS:
                return
            x = round(cut.x + sign * 2.0 * (height - depth), 4)
            motions.append(
                replace(
                    cut,
                    words={**cut.words, "X": round(x, 3)},
                    x=x,
                    cycle_pass=n,
                    finishing=finishing,
                )
            )

    def _check_addresses(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]],
        calls: bool = False,
    ) -> None:
        # ``calls``: P is a program or sequence number (M98, M99, G65: a whole number); with
        # G04 it is a dwell.
        for address, v, w in order:
            if isinstance(v, Unknown) or v is None:
                continue
            if (address in INTEGER_ADDRESSES or (address == "P" and calls)) and v != int(v):
                message = f"{address} gets {fmt(v)}: {address} takes a whole number"
                self._finding(
                    act.ctx,
                    AddressNotInteger(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address == "G" and round(v, 1) != v:
                message = f"G gets {fmt(v)}: not a G code"
                self._finding(
                    act.ctx,
                    AddressNotInteger(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address in ("S", "T", "M", "H", "D", "F") and v < 0:
                message = f"{address} gets {fmt(v)}: {address} cannot be negative"
                self._finding(
                    act.ctx,
                    AddressOutOfRange(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )
            elif address == "S" and v > self.config.max_spindle_speed:
                message = (
                    f"S gets {fmt(v)} rpm, above the machine's maximum "
                    f"{fmt(self.config.max_spindle_speed)} rpm"
                )
                self._finding(
                    act.ctx,
                    AddressOutOfRange(
                        self._line, w.start, w.end, message, act.ctx.uri, address=address
                    ),
                )

    # ---- calls -----------------------------------------------------------------------------
    def _find(
        self, act: Activation, cl: CompiledLine, number: Value, what: str
    ) -> ProgramContext | None:
        if isinstance(number, Unknown) or number is None:
            return None
        ctx = self.programs.get(int(number))
        if ctx is None:
            message = (
                f"{what} calls O{int(number):04d}, which the analysis does not "
                "have; the call is skipped"
            )
            width = len(act.ctx.doc.blocks[self._line].text)
            self._finding(
                act.ctx,
                ProgramNotFound(self._line, 0, width, message, act.ctx.uri, program=int(number)),
            )
        return ctx

    def _sub_call(self, act: Activation, cl: CompiledLine, values: dict[str, Value]) -> Activation:
        p = values.get("P")
        l_value = values.get("L")
        repeat = 1
        if (
            isinstance(p, float)
            and l_value is None
            and self.config.four_digit_programs
            and (p >= 10000)
        ):
            repeat = int(p) // 10000
            p = float(int(p) % 10000)
        elif isinstance(l_value, float):
            repeat = int(l_value)
        callee = self._find(act, cl, p, "M98")
        if callee is None or repeat <= 0:
            if repeat > 0:
                self._call_unknown(act, shares_locals=True)
            act.pc = self._line + 1
            return act
        # M98 opens no new local level: the callee shares the caller's locals.
        return self._enter(act, callee, act.locals, False, self._line + 1, repeat)

    def _macro_call(
        self,
        act: Activation,
        cl: CompiledLine,
        order: list[tuple[str, Value, CompiledWord]],
        modal_call: bool,
    ) -> Activation:
        p: Value = None
        repeat = 1
        args: list[Value] = [None] * 34
        seen_g = False
        ijk_set = -1
        ijk_seen: set[str] = set()
        for address, v, _w in order:
            if address == "G" and not seen_g:
                seen_g = True
                continue
            if address == "P":
                p = v
            elif address == "L":
                repeat = int(v) if isinstance(v, float) else 1
            elif address in "IJK":
                # Specification II: repeated I/J/K fill #4-#33 in sets of three.
                if (
                    ijk_set < 0
                    or address in ijk_seen
                    or "IJK".index(address) < max("IJK".index(a) for a in ijk_seen)
                ):
                    ijk_set += 1
                    ijk_seen = set()
                ijk_seen.add(address)
                n = 4 + 3 * ijk_set + "IJK".index(address)
                if n <= 33:
                    args[n] = v
            elif address in ARGUMENT_VARIABLES:
                args[ARGUMENT_VARIABLES[address]] = v
        callee = self._find(act, cl, p, "G66" if modal_call else "G65")
        if modal_call:
            self.modal.modal_calls.append((callee, args, repeat))
            return act
        if callee is None:
            self._call_unknown(act, shares_locals=False)
            act.pc = self._line + 1
            return act
        return self._enter(act, callee, args, True, self._line + 1, repeat)

    def _call_unknown(self, act: Activation, shares_locals: bool) -> None:
        """After a call the analysis cannot follow (a program not in the analysed files, such
        as a probe vendor's O9814, or a P it cannot compute), what the callee may have changed
        is unknown: the run goes on, but no verdict rests on a value from before the call."""
        # The callee may write every common variable (#100-#199, #500-#999, the extended
        # ranges) and every writable system variable (tool offsets #2001+/#10001+, work
        # offsets #5201+, #7001+, #14001+, #15801+ on some controls), and what it does moves
        # the read-only ones (positions, modal information). The store holds only what this
        # run set, and a number missing from it reads as unknown ("depends on #135").
        # [shared reference macro-b.md §9; the ranges are unverified against a manual]
        self.store.clear()
        if shares_locals:
            # M98 opens no local level: the callee reads and writes the caller's #1-#33
            # [M FANUC-16i-PB, custom macro: "local variables"].
            locals_ = act.locals
            for n in range(1, 34):
                locals_[n] = self.unknown_of(n)
        modal = self.modal
        # F, S and where the tool stands are modal: the callee leaves its own.
        modal.feed = UNKNOWN
        modal.speed = UNKNOWN
        modal.position.clear()
        modal.position_line.clear()
        if self.toolpath is not None:
            ctx = act.ctx
            self.toolpath.lose_all(
                self._line,
                ctx.name,
                ctx.uri,
                "a call the analysis cannot follow moves the tool where it does not know",
            )

    def _enter(
        self,
        act: Activation,
        callee: ProgramContext,
        locals_: list[Value],
        new_level: bool,
        return_pc: int,
        repeat: int,
    ) -> Activation:
        depth = 0
        level = act.macro_level
        a: Activation | None = act
        while a is not None:
            depth += 1
            a = a.caller
        if new_level:
            level += 1
            if level > MAX_MACRO_LEVEL:
                raise MacroAlarm(
                    "PS0077",
                    AlarmKind.NESTING,
                    f"macro call nesting deeper than "
                    f"{MAX_MACRO_LEVEL} levels (TOO MANY SUB,MACRO NESTING)",
                )
        if depth > MAX_NESTING:
            raise MacroAlarm(
                "PS0077",
                AlarmKind.NESTING,
                f"call nesting deeper than {MAX_NESTING} (TOO MANY SUB,MACRO NESTING)",
            )
        callee.facts.analysed_programs.add(callee.program.first_line)
        locals_list = list(locals_) if new_level else locals_
        new = Activation(self, callee, locals_list, level, act, return_pc, repeat - 1)
        if new_level and repeat > 1:
            new.arguments = tuple(locals_)  # G65 L: each repetition starts from the arguments
        new.undecided_loops = set()
        return new

    def _return(self, act: Activation, p: Value, line: int) -> Activation:
        if act.repeats_left > 0:
            act.repeats_left -= 1
            act.pc = act.ctx.program.first_line
            if act.arguments is not None:
                act.locals[:] = act.arguments
            return act
        caller = act.caller
        if caller is None:
            # M99 in a program nobody called: the control restarts it (unverified); the run
            # stops here rather than loop.
            raise _Stop("end of program")
        if isinstance(p, float):
            target = self._label(caller.ctx, int(p), caller.pc)
            if target is None:
                raise MacroAlarm(
                    "PS0078",
                    AlarmKind.RETURN_MISSING,
                    f"M99 P{int(p)}: no N{int(p)} in {caller.ctx.name} (SEQUENCE NUMBER NOT FOUND)",
                    p,
                )
            caller.pc = target
        else:
            caller.pc = act.return_pc
        return caller

    # ---- ends ------------------------------------------------------------------------------
    def _alarm(self, act: Activation, cl: CompiledLine, alarm: MacroAlarm) -> str:
        ctx = act.ctx
        block = ctx.doc.blocks[self._line]
        node = alarm.node
        span = getattr(node, "span", None) or getattr(cl.node, "span", None)
        start, end = (span.start, span.end) if span is not None else (0, len(block.text))
        detail = ""
        if node is not None:
            args = getattr(node, "args", None) or (getattr(node, "right", None),)
            arg = args[0]
            if arg is not None:
                detail = f" = {block.source(arg.span).strip()}"
                shown: list[str] = []
                for sub in subexpressions(arg):
                    if isinstance(sub, Var) and sub.number is not None:
                        n = int(sub.number)
                        v = act.locals[n] if 1 <= n <= 33 else self.store.get(n)
                        text = f"#{n}={fmt(v)}"
                        if text not in shown:
                            shown.append(text)
                if shown:
                    detail += " with " + ", ".join(shown)
        message = f"{alarm.message}{detail} (alarm {alarm.alarm}) in {ctx.name}"
        found = ALARM_FINDINGS[alarm.kind]
        self._finding(
            ctx,
            found(self._line, start, end, message, ctx.uri, alarm=alarm.kind, number=alarm.alarm),
        )
        return message

    def _budget_spent(self, act: Activation) -> None:
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
        budget = f"the step budget ({self.budget:,} blocks)"
        runs = facts.runs.get(head, 0)
        width = len(ctx.doc.blocks[head].text)
        if read and all(n >= 100 for n in read) and not read & written:
            # Nothing in the loop changes what it tests: it waits for the PMC, a FOCAS client
            # or another path to write a common or system variable.
            names = ", ".join(f"#{n}" for n in sorted(read))
            message = (
                f"loop waits for {names} to be changed from outside the program (PMC, "
                f"FOCAS, another path): nothing in it writes {names}; the analysis "
                f"stopped after {runs} turns ({budget})"
            )
            self._finding(ctx, PollingLoop(head, 0, width, message, ctx.uri))
            return
        cl = ctx.lines[head]
        still = [n for n in cl.reads if (s := facts.reads.get((head, n))) and s.constant]
        approaching = _approaching(cl.node, facts, head)
        if not still and approaching:
            # The test's variables move towards its bound: a long loop, not an endless one.
            message = (
                f"loop still running after {runs} turns when {budget} ran out: it "
                "gets nearer its end every turn, so it is long rather than endless; "
                "values after it are not analysed"
            )
            self._finding(ctx, LongLoop(head, 0, width, message, ctx.uri))
            return
        moving = [n for n in cl.reads if n not in still]
        if still:
            why = ", ".join(f"#{n} stays {fmt(facts.reads[(head, n)].first)}" for n in still)
        elif moving:
            names = ", ".join(f"#{n}" for n in moving)
            why = f"the condition stays true, {names} moving away from its bound"
        else:
            why = "nothing in the condition changes"
        message = f"loop never ends: the block ran {runs} times before {budget} ran out; {why}"
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


def _unknown_value(frame: object) -> Value:
    return UNKNOWN


def compile_line(parsed: ParsedLine) -> CompiledLine:
    """A parsed line's statement; a block that does not parse but plainly assigns ``#n``
    assigns it an unknown value, so that later reads of #n are not taken for vacant.

    Lines of the same code share their statement (the parser's lines that differ in their
    comments only) and so their compiled line, boundary included: a line is a boundary by the
    text of its statement."""
    statement = parsed.statement
    if statement is None:
        if parsed.failed_assignment is not None:
            line = CompiledLine(
                K_ASSIGN, target_number=parsed.failed_assignment, value=_unknown_value
            )
        else:
            line = CompiledLine(K_EMPTY)
        line.boundary = _is_boundary(parsed.text)
        return line
    shared = _COMPILED_BY_STATEMENT.get(id(statement))
    if shared is not None and shared[0] is statement:
        return shared[1]
    if type(statement) is PlainNc:  # most lines: compile_statement's first case
        line = _compile_plain_code(statement)
    else:
        line = compile_statement(statement, parsed.text)
    line.boundary = _is_boundary(_statement_text(parsed, statement))
    kept(_COMPILED_BY_STATEMENT, id(statement), (statement, line), _COMPILED_BY_STATEMENT_LIMIT)
    return line


# Compiled lines by their statement (kept alive here, so that its id names it): the statements
# the parser shares between lines of the same code compile once. The oldest quarter goes when
# it is full; a line whose statement is no longer here compiles again, to an equal line.
_COMPILED_BY_STATEMENT: dict[int, tuple[Statement, CompiledLine]] = {}
_COMPILED_BY_STATEMENT_LIMIT = 4096


def _is_boundary(text: str) -> bool:
    return zlib.crc32(text.encode("utf-8", "surrogatepass")) & 7 == 0


def _statement_text(parsed: ParsedLine, statement: Statement) -> str:
    """The statement's columns of the line, the comments among them blanked: the same for
    every line of the same code."""
    start, end = statement.span.start, statement.span.end
    text = parsed.text[start:end]
    for comment in parsed.comments:
        c_start, c_end = comment.span.start, comment.span.end
        if start <= c_start and c_end <= end:
            text = text[: c_start - start] + " " * (c_end - c_start) + text[c_end - start :]
    return text


_KEEP_COMPILED: Callable[[ParsedLine, object], None] = vars(ParsedLine)["compiled"].__set__


def compiled(parsed: ParsedLine) -> CompiledLine:
    """The compiled statement of a parsed line: closures that do not depend on where it stands,
    kept on the line (every block of the same text shares it)."""
    found = parsed.compiled
    if found is None:
        found = compile_line(parsed)
        _KEEP_COMPILED(parsed, found)
    return found  # type: ignore[return-value]  # only compile_line sets it


_PROGRAM_ENDS = (("M", 2.0), ("M", 30.0))


def _ends_program_line(parsed: ParsedLine) -> bool | None:
    statement = parsed.statement
    if type(statement) is PlainNc:  # its M codes say it, without the compiled line
        return any(code in statement.codes for code in _PROGRAM_ENDS) or None
    return compiled(parsed).ends_program or None


# The blocks with M02 or M30, by document: kept across edits, where a look at every block for
# a program's first end took milliseconds per analysis of a long program (it ends at its last).
_program_end_lines: LineMap[bool] = LineMap(_ends_program_line)


def _plain_profile_line(cl: CompiledLine) -> bool:
    """Whether a line of a G70-G73 profile is one the evaluator follows: an NC block with no
    call, return, end or cycle, or a line with no block (empty, a comment)."""
    kind = cl.kind
    if kind in (K_EMPTY, K_OTHER):
        return True
    if kind != K_NC or cl.cond is not None or cl.second is not None:
        return False
    const = cl.constant
    if const is not None:
        g_codes: Iterable[float] = const.g_codes
        m_codes: Iterable[float] = const.m_codes
    else:
        assert cl.nc is not None
        g_list: list[float] = []
        m_list: list[float] = []
        for w in cl.nc.words:
            if w.address in ("G", "M"):
                v = constant_value(w.value)
                if v is None:
                    return False  # a computed G or M code
                (g_list if w.address == "G" else m_list).append(round(v, 1))
        g_codes, m_codes = g_list, m_list
    return NOT_IN_PROFILE_G.isdisjoint(g_codes) and NOT_IN_PROFILE_M.isdisjoint(m_codes)


def _reads_block_end(parsed: ParsedLine) -> bool | None:
    """Whether a line reads #5001-#5008 directly (the block end position)."""
    if type(parsed.statement) is PlainNc:
        return None  # numbers only
    reads = compiled(parsed).reads
    return any(BLOCK_END_FIRST <= n <= BLOCK_END_LAST for n in reads) or None


# The lines that read the block end position, by document (see run.tracks_positions).
block_end_reads: LineMap[bool] = LineMap(_reads_block_end)


def _volatile(number: int) -> bool:
    """System variables the control changes by itself: clocks, signals, positions."""
    return (
        number in (3001, 3002)
        or 1000 <= number <= 1133
        or 5001 <= number <= 5120
        or (4001 <= number <= 4430)
    )


_G_NAMES: dict[float, str] = {}


def _g_name(code: float) -> str:
    name = _G_NAMES.get(code)
    if name is None:
        name = f"G{int(code):02d}" if code == int(code) else f"G{code:g}"
        _G_NAMES[code] = name
    return name


def build_contexts(
    docs: list[tuple[str, Document, ProgramIndex]],
    facts: Facts,
    compiled_before: dict[str, list[CompiledLine]] | None = None,
    changed: dict[str, set[int]] | None = None,
) -> tuple[dict[int, ProgramContext], list[ProgramContext]]:
    """Compile every program of the given documents: by number, and all in order.

    ``compiled_before``: the compiled lines of an earlier version of the documents, in which
    only the ``changed`` lines differ (same line counts): those alone are compiled again."""
    contexts: dict[int, ProgramContext] = {}
    every: list[ProgramContext] = []
    for uri, doc, index in docs:
        lines: list[CompiledLine] | None = None
        if compiled_before is not None and changed is not None and uri in compiled_before:
            lines = list(compiled_before[uri])
            for line in changed.get(uri, ()):
                lines[line] = compiled(doc.blocks[line].parsed)
        for ctx in contexts_of(uri, doc, index, facts, lines):
            every.append(ctx)
            if ctx.program.number is not None and ctx.program.number not in contexts:
                contexts[ctx.program.number] = ctx
    return contexts, every


def locals_read_first(ctx: ProgramContext) -> tuple[tuple[int, int], ...]:
    """The locals a program reads before any block of it sets them, in the order of the text,
    each with the line of its first read: (number, line)."""
    set_: set[int] = set()
    found: dict[int, int] = {}
    lines = ctx.lines
    for line in range(ctx.program.first_line, ctx.program.end_line):
        part: CompiledLine | None = lines[line]
        assert part is not None
        for n in part.reads:
            if n <= 33 and n not in set_ and n not in found:
                found[n] = line
        while part is not None:  # the assignment, or the macro part of a mixed block
            target = part.target_number
            if target is not None and 1 <= target <= 33:
                set_.add(target)
                if len(set_) == 33:  # every local set: no later read comes first
                    return tuple(found.items())
            part = part.second
    return tuple(found.items())


def _ends_program(statement: Statement | None) -> bool:
    nc = statement.nc if isinstance(statement, Mixed) else statement
    return isinstance(nc, NcStatement) and any(
        w.address == "M" and constant_value(w.value) in (2.0, 30.0) for w in nc.words
    )


def contexts_of(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    facts: Facts,
    lines: list[CompiledLine] | None = None,
) -> list[ProgramContext]:
    doc_facts = facts.document(uri)
    if lines is None:
        lines = [compiled(b.parsed) for b in doc.blocks]
    out: list[ProgramContext] = []
    ends = _program_end_lines(doc).lines
    for program in index.programs:
        loop_end = {lp.do_line: lp.end_line for lp in program.loops if lp.end_line is not None}
        loop_do = {e: d for d, e in loop_end.items()}
        at = bisect_left(ends, program.first_line)
        first_end = ends[at] if at < len(ends) and ends[at] < program.end_line else None
        is_main = first_end is not None
        if first_end is not None:
            doc_facts.program_ends[program.first_line] = first_end
        out.append(ProgramContext(uri, doc, program, lines, loop_end, loop_do, doc_facts, is_main))
    return out
