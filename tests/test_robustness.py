"""No input freezes or crashes the analysis: hostile lines, deep and long expressions, huge
files, arithmetic past the control's range.

Time is checked as growth where it can be (twice the input may cost at most about three times
as much: a backtracking regex grows four times or more per word), with generous wall-clock
bounds only as a backstop.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.blocks import cut_comments
from fanuc_macro.config import Config
from fanuc_macro.evaluator import compiler
from fanuc_macro.evaluator.compiler import compile_cond, compile_expr, constant_of
from fanuc_macro.parser import BlockParser, fast_parse
from fanuc_macro.syntax import Binary, Call, Compare, Cond, Expr, Logic, Num, Span, Var
from fanuc_macro.walk import bracket_depth, cond_exprs, subexpressions

GRAMMAR = BlockParser(use_fast_path=False)

# Lines that froze the fast path's old regex (it backtracked exponentially on them), and lines
# built to make a regex or a scanner retry: long runs that fail at their very end.
HOSTILE_LINES = {
    "integer words then a bracket": "G65P9010A1000B1000C1000D1000E1000F1000H1000I1000J1000K1000"
    "X#[#1+1]",
    "repeated words then '['": "X11" * 22 + "[",
    "digits then a letter": "X" + "1" * 3000 + "a",
    "spaces then a bad character": "X" + " " * 3000 + "!",
    "block delete then spaces": "/" + " " * 3000 + "!",
    "letters": "A" * 3000,
    "semicolons": ";" * 3000,
    "words then a comma": "X1.0" * 700 + ",",
    "decimal points": "X1." * 1000 + ".",
    "signs": "X-" * 1000 + "1",
}


def _seconds(fn: Callable[[], object], repeat: int = 5) -> float:
    """The best of a few runs: the least disturbed by the other processes of the machine."""
    best = float("inf")
    for _ in range(repeat):
        started = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - started)
    return best


def _growth(make: Callable[[int], str], parse: Callable[[str], object], n: int) -> float:
    """How much longer the input of size 4n takes than the one of size n."""
    small, large = make(n), make(4 * n)
    return _seconds(lambda: parse(large)) / max(_seconds(lambda: parse(small)), 1e-6)


# ---- the scanner: linear on every line -------------------------------------------------------

FAMILIES: dict[str, Callable[[int], str]] = {
    "integer words then '['": lambda n: "G65P9010" + "A1000" * n + "X#[#1+1]",
    "words then '['": lambda n: "X11" * n + "[",
    "words then a comma": lambda n: "X1.0" * n + ",",
    "a digit run then a letter": lambda n: "X" + "1" * (4 * n) + "a",
    "a space run then '!'": lambda n: "X" + " " * (4 * n) + "!",
    "block delete, spaces": lambda n: "/" + " " * (4 * n) + "!",
    "signed words then '#'": lambda n: "X-1.5 Y+2." * n + "#",
}


@pytest.mark.parametrize("name", FAMILIES)
def test_fast_path_time_grows_linearly(name: str) -> None:
    make = FAMILIES[name]
    growth = _growth(make, fast_parse, 400)
    # Linear is 4; the old regex was 4**400 on the first family. 12 leaves room for noise.
    assert growth < 12, f"{name}: 4x the input took {growth:.1f}x the time"


@pytest.mark.parametrize("name", FAMILIES)
def test_whole_line_parse_time_grows_linearly(name: str) -> None:
    """Fast path, grammar and the description of the syntax error together."""
    make = FAMILIES[name]
    growth = _growth(make, lambda text: BlockParser().parse_line(text), 200)
    assert growth < 12, f"{name}: 4x the input took {growth:.1f}x the time"


@pytest.mark.parametrize("name", HOSTILE_LINES)
def test_hostile_line_is_read_quickly_and_as_the_grammar_reads_it(name: str) -> None:
    text = HOSTILE_LINES[name]
    fast = BlockParser()
    started = time.perf_counter()
    parsed = fast.parse_line(text)
    assert time.perf_counter() - started < 1.0  # a backstop: these take milliseconds
    assert parsed == GRAMMAR.parse_line(text)


def test_cut_comments_is_linear_in_end_of_block_marks() -> None:
    growth = _growth(lambda n: ";" * (4 * n), cut_comments, 2000)
    assert growth < 12


# ---- expressions of any length and depth: compiled, folded and walked without recursion -------


def _sum_of_ones(terms: int) -> Expr:
    """1+1+...+1 as the grammar builds it: a left-leaning chain ``terms`` levels deep."""
    expr: Expr = Num(1.0, "1", Span(0, 1))
    for _ in range(terms - 1):
        expr = Binary("+", expr, Num(1.0, "1", Span(0, 1)), Span(0, 1))
    return expr


def _nested_sines(levels: int, inner: Expr) -> Expr:
    expr = inner
    for _ in range(levels):
        expr = Call("SIN", (expr,), Span(0, 1), Span(0, 1))
    return expr


def test_a_sum_of_20000_terms_folds_to_its_value() -> None:
    assert constant_of(_sum_of_ones(20_000)) == 20_000.0
    assert compile_expr(_sum_of_ones(20_000))(None) == 20_000.0  # type: ignore[arg-type]


def test_functions_nested_20000_deep_fold_and_walk() -> None:
    assert constant_of(_nested_sines(20_000, Num(0.0, "0", Span(0, 1)))) == 0.0
    variable = _nested_sines(20_000, Var(1.0, None, Span(0, 1)))
    assert constant_of(variable) is None
    compile_expr(variable)  # compiling is iterative; running it is bounded by the parser
    assert bracket_depth(variable) == 20_000
    assert sum(1 for _ in subexpressions(variable)) == 20_001


def test_constant_folding_compiles_each_node_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """Folding at every level walked the subtree again: quadratic in the length."""
    calls = 0
    compile_node = compiler._compile_node

    def counted(*args: Any) -> Any:
        nonlocal calls
        calls += 1
        return compile_node(*args)

    monkeypatch.setattr(compiler, "_compile_node", counted)
    compile_expr(_sum_of_ones(5000))
    assert calls == 4999  # one per operator


def test_conditions_nested_deep_compile_and_walk() -> None:
    compare = Compare("EQ", Var(1.0, None, Span(0, 1)), Num(1.0, "1", Span(0, 1)), Span(0, 1))
    cond: Cond = compare
    for _ in range(20_000):
        cond = Logic(cond, (("OR", compare),), Span(0, 1))
    assert sum(1 for _ in cond_exprs(cond)) == 2 * 20_001
    compile_cond(cond)


# ---- arithmetic past the largest value: the control's overflow alarm, with the operands ------

TWELVE_NINES = "999999999999"
HUGE = "*".join([TWELVE_NINES] * 22)  # about 1e264: no exponent on FANUC, so a product


@pytest.mark.parametrize(
    ("block", "shown"),
    [
        (f"#1=BCD[{HUGE}]", "BCD[1e+264] overflows"),
        (f"#1={HUGE}*{HUGE}", "1e+300 * 999999999999. overflows"),
        (f"G01 X[{HUGE}*{HUGE}] F1.", "1e+300 * 999999999999. overflows"),
        ("#1=POW[10,400]", "POW[10.,400.] overflows"),
        (f"#2={TWELVE_NINES}.*{TWELVE_NINES}.\n#3=#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2"
         f"*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2", "* 1e+24 overflows"),
    ],
)  # fmt: skip
@pytest.mark.parametrize("controller", ["0i-TF", "30i"])
def test_overflow_is_alarm_ps0111_with_its_operands(
    block: str, shown: str, controller: str
) -> None:
    found = analyse(f"O1\n{block}\nM30\n", "o.nc", config=Config(controller=controller))
    codes = [d.code for d in found.diagnostics]
    assert "MB000" not in codes
    messages = [d.message for d in found.diagnostics if d.code == "MB501"]
    assert any(shown in m and "PS0111" in m and "OVERFLOW" in m for m in messages), messages
