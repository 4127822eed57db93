"""The macro reader (``syntax/fast_statements.py``) must give what the grammar gives: every line
it takes parses, through ``BlockParser``, to a ``ParsedLine`` equal field by field to the
grammar's (``BlockParser(use_fast_path=False)``), with nodes of the same classes, the same
numbers (sign of zero included), the same spans and the same shared span objects. Compared on
every line of the corpus and the fixtures, on edge cases, and on random macro lines."""

from __future__ import annotations

import dataclasses
import math
import random
from collections.abc import Iterator
from pathlib import Path

import pytest

from fanuc_macro.database import Database
from fanuc_macro.syntax import fast_statements
from fanuc_macro.syntax.fast_statements import fast_statement
from fanuc_macro.syntax.lines import cut_comments, decode_bytes, split_lines
from fanuc_macro.syntax.parser import MAX_DIGITS, BlockParser, grammar_lark
from fanuc_macro.syntax.tree import SHARED_COLUMNS, NcStatement, ParsedLine, PlainNc, Span, Word

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures"
CORPUS = ROOT.parent / "shared" / "corpus"


# ---- a strict comparison


def _same(a: object, b: object, where: str, shared: bool) -> None:
    """``a`` and ``b`` alike: the same classes, equal numbers with the same sign, equal spans
    and, where ``shared``, the same span objects (``tree.shared_span``'s)."""
    if isinstance(a, PlainNc) or isinstance(b, PlainNc):  # the plain path's: compared as words
        assert isinstance(a, NcStatement) and isinstance(b, NcStatement), where
        _same(a.span, b.span, f"{where}.span", shared)
        _same(a.words, b.words, f"{where}.words", shared)
        return
    assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, float):
        assert isinstance(b, float)
        assert a == b and math.copysign(1.0, a) == math.copysign(1.0, b), f"{where}: {a} {b}"
    elif isinstance(a, Span):
        assert a == b, f"{where}: {a} != {b}"
        if shared and a.start >= 0 and a.end < SHARED_COLUMNS:
            assert a is b, f"{where}: {a} is not the shared span"
    elif isinstance(a, tuple):
        assert isinstance(b, tuple) and len(a) == len(b), f"{where}: {a!r} != {b!r}"
        for k, (x, y) in enumerate(zip(a, b, strict=True)):
            _same(x, y, f"{where}[{k}]", shared)
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            if f.name in ("bare", "compiled"):  # neither compared (the plain path sets bare)
                continue
            inside = shared and f.name not in ("problem", "notes")  # their spans are made new
            _same(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}", inside)
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


def _compare(lines: list[str]) -> tuple[int, int]:
    """Parses every line with the fast paths and with the grammar alone (in one database, so
    that shared spans are the same objects); how many lines the macro reader took and how many
    the grammar rejected."""
    fast, grammar = BlockParser(), BlockParser(use_fast_path=False)
    taken = rejected = 0
    for text in lines:
        expected = grammar.parse_line(text)
        got = fast.parse_line(text)
        _same(got, expected, repr(text), True)
        assert got == expected, text
        code = cut_comments(text).code
        if code == code.upper() and fast_statement(code) is not None:
            taken += 1
            assert expected.problem is None, text
        rejected += expected.problem is not None
    return taken, rejected


# ---- the lines of real programs and of the fixtures


def _file_lines(paths: list[Path]) -> list[str]:
    out: list[str] = []
    for path in paths:
        out.extend(split_lines(decode_bytes(path.read_bytes()).text))
    return out


def test_every_corpus_line() -> None:
    if not CORPUS.is_dir():
        pytest.skip(f"the shared corpus is not there ({CORPUS})")
    lines = _file_lines(sorted(p for p in CORPUS.rglob("*") if p.is_file()))
    assert len(lines) > 2000
    taken, rejected = _compare(lines)
    assert taken > 500 and rejected > 50


def test_every_fixture_line() -> None:
    lines = _file_lines(sorted(FIXTURES.rglob("*.nc")))
    assert len(lines) > 2000
    taken, rejected = _compare(lines)
    assert taken > 500 and rejected > 50


