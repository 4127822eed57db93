"""Macro statements, and NC words with bracketed values, read without the grammar's tables.

The blocks of a macro program that are not plain NC words (``parser._fast_parse``) are mostly
a few forms: assignments, IF/GOTO/WHILE/DO/END, words whose values are expressions. The LALR
driver reads them at a few dozen microseconds a block; :func:`fast_statement` reads them by
recursive descent over the same rules (``data/macro_b.lark``) and builds the nodes the
grammar's transformer (``parser._ToAst``) builds, with the same spans (shared as
``tree.shared_span`` shares them). Whatever it is not sure of (lower case, a program number,
DPRNT, a number of more than 12 characters, an error of any kind) it leaves to the grammar by
returning None. tests/test_fast_statements.py compares the two on every line it has.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from itertools import accumulate
from typing import Any, NoReturn

from ..database import TableKey, current
from .tree import (
    SHARED_COLUMNS,
    SHARED_SPANS,
    Assign,
    BareCond,
    Binary,
    BlockIf,
    Bracket,
    Call,
    Compare,
    Cond,
    End,
    Expr,
    Goto,
    IfGoto,
    IfNc,
    IfThen,
    Logic,
    MacroStatement,
    Mixed,
    NcStatement,
    Num,
    Print,
    Span,
    Statement,
    Unary,
    Var,
    While,
    Word,
    quick_nc,
)

# The grammar's tokens: a variable's '#' and the number after it (one token here: they are one
# node), a number, a run of letters, a comma address, or any other character alone; ``split``
# gives them with the blanks the grammar skips between them. The grammar's
# terminals of letters are made of letters alone, so a run that is one of them (or a letter)
# is that one token there too (its lexer takes the first terminal that matches, and none
# other matches the whole run: a test asks it); the reader takes no other run, nor a
# character where the grammar has none. The input has no lower case.
_TOKENS = re.compile(
    r"(#(?:[0-9]+\.?[0-9]*|\.[0-9]+)|[0-9]+\.?[0-9]*|\.[0-9]+|[A-Z]+|,[ \t]*[ACR]|[^ \t\f\v])"
)
_split: Callable[[str], list[str]] = _TOKENS.split
_END = "$end"  # after the last token: no token is this text

_NUMBER_STARTS = frozenset("0123456789.")  # a token of these is a number ("." alone refused)
_ADDRESS_LETTERS = frozenset("ABCDEFGHIJKLMPQRSTUVWXYZ")
_ADDITIVE = frozenset(("+", "-", "OR", "XOR"))
_MULTIPLICATIVE = frozenset(("*", "/", "AND", "MOD"))
_LOGIC = frozenset(("AND", "OR", "XOR"))
_RELOPS = frozenset(("EQ", "NE", "GT", "GE", "LT", "LE"))
_FUNCTIONS = frozenset("SIN COS TAN ASIN ACOS SQRT ABS ROUND FIX FUP LN EXP ADP BIN BCD".split())  # noqa: SIM905
_CALLS = _FUNCTIONS | {"ATAN", "POW"}
_MACRO_STARTS = frozenset(
    ("GOTO", "IF", "WHILE", "WH", "DO", "END", "ELSE", "ENDIF", "POPEN", "PCLOS")
)
# The keywords and names the reader takes, each one token of the grammar (tests ask its lexer).
RUNS = _ADDRESS_LETTERS | _ADDITIVE | _MULTIPLICATIVE | _RELOPS | _CALLS | _MACRO_STARTS | {"THEN"}
# Numbers of at most this many characters are read here; the grammar's way reads any of them
# the same (``parser.MAX_DIGITS``, at least as many, limits its digits) and reports longer ones.
_LONGEST_NUMBER = 12
# The values of number texts read (a table of the database): float() of a text costs several
# dict look-ups, and a program writes the same variable numbers and constants over and over. The
# first ones seen are kept, up to the limit.
_NUMBER_VALUES: TableKey[str, float] = TableKey("syntax.number_values", cache=True)
_NUMBER_VALUES_LIMIT = 1 << 12
# Words by column and text ('X[#24+1.]' at 20), with how many tokens they are (a table of the
# database): a program writes the same few at the same columns. The first ones seen are kept,
# up to the limit; words that end past the column limit are a long line's own.
_WORDS: TableKey[tuple[int, str], tuple[Word, int]] = TableKey("syntax.macro_words", cache=True)
_WORDS_SEEN_LIMIT = 1 << 12
_SHARED_WORD_COLUMNS = 128
_SIGNS = frozenset("+-")
# Tokens in a block this reader takes: its recursion (three calls a level of brackets) stays
# far from Python's limit. Real blocks have a few dozen.
_MOST_TOKENS = 120
_HEADS = frozenset(("/", "N", _END))  # what a block delete, an N number or nothing begins with


def _layout(cls: type) -> Any:
    """A class of ``cls``'s slots without its frozen ``__setattr__``: a node is filled as one of
    these and then made a ``cls`` (``__class__`` assignment, allowed between classes of one
    layout, as ``tree.quick_line`` does), at a third of the cost of the dataclass's
    ``__init__``. (Typed Any: its attributes are ``cls``'s.)"""
    made = type(f"_{cls.__name__}Layout", (), {"__slots__": vars(cls)["__slots__"]})
    probe = made()
    probe.__class__ = cls  # a layout that differs fails here, at import
    return made


# The nodes a block of expressions is mostly made of.
_NUM = _layout(Num)
_VAR = _layout(Var)
_BINARY = _layout(Binary)
_UNARY = _layout(Unary)
_BRACKET = _layout(Bracket)
_WORD = _layout(Word)
_ASSIGN = _layout(Assign)
_CALL = _layout(Call)


class _Refused(Exception):
    """The block is not one this reader is sure of: the grammar reads it."""


def _refuse() -> NoReturn:
    raise _Refused


class _Reader:
    """The tokens of one block, read left to right: ``texts`` (``_END`` after the last) and
    ``bounds`` (token k from column ``bounds[2k]`` to ``bounds[2k + 1]``). Every column is
    below ``SHARED_COLUMNS``: each span is a shared one (``tree.shared_span``), looked up in
    ``spans`` (``get``: its ``get``)."""

    __slots__ = ("bounds", "code", "floats", "get", "i", "spans", "texts", "words_seen")

    def __init__(self, code: str, texts: list[str], bounds: list[int]) -> None:
        db = current()
        self.code = code
        self.texts = texts
        self.bounds = bounds
        self.spans = db.table(SHARED_SPANS)
        self.get = self.spans.get
        self.floats = db.table(_NUMBER_VALUES)
        self.words_seen = db.table(_WORDS)
        self.i = 0

    def span(self, start: int, end: int) -> Span:
        key = start * SHARED_COLUMNS + end
        found = self.get(key)
        if found is None:
            found = self.spans[key] = Span(start, end)
        return found

    def to_float(self, text: str) -> float:
        """The value of a number's text, or of a variable's ("#100"), which ``floats`` lacks
        (or which is 0)."""
        digits = text[1:] if text[0] == "#" else text
        if len(digits) > _LONGEST_NUMBER:
            _refuse()
        value = float(digits)
        if len(self.floats) < _NUMBER_VALUES_LIMIT:
            self.floats[text] = value
        return value

    def token_span(self, k: int) -> Span:
        bounds = self.bounds
        return self.span(bounds[2 * k], bounds[2 * k + 1])

    def close(self) -> int:
        """Takes the ']' at the current token; its end column."""
        i = self.i
        if self.texts[i] != "]":
            _refuse()
        self.i = i + 1
        return self.bounds[2 * i + 1]

    def number(self, k: int) -> Num:
        """The number at token ``k`` (known to be one)."""
        text = self.texts[k]
        start = self.bounds[2 * k]
        end = self.bounds[2 * k + 1]
        node = _NUM()
        node.value = self.floats.get(text) or self.to_float(text)
        node.text = text
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Num
        made: Num = node
        return made

    def unary(self, op: str, operand: Expr, start: int) -> Unary:
        end = operand.span.end
        node = _UNARY()
        node.op = op
        node.operand = operand
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Unary
        made: Unary = node
        return made

    # ---- expressions: ?expr (+ - OR XOR) over ?term (* / AND MOD) over ?factor

    def expr(self, first: Expr | None = None) -> Expr:
        """The expression from the current token, or from the factor ``first`` already read:
        products (* / AND MOD) summed (+ - OR XOR), each from the left."""
        texts = self.texts
        term = self.factor() if first is None else first
        op = texts[self.i]
        total: Expr | None = None  # the sum of the terms before ``term``
        total_op = ""
        while True:
            while op in _MULTIPLICATIVE:
                self.i += 1
                right = self.factor()
                term = self.binary(op, term, right)
                op = texts[self.i]
            total = term if total is None else self.binary(total_op, total, term)
            if op not in _ADDITIVE:
                return total
            total_op = op
            self.i += 1
            term = self.factor()
            op = texts[self.i]

    def factor(self) -> Expr:
        i = self.i
        tok = self.texts[i]
        node: Any
        if tok[0] in _NUMBER_STARTS:  # a number, made here (the most frequent factor)
            self.i = i + 1
            start = self.bounds[2 * i]
            end = self.bounds[2 * i + 1]
            node = _NUM()
            node.value = self.floats.get(tok) or self.to_float(tok)
            node.text = tok
            node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
            node.__class__ = Num
            return node  # type: ignore[no-any-return]
        if tok[0] == "#":
            return self.var()
        if tok == "[":
            return self.bracket(self.bounds[2 * i])
        if tok == "-" or tok == "+":
            self.i = i + 1
            return self.unary(tok, self.factor(), self.bounds[2 * i])
        if tok in _CALLS:
            return self.call()
        _refuse()

    def bracket(self, start: int) -> Bracket:
        """``[expr]`` at the current token, its span from ``start``."""
        self.i += 1
        inner = self.expr()
        i = self.i
        if self.texts[i] != "]":
            _refuse()
        self.i = i + 1
        return self.bracketed(inner, start, self.bounds[2 * i + 1])

    def binary(self, op: str, left: Expr, right: Expr) -> Binary:
        start = left.span.start
        end = right.span.end
        node = _BINARY()
        node.op = op
        node.left = left
        node.right = right
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Binary
        made: Binary = node
        return made

    def bracketed(self, inner: Expr, start: int, end: int) -> Bracket:
        node = _BRACKET()
        node.inner = inner
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Bracket
        made: Bracket = node
        return made

    def signed(self, sign: str, k: int) -> Num:
        """``-5.`` or ``+5.``: the sign at token ``k``, the number after it."""
        text = self.texts[k + 1]
        start = self.bounds[2 * k]
        end = self.bounds[2 * k + 3]
        node = _NUM()
        value = self.floats.get(text) or self.to_float(text)
        node.value = -value if sign == "-" else value
        node.text = sign + text
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Num
        made: Num = node
        return made

    def var(self) -> Var:
        """``#n`` (one token, or '#' and a number after blanks) or ``#[expr]``."""
        i = self.i
        tok = self.texts[i]
        bounds = self.bounds
        node = _VAR()
        if len(tok) > 1:
            self.i = i + 1
            end = bounds[2 * i + 1]
            node.number = self.floats.get(tok) or self.to_float(tok)
            node.index = None
        else:
            after = self.texts[i + 1]
            self.i = i + 2
            if after[0] in _NUMBER_STARTS:
                end = bounds[2 * i + 3]
                node.number = self.floats.get(after) or self.to_float(after)
                node.index = None
            elif after == "[":
                node.index = self.expr()
                node.number = None
                end = self.close()
            else:
                _refuse()
        start = bounds[2 * i]
        node.span = self.get(start * SHARED_COLUMNS + end) or self.span(start, end)
        node.__class__ = Var
        made: Var = node
        return made

    def call(self) -> Call:
        i = self.i
        name = self.texts[i]
        start = self.bounds[2 * i]
        if self.texts[i + 1] != "[":
            _refuse()
        self.i = i + 2
        first = self.expr()
        if self.texts[self.i] == ",":
            if name != "ATAN" and name != "POW":
                _refuse()
            self.i += 1
            second = self.expr()
            end = self.close()
            return self.made_call(name, (first, second), start, end, False)
        if name == "POW":
            _refuse()
        end = self.close()
        if name == "ATAN" and self.texts[self.i] == "/":
            # ATAN[a]/[b]: the grammar takes the '/' into the call (it shifts), so a '/'
            # after ATAN[a] that no '[' follows is an error there.
            if self.texts[self.i + 1] != "[":
                _refuse()
            self.i += 2
            second = self.expr()
            end = self.close()
            return self.made_call("ATAN", (first, second), start, end, True)
        return self.made_call(name, (first,), start, end, False)

    def made_call(
        self, name: str, args: tuple[Expr, ...], start: int, end: int, slash_form: bool
    ) -> Call:
        node = _CALL()
        node.name = name
        node.args = args
        node.span = self.span(start, end)
        node.name_span = self.span(start, start + len(name))
        node.slash_form = slash_form
        node.__class__ = Call
        made: Call = node
        return made

    # ---- conditions

    def cond(self) -> Cond:
        """A condition up to the ']' that closes its bracket."""
        node, bare = self.cond_or_expr()
        if bare:
            assert not isinstance(node, (Compare, Logic, BareCond))
            return BareCond(node, node.span)
        assert isinstance(node, (Compare, Logic, BareCond))
        return node

    def cond_or_expr(self) -> tuple[Expr | Cond, bool]:
        """What stands in a bracket where a condition may: a condition, or an expression (True)
        that the caller makes a ``BareCond`` or, in a bracket that opens a condition's first
        term, a ``Bracket``."""
        texts = self.texts
        if texts[self.i] != "[":
            return self.compare_or_expr(self.expr())
        # '[' opens either a bracketed expression or the first term of [c] AND [c]: the grammar
        # reads a bracket around an expression as the expression's (it shifts its ']'), and a
        # bracket around a comparison or a logic as a term.
        start = self.bounds[2 * self.i]
        self.i += 1
        inner, bare = self.cond_or_expr()
        end = self.close()
        if bare:
            assert not isinstance(inner, (Compare, Logic, BareCond))
            return self.compare_or_expr(self.expr(self.bracketed(inner, start, end)))
        assert isinstance(inner, (Compare, Logic, BareCond))
        rest: list[tuple[str, Cond]] = []
        while texts[self.i] in _LOGIC:
            op = texts[self.i]
            if texts[self.i + 1] != "[":
                _refuse()
            self.i += 2
            term = self.cond()
            self.close()
            rest.append((op, term))
        if not rest:
            _refuse()
        return Logic(inner, tuple(rest), self.span(inner.span.start, rest[-1][1].span.end)), False

    def compare_or_expr(self, left: Expr) -> tuple[Expr | Cond, bool]:
        op = self.texts[self.i]
        if op not in _RELOPS:
            return left, True
        self.i += 1
        right = self.expr()
        return Compare(op, left, right, self.span(left.span.start, right.span.end)), False

    # ---- NC words

    def words(self) -> NcStatement:
        texts = self.texts
        found: list[Word] = []
        while True:
            tok = texts[self.i]
            if tok in _ADDRESS_LETTERS:
                found.append(self.word(tok))
            elif tok[0] == "," and len(tok) > 1:
                found.append(self.word("," + tok[-1]))  # ",C" ",R" ",A"
            else:
                break
        if not found:
            _refuse()
        return quick_nc(tuple(found), self.span(found[0].span.start, found[-1].span.end))

    def word(self, address: str) -> Word:
        """The word at the current token. One seen before at the same column with the same
        text is shared (as ``parser._SHARED_WORDS`` shares plain words): its nodes are
        immutable and its spans are its columns."""
        i = self.i
        texts = self.texts
        bounds = self.bounds
        start = bounds[2 * i]
        # Where the word ends, when its text tells without reading it: a value of one token,
        # or a bracket in which none nests (-1: not told).
        value_tok = texts[i + 1]
        first = value_tok[0]
        end = -1
        if first in _NUMBER_STARTS or (first == "#" and len(value_tok) > 1):
            end = bounds[2 * i + 3]
        elif value_tok == "[" or (first in _SIGNS and texts[i + 2] == "["):
            code = self.code
            opened = bounds[2 * i + 2] if first == "[" else bounds[2 * i + 4]
            close = code.find("]", opened)
            if close > 0 and code.find("[", opened + 1, close) < 0:
                end = close + 1
        key: tuple[int, str] | None = None
        if 0 < end < _SHARED_WORD_COLUMNS:
            key = (start, self.code[start:end])
            known = self.words_seen.get(key)
            if known is not None:
                self.i = i + known[1]
                return known[0]
        self.i = i + 1
        value = self.word_value()
        value_end = value.span.end
        node = _WORD()
        node.address = address
        node.value = value
        node.span = self.get(start * SHARED_COLUMNS + value_end) or self.span(start, value_end)
        node.address_lowercase = False
        node.__class__ = Word
        word: Word = node
        if key is not None and value_end == end and len(self.words_seen) < _WORDS_SEEN_LIMIT:
            self.words_seen[key] = (word, self.i - i)
        return word

    def word_value(self) -> Expr:
        i = self.i
        texts = self.texts
        tok = texts[i]
        if tok[0] in _NUMBER_STARTS:
            self.i = i + 1
            return self.number(i)
        if tok[0] == "#":
            return self.var()
        if tok == "[":
            return self.bracket(self.bounds[2 * i])
        if tok != "-" and tok != "+":
            _refuse()
        start = self.bounds[2 * i]
        after = texts[i + 1]
        if after[0] in _NUMBER_STARTS:
            self.i = i + 2
            return self.signed(tok, i)
        self.i = i + 1
        if after[0] == "#":
            return self.unary(tok, self.var(), start)
        if after != "[":
            _refuse()
        if tok == "+":  # "+[...]" is the bracket, from the sign
            return self.bracket(start)
        return self.unary("-", self.bracket(self.bounds[2 * i + 2]), start)

    # ---- statements

    def body(self) -> Statement:
        """The statement of a block, from the current token to the end."""
        texts = self.texts
        tok = texts[self.i]
        statement: Statement
        if tok in _ADDRESS_LETTERS or tok[0] == ",":
            nc = self.words()
            if texts[self.i] in _MACRO_STARTS or texts[self.i][0] == "#":
                macro = self.macro()
                statement = Mixed(nc, macro, self.span(nc.span.start, macro.span.end))
            else:
                statement = nc
        elif tok[0] == "#":
            assign = self.assign()
            if texts[self.i] in _ADDRESS_LETTERS or texts[self.i][0] == ",":
                nc = self.words()
                statement = Mixed(nc, assign, self.span(assign.span.start, nc.span.end))
            else:
                statement = assign
        else:
            statement = self.macro()
        if texts[self.i] != _END:
            _refuse()
        return statement

    def assign(self) -> Assign:
        if self.texts[self.i][0] != "#":
            _refuse()
        target = self.var()
        if self.texts[self.i] != "=":
            _refuse()
        self.i += 1
        value = self.expr()
        node = _ASSIGN()
        node.target = target
        node.value = value
        node.span = self.span(target.span.start, value.span.end)
        node.__class__ = Assign
        made: Assign = node
        return made

    def macro(self) -> MacroStatement:
        i = self.i
        tok = self.texts[i]
        start = self.bounds[2 * i]
        if tok[0] == "#":
            return self.assign()
        if tok == "GOTO":
            return self.goto()
        if tok == "IF":
            return self.if_statement()
        if tok == "WHILE" or tok == "WH":
            if self.texts[i + 1] != "[":
                _refuse()
            self.i = i + 2
            cond = self.cond()
            self.close()
            if self.texts[self.i] != "DO":
                _refuse()
            self.i += 1
            loop = self.loop_number()
            return While(cond, loop.value, loop.span, self.span(start, loop.span.end))
        if tok == "DO" or tok == "END":
            self.i = i + 1
            loop = self.loop_number()
            if tok == "DO":
                return While(None, loop.value, loop.span, self.span(start, loop.span.end))
            return End(loop.value, loop.span, self.span(start, loop.span.end))
        if tok == "ELSE" or tok == "ENDIF":
            self.i = i + 1
            return BlockIf(tok, None, self.token_span(i))
        if tok == "POPEN" or tok == "PCLOS":
            self.i = i + 1
            return Print(tok, tok, self.token_span(i))
        _refuse()

    def loop_number(self) -> Num:
        i = self.i
        if self.texts[i][0] not in _NUMBER_STARTS:
            _refuse()
        self.i = i + 1
        return self.number(i)

    def goto(self) -> Goto:
        i = self.i  # at GOTO
        texts = self.texts
        start = self.bounds[2 * i]
        tok = texts[i + 1]
        target: Expr
        if tok[0] in _NUMBER_STARTS:
            self.i = i + 2
            target = self.number(i + 1)
        elif tok[0] == "#":
            self.i = i + 1
            target = self.var()
        elif tok == "[":
            self.i = i + 1
            target = self.bracket(self.bounds[2 * i + 2])
        elif tok == "-" and texts[i + 2][0] in _NUMBER_STARTS:
            self.i = i + 3
            target = self.signed("-", i + 1)
        else:
            _refuse()
        return Goto(target, self.span(start, target.span.end))

    def if_statement(self) -> MacroStatement:
        i = self.i  # at IF
        start = self.bounds[2 * i]
        if self.texts[i + 1] != "[":
            _refuse()
        self.i = i + 2
        cond = self.cond()
        self.close()
        k = self.i
        tok = self.texts[k]
        if tok == "GOTO":
            goto = self.goto()
            return IfGoto(cond, goto, self.span(start, goto.span.end))
        if tok == "THEN":
            self.i = k + 1
            after = self.texts[k + 1]
            if after[0] == "#":
                then = self.assign()
                return IfThen(cond, then, self.span(start, then.span.end))
            if after == _END:
                return BlockIf("IF", cond, self.span(start, self.bounds[2 * k + 1]))
            words = self.words()
            return IfNc(cond, words, True, self.span(start, words.span.end))
        words = self.words()
        return IfNc(cond, words, False, self.span(start, words.span.end))


def fast_statement(
    code: str,
) -> tuple[int | None, int | None, Span | None, Statement | None] | None:
    """A block's block delete level, N number, its span and statement, as the grammar reads
    them, for a block of upper case code (comments cut out); None when the grammar is to read
    it."""
    if len(code) >= SHARED_COLUMNS:
        return None
    parts = _split(code)
    if len(parts) > 2 * _MOST_TOKENS:
        return None
    texts = parts[1::2]
    if "." in texts:  # a point that is no number's
        return None
    texts.append(_END)
    # The columns where each token starts and ends, from the lengths of blanks and tokens.
    reader = _Reader(code, texts, list(accumulate(map(len, parts))))
    try:
        if texts[0] in _HEADS:
            return _head(reader)
        return None, None, None, reader.body()
    except (_Refused, RecursionError):
        return None


def _head(reader: _Reader) -> tuple[int | None, int | None, Span | None, Statement | None]:
    """A block that begins with a block delete or an N number."""
    texts = reader.texts
    i = 0
    skip: int | None = None
    if texts[0] == "/":
        i = 1
        skip = 0
        if texts[1][0] in _NUMBER_STARTS:
            skip = int(reader.number(1).value)
            i = 2
    seq: int | None = None
    seq_span: Span | None = None
    if texts[i] == "N":
        if texts[i + 1][0] not in _NUMBER_STARTS:
            _refuse()
        seq = int(reader.number(i + 1).value)
        seq_span = reader.span(reader.bounds[2 * i], reader.bounds[2 * i + 3])
        i += 2
    if texts[i] == _END:
        return skip, seq, seq_span, None
    reader.i = i
    return skip, seq, seq_span, reader.body()


__all__ = ("RUNS", "fast_statement")
