"""Block-by-block parsing with the Lark LALR grammar ``grammars/macro_b.lark``.

A program is parsed one line at a time, as the control reads it: a bad block yields one
:class:`SyntaxProblem` and the rest of the file still parses. Parsed lines are cached by their
text, so an edit re-parses only the lines it changed.
"""

from __future__ import annotations

import gc
import re
import sys
import threading
import unicodedata
import zlib
from bisect import bisect_right
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import replace
from functools import cached_property
from importlib import resources
from itertools import accumulate, islice
from operator import attrgetter, itemgetter
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, cast

from ..cancel import READING, SLICE, CancelToken, raise_if_cancelled
from ..database import TableKey, current
from ..lazy_regex import LazyPattern
from ..translation import Text, joined, tr
from . import dialects, grammar_tables
from .diff import Diff
from .fast_statements import fast_statement
from .lalr_driver import (
    TABLES_FORMAT,
    TableParser,
    Token,
    UnexpectedCharacters,
    UnexpectedInput,
    UnexpectedToken,
)
from .lines import (
    MAX_LINE_LENGTH,
    READ_WHOLE,
    LineCode,
    ReadLimits,
    cut_comments,
    decode_bytes,
    split_lines,
)
from .marks import CALL_CODES, INDEXED_STATEMENTS, mentions_call
from .tree import (
    BARE_CODES,
    SHARED_COLUMNS,
    SHARED_SPANS,
    Assign,
    BareCond,
    Binary,
    Block,
    BlockIf,
    Bracket,
    Call,
    Compare,
    Cond,
    Document,
    End,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    LineNote,
    Logic,
    MacroStatement,
    Mixed,
    NcStatement,
    Num,
    ParsedLine,
    PlainNc,
    Print,
    ProgramStart,
    Span,
    Statement,
    SyntaxProblem,
    Unary,
    Var,
    While,
    Word,
    quick_line,
    quick_nc,
    quick_num,
    quick_plain,
    quick_word,
    shared_span,
)
from .walk import bracket_depth, expression_depth, top_expressions

if TYPE_CHECKING:
    from lark import Lark


def grammar_text() -> str:
    return resources.files("fanuc_macro").joinpath("data/macro_b.lark").read_text("utf-8")


def grammar_crc32() -> int:
    """What grammar_tables.py was written from, with the format of its data: a check of an
    edit, not of an attack, so a CRC (zlib, which the evaluator loads too; hashlib would load
    OpenSSL at each start)."""
    text = f"{grammar_text()}\n{TABLES_FORMAT}"
    return zlib.crc32(text.encode("utf-8"))


def grammar_lark(cache: bool = True) -> Lark:
    """Lark's parser of the grammar, as the tables come from (``cache``: the grammar's tables
    kept in the temp folder, which a start then need not build: the server starts 40 ms
    sooner). Lark is imported here: the parser runs the shipped tables without it."""
    # Lark imports the ``regex`` package when it is installed, for its option regex=True,
    # which this grammar does not use: hidden while Lark loads, it is not imported (10 ms).
    hide_regex = "regex" not in sys.modules and "lark" not in sys.modules
    if hide_regex:
        sys.modules["regex"] = None  # type: ignore[assignment]  # 'import regex' raises ImportError
    try:
        from lark import Lark
    finally:
        if hide_regex:
            del sys.modules["regex"]
    return Lark(
        grammar_text(),
        parser="lalr",
        lexer="basic",
        transformer=_ToAst(),
        keep_all_tokens=True,
        maybe_placeholders=False,
        cache=cache,
    )


# Every node's span comes from these: they run a few hundred thousand times on a cold parse.
# A token is a str: the driver's Token, or Lark's when Lark parses (tests compare the two); the
# nodes are not. (Typed Any, so that the check leaves a node of Any as it is.)
_TOKEN: Any = str


def _span(node: Any) -> Span:
    if isinstance(node, _TOKEN):
        if node.start_pos is None or node.end_pos is None:
            return Span(node.start_pos, node.end_pos)
        return shared_span(node.start_pos, node.end_pos)
    span: Span = node.span
    return span


def _cover(first: Any, last: Any) -> Span:
    start: int = (first.start_pos or 0) if isinstance(first, _TOKEN) else first.span.start
    end: int = (last.end_pos or 0) if isinstance(last, _TOKEN) else last.span.end
    return shared_span(start, end)


MAX_DIGITS = 12  # FANUC takes 8 (0i) to 12 (30i) digits; more is a typo, and would overflow
# Levels of nesting in one block that the analysis follows (each operator, sign, bracket,
# function, AND/OR is one). Real blocks stay far below: FANUC allows five brackets. Deeper ASTs
# would exhaust Python's recursion in the nodes' own ==, hash and repr.
MAX_EXPRESSION_DEPTH = 100


def _number(token: Token) -> float:
    return _to_float(str(token))


def _to_float(text: str) -> float:
    if " " in text or "\t" in text:
        text = text.replace(" ", "").replace("\t", "")
    if len(text) > MAX_DIGITS and sum(ch.isdigit() for ch in text) > MAX_DIGITS:
        raise ValueError(
            tr(
                "the number {number_text}... has more than {digits} digits",
                number_text=text[:16],
                digits=MAX_DIGITS,
            )
        )
    return float(text)