# ---- edge cases

EDGE_LINES = [
    "#7=#101*123.+SQRT[5.] (计算 123)",
    "G00 X[#100+3.] Z7.123",
    "G92 X[#100-0.5] W-[#102+#101+0.123] F#101 (螺纹加工 9)",
    "G01 W[123.*0.0001] (偏移)",
    "IF[#1GT#2]GOTO10",
    "WHILE[#20LT25]DO1",
    "#[#1+1]=ABS[#2]",
    "#1=-[#2]",
    "#1=--1",
    "#1=-+-1",
    "#1=+1",
    "#1=1++1",
    "#1=1--1",
    "#1=-#2*#3",
    "#1=#2*-#3",
    "#1=-0",
    "#1=-0.",
    "X-0",
    "X-[0]",
    "GOTO-0",
    "X-[#1]",
    "X+[#1]",
    "X+#1",
    "X-#1",
    "X - 5.",
    "X + .5",
    "X--1",
    "X-SIN[1]",
    "XSIN[1]",
    "G#1",
    "G# 1",
    "G#[#1]",
    "#1=#2#3",
    "#1=[]",
    "#1=[1",
    "#1=1]",
    "#1=[[1]",
    "#1=[1]]",
    "X[]",
    "X[",
    "#1=",
    "#1",
    "#",
    "#.5=1",
    "#1.=2.",
    "#1=1.2.3",
    "#1=1..",
    "#1=.",
    "X.",
    "X1.2.3",
    "#1=" + "9" * 12,
    "#1=" + "9" * 13,
    "#1=0." + "0" * 11 + "1",
    "#" + "9" * 13 + "=1",
    "X[" + "9" * 13 + "]",
    "GOTO" + "9" * 13,
    "N" + "9" * 13 + " #1=1",
    "/" + "9" * 13 + " #1=1",
    "#1=[[[[[[1]]]]]]",
    "#1=" + "[" * 40 + "1" + "]" * 40,
    "#1=" + "-" * 150 + "1",
    "#1=" + "+".join(["1"] * 120),
    "#1=ATAN[1]/[2]",
    "#1=ATAN[1]/[2]/3",
    "#1=ATAN[1]/[2]/[3]",
    "#1=ATAN[1]/2",
    "#1=ATAN[1]/-[2]",
    "#1=ATAN[1]*[2]",
    "#1=ATAN[1,2]",
    "#1=ATAN[1,2]/[3]",
    "#1=ATAN[1]/[2,3]",
    "#1=ATAN[1]",
    "#1=ATAN [ 1 ] / [ 2 ]",
    "#1=ATAN[1,ABS[2]]",
    "#1=ATAN[1, COS[2]]",
    "#1=ATAN[1 ,ROUND[2]]",
    "#1=POW[2,3]",
    "#1=POW[2]",
    "#1=SIN[1,2]",
    "#1=ROUND[#1]+FIX[#2]-FUP[#3]*BIN[#4]/BCD[#5]",
    "#1=ASIN[1]+ACOS[1]+SQRT[1]+LN[1]+EXP[1]+ADP[1]+TAN[1]+COS[1]",
    "#1=#2 AND #3 OR #4 XOR #5 MOD #6",
    "#1=#2AND#3OR#4XOR#5MOD#6",
    "#1=[1]OR[2]XOR[3]AND[4]",
    "#1=POW[2,3]+ATAN[1]+ABS[-1]MOD3",
    "#1=1+2*3-4/5",
    "#1=1*2+3*4-5*6",
    "IF[[#1GT1]AND[#2LT2]]GOTO1",
    "IF[[#1]AND[#2]]GOTO1",
    "IF[[#1GT1]AND[#2]]GOTO1",
    "IF[[#2]AND[#1GT1]]GOTO1",
    "IF[[[#1GT1]]AND[#2GT1]]GOTO1",
    "IF[[#1GT1]]GOTO1",
    "IF[[#1]GT1]GOTO1",
    "IF[[#1]+1GT[2]]GOTO1",
    "IF[[[#1GT1]AND[#2GT2]]OR[#3GT3]]GOTO1",
    "IF[[#1GT1]AND[[#2]GT2]]GOTO1",
    "IF[[#1GT1]AND[[#2GT2]OR[#3GT3]]]GOTO1",
    "IF[[#1EQ1]OR[#2EQ2]AND[#3EQ3]]THEN#4=1",
    "IF[[#1GT1]AND]GOTO1",
    "IF[[#1GT1]AND[#2GT2]GT3]GOTO1",
    "IF[#1GT#2GT#3]GOTO1",
    "IF[#1 GT 1 AND #2]GOTO1",
    "IF[#1]GOTO5",
    "IF[#1EQ#2]GOTO#3",
    "IF[#1EQ#2]GOTO[#3+1]",
    "IF[#1EQ#2]GOTO-5",
    "IF[#1EQ#2]GOTO+5",
    "IF[#1EQ#2]THEN#3=1",
    "IF[#1EQ#2]THEN #3=1 X1",
    "IF[#1EQ#2]THEN",
    "IF[#1EQ#2]THEN X1 Y2",
    "IF[#1EQ#2] S#20 F#30",
    "IF[#1=#2]GOTO1",
    "IF[#1<>#2]GOTO1",
    "IF#1EQ#2GOTO1",
    "IF[#1EQ#2]",
    "WHILE[#1LT2]DO1",
    "WH[[#1GE#2]AND[#3GE#7]]DO1",
    "WHILE[#1]DO1",
    "WHILE[#1LT2]DO",
    "WHILE[#1LT2]",
    "WHILE[#107LT[#104+1]]DO1",
    "DO1",
    "DO1.5",
    "DO",
    "END1",
    "END 1",
    "END",
    "ELSE",
    "ENDIF",
    "POPEN",
    "PCLOS",
    "POPEN X1",
    "DPRNT[X#1[53]]",
    "BPRNT[A]",
    "GOTO5",
    "GOTO 99",
    "GOTO#1",
    "GOTO[#1+10]",
    "GOTO-5",
    "GOTO - 5",
    "GOTO-#1",
    "GOTO+5",
    "GOTO",
    "O1000",
    "O1000 #1=2",
    ":1000",
    "O<NAME>",
    "N10",
    "N10 #1=1",
    "N10#1=1",
    "N 10 IF[#1GT0]GOTO5",
    "N10 G01 X[#1] Y#2",
    "N#1",
    "N",
    "/",
    "/1",
    "/ 1 #1=1",
    "/1.5 #1=1",
    "/#1=1",
    "/N10 X[1]",
    "/ N10",
    "/ N10 G01 X#1",
    "G01 X#1 #2=5",
    "G01 X[#1] GOTO5",
    "G01 X[#1] IF[#1GT1]GOTO5",
    "G01 X[#1] IF[#1]X2",
    "G01 X[#1] WHILE[#1LT2]DO1",
    "G01 X[#1] DO1",
    "G01 X[#1] END1",
    "G01 X[#1] ELSE",
    "G01 X#1 #2=3 Y4",
    "#1=5 X1",
    "#1=5 X1 Y[#2]",
    "#1=5 X1 #2=3",
    "#1=#2 G1",
    "#1=5 ,C1.",
    "N10 #1=1 G1 X2",
    "G01 X10. ,C2.",
    "G01 X10. ,R[#1]",
    "G01 X10., A30.",
    "G01 X10. ,B2.",
    "G01 X10. , C-[#1]",
    "G1 X-#1 Y+#2 Z-[#3] A+[#4] B-1 C+2",
    "G65 P9123 A[#1] B2.0",
    "G65 P[#1]",
    "M98 P[#1]",
    "M[98] P1",
    "M[99]",
    "G[65] P1",
    "M-[98]",
    "G66.1 P[9011]",
    "G01 X[#1] M99",
    "#1=#2 M98 P1",
    "G1 X1 M98",
    "X#814+.1",
    "G01X[#1]Y[#2]Z[#3]F[#4]",
    "G01 X [ #1 + 2 ] Y [ # 2 ]",
    "G01\tX[#1]\tY[#2]",
    "G01 \f X[#1] \v Y[#2]",
    "G01 X[#1]  ",
    "  G01 X[#1]",
    "G01 X[#1];",
    "G01 X[#1] ; X2",
    "G01 X[#1]%",
    "% G01 X[#1]",
    "G01 X[#1] (C) Y[#2]",
    "G01 X[#1] (C",
    "G01 X[(C)#1]",
    "G01 X[#1] ((N)) Y2",
    "#1=#2(C)+#3",
    "g01 x[#1]",
    "#1=sin[#2]",
    "if[#1gt#2]goto10",
    "G01 X[#1] y[#2]",
    "G01 X[#１]",
    "G01 X[#1]\u3000",
    "G01 X[#1]\xa0",
    "G01 X[#1]\x1a",
    "\x1a",
    "G01 X[#1] \u212a1",
    "G01 X[#1] \u017f1",
    "G01 X[#1]?",
    "G01 X[#1]é",
    "#1=1 ?",
    "#1=1\n#2=2",
    "#1=1\r",
    "#5=#4*2:",
    "#1:=2",
    "#1==2",
    "#1=2=3",
    "#1=ABC[2]",
    "#1=FOO[2]",
    "#1=SINN[2]",
    "#1=SQR[2]",
    "#1=COSX[2]",
    "#1=GOTO",
    "#1=XOR",
    "#1=X",
    "#1=#2 X",
    "X#1X",
    "XX1",
    "X1X",
    "X1Y",
    "GOTO5X1",
    "G0TO5",
    "THEN",
    "THEN #1=1",
    "DO1 X1",
    "END1 X1",
    "#1=1 END1",
    "#1=1 IF[#1]GOTO1",
    "X1 #1=1 #2=2",
    "[#1]",
    "]",
    "[",
    "=",
    "+",
    "-1",
    "1",
    "1.5",
    "",
    "   ",
    "\t\f\v",
    "#1=#2 ,",
    "#1=#2,",
    "X1,",
    "X1 ,D2.",
    "X1<A>",
    "#1=1 <A>",
    "S1=500",
    "#30001.116=1",
    "#[#[#[1]]]=#[#[2]]",
    "#[1]=[#[1]]",
    "#1=#[#2+#[#3]]",
]


