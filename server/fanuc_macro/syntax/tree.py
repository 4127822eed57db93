"""The typed AST of one block.

Every node is a frozen dataclass with a ``span``: the columns it covers in its line (0-based, end
exclusive, in characters). Nodes never hold a line number, so a parsed line can be shared by every
block whose text is the same (see :mod:`fanuc_macro.syntax.parser`); the block adds the line.
The node's original text is ``block.text[node.span.start:node.span.end]`` (:meth:`Block.source`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import FrozenInstanceError, dataclass, field, fields
from typing import NamedTuple

from ..database import TableKey, current


@dataclass(frozen=True, slots=True)
class Span:
    start: int
    end: int


# Spans of short lines, shared (a table of the analysis database): lines hold the same few
# columns over and over, and a span is frozen. Keyed by start * SHARED_COLUMNS + end.
SHARED_COLUMNS = 512
SHARED_SPANS: TableKey[int, Span] = TableKey("syntax.shared_spans", cache=True)


def shared_span(start: int, end: int) -> Span:
    """``Span(start, end)``, the same object for the same columns (up to column 512)."""
    if end >= SHARED_COLUMNS or start < 0:
        return Span(start, end)
    key = start * SHARED_COLUMNS + end
    spans = current().table(SHARED_SPANS)
    found = spans.get(key)
    if found is None:
        found = spans[key] = Span(start, end)
    return found


# ---- expressions -----------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Num:
    value: float
    text: str  # as written: "10." and "10" differ for an NC address (decimal point rules)
    span: Span

    @property
    def has_decimal_point(self) -> bool:
        return "." in self.text


@dataclass(frozen=True, slots=True)
class Var:
    """``#100`` (``number`` set) or ``#[expr]`` (``index`` set)."""

    number: float | None
    index: Expr | None
    span: Span


@dataclass(frozen=True, slots=True)
class Unary:
    op: str  # "-" or "+"
    operand: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class Binary:
    op: str  # + - * / OR XOR AND MOD (upper case)
    left: Expr
    right: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class Bracket:
    """``[expr]``: kept as a node because FANUC limits bracket nesting to five."""

    inner: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class Call:
    """A function: SIN[x], ATAN[a]/[b] (``slash_form``), ATAN[a,b], POW[a,b]."""

    name: str  # upper case
    args: tuple[Expr, ...]
    span: Span
    name_span: Span
    slash_form: bool = False


Expr = Num | Var | Unary | Binary | Bracket | Call


@dataclass(frozen=True, slots=True)
class Compare:
    op: str  # EQ NE GT GE LT LE
    left: Expr
    right: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class Logic:
    """``[c1] AND [c2] OR [c3]``: evaluated left to right."""

    first: Cond
    rest: tuple[tuple[str, Cond], ...]
    span: Span


@dataclass(frozen=True, slots=True)
class BareCond:
    """``IF [#1] GOTO 5``: a value as a condition (Haas NGC, not FANUC)."""

    value: Expr
    span: Span


Cond = Compare | Logic | BareCond


# ---- statements ------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Word:
    """An NC word: address letter and value (``X10.``, ``G#8``, ``Z[#26-1.]``, ``X-#24``)."""

    address: str  # upper case
    value: Expr
    span: Span
    address_lowercase: bool = False


@dataclass(frozen=True, slots=True)
class NcStatement:
    words: tuple[Word, ...]
    span: Span

    def find(self, address: str) -> Word | None:
        for word in self.words:
            if word.address == address:
                return word
        return None


# (letter, number) of each word of a plain block's code (letters as written).
_PLAIN_PAIRS = re.compile(r"([A-Za-z])([-+]?[.0-9]+)")


# The G codes of a ``ParsedLine.bare`` block: motions, planes, tool radius compensation off,
# absolute and incremental. No line map looks for them (M codes, G67, other controls' codes).
BARE_CODES = frozenset(
    ("G", code) for code in (0.0, 1.0, 2.0, 3.0, 17.0, 18.0, 19.0, 40.0, 90.0, 91.0)
)


def _plain_words(code: str) -> tuple[Word, ...]:
    """The words of a plain block's code, as the parser reads them (it owns the reading and
    imports this module: imported when a block's words are first asked for)."""
    from .parser import plain_words

    return plain_words(code)