class _ToAst:
    """Builds :mod:`fanuc_macro.syntax.tree` nodes while the LALR parser reduces (no parse tree):
    a transformer for the driver, and for Lark (its methods named after the grammar's rules)."""

    # ---- expressions
    def num(self, c: list[Any]) -> Num:
        if len(c) == 2:  # "-" NUMBER in a GOTO target
            return Num(-_number(c[1]), "-" + str(c[1]), _cover(c[0], c[1]))
        tok = c[0]
        return Num(_number(tok), str(tok).replace(" ", ""), _span(tok))

    neg_num = num

    def var_direct(self, c: list[Any]) -> Var:
        return Var(_number(c[1]), None, _cover(c[0], c[1]))

    def var_indirect(self, c: list[Any]) -> Var:
        return Var(None, c[2], _cover(c[0], c[3]))

    def binary(self, c: list[Any]) -> Binary:
        return Binary(str(c[1]).upper(), c[0], c[2], _cover(c[0], c[2]))

    def neg(self, c: list[Any]) -> Unary:
        return Unary("-", c[1], _cover(c[0], c[1]))

    def pos(self, c: list[Any]) -> Unary:
        return Unary("+", c[1], _cover(c[0], c[1]))

    def bracket(self, c: list[Any]) -> Bracket:
        if len(c) == 4:  # "+" "[" expr "]" after an address
            return Bracket(c[2], _cover(c[0], c[3]))
        return Bracket(c[1], _cover(c[0], c[2]))

    def neg_bracket(self, c: list[Any]) -> Unary:
        inner = Bracket(c[2], _cover(c[1], c[3]))
        return Unary("-", inner, _cover(c[0], c[3]))

    def call(self, c: list[Any]) -> Call:
        return Call(str(c[0]).upper(), (c[2],), _cover(c[0], c[3]), _span(c[0]))

    def call2(self, c: list[Any]) -> Call:
        return Call(str(c[0]).upper(), (c[2], c[4]), _cover(c[0], c[5]), _span(c[0]))

    def atan_slash(self, c: list[Any]) -> Call:
        # ATAN[a]/[b]: FANUC's two-argument arctangent, not a division.
        return Call("ATAN", (c[2], c[6]), _cover(c[0], c[7]), _span(c[0]), slash_form=True)

    # ---- conditions
    def compare(self, c: list[Any]) -> Compare:
        return Compare(str(c[1]).upper(), c[0], c[2], _cover(c[0], c[2]))

    def cond_term(self, c: list[Any]) -> Any:
        return c[1]

    def logic(self, c: list[Any]) -> Logic:
        terms = [x for x in c if not (isinstance(x, _TOKEN) and x.type in ("LSQB", "RSQB"))]
        first = terms[0]
        rest: list[tuple[str, Cond]] = []
        for i in range(1, len(terms), 2):
            rest.append((str(terms[i]).upper(), terms[i + 1]))
        return Logic(first, tuple(rest), _cover(c[0], c[-1]))

    def bare_cond(self, c: list[Any]) -> BareCond:
        return BareCond(c[0], _span(c[0]))

    # ---- statements
    def assign(self, c: list[Any]) -> Assign:
        return Assign(c[0], c[2], _cover(c[0], c[2]))

    def goto(self, c: list[Any]) -> Goto:
        return Goto(c[1], _cover(c[0], c[1]))

    def if_goto(self, c: list[Any]) -> IfGoto:
        return IfGoto(c[2], c[4], _cover(c[0], c[4]))

    def if_then(self, c: list[Any]) -> IfThen:
        return IfThen(c[2], c[5], _cover(c[0], c[5]))

    def if_then_nc(self, c: list[Any]) -> IfNc:
        return IfNc(c[2], c[5], True, _cover(c[0], c[5]))

    def if_nc(self, c: list[Any]) -> IfNc:
        return IfNc(c[2], c[4], False, _cover(c[0], c[4]))

    def if_block_open(self, c: list[Any]) -> BlockIf:
        return BlockIf("IF", c[2], _cover(c[0], c[4]))

    def else_stmt(self, c: list[Any]) -> BlockIf:
        return BlockIf("ELSE", None, _span(c[0]))

    def endif_stmt(self, c: list[Any]) -> BlockIf:
        return BlockIf("ENDIF", None, _span(c[0]))

    def while_do(self, c: list[Any]) -> While:
        return While(c[2], _number(c[5]), _span(c[5]), _cover(c[0], c[5]))

    def do_forever(self, c: list[Any]) -> While:
        return While(None, _number(c[1]), _span(c[1]), _cover(c[0], c[1]))

    def end_loop(self, c: list[Any]) -> End:
        return End(_number(c[1]), _span(c[1]), _cover(c[0], c[1]))

    def print_stmt(self, c: list[Any]) -> Print:
        text = str(c[0])
        return Print(text[:5].upper(), text, _span(c[0]))

    def popen(self, c: list[Any]) -> Print:
        return Print("POPEN", str(c[0]), _span(c[0]))

    def pclos(self, c: list[Any]) -> Print:
        return Print("PCLOS", str(c[0]), _span(c[0]))

    def word(self, c: list[Any]) -> Word:
        letter = str(c[0])
        address = _ADDRESSES.get(letter) or letter.upper()
        return Word(address, c[1], _cover(c[0], c[1]), letter.islower())

    def comma_word(self, c: list[Any]) -> Word:
        # ",C2." is the address ",C": no C axis word, no arc's R (see the grammar)
        letter = str(c[0])[-1]
        return Word("," + letter.upper(), c[1], _cover(c[0], c[1]), letter.islower())

    def nc_words(self, c: list[Any]) -> NcStatement:
        return NcStatement(tuple(c), _cover(c[0], c[-1]))

    def mixed_nc_macro(self, c: list[Any]) -> Mixed:
        return Mixed(c[0], c[1], _cover(c[0], c[1]))

    def mixed_macro_nc(self, c: list[Any]) -> Mixed:
        return Mixed(c[1], c[0], _cover(c[0], c[1]))

    # ---- the line
    def signed_num(self, c: list[Any]) -> Num:
        sign = -1.0 if str(c[0]) == "-" else 1.0
        text = str(c[1]).replace(" ", "")
        return Num(sign * _number(c[1]), str(c[0]) + text, _cover(c[0], c[1]))

    def skip(self, c: list[Any]) -> tuple[str, int, Span]:
        level = int(_number(c[1])) if len(c) > 1 else 0
        return ("skip", level, _cover(c[0], c[-1]))

    def seqnum(self, c: list[Any]) -> tuple[str, float, Span]:
        return ("seq", _number(c[1]), _cover(c[0], c[1]))

    def program_number(self, c: list[Any]) -> ProgramStart:
        number: int | None = None
        name: str | None = None
        for tok in c[1:]:
            if tok.type == "NUMBER":
                number = int(_number(tok))
            elif tok.type == "PROGRAM_NAME":
                name = str(tok)[1:-1]
        return ProgramStart(number, name, _cover(c[0], c[-1]))

    def start(self, c: list[Any]) -> list[Any]:
        return c

    def program_start(self, c: list[Any]) -> list[Any]:
        return c


# The fast path scans a block word by word with regexes in which every repeat is followed by a
# character it cannot take: a failed match gives back nothing worth retrying, so a line of any
# length is scanned in linear time. (One regex for the whole line, with the words as a repeated
# group, backtracked exponentially on a long line that fails at its end: "X11X11...X11[".)
_FAST_NUMBER = r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)"
_FAST_HEAD = re.compile(
    r"[ \t]*(?:(/)[ \t]*(?:(" + _FAST_NUMBER + r")[ \t]*)?)?"
    r"(?:(N)[ \t]*(" + _FAST_NUMBER + r")[ \t]*)?",
    re.I,
)
_FAST_WORD = re.compile(
    r"([A-MP-Z])[ \t]*"
    # A number written without spaces (nearly every word) in a group of its own: its text is
    # the Num's as it stands. The second group takes the rest: spaces after the sign, #n, -#n.
    r"(?:([-+]?" + _FAST_NUMBER + r")"
    r"|((?:[-+][ \t]*)?" + _FAST_NUMBER + r"|(?:-[ \t]*)?#[ \t]*[0-9]+))"
    r"[ \t]*",
    re.I,
)


# Address letters in upper case, one string each: str.upper() makes a new one every time, and
# every word holds its address.
_ADDRESSES: Mapping[str, str] = MappingProxyType(
    {ch: sys.intern(ch.upper()) for ch in "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"}
)

# Words of a number written as it stands, by column and text ('G01' at column 0, 'Z-2.5' at
# 20): the nodes are immutable, so blocks share them (a CAM file repeats its G code and a few
# hundred Z depths at a few columns) instead of holding a word, a number, its text and its
# float each. The first words seen are kept, up to the limit (a table of the database).
_SHARED_WORDS: TableKey[tuple[int, str], Word] = TableKey("syntax.shared_words", cache=True)
_SHARED_WORDS_LIMIT = 1 << 15
_SHARED_WORD_COLUMNS = 128  # a block's words are near its start; a long line's are its own

# Matches of _FAST_WORD one after the other from a column (typeshed does not list it).
_scan_words: Callable[[str, int], Any] = _FAST_WORD.scanner  # type: ignore[attr-defined]


def _fast_value(text: str, start: int) -> Expr:
    """Value of a plain word: a number, #n or -#n (spans as the grammar gives them)."""
    end = start + len(text)
    body = text.lstrip("-+ \t")
    if body.startswith("#"):
        hash_col = start + text.index("#")
        var = Var(_to_float(body[1:]), None, shared_span(hash_col, end))
        if text.startswith("-"):
            return Unary("-", var, shared_span(start, end))
        return var
    compact = text.replace(" ", "").replace("\t", "")
    if len(body) > MAX_DIGITS:
        _to_float(body)  # the grammar reads the sign apart: a number too long is named without it
    return Num(_to_float(compact), compact, shared_span(start, end))


# A block of plain words as ``PlainNc`` keeps them: numbers written right after their letter,
# of at most MAX_DIGITS characters (a longer one goes the way that reports a number too long to
# read). The repeats are possessive: a line that fails at its end is not scanned again.
PLAIN_BLOCK_PATTERN = (
    r"(?:[A-MP-Za-mp-z][-+]?(?=[.0-9]{1,12}+(?![.0-9]))"
    r"(?:[0-9]++(?:\.[0-9]*+)?|\.[0-9]++)[ \t]*+)++"
)


