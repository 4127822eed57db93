"""Statement compilation: each parsed line to the closures and constants the machine runs.

A line compiles once per distinct statement (the compiled form is kept on the ``ParsedLine``);
a block of constant words is folded at compile time into its ``ConstantWords``. What compiled
lines share (G and M code tuples, folded words, expressions at the same place) is interned in
tables of the current database (:mod:`fanuc_macro.database`).
"""

from __future__ import annotations

import re
import zlib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from operator import itemgetter
from types import MappingProxyType

from ..database import TableKey, current
from ..syntax.marks import constant_value
from ..syntax.tree import (
    Assign,
    Bracket,
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
from ..syntax.walk import all_line_variables, variables
from .compiler import (
    CondEvaluator,
    Evaluator,
    compile_cond,
    compile_expr,
    compile_with_constant,
    kept,
)
from .values import UNKNOWN, Value

# Block kinds of the compiled program.
K_EMPTY, K_ASSIGN, K_GOTO, K_IFGOTO, K_IFTHEN, K_WHILE, K_END, K_NC, K_HEADER, K_OTHER = range(10)

AXES = frozenset("XYZUVWABC")
# Addresses whose values are lengths or angles in the least input increment (ROUND in them
# rounds to that increment); the others take whole numbers.
LENGTH_ADDRESSES = frozenset("XYZUVWABCIJKRQF")
INTEGER_ADDRESSES = frozenset("MSTLHD")  # P too, when it names a program (M98, G65, M99)


@dataclass(slots=True, eq=False, repr=False)
class CompiledWord:
    address: str
    evaluate: Evaluator
    start: int
    end: int
    decimal_point: bool = False  # written as a number with a decimal point (``Q0.4``)


class CompiledLine:
    """What the machine runs of a line: a ``FullLine``, or for most lines of a long program (a
    plain NC block of constant words) a ``PlainLine``, which holds only what differs."""

    __slots__ = ()
    kind: int
    reads: tuple[int, ...]  # direct variables the block reads (for the facts)
    target: Evaluator | None  # assignment target index (indirect) or GOTO target
    target_number: int | None  # direct assignment target
    value: Evaluator | None
    cond: CondEvaluator | None
    words: tuple[CompiledWord, ...]
    nc: NcStatement | None
    node: Statement | None
    second: CompiledLine | None  # the macro part of a mixed block
    constant: ConstantWords | None  # an NC block whose words are all constants
    ends_program: bool  # M02/M30: the program is a main program
    # One line in eight, by its text: where the run may take a checkpoint (see Machine._loop).
    boundary: bool
    # How the run reads ``reads`` for the facts when they are locals (see FullLine).
    read_local: int
    read_locals: Callable[[list[Value]], tuple[Value, ...]] | None
    local_target: int
    writes_after_reads: bool
    turns_after_reads: bool


@dataclass(slots=True)
class FullLine(CompiledLine):
    """A compiled line of any statement."""

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
    # How the run reads ``reads`` for the facts when they are locals: the one local's number,
    # or a function of the locals that gives their values in a tuple (0, None: otherwise).
    read_local: int = field(default=0, compare=False)
    read_locals: Callable[[list[Value]], tuple[Value, ...]] | None = field(
        default=None, compare=False
    )
    local_target: int = field(default=0, compare=False)  # target_number when it is #1-#33
    # An assignment to a local that reads variables: the run keeps each value it writes in
    # the list of its reads, after them (see MachineBase._read_buffer).
    writes_after_reads: bool = field(default=False, compare=False)
    # A WHILE that reads variables: the run keeps whether its test held in that list too.
    turns_after_reads: bool = field(default=False, compare=False)


class ConstantWords:
    """What an NC block of constant words evaluates to, worked out once at compile time: a
    ``FullWords``, or the block's ``PlainLine`` itself. Nothing here is mutated by a run."""

    __slots__ = ()
    # The words by address, first of each; None when they are ``codes`` then the motion's
    # words (a plain block "G01 X.. Y..": the run makes them, kept for no block).
    kept_values: dict[str, Value] | None
    g_codes: tuple[float, ...]
    m_codes: tuple[float, ...]
    nc: NcStatement | None
    # The words' values, in the order of the block; None when each is its Num's value.
    constants: tuple[float, ...] | None
    motion_words: dict[str, float]  # the motion record's words
    has_axis: bool
    # No word can get an address finding (MB5xx: whole numbers, G codes, signs, the spindle's
    # maximum), whatever the settings: the run need not look at them.
    quiet: bool
    _order: list[tuple[str, Value, CompiledWord]] | None
    # The G and M words by address (shared by every block of the same codes), when
    # ``kept_values`` is None.
    codes: Mapping[str, float] | None

    @property
    def values(self) -> dict[str, Value]:
        """The words by address, in the order of the block (first of each address)."""
        kept = self.kept_values
        if kept is not None:
            return kept
        return {**self.codes, **self.motion_words}  # type: ignore[dict-item]  # codes set then

    def __eq__(self, other: object) -> bool:
        # The words by address, however they are held.
        return isinstance(other, ConstantWords) and _compared(self) == _compared(other)

    __hash__ = None  # type: ignore[assignment]  # mutable

    @property
    def order(self) -> list[tuple[str, Value, CompiledWord]]:
        """Each word: its address, value and compiled word. Made when a run first asks (a
        block with a call, a G76, a word to check): most blocks never need it."""
        order = self._order
        if order is None:
            assert self.nc is not None
            words = self.nc.words
            constants = self.constants
            values = [w.value.value for w in words] if constants is None else constants  # type: ignore[union-attr]
            order = [
                (
                    w.address,
                    v,
                    _folded_word(
                        w.address, w.span.start, w.span.end, _written_with_decimal_point(w.value)
                    ),
                )
                for w, v in zip(words, values, strict=True)
            ]
            self._order = order  # type: ignore[misc]  # a slot of each subclass
        return order


@dataclass(slots=True, eq=False)
class FullWords(ConstantWords):
    """The constant words of any NC block."""

    kept_values: dict[str, Value] | None
    g_codes: tuple[float, ...]
    m_codes: tuple[float, ...]
    nc: NcStatement | None
    constants: tuple[float, ...] | None
    motion_words: dict[str, float]
    has_axis: bool
    quiet: bool = False
    _order: list[tuple[str, Value, CompiledWord]] | None = None
    codes: Mapping[str, float] | None = None


class PlainLine(CompiledLine, ConstantWords):
    """A plain NC block of constant words (most lines of CAM output), its own constant words:
    the parts a ``FullLine`` and ``FullWords`` of it hold that are the same for every such
    block are the class's, its codes' are shared with every block of the same codes."""

    __slots__ = ("_codes", "_order", "boundary", "has_axis", "motion_words", "nc", "quiet")
    kind = K_NC
    reads = ()
    target = None
    target_number = None
    value = None
    cond = None
    words = ()
    second = None
    read_local = 0
    read_locals = None
    local_target = 0
    writes_after_reads = False
    turns_after_reads = False
    kept_values = None
    constants = None

    def __init__(
        self,
        nc: NcStatement,
        codes: CompiledCodes,
        motion_words: dict[str, float],
        has_axis: bool,
        quiet: bool,
    ) -> None:
        self.nc = nc
        self._codes = codes
        self.motion_words = motion_words
        self.has_axis = has_axis
        self.quiet = quiet
        self._order = None
        self.boundary = False

    @property
    def node(self) -> Statement | None:  # type: ignore[override]  # the line's own
        return self.nc

    @property
    def constant(self) -> ConstantWords:  # type: ignore[override]  # the line's own
        return self

    @property
    def g_codes(self) -> tuple[float, ...]:  # type: ignore[override]  # its codes'
        return self._codes[0]

    @property
    def m_codes(self) -> tuple[float, ...]:  # type: ignore[override]  # its codes'
        return self._codes[1]

    @property
    def ends_program(self) -> bool:  # type: ignore[override]  # its codes'
        return self._codes[3]

    @property
    def codes(self) -> Mapping[str, float] | None:  # type: ignore[override]  # its codes'
        return self._codes[4]

    @property
    def values(self) -> dict[str, Value]:
        """The words by address, in the order of the block."""
        codes = self._codes[4]
        return {**codes, **self.motion_words} if codes else self.motion_words  # type: ignore[return-value]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, CompiledLine) and _line_compared(self) == _line_compared(other)

    __hash__ = None  # mutable, as a FullLine

    def full(self) -> FullLine:
        """The same line as a ``FullLine`` (to which a macro statement can be added)."""
        line = FullLine(K_NC, nc=self.nc, node=self.nc, ends_program=self.ends_program)
        line.constant = FullWords(
            self.kept_values,
            self.g_codes,
            self.m_codes,
            self.nc,
            None,
            self.motion_words,
            self.has_axis,
            self.quiet,
            None,
            self.codes,
        )
        line.boundary = self.boundary
        return line


def _line_compared(line: CompiledLine) -> tuple[object, ...]:
    """What FullLine's equality compares (the constant words by their own)."""
    constant = line.constant
    return (
        line.kind,
        line.reads,
        line.target,
        line.target_number,
        line.value,
        line.cond,
        line.words,
        line.nc,
        line.node,
        line.second,
        None if constant is None else _compared(constant),
        line.ends_program,
        line.boundary,
    )


def _compared(c: ConstantWords) -> tuple[object, ...]:
    return (c.values, c.g_codes, c.m_codes, c.nc, c.constants, c.motion_words, c.has_axis, c.quiet)


def _direct_reads(statement: Statement, walked: Iterable[Var] | None = None) -> tuple[int, ...]:
    """The numbers of the variables ``statement`` reads, in the order of the walk of its
    variables (``walked``: that walk, when the line has it)."""
    numbers: list[int] = []
    skip_target: Var | None = None
    if isinstance(statement, Assign):
        skip_target = statement.target
    elif isinstance(statement, IfThen):
        skip_target = statement.then.target
    # The variables in the order of subexpressions' walk, without walking what holds none.
    for var in variables(statement) if walked is None else walked:
        number = var.number
        if number is None or var is skip_target:
            continue
        n = int(number)
        if n == number and n and n not in numbers:
            numbers.append(n)
    return tuple(numbers)


def _compile_assign(kind: int, assign: Assign, text: str | None) -> FullLine:
    target = assign.target
    compiled = FullLine(kind, value=_compile_word(assign.value, False, text), node=assign)
    if target.number is not None:
        compiled.target_number = int(target.number) if target.number == int(target.number) else -1
        if 1 <= compiled.target_number <= 33:
            compiled.local_target = compiled.target_number
    else:
        assert target.index is not None
        compiled.target = compile_expr(target.index)
    return compiled


def compile_statement(
    statement: Statement | None, text: str | None = None, walked: Iterable[Var] | None = None
) -> CompiledLine:
    """The closures of one statement; they do not depend on where the line stands. With the
    line's ``text``, expressions are shared with other lines' (see ``_compile_word``);
    ``walked``: the statement's variables, when the line has them walked."""
    if statement is None:
        return FullLine(K_EMPTY)
    if type(statement) is PlainNc:
        return _compile_plain_code(statement)
    if type(statement) is NcStatement:
        plain = _compile_plain_nc(statement)
        if plain is not None:
            return plain
        # Its reads come from the compile of its words (see _compile_nc).
        nc_line = _compile_nc(statement, text)
        _set_local_reads(nc_line)
        nc_line.ends_program = _ends_program(statement)
        return nc_line
    reads = _direct_reads(statement, walked)
    if isinstance(statement, Mixed):
        nc_part = compile_statement(statement.nc, text)
        first = nc_part.full() if isinstance(nc_part, PlainLine) else nc_part
        assert isinstance(first, FullLine)
        first.second = compile_statement(statement.macro, text)
        first.reads = reads
        _set_local_reads(first)
        return first
    if isinstance(statement, Assign):
        c = _compile_assign(K_ASSIGN, statement, text)
    elif isinstance(statement, IfThen):
        c = _compile_assign(K_IFTHEN, statement.then, text)
        c.cond = compile_cond(statement.cond)
        c.node = statement
    elif isinstance(statement, Goto):
        c = FullLine(K_GOTO, target=compile_expr(statement.target), node=statement)
    elif isinstance(statement, IfGoto):
        c = FullLine(
            K_IFGOTO,
            target=compile_expr(statement.goto.target),
            cond=compile_cond(statement.cond),
            node=statement,
        )
    elif isinstance(statement, While):
        cond = compile_cond(statement.cond) if statement.cond is not None else None
        c = FullLine(K_WHILE, cond=cond, node=statement)
    elif isinstance(statement, End):
        c = FullLine(K_END, node=statement)
    elif isinstance(statement, NcStatement):
        c = _compile_nc(statement, text)
    elif isinstance(statement, IfNc):
        c = _compile_nc(statement.words, text)
        c.cond = compile_cond(statement.cond)
    elif isinstance(statement, ProgramStart):
        c = FullLine(K_HEADER, node=statement)
    else:
        c = FullLine(K_OTHER, node=statement)
    c.reads = reads
    _set_local_reads(c)
    c.ends_program = _ends_program(statement)
    return c


def _set_local_reads(c: FullLine) -> None:
    reads = c.reads
    c.writes_after_reads = c.kind == K_ASSIGN and bool(reads) and c.local_target > 0
    c.turns_after_reads = c.kind == K_WHILE and bool(reads)
    if reads and all(1 <= n <= 33 for n in reads):
        if len(reads) == 1:
            c.read_local = reads[0]
        else:
            c.read_locals = itemgetter(*reads)


def _folded(_: object) -> Value:
    raise AssertionError("a block of constant words is run from its ConstantWords")


def _compile_nc(nc: NcStatement, text: str | None = None) -> FullLine:
    # Each word's tree is walked once, or not at all when another line shares it: its value
    # when constant and its closure, kept for when the block is not folded.
    made = []
    constants: list[float | None] = []
    numbers: list[int] = []
    for w in nc.words:  # one loop: every block with brackets comes here
        word = _shared_word(w.value, w.address in LENGTH_ADDRESSES, text)
        made.append(word)
        constants.append(word[1])
        for n in word[2]:
            if n not in numbers:
                numbers.append(n)
    reads = tuple(numbers)
    if None in constants:
        shared = current().table(SHARED_EXPRESSIONS)
        compiled_words: list[CompiledWord] = []
        for w, (evaluator, c, found, key) in zip(nc.words, made, strict=True):
            if key is not None:
                evaluator = kept(shared, key, (evaluator, c, found), MAX_SHARED_EXPRESSIONS)[0]
            span = w.span
            compiled_words.append(
                CompiledWord(
                    w.address, evaluator, span.start, span.end, _written_with_decimal_point(w.value)
                )
            )
        return FullLine(K_NC, reads=reads, words=tuple(compiled_words), nc=nc, node=nc)
    # A block of constant words is run from its ConstantWords: its words need no closures.
    compiled = FullLine(K_NC, reads=reads, nc=nc, node=nc)
    values: dict[str, Value] = {}
    pairs = [(w.address, c) for w, c in zip(nc.words, constants, strict=True)]
    for a, c in pairs:
        values.setdefault(a, c)
    compiled.constant = FullWords(
        values,
        _shared_codes(round(v, 1) for a, v in pairs if a == "G" and isinstance(v, float)),
        _shared_codes(v for a, v in pairs if a == "M" and isinstance(v, float)),
        nc,
        tuple(c for c in constants if c is not None),
        recorded_words(values),
        any(a in AXES for a in values),
    )
    return compiled


def _compile_plain_nc(nc: NcStatement) -> FullLine | None:
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
_ADDRESS_OF: Mapping[str, str] = MappingProxyType(
    {ch: ch.upper() for ch in "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"}
)


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
    codes = current().table(CODES_COMPILED).get(written)
    if codes is None:
        codes = _compile_codes(written)
    g_codes, m_codes, quiet, ends_program, _ = codes
    motion_words = values
    kept: dict[str, float] | None = values
    if written:  # G or M words (the words hold no N): the motion's are the others
        motion_words = values.copy()  # in the same order
        if g_codes:
            del motion_words["G"]
        if m_codes:
            del motion_words["M"]
        if _codes_first(values, written):
            kept = None  # the run makes them from the codes and the motion's words
    motion_words = _compact(motion_words)
    if kept is not None:
        kept = motion_words if motion_words == kept else _compact(kept)
    if quiet and not _CHECKED_ADDRESSES.isdisjoint(values):
        for address in _CHECKED_ADDRESSES.intersection(values):
            v = values[address]
            if address == "S" or v < 0 or (address in _WHOLE_ADDRESSES and v != int(v)):
                quiet = False
                break
    if kept is not None and kept is not motion_words:  # G or M words after others
        line = FullLine(K_NC, nc=nc, node=nc, ends_program=ends_program)
        line.constant = FullWords(
            kept,  # type: ignore[arg-type]  # of floats only
            g_codes,
            m_codes,
            nc,
            None,
            motion_words,
            not AXES.isdisjoint(values),
            quiet,
        )
        return line
    return PlainLine(nc, codes, motion_words, not AXES.isdisjoint(values), quiet)


def _codes_first(values: dict[str, float], written: tuple[tuple[str, float], ...]) -> bool:
    """The block's words are its G and M words, as the parser read them, then the others."""
    for (address, v), (letter, code) in zip(values.items(), written, strict=False):
        if address != letter or v != code or (v == 0.0 and str(v) != str(code)):
            return False
    return True


class _Words:
    """Its instances' dicts, of the same addresses in the same order, share one table of keys
    (CPython's split dicts): a block's words kept by it in 100 bytes less."""


# The class whose instances' dicts hold words of these addresses, by the addresses.
WORD_LAYOUTS: TableKey[tuple[str, ...], type[_Words]] = TableKey(
    "evaluator.word_layouts", cache=True
)
MAX_WORD_LAYOUTS = 1000


def _compact(words: dict[str, float]) -> dict[str, float]:
    """A dict equal to ``words``, in the same order, held in less memory where it can be."""
    layouts = current().table(WORD_LAYOUTS)
    key = tuple(words)
    layout = layouts.get(key)
    if layout is None:
        if len(layouts) >= MAX_WORD_LAYOUTS:
            return words
        layout = layouts[key] = type("Words", (_Words,), {})
    held = layout()
    for address, v in words.items():
        setattr(held, address, v)
    compact: dict[str, float] = held.__dict__
    return compact


# What a plain block's G and M codes (shared by the parser) compile to: the G codes at their
# least increment, the M codes, whether the G codes need no rounding, whether M02/M30 ends,
# the codes by address.
CompiledCodes = tuple[tuple[float, ...], tuple[float, ...], bool, bool, Mapping[str, float]]
CODES_COMPILED: TableKey[tuple[tuple[str, float], ...], CompiledCodes] = TableKey(
    "evaluator.codes_compiled", cache=True
)


def _compile_codes(codes: tuple[tuple[str, float], ...]) -> CompiledCodes:
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
        dict(codes),
    )
    compiled_codes = current().table(CODES_COMPILED)
    if len(compiled_codes) >= MAX_SHARED_CODES:
        compiled_codes.clear()
    compiled_codes[codes] = found
    return found