def test_edge_lines() -> None:
    taken, rejected = _compare(EDGE_LINES)
    assert taken > 100 and rejected > 100


@pytest.mark.parametrize(
    "code",
    [
        "#7=#101*123.+SQRT[5.]",
        "G00 X[#100+3.] Z7.123",
        "G92 X[#100-0.5] W-[#102+#101+0.123] F#101",
        "G01 W[123.*0.0001]",
        "IF[#1GT#2]GOTO10",
        "WHILE[#20LT25]DO1",
        "#[#1+1]=ABS[#2]",
        "IF[[#1GT1]AND[#2LT2]]GOTO1",
        "#1=ATAN[1]/[2]",
        "N10 G01 X[#1] Y#2",
        "/1 #1=1",
        "G01 X[#1] #2=5",
        "#1=5 X1",
        "DO1",
        "END1",
        "GOTO[#1]",
        "G01 X10. ,C[#1]",
        "IF[#1EQ1]THEN",
    ],
)
def test_the_reader_takes_common_macro_blocks(code: str) -> None:
    assert fast_statement(code) is not None


@pytest.mark.parametrize(
    "code",
    [
        "g01 x[#1]",  # lower case (the parser does not ask)
        "O1000",
        ":1000",
        "DPRNT[X#1[53]]",
        "#1=" + "9" * 13,  # a number too long: the grammar's way reports it
        "#1=1 ?",
        "#1=1.2.3",
        "X.",
        "#1=[1",
        "#1=ATAN[1]/2",
        "IF[[#2]AND[#1GT1]]GOTO1",
        "#1=" + "1+" * 130 + "1",  # more tokens than the reader takes
        "G01 X[#1]" + " " * SHARED_COLUMNS + "Y1",  # columns past the shared spans
        "G01 X[#1]\u3000",
        "#1=1\n#2=2",
    ],
)
def test_the_reader_leaves_other_blocks_to_the_grammar(code: str) -> None:
    assert fast_statement(code) is None