def without_possessive_repeats(pattern: str) -> str:
    """``pattern`` with its possessive repeats (``*+``, ``++``, ``?+``, ``{m,n}+``) made
    greedy ones, for Python 3.10's ``re``, which has none (the pattern has no ``+`` after one
    of ``*+?}`` in a character class). A pattern of which no repeat can give back a character
    that what follows takes, as _PLAIN_BLOCK's, matches the same lines: only a line that fails
    is scanned again, its length once more at most."""
    return re.sub(r"(?<!\\)([*+?}])\+", r"\1", pattern)


_PLAIN_BLOCK = re.compile(
    PLAIN_BLOCK_PATTERN
    if sys.version_info >= (3, 11)
    else without_possessive_repeats(PLAIN_BLOCK_PATTERN)
)
# The G and M words of a plain block (its code is known to be words of numbers).
_PLAIN_CODE_WORDS = re.compile(r"([GMgm])([-+]?[.0-9]+)")
# The G and M codes of plain blocks by their words' text, shared (a program repeats a few
# combinations; a table of the database); _CALLS for the words of a call or a return.
_PLAIN_CODES: TableKey[tuple[tuple[str, str], ...], tuple[tuple[str, float], ...]] = TableKey(
    "syntax.plain_codes", cache=True
)
_PLAIN_CODES_LIMIT = 10_000
_CALLS: tuple[tuple[str, float], ...] = (("M", 98.0),)


def _plain_codes(
    written: tuple[tuple[str, str], ...],
    shared: dict[tuple[tuple[str, str], ...], tuple[tuple[str, float], ...]],
) -> tuple[tuple[str, float], ...]:
    codes = tuple([(_ADDRESSES[letter], float(number)) for letter, number in written])
    if not CALL_CODES.isdisjoint(codes):
        codes = _CALLS
    if len(shared) >= _PLAIN_CODES_LIMIT:
        shared.clear()
    shared[written] = codes
    return codes


def _plain_block(
    code: str,
) -> tuple[int | None, int | None, Span | None, PlainNc] | None:
    """A block of words of numbers written without spaces, and no call or return, as a
    ``PlainNc`` (its nodes built on demand); None for any other block, which ``_fast_parse``
    or the grammar reads."""
    # A block that begins with its first word has no head to read (most blocks).
    head = None if code[:1] not in _HEAD_STARTS else _FAST_HEAD.match(code)
    pos = 0 if head is None else head.end()
    if _PLAIN_BLOCK.fullmatch(code, pos) is None:
        return None
    written = tuple(_PLAIN_CODE_WORDS.findall(code, pos))
    db = current()
    shared = db.table(_PLAIN_CODES)
    codes = shared.get(written)
    if codes is None:
        codes = _plain_codes(written, shared)
    if codes is _CALLS:
        return None  # the index looks at its words: built in full
    skip: int | None = None
    seq: int | None = None
    seq_span: Span | None = None
    if head is not None and head.lastindex is not None:
        slash, level, n_letter, n_value = head.group(1, 2, 3, 4)
        if (level is not None and len(level) > MAX_DIGITS) or (
            n_value is not None and len(n_value) > MAX_DIGITS
        ):
            return None
        skip = None if slash is None else int(float(level)) if level else 0
        if n_letter is not None:
            seq = int(float(n_value))
            seq_span = shared_span(head.start(3), head.end(4))
    # The words' span from the database at hand: a look-up of it less per plain block.
    end = len(code.rstrip())
    span = db.table(SHARED_SPANS).get(pos * SHARED_COLUMNS + end) if end < SHARED_COLUMNS else None
    if span is None:
        span = shared_span(pos, end)
    return skip, seq, seq_span, quick_plain(code, span, codes)


_HEAD_STARTS = frozenset("Nn/ \t")  # what a block's head (block skip, N number) begins with


def plain_words(code: str) -> tuple[Word, ...]:
    """The words of a ``PlainNc``'s code, as the fast parse builds them."""
    found = _fast_parse(code)
    assert found is not None and found[3] is not None  # a plain block is a fast one
    return found[3].words


def fast_parse(code: str) -> tuple[int | None, int | None, Span | None, NcStatement | None] | None:
    """Blocks of NC words with plain values, the bulk of real programs, without Lark.

    Returns None when the block is anything else; then the grammar decides. The result must
    equal the grammar's: tests/test_parser.py compares the two on every line it has.
    """
    found = _fast_parse(code)
    return None if found is None else found[:4]


def _fast_parse(
    code: str,
) -> tuple[int | None, int | None, Span | None, NcStatement | None, bool] | None:
    """``fast_parse`` and whether the block has a word that calls or returns (``has_call``)."""
    head = _FAST_HEAD.match(code)
    assert head is not None  # every part of it is optional
    slash, level, n_letter, n_value = head.group(1, 2, 3, 4)
    skip = None if slash is None else int(_to_float(level)) if level else 0
    seq: int | None = None
    seq_span: Span | None = None
    if n_letter is not None:
        seq = int(_to_float(n_value))
        seq_span = shared_span(head.start(3), head.end(4))
    pos = head.end()
    size = len(code)
    if pos == size:
        return skip, seq, seq_span, None, False
    words: list[Word] = []
    db = current()
    spans = db.table(SHARED_SPANS)
    has_call = False
    # A number too long to read is reported only once the whole block has matched: in a block
    # the grammar rejects for another reason, the grammar's message is the one to give.
    unreadable: ValueError | None = None
    # The scanner's matches follow one another, each where the last ended, until a word fails.
    shared = db.table(_SHARED_WORDS)
    for wm in iter(_scan_words(code, pos).match, None):
        letter, number, other = wm.groups()
        pos = wm.end()
        key: tuple[int, str] | None = None
        if number is not None:
            value_start, value_end = wm.span(2)
            if value_end < _SHARED_WORD_COLUMNS:
                key = (wm.start(), code[wm.start() : value_end])
                word = shared.get(key)
                if word is not None:
                    if word.address in "GM":
                        has_call = has_call or (word.address, word.value.value) in CALL_CODES  # type: ignore[union-attr]
                    words.append(word)
                    continue
            if len(number) > MAX_DIGITS:
                try:
                    _to_float(number.lstrip("+-"))  # named without its sign, as the grammar does
                except ValueError as err:
                    unreadable = unreadable or err
                    continue
            span = spans.get(value_start * SHARED_COLUMNS + value_end)
            if span is None or value_end >= SHARED_COLUMNS:
                span = shared_span(value_start, value_end)
            value: Expr = quick_num(float(number), number, span)
        else:
            value_start, value_end = wm.span(3)
            try:
                value = _fast_value(other, value_start)
            except ValueError as err:
                unreadable = unreadable or err
                continue
        start = wm.start()
        span = spans.get(start * SHARED_COLUMNS + value_end)
        if span is None or value_end >= SHARED_COLUMNS:
            span = shared_span(start, value_end)
        upper = _ADDRESSES.get(letter) or letter.upper()
        if upper in "GM" and type(value) is Num:
            has_call = has_call or (upper, value.value) in CALL_CODES
        word = quick_word(upper, value, span, letter != upper)
        if key is not None and len(shared) < _SHARED_WORDS_LIMIT:
            shared[key] = word
        words.append(word)
    if pos < size:
        return None
    if unreadable is not None:
        raise unreadable
    return (
        skip,
        seq,
        seq_span,
        quick_nc(tuple(words), shared_span(words[0].span.start, words[-1].span.end)),
        has_call,
    )


# The statements that hold NC words: only a word calls (``mentions_call``).
_WITH_WORDS = frozenset((NcStatement, PlainNc, Mixed, IfNc))


def _line(
    text: str,
    cut: LineCode,
    skip: int | None,
    seq: int | None,
    seq_span: Span | None,
    statement: Statement | None,
    problem: SyntaxProblem | None,
    has_lower: bool,
) -> ParsedLine:
    failed_assignment: int | None = None
    if statement is None and problem is not None:
        # What a rejected block plainly still says, so that one typing mistake does not make
        # later blocks wrong too: its N number (a GOTO's target) and the variable it assigns.
        head = _REJECTED_HEAD.match(cut.code)
        if head is not None:
            if seq is None and head.group("seq") is not None:
                seq = int(head.group("seq"))
                seq_span = shared_span(head.start("n"), head.end("seq"))
            if head.group("var") is not None and int(head.group("var")) > 0:
                failed_assignment = int(head.group("var"))
    has_call = type(statement) in _WITH_WORDS and mentions_call(statement)
    indexed = (
        seq is not None
        or cut.tape_mark
        or has_call
        or (statement is not None and type(statement) in INDEXED_STATEMENTS)
    )
    return quick_line(
        text, cut.tape_mark, skip, seq, seq_span, statement, cut.comments, problem, cut.notes,
        has_lower, has_call, indexed, failed_assignment,
    )  # fmt: skip