def _compile_words(nc: NcStatement, words: list[tuple[str, str, float]]) -> FullLine:
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
                if decimals <= 3 or address == "F":  # F as written: see recorded_words
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
    compiled = FullLine(K_NC, nc=nc, node=nc)
    compiled.constant = FullWords(
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
FOLDED_WORDS: TableKey[tuple[str, int, int, bool], CompiledWord] = TableKey(
    "evaluator.folded_words", cache=True
)
# The G and M codes of constant blocks: a few combinations recur in every program.
CODE_TUPLES: TableKey[tuple[float, ...], tuple[float, ...]] = TableKey(
    "evaluator.code_tuples", cache=True
)
MAX_SHARED_CODES = 10_000  # entries of each: emptied when full


def _folded_word(address: str, start: int, end: int, decimal_point: bool) -> CompiledWord:
    key = (address, start, end, decimal_point)
    folded_words = current().table(FOLDED_WORDS)
    word = folded_words.get(key)
    if word is None:
        if len(folded_words) >= MAX_SHARED_CODES:
            folded_words.clear()
        word = folded_words[key] = CompiledWord(address, _folded, start, end, decimal_point)
    return word


def _shared_codes(codes: Iterable[float]) -> tuple[float, ...]:
    found = tuple(codes)
    code_tuples = current().table(CODE_TUPLES)
    shared = code_tuples.get(found)
    if shared is None:
        if len(code_tuples) >= MAX_SHARED_CODES:
            code_tuples.clear()
        shared = code_tuples[found] = found
    return shared


# Compiled expressions by their place and text in a line: the same text at the same column
# compiles to the same closures (spans included, which alarms report), constant and reads, so
# lines that repeat an expression (X[#100+2.] in every pass) share them. Emptied when it
# reaches its bound.
SharedWord = tuple[Evaluator, float | None, tuple[int, ...]]
SHARED_EXPRESSIONS: TableKey[tuple[int, int, str, bool], SharedWord] = TableKey(
    "evaluator.shared_expressions", cache=True
)
MAX_SHARED_EXPRESSIONS = 100_000


def _compile_word(expr: Expr, in_address: bool, text: str | None) -> Evaluator:
    """``compile_expr``, shared between lines with the same expression at the same place when
    the line's ``text`` is given."""
    evaluator, constant, numbers, key = _shared_word(expr, in_address, text)
    if key is not None:
        shared = current().table(SHARED_EXPRESSIONS)
        evaluator = kept(shared, key, (evaluator, constant, numbers), MAX_SHARED_EXPRESSIONS)[0]
    return evaluator


def _shared_word(
    expr: Expr, in_address: bool, text: str | None
) -> tuple[Evaluator, float | None, tuple[int, ...], tuple[int, int, str, bool] | None]:
    """The closure, constant value and variables read (as ``_direct_reads``) of ``expr``,
    another line's when shared; with the key to share them under when they were compiled here
    (None: found, or not to share)."""
    key = None
    if text is not None and type(expr) is not Num:
        span = expr.span
        key = (span.start, span.end, text[span.start : span.end], in_address)
        found = current().table(SHARED_EXPRESSIONS).get(key)
        if found is not None:
            return (*found, None)
    variables: list[Var] = []
    evaluator, constant = compile_with_constant(expr, in_address, variables)
    numbers = []
    for var in variables:
        number = var.number
        if number is not None:
            n = int(number)
            if n == number and n:
                numbers.append(n)
    return evaluator, constant, tuple(numbers), key


def _written_with_decimal_point(expr: Expr) -> bool:
    kind = type(expr)  # no class of the tree is subclassed
    while kind is Unary or kind is Bracket:
        expr = expr.operand if kind is Unary else expr.inner  # type: ignore[union-attr]
        kind = type(expr)
    return kind is Num and expr.has_decimal_point  # type: ignore[union-attr]


def recorded_words(values: dict[str, Value], inch: bool = False) -> dict[str, float]:
    """A block's words as its motion records them: no G, M or N, numbers at the least input
    increment (IS-B: 0.001 mm, 0.0001 inch in G20); F as it is (a lead of 0.0769 inch, a
    feed of 0.0035 inch per revolution: F has its own increments)."""
    words: dict[str, float] = {}
    places = 4 if inch else 3
    for address, v in values.items():
        if address in ("G", "M", "N") or not isinstance(v, float):
            continue
        if address == "F":
            words[address] = v
            continue
        rounded = round(v, places)
        words[address] = v if rounded == v else rounded  # the same value, no second float
    return words


def _unknown_value(frame: object) -> Value:
    return UNKNOWN


def compile_line(parsed: ParsedLine) -> CompiledLine:
    """A parsed line's statement; a block that does not parse but plainly assigns ``#n``
    assigns it an unknown value, so that later reads of #n are not taken for vacant.

    Lines of the same code share their statement (the parser's lines that differ in their
    comments only) and so their compiled line, boundary included: a line is a boundary by the
    text of its statement."""
    statement = parsed.statement
    line: CompiledLine
    if statement is None:
        if parsed.failed_assignment is not None:
            line = FullLine(K_ASSIGN, target_number=parsed.failed_assignment, value=_unknown_value)
        else:
            line = FullLine(K_EMPTY)
        line.boundary = _is_boundary(parsed.text)
        return line
    by_statement = current().table(COMPILED_BY_STATEMENT)
    shared = by_statement.get(id(statement))
    if shared is not None and shared[0] is statement:
        return shared[1]
    if type(statement) is PlainNc:  # most lines: compile_statement's first case
        line = _compile_plain_code(statement)
    else:
        walked = None if type(statement) is NcStatement else all_line_variables(parsed)
        line = compile_statement(statement, parsed.text, walked)
    line.boundary = _is_boundary(_statement_text(parsed, statement))  # type: ignore[misc]  # a FullLine or a PlainLine
    kept(by_statement, id(statement), (statement, line), _COMPILED_BY_STATEMENT_LIMIT)
    return line


# Compiled lines by their statement (kept alive here, so that its id names it): the statements
# the parser shares between lines of the same code compile once. The oldest quarter goes when
# it is full; a line whose statement is no longer here compiles again, to an equal line.
COMPILED_BY_STATEMENT: TableKey[int, tuple[Statement, CompiledLine]] = TableKey(
    "evaluator.compiled_by_statement", cache=True
)
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


def _ends_program(statement: Statement | None) -> bool:
    nc = statement.nc if isinstance(statement, Mixed) else statement
    if not isinstance(nc, NcStatement):
        return False
    for w in nc.words:  # noqa: SIM110  # a loop, not any(): every block of a program asks
        if w.address == "M" and constant_value(w.value) in (2.0, 30.0):
            return True
    return False