class PlainNc(NcStatement):
    """A block of NC words whose values are numbers written without spaces (``G01 X1.5 Y-2.``,
    nearly every block of CAM output), kept as the line's code: its ``Word`` and ``Num``
    nodes are built from the text when first asked for, and equal the nodes the parse of the
    words gives. What runs or checks every line (the compiler, the line rules) reads ``pairs``
    and ``codes`` instead, so that a big program holds no nodes for these blocks.

    ``code`` is the line with its comments cut out (columns kept); the words are
    ``code[span.start:span.end]``. ``codes`` are the G and M words' addresses (upper case) and
    values, in the block's order. The parser makes it for blocks without a call (M98, G65...)."""

    __slots__ = ("code", "codes")
    code: str
    codes: tuple[tuple[str, float], ...]

    def __init__(self, code: str, span: Span, codes: tuple[tuple[str, float], ...] = ()) -> None:
        _NC_SPAN(self, span)
        _PLAIN_CODE(self, code)
        _PLAIN_CODES(self, codes)

    @property
    def words(self) -> tuple[Word, ...]:
        try:
            found: tuple[Word, ...] = _NC_WORDS_GET(self, PlainNc)
        except AttributeError:
            found = _plain_words(self.code)
            _NC_WORDS(self, found)
        return found

    def pairs(self) -> list[tuple[str, str]]:
        """Each word's letter (as written) and number text, in order, read from the code."""
        span = self.span
        return _PLAIN_PAIRS.findall(self.code, span.start, span.end)

    def text(self) -> str:
        """The words as written, from the first letter to the last digit."""
        span = self.span
        return self.code[span.start : span.end]

    def built(self) -> bool:
        """Whether the words were asked for (the tests count the blocks that built them)."""
        try:
            _NC_WORDS_GET(self, PlainNc)
        except AttributeError:
            return False
        return True

    def __eq__(self, other: object) -> bool:
        if type(other) is PlainNc:
            span = self.span
            return span == other.span and (
                self.code[span.start : span.end] == other.code[span.start : span.end]
            )
        if isinstance(other, NcStatement):
            return self.span == other.span and self.words == other.words
        return NotImplemented

    def __hash__(self) -> int:
        return hash((self.words, self.span))  # NcStatement's, to which it is equal

    def __setattr__(self, name: str, value: object) -> None:
        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    def __delattr__(self, name: str) -> None:
        raise FrozenInstanceError(f"cannot delete field {name!r}")


@dataclass(frozen=True, slots=True)
class Assign:
    target: Var
    value: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class Goto:
    target: Expr
    span: Span


@dataclass(frozen=True, slots=True)
class IfGoto:
    cond: Cond
    goto: Goto
    span: Span


@dataclass(frozen=True, slots=True)
class IfThen:
    cond: Cond
    then: Assign
    span: Span


@dataclass(frozen=True, slots=True)
class IfNc:
    """``IF [c] THEN M31`` / ``IF [c] S#20 F#30``: Haas forms, not FANUC."""

    cond: Cond
    words: NcStatement
    has_then: bool
    span: Span


@dataclass(frozen=True, slots=True)
class BlockIf:
    """``IF [c] THEN`` / ``ELSE`` / ``ENDIF`` (Haas NGC block IF, not FANUC 0i/16i/30i)."""

    keyword: str  # IF, ELSE, ENDIF
    cond: Cond | None
    span: Span


@dataclass(frozen=True, slots=True)
class While:
    """``WHILE [c] DOm``, or ``DOm`` alone (``cond`` None: loops forever)."""

    cond: Cond | None
    loop_id: float
    id_span: Span
    span: Span


@dataclass(frozen=True, slots=True)
class End:
    loop_id: float
    id_span: Span
    span: Span


@dataclass(frozen=True, slots=True)
class Print:
    """DPRNT[...] / BPRNT[...] / POPEN / PCLOS."""

    keyword: str
    text: str
    span: Span


@dataclass(frozen=True, slots=True)
class Mixed:
    """An NC statement and a macro statement in one block (FANUC alarm PS0127)."""

    nc: NcStatement
    macro: MacroStatement
    span: Span


@dataclass(frozen=True, slots=True)
class ProgramStart:
    """``O3331``, ``:3331``, ``O9123<HOLE BORE>`` or ``O<NAME>`` (30i)."""

    number: int | None
    name: str | None
    span: Span


MacroStatement = Assign | Goto | IfGoto | IfThen | IfNc | BlockIf | While | End | Print
Statement = MacroStatement | NcStatement | Mixed | ProgramStart