# The start of a block: block skip, N number, and an assignment '#n=' (or Syntec's '#n:='),
# alone or after IF [...] THEN.
_REJECTED_HEAD = re.compile(
    r"\s*(?:/\s*\d?\s*)?(?:(?P<n>N)\s*(?P<seq>\d{1,8})(?!\d)\s*)?"
    r"(?:(?:IF\s*\[.*\]\s*THEN\s*)?#\s*(?P<var>\d{1,6})\s*:?=(?!=))?",
    re.IGNORECASE,
)


@contextmanager
def quiet_gc() -> Iterator[None]:
    """No cyclic garbage collection while a document is parsed or analysed.

    The AST and the facts have no cycles, so reference counting frees them. Left on, the
    collector rescans the parse cache's growing heap again and again: it took more time than
    the parse itself. What exists after the run is not frozen out of later collections
    (``gc.freeze``): a frozen cycle is never freed, and every run left some (a parser's
    closures, a dropped workspace, an exception's frames), 1.4 MB an input in a fuzz campaign.
    The caches' budget (``analysis.CACHE_BUDGET``) bounds the heap a full collection scans.
    """
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()


# How many references an object has (CPython); elsewhere every cached line counts as unheld.
_refcount: Callable[[object], int] = getattr(sys, "getrefcount", lambda _obj: 0)


def _too_long(text: str, limit: int) -> ParsedLine:
    """A line longer than the analysis reads: only its block delete and sequence number (at its
    head, where the control reads them first) are kept, so that a GOTO to it still finds it."""
    head = _FAST_HEAD.match(text)
    assert head is not None  # every part of it is optional
    skip: int | None = None
    seq: int | None = None
    seq_span: Span | None = None
    try:
        if head.group(1) is not None:
            skip = int(_to_float(head.group(2))) if head.group(2) else 0
        if head.group(3) is not None:
            seq = int(_to_float(head.group(4)))
            seq_span = shared_span(head.start(3), head.end(4))
    except ValueError:  # a number too long to be one
        skip = seq = seq_span = None
    note = LineNote(
        "too-long",
        tr(
            "this block is {length} characters long, more than the {limit} the analysis reads "
            "(setting fanuc-macro.analysis.maxLineLength, --max-line-length): it is not analysed",
            length=len(text),
            limit=limit,
        ),
        Span(limit, len(text)),
    )
    return ParsedLine(
        text, False, skip, seq, seq_span, None, (), None, (note,), indexed=seq is not None
    )


def _too_deep(statement: Statement, depth: int) -> LineNote:
    brackets = max((bracket_depth(e) for e in top_expressions(statement)), default=0)
    message = tr(
        "the block nests {depth} levels deep (each operator, sign, bracket, function and "
        "AND/OR is a level), more than the {most} the analysis follows: it is not analysed",
        depth=depth,
        most=MAX_EXPRESSION_DEPTH,
    )
    if brackets > 5:
        message = tr(
            "{message}; its brackets nest {brackets} deep, and the control stops with alarm "
            "PS0118 past 5",
            message=message,
            brackets=brackets,
        )
    return LineNote("too-deep", message, statement.span)


# What a line's code parses to, apart from its comments: (made by the fast paths, block
# delete, N number and its span, the statement, whether it calls a program). Lines that differ
# in their comments only (a thread's passes numbered in them) share it, and so their nodes:
# the nodes are immutable and their spans are columns of the line, which the comments keep.
_ParsedCode = tuple[bool, int | None, int | None, Span | None, Statement | None, bool]
_BY_CODE_LIMIT = 4096  # codes kept; the oldest quarter goes when it is full
# The blanks the grammar skips (its %ignore): codes that differ only in trailing ones parse
# alike. str.rstrip() with no argument also strips U+00A0, U+3000 and the like, which the
# grammar rejects (MB001): keyed by that, such a code took its ASCII twin's parse.
_BLANKS = " \t\f\v"
_BLANKS_OR_EOF = _BLANKS + "\x1a"


def _line_of_code(text: str, cut: LineCode, has_lower: bool, code: _ParsedCode) -> ParsedLine:
    quick, skip, seq, seq_span, statement, has_call = code
    if quick:
        # What _line works out, known here: a block of plain words is indexed for its N
        # number, a tape mark or a call only.
        indexed = seq is not None or cut.tape_mark or has_call
        return quick_line(
            text, cut.tape_mark, skip, seq, seq_span, statement, cut.comments, None, cut.notes,
            has_lower, has_call, indexed, None,
        )  # fmt: skip
    return _line(text, cut, skip, seq, seq_span, statement, None, has_lower)