def test_numbers_the_reader_takes_are_within_the_grammars_digits() -> None:
    # The reader takes numbers of at most 12 characters and leaves longer ones to the grammar,
    # which reports those of more than MAX_DIGITS digits.
    assert MAX_DIGITS >= 12
    assert fast_statement("#1=" + "1" * 12) is not None
    assert fast_statement("#1=" + "1" * 13) is None


# ---- the lexer: a run of letters the reader takes is one token of the grammar's


@pytest.mark.parametrize("after", ["", "[", "1", "#1", " ", ".5", "]"])
def test_each_run_the_reader_takes_is_one_grammar_token(after: str) -> None:
    lark = grammar_lark()
    for run in sorted(fast_statements.RUNS):
        tokens = list(lark.lex(run + after))
        assert str(tokens[0]) == run, (run, after, tokens)


# ---- shared words


def test_words_of_the_same_text_at_the_same_column_are_shared() -> None:
    with Database("shared words").active():
        parser = BlockParser()
        one = parser.parse_line("G01 X[#1+1.] Y2. F#9 (A)").statement
        two = parser.parse_line("G01 X[#1+1.] Y3. F#9").statement
        moved = parser.parse_line("G1 X[#1+1.]").statement
    assert isinstance(one, NcStatement) and isinstance(two, NcStatement)
    assert isinstance(moved, NcStatement)
    assert one.words[1] is two.words[1] and one.words[3] is two.words[3]
    assert one.words[2] is not two.words[2]
    assert moved.words[1] == Word(moved.words[1].address, moved.words[1].value, Span(3, 11))
    assert moved.words[1] is not one.words[1]