# ---- one line --------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Comment:
    text: str  # between the parentheses
    span: Span  # including the parentheses
    closed: bool = True


@dataclass(frozen=True, slots=True)
class SyntaxProblem:
    message: str
    span: Span
    expected: tuple[str, ...] = ()
    dialect: str | None = None  # "Haas", "Mitsubishi/Citizen", "LinuxCNC", ... when recognised
    unknown_function: str | None = None  # "FOO" in "#1=FOO[2]"


@dataclass(frozen=True, slots=True)
class LineNote:
    """Something the block reader noticed that is not a syntax error (nested comment...)."""

    kind: str
    message: str
    span: Span


@dataclass(frozen=True, slots=True)
class ParsedLine:
    """Everything known about one line of text, independent of where the line stands."""

    text: str
    tape_mark: bool  # the line holds "%"
    skip: int | None  # block delete: 0 for "/", 1-9 for "/1".."/9"
    seq: int | None  # N number
    seq_span: Span | None
    statement: Statement | None
    comments: tuple[Comment, ...]
    problem: SyntaxProblem | None
    notes: tuple[LineNote, ...] = ()
    has_lowercase: bool = False
    # The block has an M98/M97/M99/G65/G66 word: the program index looks closer only then.
    has_call: bool = False
    # The program index needs this line (label, jump, loop, call, program start, tape mark).
    indexed: bool = False
    # A block that does not parse but plainly assigns a variable ('#5=#4*2:', '#1=ABC[2]'):
    # its number. The analysis takes it as set, to a value it does not know.
    failed_assignment: int | None = None
    # A ``PlainNc`` of upper case words alone (no comment, note or tape mark) whose G codes, if
    # any, are among ``BARE_CODES``: what nearly every line of CAM output is, and a line in
    # which no ``line_maps.LineMap`` finds anything (``tests/test_line_maps.py`` checks each
    # map), so the maps do not look at it.
    bare: bool = field(default=False, init=False, compare=False)
    # What the evaluator compiles the line to (``evaluator.machine.compiled``), set the first
    # time it is asked for: a cache of what the line alone decides, held as long as the line
    # (an entry in a cache by text cost a hundred bytes more). Neither compared nor copied.
    compiled: object = field(default=None, init=False, compare=False, repr=False)
    # The variables of its statements (``walk.all_line_variables``), walked the first time a
    # rule asks and kept as ``compiled`` is: several line rules and the compiler read them.
    statement_variables: tuple[Var, ...] | None = field(
        default=None, init=False, compare=False, repr=False
    )

    @property
    def is_empty(self) -> bool:
        return self.statement is None and self.seq is None and self.problem is None


class Block(NamedTuple):
    """A parsed line at its place in a document (``line`` is 0-based).

    A named tuple, not a dataclass: a document of 100,000 lines makes 100,000 of them on every
    edit, and a tuple is the cheapest object Python builds.
    """

    line: int
    parsed: ParsedLine

    @property
    def text(self) -> str:
        return self.parsed.text

    @property
    def statement(self) -> Statement | None:
        return self.parsed.statement

    def source(self, span: Span) -> str:
        return self.parsed.text[span.start : span.end]


class WeaklyReferable:
    """A base whose one slot is ``__weakref__``, for a slotted dataclass that must be weakly
    referable: ``dataclass(weakref_slot=True)`` came with Python 3.11, and ``slots=True``
    refuses a class that names its own ``__slots__``."""

    __slots__ = ("__weakref__",)


@dataclass(frozen=True, slots=True)
class Document(WeaklyReferable):
    """A whole file: its blocks, in order, one per line. (Weakly referable: the cache of line
    diffs names versions without keeping them alive, ``syntax.diff.line_diff``.)"""

    uri: str
    blocks: tuple[Block, ...]
    encoding: str = "utf-8"
    decode_note: str | None = None
    line_count: int = field(default=0)
    # Set when the document is larger than the analysis reads: the first line left unread
    # (``blocks`` stop before it), and what was read of how much.
    unread_from: int | None = None
    unread_note: str | None = None
    # The lines that are not ``ParsedLine.bare`` (a ``range`` of all when most are not),
    # worked out when a line map first looks at the whole document (``line_maps``).
    unbare: Sequence[int] | None = field(default=None, init=False, compare=False, repr=False)