class BlockParser:
    """Parses lines; thread-safe; caches parsed lines by text (LRU)."""

    def __init__(self, cache_size: int = 200_000, use_fast_path: bool = True) -> None:
        self.use_fast_path = use_fast_path
        # Our driver runs the grammar's LALR tables faster than Lark's loop. They are shipped
        # as data (grammar_tables.py): a start loads no Lark object, unless the grammar changed.
        if grammar_crc32() == grammar_tables.GRAMMAR_CRC32:
            self._table = TableParser.from_tables(grammar_tables.tables(), _ToAst())
        else:
            self._table = TableParser(self._lark)
        # Insertion-ordered, so that the oldest lines are looked at first when it is full. A hit
        # costs one dict look-up: the order is refreshed at eviction, not on every hit.
        self._cache: dict[str, ParsedLine] = {}
        self._cache_size = cache_size
        self._sweep_at = cache_size  # the size at which the cache next looks for lines to drop
        self._longest_cached = 0  # no cached line is longer: a hit needs no length check
        self._cached_chars = 0  # of the cached lines' texts: what their trees grow with
        self._by_code: dict[str, _ParsedCode] = {}  # insertion-ordered: the oldest go first
        self._lock = threading.Lock()

    def cached(self) -> tuple[int, int]:
        """How many lines the cache holds, and their characters."""
        return len(self._cache), self._cached_chars

    def clear_cache(self) -> None:
        """Forget every cached line (the documents keep theirs). The dicts are replaced, so a
        parse in another thread goes on with the old ones."""
        with self._lock:
            self._cache = {}
            self._by_code = {}
            self._cached_chars = 0
            self._longest_cached = 0
            self._sweep_at = self._cache_size

    @cached_property
    def _lark(self) -> Lark:
        """Lark's parser of the grammar (the tables' source; for tests)."""
        return grammar_lark()

    def parse_line(self, text: str, max_line_length: int = MAX_LINE_LENGTH) -> ParsedLine:
        if len(text) > max_line_length:
            return _too_long(text, max_line_length)
        cached = self._cache.get(text)
        if cached is not None:
            return cached
        parsed = self._parse_uncached(text)
        size = len(text)
        with self._lock:
            cache = self._cache
            if text not in cache:
                self._cached_chars += size
            cache[text] = parsed
            if size > self._longest_cached:
                self._longest_cached = size
            if len(cache) > self._sweep_at:
                self._evict()
        return parsed

    def _evict(self) -> None:
        """Drops the oldest lines that no document (nor a per-line cache) holds any more, down
        to three quarters of the bound; the lines still held go to the end of the order. Those
        cost the cache only their entry, since their owner keeps them alive, and dropping them
        would make a document of more distinct lines than the bound parse every line again on
        each edit. So the cache holds at most ``cache_size`` lines of its own."""
        cache = self._cache
        batch = max(1, self._cache_size // 4)
        target = self._cache_size - batch  # room for a batch of new lines before the next sweep
        for key in list(cache):
            if len(cache) <= target:
                break
            parsed = cache.pop(key)
            # The references: the line's holders, ``parsed`` and getrefcount's argument.
            if _refcount(parsed) > 2:
                cache[key] = parsed
            else:
                self._cached_chars -= len(key)
        # When documents hold most lines, no new sweep before the cache has grown by a batch:
        # a sweep per new line would make a big document's parse quadratic.
        self._sweep_at = max(self._cache_size, len(cache) + batch)

    def _parse_uncached(self, text: str) -> ParsedLine:
        if (
            self.use_fast_path
            and "[" not in text  # no plain block has a bracket or an assignment
            and "=" not in text
            and "(" not in text
            and ";" not in text
            and "%" not in text
            and ")" not in text
        ):
            # No comment, end of block or tape mark: the code is the text. A block of plain
            # words without a call is indexed for its N number only.
            plain = _plain_block(text)
            if plain is not None:
                plain_skip, plain_seq, plain_seq_span, plain_nc = plain
                lower = text != text.upper()
                return quick_line(
                    text, False, plain_skip, plain_seq, plain_seq_span, plain_nc, (), None, (),
                    lower, False, plain_seq is not None, None,
                    not lower and BARE_CODES.issuperset(plain_nc.codes),
                )  # fmt: skip
        cut = cut_comments(text)
        code = cut.code
        # ASCII blanks only: a line of U+3000 or U+00A0 is no empty block to FANUC. A line of
        # DOS's end-of-file mark (Ctrl-Z, 0x1A, after the closing % of an old file) is none
        # either: the sending program stops at it, and the control never reads it.
        if code[:1] in _BLANKS_OR_EOF and not code.strip(_BLANKS_OR_EOF):
            return _line(text, cut, None, None, None, None, None, False)
        has_lower = code != code.upper()
        # A line with a comment: lines of the same code share what it parses to.
        key = code.rstrip(_BLANKS) if code is not text else None
        if key is not None:
            known = self._by_code.get(key)
            if known is not None:
                return _line_of_code(text, cut, has_lower, known)
        parsed_code = self._parse_code(code, text, cut, has_lower)
        if isinstance(parsed_code, ParsedLine):
            return parsed_code
        if key is not None:
            with self._lock:
                by_code = self._by_code
                by_code[key] = parsed_code
                if len(by_code) > _BY_CODE_LIMIT:
                    for oldest in list(islice(by_code, _BY_CODE_LIMIT // 4)):
                        del by_code[oldest]
        return _line_of_code(text, cut, has_lower, parsed_code)

    def _parse_code(
        self, code: str, text: str, cut: LineCode, has_lower: bool
    ) -> ParsedLine | _ParsedCode:
        """What a line's code parses to, or the whole line where the code has a problem."""
        read: tuple[int | None, int | None, Span | None, Statement | None] | None = None
        if self.use_fast_path:
            # No plain block has a bracket or an assignment: those go to the macro reader.
            if "[" not in code and "=" not in code:
                plain = _plain_block(code)
                if plain is not None:
                    # Plain words without a call: indexed for an N number or a tape mark.
                    plain_skip, plain_seq, plain_seq_span, plain_nc = plain
                    return (True, plain_skip, plain_seq, plain_seq_span, plain_nc, False)
                try:
                    fast = _fast_parse(code)
                except ValueError as err:  # a number too long to be one
                    problem = SyntaxProblem(_unreadable_number(err), Span(0, len(text.rstrip())))
                    return _line(text, cut, None, None, None, None, problem, has_lower)
                if fast is not None:
                    return (True, *fast)
            if not has_lower:
                read = fast_statement(code)
        if read is None:
            grammar = self._grammar_parse(code, text, cut, has_lower)
            if isinstance(grammar, ParsedLine):
                return grammar
            read = grammar
        skip, seq, seq_span, statement = read
        # A block nests at most as deep as it has characters: most need no measuring.
        if statement is not None and len(code) > MAX_EXPRESSION_DEPTH:
            depth = expression_depth(statement)
            if depth > MAX_EXPRESSION_DEPTH:
                note = _too_deep(statement, depth)
                deep = LineCode(cut.code, cut.comments, cut.tape_mark, (*cut.notes, note))
                return _line(text, deep, skip, seq, seq_span, None, None, has_lower)
        return (False, skip, seq, seq_span, statement, False)

    def _grammar_parse(
        self, code: str, text: str, cut: LineCode, has_lower: bool
    ) -> ParsedLine | tuple[int | None, int | None, Span | None, Statement | None]:
        """A line's code read by the grammar's tables, or the whole line where it is rejected."""
        try:
            # The transformer's start() makes the result a list, not a tree.
            items = cast("list[Any]", self._table.parse(code))
        except UnexpectedInput as err:
            problem = _describe(code, err, text)
            return _line(text, cut, None, None, None, None, problem, has_lower)
        except (ValueError, OverflowError) as err:  # a number too long to be one
            problem = SyntaxProblem(_unreadable_number(err), Span(0, len(text.rstrip())))
            return _line(text, cut, None, None, None, None, problem, has_lower)
        skip: int | None = None
        seq: int | None = None
        seq_span: Span | None = None
        statement: Statement | None = None
        for item in items:
            if isinstance(item, tuple):
                if item[0] == "skip":
                    skip = item[1]
                else:
                    seq = int(item[1])
                    seq_span = item[2]
            else:
                statement = item
        return skip, seq, seq_span, statement

    def parse_lines(
        self, lines: Iterable[str], max_line_length: int = MAX_LINE_LENGTH
    ) -> list[ParsedLine]:
        get = self._cache.get
        parse = self.parse_line
        with quiet_gc():
            if self._longest_cached <= max_line_length:
                return [get(line) or parse(line, max_line_length) for line in lines]
            # A lower limit than lines already cached: each line is measured first.
            return [parse(line, max_line_length) for line in lines]


def _unreadable_number(err: Exception) -> Text:
    """MB001 for a number the reader cannot take (too many digits)."""
    reason = err.args[0] if err.args and isinstance(err.args[0], Text) else str(err)
    return tr("cannot read a number: {reason}", reason=reason)


_TOKEN_NAMES: Mapping[str, str] = MappingProxyType(
    {
        "NUMBER": tr("a number"),
        "SIGNED_NUMBER": tr("a number"),
        "ADDRESS": tr("an address letter"),
        "COMMA_ADDRESS": tr("an address letter"),  # ",C" ",R" ",A": said once with the others
        "LSQB": "'['",
        "RSQB": "']'",
        "EQUAL": "'='",
        "RELOP": "EQ/NE/GT/GE/LT/LE",
        "HASH": "'#'",
        "MINUS": "'-'",
        "PLUS": "'+'",
        "COMMA": "','",
        "COLON": "':'",
        "FUNC": tr("a function"),
        "ADD_OP": tr("an operator"),
        "MUL_OP": tr("an operator"),
        "$END": tr("end of block"),
    }
)


def _expected_words(expected: Iterable[str]) -> tuple[str, ...]:
    words: list[str] = []
    for name in sorted(expected):
        word = _TOKEN_NAMES.get(name)
        if word is None:
            if name.startswith("__ANON") or name.startswith("_"):
                continue
            word = name.replace("LOGIC_", "")
        if word not in words:
            words.append(word)
    return tuple(words)


def _describe(code: str, err: UnexpectedInput, text: str | None = None) -> SyntaxProblem:
    """A message a CNC programmer can act on: what was found, where, what would do."""
    if isinstance(err, UnexpectedCharacters):
        col = err.column - 1 if err.column and err.column > 0 else err.pos_in_stream or 0
        found = code[col : col + 1]
        expected = _expected_words(err.allowed or ())
    elif isinstance(err, UnexpectedToken):
        tok = err.token
        col = tok.start_pos if tok.start_pos is not None else len(code.rstrip())
        found = "end of block" if tok.type == "$END" else str(tok)
        expected = _expected_words(err.expected or ())
    else:  # pragma: no cover - the driver raises only the two above
        col, found, expected = 0, "", ()
    if found == "end of block" or col >= len(code.rstrip()):
        end = max(col, len(code.rstrip()))
        span = Span(max(0, end - 1), end) if end > 0 else Span(0, 0)
    else:
        span = Span(col, col + max(1, len(found)))
    dialect = dialects.recognise(code, text)
    if dialect is not None:
        return SyntaxProblem(dialect.message, span, expected, dialect.name)
    misspelt = _misspelt_keyword(code)
    if misspelt is not None:
        name, name_col, keyword = misspelt
        return SyntaxProblem(
            tr(
                "{word_text} at column {column} is no FANUC word: {keyword}?",
                word_text=repr(name),
                column=name_col + 1,
                keyword=keyword,
            ),
            Span(name_col, name_col + len(name)),
            expected,
        )
    unknown = _unknown_function(code, col)
    if unknown is not None:
        name, name_col = unknown
        return SyntaxProblem(
            tr(
                "unknown function {function_text}: FANUC has SIN COS TAN ASIN ACOS ATAN SQRT ABS "
                "ROUND FIX FUP LN EXP POW ADP BIN BCD",
                function_text=repr(name),
            ),
            Span(name_col, name_col + len(name)),
            expected,
            None,
            name.upper(),
        )
    typed = _typing_mistake(code, col, found, expected)
    if typed is not None:
        message, typed_span = typed
        return SyntaxProblem(message, typed_span or span, expected)
    weak = dialects.recognise_weak(code)
    if weak is not None:  # PLAIN (""): a syntax error, no dialect
        return SyntaxProblem(weak.message, span, expected, weak.name or None)
    if found == "end of block":
        message = tr("unexpected end of block at column {column}", column=col + 1)
    else:
        message = tr(
            "unexpected {found_text} at column {column}", found_text=repr(found), column=col + 1
        )
    if expected:
        message = tr(
            "{message}; expected {expected}", message=message, expected=joined(", ", expected[:8])
        )
    return SyntaxProblem(message, span, expected, None)


def _depth_before(code: str, col: int) -> tuple[int, int | None]:
    """Bracket depth at ``col`` and the column of the innermost '[' still open there."""
    opened: list[int] = []
    depth = 0
    for i, ch in enumerate(code[:col]):
        if ch == "[":
            opened.append(i)
            depth += 1
        elif ch == "]":
            depth -= 1
            if opened:
                opened.pop()
    return depth, (opened[-1] if opened else None)


_NUMBER_TEXT = LazyPattern(r"[0-9]*\.?[0-9]*")
# No two repeats here can take the same characters (a space run, a digit run): a failed search
# on a long line stays linear.
_WORD_BEFORE = LazyPattern(
    r"([A-MP-Z])[ \t]*((?:[-+][ \t]*)?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+))[ \t]*$", re.I
)
_ADDRESS_BEFORE = LazyPattern(r"([A-MP-Z])[ \t]*(?:[-+][ \t]*)?$", re.I)
_BLOCK_HEAD = LazyPattern(r"\s*(?:/\s*(?:\d\s*)?)?(?:N\s*\d+\s*)?", re.I)
_LETTERS = LazyPattern(r"[A-Z]+", re.I)
_CONDITION = LazyPattern(r"^\s*(N\d+\s*)?(IF|WHILE|WH)\s*\[", re.I)


def _non_ascii_mistake(code: str, col: int) -> tuple[str, Span | None] | None:
    """A character FANUC does not read: a full-width letter, any other non-ASCII."""
    ch = code[col : col + 1]
    if not ch or ord(ch) <= 127:
        return None
    plain = unicodedata.normalize("NFKC", ch)
    if plain != ch and plain.isascii():
        name = unicodedata.name(ch, "")
        described = (
            tr("full-width {char_text}", char_text=repr(ch))
            if name.startswith("FULLWIDTH") or not name
            else tr("{name_text} {char_text}", name_text=name.lower(), char_text=repr(ch))
        )
        return (
            tr(
                "{character} (U+{code:04X}) at column {column}: FANUC reads ASCII program "
                "text only; write {plain_text}",
                character=described,
                code=ord(ch),
                column=col + 1,
                plain_text=repr(plain),
            ),
            Span(col, col + 1),
        )
    return (
        tr(
            "{char_text} (U+{code:04X}) at column {column}: FANUC reads ASCII program text only",
            char_text=repr(ch),
            code=ord(ch),
            column=col + 1,
        ),
        Span(col, col + 1),
    )


def _bracket_mistake(
    code: str, col: int, found: str, expected: tuple[str, ...]
) -> tuple[bool, tuple[str, Span | None] | None]:
    """A bracket left open or closing nothing, or a comparison written as another language
    does: (whether the block's mistake is decided here, the mistake)."""
    depth, open_col = _depth_before(code, len(code) if found == "end of block" else col)
    if found == "end of block" or found.upper() in ("DO", "GOTO", "THEN"):
        if depth > 0 and open_col is not None:
            return True, (
                tr(
                    "'[' at column {column} is not closed before the end of the block",
                    column=open_col + 1,
                )
                if found == "end of block"
                else tr(
                    "'[' at column {column} is not closed before {found_text}",
                    column=open_col + 1,
                    found_text=repr(found),
                ),
                Span(open_col, open_col + 1),
            )
        if found == "end of block" and "'='" in expected and re.fullmatch(r"\s*#\s*\d+\s*", code):
            written = code.strip()
            return True, (
                tr(
                    "a variable alone is no block: {variable}=<value> assigns it, and an address "
                    "letter before it (X{variable}) makes it a word",
                    variable=written,
                ),
                None,
            )
        return True, None
    if found == "]" and depth <= 0:
        return True, (tr("']' at column {column} closes no '['", column=col + 1), None)
    if depth > 0:
        if _CONDITION.match(code):
            if found == "=":
                if "<>" in code:
                    return True, (
                        tr(
                            "'=' at column {column} is no comparison on FANUC: write EQ (and "
                            "'<>' for NE)",
                            column=col + 1,
                        ),
                        None,
                    )
                return True, (
                    tr(
                        "'=' at column {column} is no comparison on FANUC: write EQ", column=col + 1
                    ),
                    None,
                )
            if found == "<" and code[col : col + 2] == "<>":
                return True, (
                    tr(
                        "'<>' at column {column} is no comparison on FANUC: write NE",
                        column=col + 1,
                    ),
                    None,
                )
        return True, None
    return False, None


def _number_without_address(
    code: str, col: int, found: str, before: str
) -> tuple[str, Span | None]:
    """A number typed where a word begins: the letter O as the digit 0, a G left out."""
    at_head = _BLOCK_HEAD.fullmatch(before) is not None
    if at_head and found.startswith("0") and len(found) >= 2:
        if not code[col + len(found) :].strip():
            return (
                tr(
                    "{number_text} at column {column} has no address letter: the letter O "
                    "typed as the digit 0? A program number is written O{digits}",
                    number_text=repr(found),
                    column=col + 1,
                    digits=found[1:],
                ),
                None,
            )
        return (
            tr(
                "{number_text} at column {column} has no address letter (G{digits} meant, "
                "or the letter O typed as the digit 0?)",
                number_text=repr(found),
                column=col + 1,
                digits=found,
            ),
            None,
        )
    return (
        tr(
            "the number {number_text} at column {column} has no address letter",
            number_text=repr(found),
            column=col + 1,
        ),
        None,
    )


def _typing_mistake(
    code: str, col: int, found: str, expected: tuple[str, ...]
) -> tuple[str, Span | None] | None:
    """What FANUC rejects in blocks typed wrong: a full-width letter, a decimal comma, a number
    without its address, an expression outside brackets, an unclosed '['."""
    mistake = _non_ascii_mistake(code, col)
    if mistake is not None:
        return mistake
    decided, mistake = _bracket_mistake(code, col, found, expected)
    if decided:
        return mistake
    before = code[:col].rstrip()
    if found == "," and before[-1:].isdigit():
        word = _WORD_BEFORE.search(code[:col])
        value = word.group(2).replace(" ", "") if word else before.split()[-1]
        tail = _NUMBER_TEXT.match(code, col + 1)
        digits = tail.group(0) if tail else ""
        return (
            tr(
                "',' at column {column} in {number_text}: FANUC's decimal point is '.'; write "
                "{fixed_text}",
                column=col + 1,
                number_text=repr(value + "," + digits),
                fixed_text=value + "." + digits,
            ),
            None,
        )
    if (
        found.startswith(".")
        and before
        and before[-1] in "0123456789."
        and "." in before.split()[-1]
    ):
        word = _WORD_BEFORE.search(code[:col])
        value = word.group(2).replace(" ", "") if word else before.split()[-1]
        return (
            tr(
                "a second decimal point at column {column}, in {number_text}",
                column=col + 1,
                number_text=repr(value + found),
            ),
            None,
        )
    if found[:1] in "*/+-" and _WORD_BEFORE.search(code[:col]):
        word = _WORD_BEFORE.search(code[:col])
        assert word is not None
        letter = word.group(1).upper()
        expression = _expression_from(code, word.start(2))
        return (
            tr(
                "an expression after an address must be in brackets on FANUC: write "
                "{letter}[{expression_text}], not {letter}{expression_text}",
                letter=letter,
                expression_text=expression,
            ),
            None,
        )
    name = found.upper()
    if name in _KNOWN_FUNCTIONS:
        address = _ADDRESS_BEFORE.search(code[:col])
        if address is not None and address.group(0).strip():
            letter = address.group(1).upper()
            return (
                tr(
                    "a function after an address must be in brackets on FANUC: write "
                    "{letter}[{function}[...]], not {letter}{function}[...]",
                    letter=letter,
                    function=name,
                ),
                None,
            )
        return (
            tr(
                "{function}[...] at column {column} has no address letter: a value needs one "
                "(X[{function}[...]]), or an assignment (#1={function}[...])",
                function=name,
                column=col + 1,
            ),
            None,
        )
    if _NUMBER_TEXT.fullmatch(found) and found.strip("."):
        return _number_without_address(code, col, found, before)
    if found[:1].isalpha() and _ADDRESS_BEFORE.search(code[:col]):
        address = _ADDRESS_BEFORE.search(code[:col])
        assert address is not None
        return (
            tr(
                "address {address} at column {address_column} has no value (found {found_text} "
                "at column {column})",
                address=address.group(1).upper(),
                address_column=address.start(1) + 1,
                found_text=repr(found),
                column=col + 1,
            ),
            None,
        )
    return None


def _expression_from(code: str, start: int) -> str:
    """The text of an unbracketed expression from ``start`` to the next address letter."""
    depth = 0
    i = start
    while i < len(code):
        ch = code[i]
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
        elif ch.isalpha() and depth == 0:
            name = _LETTERS.match(code, i)
            word = name.group(0).upper() if name else ""
            known = next(
                (f for f in (*_KNOWN_FUNCTIONS, *_OPERATOR_WORDS) if word.startswith(f)), None
            )
            if known is None:
                break
            i += len(known)
            continue
        i += 1
    return code[start:i].strip()


_OPERATOR_WORDS = ("MOD", "AND", "OR", "XOR")
_KEYWORDS = ("WHILE", "GOTO", "THEN", "END", "POPEN", "PCLOS", "DPRNT", "BPRNT")
_LEADING_NAME = LazyPattern(r"^\s*(?:N\d+\s*)?([A-Z]{3,})", re.I)


def _misspelt_keyword(code: str) -> tuple[str, int, str] | None:
    """'WHIL[' or 'GOT 10': a keyword one letter off, at the head of the block."""
    m = _LEADING_NAME.match(code)
    if m is None:
        return None
    name = m.group(1).upper()
    if name in _KEYWORDS or name in _KNOWN_FUNCTIONS or name.startswith(("IF", "GOTO")):
        return None
    import difflib  # for a misspelt keyword only: not on every start's path

    close = difflib.get_close_matches(name, _KEYWORDS, n=1, cutoff=0.8)
    if not close:
        return None
    return m.group(1), m.start(1), close[0]


_KNOWN_FUNCTIONS = frozenset(
    "SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP POW ADP BIN BCD".split()  # noqa: SIM905
)
# From the first letter of a run only: tried at every letter, a long run of letters with no
# '[' after it took quadratic time.
_WORD_BEFORE_BRACKET = LazyPattern(r"(?<![A-Z])([A-Z]{2,})\s*\[", re.I)


def _unknown_function(code: str, col: int) -> tuple[str, int] | None:
    """A name written like a function (``FOO[``) that FANUC does not have, near the error."""
    for m in _WORD_BEFORE_BRACKET.finditer(code):
        name = m.group(1).upper()
        # "GOTO[", "IF[", "WHILE[", "DPRNT[" are statements; a trailing known name is a call.
        if name in _KNOWN_FUNCTIONS or name in ("IF", "WHILE", "WH", "GOTO", "DPRNT", "BPRNT"):
            continue
        if any(name.endswith(f) for f in _KNOWN_FUNCTIONS) or name.endswith(("IF", "GOTO")):
            continue
        if m.start() <= col <= m.end():
            return m.group(1), m.start()
    return None


# The parser of the code that names none, one per database: its cache of parsed lines is the
# database's (a workspace's lines live and go with it).
_DEFAULT_PARSER: TableKey[str, BlockParser] = TableKey("syntax.default_parser")


def default_parser() -> BlockParser:
    """The current database's parser (:mod:`fanuc_macro.database`), made on first use."""
    parsers = current().table(_DEFAULT_PARSER)
    parser = parsers.get("")
    if parser is None:
        # Two threads asking at once may both make one: the first stored is the one kept.
        parser = parsers.setdefault("", BlockParser())
    return parser


def parse_text(
    text: str,
    uri: str = "",
    parser: BlockParser | None = None,
    previous: Document | None = None,
    limits: ReadLimits = READ_WHOLE,
    cancel: CancelToken | None = None,
    previous_limits: ReadLimits | None = None,
    previous_text: str | None = None,
) -> Document:
    """Parse a document; with ``previous`` (its last version) unchanged lines keep their blocks.

    Past the ``limits`` of a document the lines get no block (``line_count`` still counts
    them), and ``unread_note`` says what was left out. ``cancel`` is looked at every
    :data:`~fanuc_macro.cancel.SLICE` lines (see :mod:`fanuc_macro.cancel`). When
    ``previous`` was read by the same parser with ``previous_limits`` equal to ``limits``, its
    lines are compared by text and only those between the first and the last change parsed;
    with ``previous_text`` too (the text ``previous`` was read from), the texts are compared
    instead and only the lines of the edit are split out of ``text``."""
    raise_if_cancelled(cancel)
    bp = parser or default_parser()
    if previous is not None and previous_text is not None and previous_limits == limits:
        edited = _edited_document(previous, previous_text, text, bp, limits, cancel)
        if edited is not None:
            return edited
    lines = split_lines(text)
    read = _lines_read(text, lines, limits)
    with quiet_gc():
        if previous is not None and previous_limits == limits:
            blocks = _blocks_by_text(
                previous.blocks, lines if read == len(lines) else lines[:read], bp, limits, cancel
            )
        else:
            parsed = _parse_lines(bp, lines if read == len(lines) else lines[:read], limits, cancel)
            if previous is None:
                blocks = tuple(map(Block, range(read), parsed))
            else:
                blocks = _blocks_after_edit(previous.blocks, parsed)
    if read == len(lines):
        return Document(uri, blocks, "utf-8", None, len(lines))
    note = _unread_note(text, lines, read, limits)
    return Document(uri, blocks, "utf-8", None, len(lines), read, note)


def _edited_document(
    previous: Document,
    old: str,
    new: str,
    bp: BlockParser,
    limits: ReadLimits,
    cancel: CancelToken | None,
) -> Document | None:
    """The new version of a document read whole from its text and the previous version's, for
    texts with LF line ends only: the characters both share at the start and at the end are
    found by comparing slices in C, and only the lines between are split and parsed (splitting
    a whole text per keystroke cost more than the rest of reading it). None: read it the
    usual way (CR in either text, or a limit that leaves lines unread)."""
    if previous.unread_from is not None or "\r" in new or "\r" in old:
        return None
    if limits.max_characters is not None and len(new) > limits.max_characters:
        return None
    parts = new.count("\n") + 1  # what str.split("\n") gives; a final "" is no line
    count = parts - 1 if parts > 1 and new.endswith("\n") else parts
    if limits.max_blocks is not None and count > limits.max_blocks:
        return None
    old_parts = old.count("\n") + 1
    old_count = old_parts - 1 if old_parts > 1 and old.endswith("\n") else old_parts
    blocks = previous.blocks
    if len(blocks) != old_count:
        return None
    head = _common_head(old, new)
    tail = _common_tail(old, new, min(len(old), len(new)) - head)
    if head == len(old) == len(new):
        return Document(previous.uri, blocks, "utf-8", None, count)
    # The parts (lines, and a final "" after a last line end) the edit touched: from the one
    # that holds the first changed character to the one that holds the last (or where the
    # text was cut, when it was only cut); the parts around are the same in both texts.
    first = old.count("\n", 0, head)
    start = old.rfind("\n", 0, head) + 1
    old_end, new_end = len(old) - tail, len(new) - tail
    old_last = first + old.count("\n", start, old_end)
    stop = new.find("\n", new_end)
    middle = new[start : len(new) if stop < 0 else stop].split("\n")
    new_last = first + len(middle) - 1
    # Parts past the last line are the final "" of a text ending with a line end.
    edited_lines = middle[: max(0, min(new_last + 1, count) - first)]
    kept_from = min(old_last + 1, old_count)
    parsed = _parse_lines(bp, edited_lines, limits, cancel)
    with quiet_gc():
        edited = tuple(map(Block, range(first, first + len(parsed)), parsed))
        after_at = first + len(parsed)
        if after_at != kept_from:
            after = tuple(map(Block, range(after_at, count), map(_PARSED, blocks[kept_from:])))
        else:
            after = blocks[kept_from:]
        out = blocks[:first] + edited + after
    if len(out) != count:  # not expected: read it the usual way rather than wrongly
        return None
    return Document(previous.uri, out, "utf-8", None, count)


_CHUNK = 2048  # characters compared at once


def _common_head(a: str, b: str) -> int:
    """How many characters ``a`` and ``b`` share at their start."""
    n = min(len(a), len(b))
    i = 0
    while i < n and a[i : i + _CHUNK] == b[i : i + _CHUNK]:
        i += _CHUNK
    if i >= n:
        return n
    end = min(i + _CHUNK, n)
    while i < end and a[i] == b[i]:
        i += 1
    return i


def _common_tail(a: str, b: str, most: int) -> int:
    """How many characters, at most ``most``, ``a`` and ``b`` share at their end."""
    la, lb = len(a), len(b)
    k = 0
    while (
        k < most
        and a[la - min(k + _CHUNK, most) : la - k] == b[lb - min(k + _CHUNK, most) : lb - k]
    ):
        k = min(k + _CHUNK, most)
    if k >= most:
        return most
    end = min(k + _CHUNK, most)
    while k < end and a[la - k - 1] == b[lb - k - 1]:
        k += 1
    return k


def _parse_lines(
    bp: BlockParser, lines: list[str], limits: ReadLimits, cancel: CancelToken | None
) -> list[ParsedLine]:
    if cancel is None:
        return bp.parse_lines(lines, limits.max_line_length)
    parsed: list[ParsedLine] = []
    for start in range(0, len(lines), SLICE):
        if start:
            cancel.reached(READING, start, len(lines))
        parsed += bp.parse_lines(lines[start : start + SLICE], limits.max_line_length)
    return parsed


_TEXT = attrgetter("text")  # ParsedLine.text, read in C


def _blocks_by_text(
    old: tuple[Block, ...],
    lines: list[str],
    bp: BlockParser,
    limits: ReadLimits,
    cancel: CancelToken | None,
) -> tuple[Block, ...]:
    """The blocks of a new version of a document read like ``old``: the lines before the first
    and after the last line whose text changed keep their parse (the parser would give them the
    same: a line's parse depends on its text and the limits alone), without a cache look-up
    per line; the lines between are parsed."""
    diff = Diff(list(map(_TEXT, map(_PARSED, old))), lines, identical=False)
    start, end = diff.start, diff.end
    edited = tuple(
        map(Block, range(start, end), _parse_lines(bp, lines[start:end], limits, cancel))
    )
    if diff.shift:
        after = tuple(map(Block, range(end, len(lines)), map(_PARSED, old[diff.old_end :])))
    else:
        after = old[diff.old_end :]
    return old[:start] + edited + after


_PARSED = itemgetter(1)  # Block.parsed, read in C


def _blocks_after_edit(old: tuple[Block, ...], parsed: list[ParsedLine]) -> tuple[Block, ...]:
    """The blocks of the new version of a document: the earlier version's where its lines
    are the same lines at the same place (the parser shares an unchanged line's parse), new
    ones for the lines between its first and last change and, when lines were added or
    removed, for the lines after it (their number changed)."""
    diff = Diff(list(map(_PARSED, old)), parsed, identical=True)
    start, end = diff.start, diff.end
    edited = tuple(map(Block, range(start, end), parsed[start:end]))
    if diff.shift:
        after = tuple(map(Block, range(end, len(parsed)), parsed[end:]))
    else:
        after = old[diff.old_end :]
    return old[:start] + edited + after


def _lines_read(text: str, lines: list[str], limits: ReadLimits) -> int:
    """How many lines, from the first, the limits let the analysis read."""
    read = len(lines)
    if limits.max_blocks is not None:
        read = min(read, limits.max_blocks)
    if limits.max_characters is not None and len(text) > limits.max_characters:
        # The lines whose text and line end fit within the limit; of a line longer than the
        # analysis reads, only that much counts (it is not read further).
        longest = limits.max_line_length
        ends = accumulate(min(len(line), longest) + 1 for line in lines[:read])
        read = min(read, bisect_right(list(ends), limits.max_characters))
    return read


def _unread_note(text: str, lines: list[str], read: int, limits: ReadLimits) -> str:
    if limits.max_blocks is not None and read == limits.max_blocks:
        return tr(
            "analysed the first {read} blocks of {count}: the document has {count} blocks, more "
            "than the {most} the analysis reads (setting fanuc-macro.analysis.maxBlocks, "
            "--max-blocks); the blocks from line {line} on are not checked",
            read=read,
            count=len(lines),
            most=limits.max_blocks,
            line=read + 1,
        )
    return tr(
        "analysed the first {read} blocks of {count}: the document has {size} characters, more "
        "than the {most} the analysis reads (setting fanuc-macro.analysis.maxFileSize, "
        "--max-file-size); the blocks from line {line} on are not checked",
        read=read,
        count=len(lines),
        size=len(text),
        most=limits.max_characters,
        line=read + 1,
    )


def parse_bytes(
    data: bytes, uri: str = "", parser: BlockParser | None = None, limits: ReadLimits = READ_WHOLE
) -> Document:
    decoded = decode_bytes(data)
    doc = parse_text(decoded.text, uri, parser, limits=limits)
    return replace(doc, encoding=decoded.encoding, decode_note=decoded.note)


def statements_of(statement: Statement | None) -> Sequence[Statement]:
    """The statements a block holds: one, or two for a mixed NC + macro block."""
    if statement is None:
        return ()
    if isinstance(statement, Mixed):
        return (statement.nc, statement.macro)
    return (statement,)


__all__ = (
    "MAX_EXPRESSION_DEPTH",
    "BlockParser",
    "Expr",
    "MacroStatement",
    "default_parser",
    "parse_bytes",
    "parse_text",
    "statements_of",
)