def test_a_shared_word_equals_the_grammars_after_the_tables_are_dropped() -> None:
    lines = ["G01 X[#1+1.] F#9", "G01 X[#1+1.] F#9 Z1.", "G01 X [#1+1.] F#9", "G01 X[#1+1.]F#9"]
    with Database("dropped").active() as db:
        first = [BlockParser().parse_line(t) for t in lines]
        db.drop_caches()
        _compare(lines)
        again = [BlockParser().parse_line(t) for t in lines]
    assert first == again


# ---- random macro lines


class _Lines:
    """Random blocks of Macro B, of the forms the reader takes and of forms near them: spacing,
    comments, signs, numbers of every form, brackets nested and unbalanced, the conditions'
    bracket forms, words with expressions, mixed blocks, and mutations of all of these."""

    FUNCS = ("SIN", "COS", "TAN", "ASIN", "ACOS", "SQRT", "ABS", "ROUND", "FIX", "FUP", "LN")
    FUNCS2 = ("EXP", "ADP", "BIN", "BCD")
    OPS = ("+", "-", "*", "/", "AND", "OR", "XOR", "MOD")
    RELOPS = ("EQ", "NE", "GT", "GE", "LT", "LE")
    LETTERS = "ABCDEFGHIJKLMPQRSTUVWXYZ"
    NOISE = (*"#[]=+-*/,.<>:;?%()", "AND", "GT", "IF", "GOTO", "ATAN", "O", "N", "é", "\t")

    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)

    def gap(self) -> str:
        return self.rng.choice(("", "", "", "", "", " ", " ", "  ", "\t", " (C) ", "(A)"))

    def number(self) -> str:
        r = self.rng
        if r.random() < 0.04:  # around the longest number the reader takes
            return r.choice(("9" * r.randint(11, 14), "1." + "5" * r.randint(9, 12)))
        digits = "".join(r.choice("0123456789") for _ in range(r.randint(1, 5)))
        return r.choice(
            (digits, digits + ".", "." + digits, digits[:2] + "." + digits[2:], "0", "0.", "1")
        )

    def var(self, depth: int) -> str:
        r = self.rng
        if depth > 0 and r.random() < 0.2:
            return "#" + self.gap() + "[" + self.expr(depth - 1) + "]"
        return "#" + r.choice(("", "", "", " ")) + r.choice((str(r.randint(0, 40)), "100", "1."))

    def atom(self, depth: int) -> str:
        r = self.rng
        k = r.random()
        g = self.gap
        if depth <= 0 or k < 0.3:
            return self.number()
        if k < 0.55:
            return self.var(depth)
        if k < 0.63:
            return "[" + g() + self.expr(depth - 1) + g() + "]"
        if k < 0.72:
            name = r.choice(self.FUNCS + self.FUNCS2)
            return name + g() + "[" + self.expr(depth - 1) + "]"
        if k < 0.77:
            a, b = self.expr(depth - 1), self.expr(depth - 1)
            return "ATAN" + g() + "[" + a + "]" + g() + "/" + g() + "[" + b + "]"
        if k < 0.8:
            return "ATAN[" + self.expr(depth - 1) + g() + "," + g() + self.expr(depth - 1) + "]"
        if k < 0.82:
            return "ATAN[" + self.expr(depth - 1) + "]"
        if k < 0.85:
            return "POW[" + self.expr(depth - 1) + "," + self.expr(depth - 1) + "]"
        if k < 0.97:
            return r.choice(("-", "+", "-", "- ")) + self.atom(depth - 1)
        return r.choice(("[]", "[", "]", "#", "--", ",", "X", ".", "#[]", "ATAN[1]/2"))

    def expr(self, depth: int) -> str:
        r = self.rng
        out = self.atom(depth)
        for _ in range(r.choice((0, 0, 1, 1, 2, 3))):
            op = r.choice(self.OPS)
            out += self.gap() + op + self.gap() + self.atom(depth)
        return out

    def cond(self, depth: int) -> str:
        r = self.rng
        k = r.random()
        if depth <= 0 or k < 0.55:
            return self.expr(2) + self.gap() + r.choice(self.RELOPS) + self.gap() + self.expr(2)
        if k < 0.8:
            terms = [self.cond(depth - 1) for _ in range(r.randint(1, 3))]
            ops = [r.choice(("AND", "OR", "XOR")) for _ in terms]
            return "".join(
                (op if n else "") + self.gap() + "[" + t + "]" + self.gap()
                for n, (t, op) in enumerate(zip(terms, ops, strict=True))
            )
        if k < 0.93:
            return self.expr(2)
        return "[" + self.cond(depth - 1) + "]" + r.choice(("", "AND", "+1", "GT1"))

    def value(self) -> str:
        r = self.rng
        g = self.gap
        if r.random() < 0.03:
            return r.choice(("", "--1", "SIN[1]", "-SIN[1]", "[", "[]", "#"))
        return r.choice(
            (
                self.number(),
                r.choice(("-", "+", "- ", "+ ")) + self.number(),
                self.var(1),
                "-" + g() + self.var(1),
                "+" + self.var(0),
                "[" + g() + self.expr(2) + g() + "]",
                "-" + g() + "[" + self.expr(2) + "]",
                "+[" + self.expr(1) + "]",
                "[" + self.expr(1) + "]",
            )
        )

    def words(self) -> str:
        r = self.rng
        out = []
        for _ in range(r.randint(1, 5)):
            letter = r.choice(self.LETTERS)
            if r.random() < 0.05:
                letter = "," + r.choice(" ") * r.randint(0, 1) + r.choice("ACRB")
            out.append(letter + r.choice(("", "", " ")) + self.value())
        return self.gap().join(out) if r.random() < 0.5 else " ".join(out)

    def target(self) -> str:
        r = self.rng
        if r.random() < 0.05:
            return r.choice(("+5", "-#1", ""))
        return r.choice(
            (
                str(r.randint(0, 9999)),
                self.var(1),
                "[" + self.expr(1) + "]",
                "-" + str(r.randint(0, 99)),
                "- " + str(r.randint(0, 99)),
            )
        )

    def body(self) -> str:
        r = self.rng
        g = self.gap
        k = r.random()
        if k < 0.25:
            return self.var(1) + g() + "=" + g() + self.expr(3)
        if k < 0.37:
            return "IF" + g() + "[" + self.cond(2) + "]" + g() + "GOTO" + g() + self.target()
        if k < 0.43:
            then = self.var(0) + "=" + self.expr(2)
            return "IF[" + self.cond(2) + "]" + g() + "THEN" + g() + then
        if k < 0.47:
            tail = r.choice(("", self.words(), "#1=2 X1"))
            return "IF[" + self.cond(1) + "]" + g() + r.choice(("THEN", "THEN ", "")) + tail
        if k < 0.55:
            loop = r.choice(("1", "2", "3", "", "1.5", "#1"))
            return r.choice(("WHILE", "WH")) + g() + "[" + self.cond(2) + "]" + g() + "DO" + loop
        if k < 0.72:
            return self.words()
        if k < 0.78:
            return self.words() + g() + self.var(0) + "=" + self.expr(1)
        if k < 0.82:
            return self.var(0) + "=" + self.expr(1) + g() + self.words()
        if k < 0.86:
            return self.words() + g() + r.choice(("GOTO5", "IF[#1GT1]GOTO2", "DO1", "END1"))
        if k < 0.92:
            return r.choice(("DO", "END", "DO ", "END ")) + r.choice(("1", "2", "#1", "", "1."))
        return r.choice(("ELSE", "ENDIF", "POPEN", "PCLOS", "GOTO" + self.target(), "O12"))

    def mutate(self, text: str) -> str:
        r = self.rng
        chars = list(text)
        for _ in range(r.randint(1, 2)):
            if not chars:
                break
            at = r.randrange(len(chars))
            k = r.random()
            if k < 0.35:
                del chars[at]
            elif k < 0.7:
                chars.insert(at, r.choice(self.NOISE))
            else:
                chars[at] = chars[at].lower()
        return "".join(chars)

    SOUP = (
        *"#[]=+-*/,.", "#1", "1", "2.", ".5", "X", "G", "N", "O", ",C",
        "AND", "OR", "XOR", "MOD", "GT", "EQ", "IF", "THEN", "GOTO", "WHILE", "DO", "END",
        "SIN", "ATAN", "POW", "ELSE", "ENDIF",
    )  # fmt: skip

    def soup(self) -> str:
        """Tokens in any order: forms no generator of statements thinks of."""
        r = self.rng
        return "".join(r.choice(self.SOUP) + self.gap() for _ in range(r.randint(1, 12)))

    def line(self) -> str:
        r = self.rng
        text = self.body()
        if r.random() < 0.15:
            text = "N" + r.choice(("", " ")) + str(r.randint(0, 99999)) + self.gap() + text
        if r.random() < 0.08:
            text = "/" + r.choice(("", "1", " 2", "3.")) + self.gap() + text
        if r.random() < 0.15:
            text += r.choice((" (NOTE)", "(计算 1)", ";", " ;", "%", "(OPEN", "  "))
        if r.random() < 0.04:
            text = text.lower()
        if r.random() < 0.1:
            text = self.mutate(text)
        return text


def _random_lines(seed: int, count: int) -> Iterator[str]:
    lines = _Lines(seed)
    for _ in range(count):
        yield lines.soup() if lines.rng.random() < 0.1 else lines.line()


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_random_macro_lines(seed: int) -> None:
    lines = list(_random_lines(seed, 6000))
    taken, rejected = _compare(lines)
    # Both sides exercised: many lines the reader takes, many the grammar rejects.
    assert taken > len(lines) // 4
    assert rejected > len(lines) // 10


def test_random_lines_through_whole_documents() -> None:
    # Documents share lines' words and the parser's caches: the same as each line alone.
    from fanuc_macro.syntax.parser import parse_text

    lines = list(_random_lines(5, 3000))
    text = "\n".join(line.replace("\n", " ").replace("\r", " ") for line in lines)
    fast = parse_text(text, "fast.nc", BlockParser())
    grammar = parse_text(text, "grammar.nc", BlockParser(use_fast_path=False))
    assert len(fast.blocks) == len(grammar.blocks)
    for got, expected in zip(fast.blocks, grammar.blocks, strict=True):
        assert isinstance(got.parsed, ParsedLine)
        _same(got.parsed, expected.parsed, repr(got.parsed.text), True)
