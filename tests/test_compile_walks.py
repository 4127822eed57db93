"""A line's compile walks each expression once: what it finds equals what the separate walks
(the variables a statement reads, the value of a constant word) find."""

from __future__ import annotations

from fanuc_macro.database import Database
from fanuc_macro.evaluator.compile_lines import (
    FullLine,
    _direct_reads,
    compile_line,
    compile_statement,
)
from fanuc_macro.evaluator.compiler import compile_with_constant, constant_of
from fanuc_macro.syntax.parser import BlockParser, statements_of
from fanuc_macro.syntax.tree import Assign, IfThen, Statement, Var
from fanuc_macro.syntax.walk import (
    all_line_variables,
    line_variables,
    subexpressions,
    top_expressions,
    variables,
)
from test_parser import program_lines

LINES = [
    "#1=#2+#[#3+#2]*#4",
    "#[#5]=#6+#5",
    "IF [#1 GT #[#2]] THEN #[#1]=#3",
    "G01 X[#100+2.] W-[#102+#101+0.1] F#101",
    "G00 X+[[#1]] Y-#1 Z#0 A#1.5",
    "X#[#[#7]] Y[1.+2.] Z[ROUND[#1]]",
    "WHILE [#1 LT [#2+#1]] DO1",
    "GOTO #[#9]",
    "#1=#1 G01 X#2",
]


def _reads_walked(statement: Statement) -> tuple[int, ...]:
    """The variables read, as a walk of every subexpression finds them."""
    numbers: list[int] = []
    assigns = (statement, statement.then if isinstance(statement, IfThen) else None)
    targets = [a.target for a in assigns if isinstance(a, Assign)]  # written, not read
    for top in top_expressions(statement):
        for node in subexpressions(top):
            if (
                isinstance(node, Var)
                and node.number is not None
                and all(node is not t for t in targets)
            ):
                n = int(node.number)
                if n == node.number and n and n not in numbers:
                    numbers.append(n)
    return tuple(numbers)


def test_direct_reads_as_the_walk_of_every_subexpression() -> None:
    parser = BlockParser()
    lines = [*LINES, *program_lines()]
    with Database().active():  # the lines' words shared as in one program
        for text in [*lines, *lines]:
            statement = parser.parse_line(text).statement
            if statement is not None:
                walked = _reads_walked(statement)
                assert _direct_reads(statement) == walked, text
                # An NC block's, from the compile of its words.
                assert compile_statement(statement, text).reads == walked, text
                # A line's, from the variables it keeps for the line rules.
                assert compile_line(parser.parse_line(text)).reads == walked, text


def test_a_line_keeps_the_variables_of_each_statement() -> None:
    parser = BlockParser()
    for text in [*LINES, *program_lines()]:
        parsed = parser.parse_line(text)
        by_statement = tuple(tuple(variables(s)) for s in statements_of(parsed.statement))
        assert line_variables(parsed) == by_statement, text
        kept = all_line_variables(parsed)
        assert kept == tuple(v for found in by_statement for v in found), text
        assert all_line_variables(parsed) is kept  # walked once


def test_one_walk_gives_the_constant_and_the_closure() -> None:
    parser = BlockParser()
    for text in [*LINES, *program_lines()]:
        statement = parser.parse_line(text).statement
        if statement is None:
            continue
        for top in top_expressions(statement):
            for in_address in (False, True):
                evaluator, constant = compile_with_constant(top, in_address)
                assert constant == constant_of(top, in_address), text
                if constant is not None:
                    assert evaluator(None) == constant, text  # type: ignore[arg-type]


def test_a_shared_word_keeps_its_constant() -> None:
    # The same expression at the same place in two blocks: the second takes the first's
    # closure, and its value when constant (the block folds as it would alone).
    parser = BlockParser()
    pairs = [("G01 X[1.+2.] Y#1", "G01 X[1.+2.] Y3."), ("G01 X[#1+2.] Y3.", "G01 X[#1+2.] Y4.")]
    for first, second in pairs:
        with Database().active():
            alone = compile_statement(parser.parse_line(second).statement, second)
        with Database().active():
            compile_statement(parser.parse_line(first).statement, first)
            after = compile_statement(parser.parse_line(second).statement, second)
        assert isinstance(alone, FullLine) and isinstance(after, FullLine)
        assert (after.constant is None) == (alone.constant is None), second
        if alone.constant is not None:
            assert after.constant is not None
            assert after.constant.constants == alone.constant.constants, second
        assert [w.address for w in after.words] == [w.address for w in alone.words], second