# ---- quick constructors ----------------------------------------------------------------------
# The same objects as Num(...), Word(...), NcStatement(...) and ParsedLine(...), made without the
# frozen dataclass's __init__ (which sets each field through object.__setattr__, at about twice
# the cost): the fast parse makes ten of them for a line of four words.


def _setters(cls: type, *names: str) -> tuple[Callable[[object, object], None], ...]:
    return tuple(vars(cls)[name].__set__ for name in names)


_NUM_VALUE, _NUM_TEXT, _NUM_SPAN = _setters(Num, "value", "text", "span")
_WORD_ADDRESS, _WORD_VALUE, _WORD_SPAN, _WORD_LOWERCASE = _setters(
    Word, "address", "value", "span", "address_lowercase"
)
_NC_WORDS, _NC_SPAN = _setters(NcStatement, "words", "span")
_NC_WORDS_GET: Callable[[object, type], tuple[Word, ...]] = vars(NcStatement)["words"].__get__
_PLAIN_CODE, _PLAIN_CODES = _setters(PlainNc, "code", "codes")


class _LineBeingMade:
    """A ``ParsedLine``'s layout (the same slots, in the same order) without the frozen
    dataclass's ``__setattr__``: ``quick_line`` sets its fields as plain slots and then makes
    it a ``ParsedLine`` (``__class__`` assignment, allowed between classes of one layout; a
    field that broke the layout would make every parse fail at once). A parse makes one per
    new line, where a call of a slot's setter per field cost three times as much."""

    __slots__ = ParsedLine.__slots__


assert _LineBeingMade.__slots__ == tuple(f.name for f in fields(ParsedLine))


def quick_num(value: float, text: str, span: Span) -> Num:
    node = Num.__new__(Num)
    _NUM_VALUE(node, value)
    _NUM_TEXT(node, text)
    _NUM_SPAN(node, span)
    return node


def quick_word(address: str, value: Expr, span: Span, address_lowercase: bool) -> Word:
    node = Word.__new__(Word)
    _WORD_ADDRESS(node, address)
    _WORD_VALUE(node, value)
    _WORD_SPAN(node, span)
    _WORD_LOWERCASE(node, address_lowercase)
    return node


def quick_nc(words: tuple[Word, ...], span: Span) -> NcStatement:
    node = NcStatement.__new__(NcStatement)
    _NC_WORDS(node, words)
    _NC_SPAN(node, span)
    return node


def quick_plain(code: str, span: Span, codes: tuple[tuple[str, float], ...]) -> PlainNc:
    node = PlainNc.__new__(PlainNc)
    _NC_SPAN(node, span)
    _PLAIN_CODE(node, code)
    _PLAIN_CODES(node, codes)
    return node


def quick_line(
    text: str,
    tape_mark: bool,
    skip: int | None,
    seq: int | None,
    seq_span: Span | None,
    statement: Statement | None,
    comments: tuple[Comment, ...],
    problem: SyntaxProblem | None,
    notes: tuple[LineNote, ...],
    has_lowercase: bool,
    has_call: bool,
    indexed: bool,
    failed_assignment: int | None,
    bare: bool = False,
) -> ParsedLine:
    line = _LineBeingMade.__new__(_LineBeingMade)
    line.text = text  # type: ignore[attr-defined]  # the slots of ParsedLine, typed there
    line.tape_mark = tape_mark  # type: ignore[attr-defined]
    line.skip = skip  # type: ignore[attr-defined]
    line.seq = seq  # type: ignore[attr-defined]
    line.seq_span = seq_span  # type: ignore[attr-defined]
    line.statement = statement  # type: ignore[attr-defined]
    line.comments = comments  # type: ignore[attr-defined]
    line.problem = problem  # type: ignore[attr-defined]
    line.notes = notes  # type: ignore[attr-defined]
    line.has_lowercase = has_lowercase  # type: ignore[attr-defined]
    line.has_call = has_call  # type: ignore[attr-defined]
    line.indexed = indexed  # type: ignore[attr-defined]
    line.failed_assignment = failed_assignment  # type: ignore[attr-defined]
    line.bare = bare  # type: ignore[attr-defined]
    line.compiled = None  # type: ignore[attr-defined]
    line.statement_variables = None  # type: ignore[attr-defined]
    line.__class__ = ParsedLine  # type: ignore[assignment]
    return line  # type: ignore[return-value]
