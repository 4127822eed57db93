"""Semantic tokens: what each variable, program, label, function and keyword of a line is, as
far as the text, the index and the evaluator tell, for the editor to colour them (the kinds
are in ``token_legend.py``). Comments and NC words are left to the editor's grammar. Tokens
never overlap and are in document order; columns are code points.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

from .. import database
from ..database import TableKey
from ..evaluator.compiler import kept
from ..program.index import Program
from ..program.variables import classify
from ..syntax.lines import cut_comments
from ..syntax.parser import statements_of
from ..syntax.tree import (
    Block,
    Call,
    IfNc,
    NcStatement,
    PlainNc,
    Print,
    ProgramStart,
    Span,
    Statement,
    Var,
)
from ..syntax.walk import subexpressions, top_expressions
from .locate import assignments_in, locals_read_before_set, number_of
from .token_legend import TokenModifier, TokenType
from .view import View


@dataclass(frozen=True)
class SemanticToken:
    line: int
    start: int  # code points
    end: int
    type: TokenType
    modifiers: frozenset[TokenModifier] = frozenset()


CONTROL_WORDS = frozenset((
    "IF", "THEN", "GOTO", "WHILE", "DO", "END", "ELSE", "ENDIF", "DPRNT", "BPRNT", "POPEN", "PCLOS",
))  # fmt: skip
OPERATOR_WORDS = frozenset(("EQ", "NE", "GT", "GE", "LT", "LE", "AND", "OR", "XOR", "MOD"))
_LETTERS = re.compile(r"[A-Za-z]+")

_COMMON_KINDS = frozenset(("common", "retained", "extended-common"))
_SYSTEM_KINDS = frozenset(("system", "null"))
_MACRO_CALLS = ("G65", "G66", "G66.1")
_LIBRARY = frozenset((TokenModifier.DEFAULT_LIBRARY,))
_DECLARATION = frozenset((TokenModifier.DECLARATION,))


@dataclass(frozen=True)
class CalledPrograms:
    """The program numbers the workspace's calls name, by how they are called."""

    by_macro_call: frozenset[int]  # G65, G66, G66.1: a new level of locals, filled by letters
    by_subprogram_call: frozenset[int]  # M98 (M97): the caller's locals

    @staticmethod
    def of(view: View) -> CalledPrograms:
        macro: set[int] = set()
        sub: set[int] = set()
        indexes = [index for key, (_, index) in view.workspace.items() if key != view.key]
        for index in (view.index, *indexes):
            for program in index.programs:
                for call in program.calls:
                    if call.program is not None:
                        (macro if call.kind in _MACRO_CALLS else sub).add(call.program)
        return CalledPrograms(frozenset(macro), frozenset(sub))


def _arguments_of(view: View, program: Program | None, called: CalledPrograms) -> frozenset[int]:
    """The locals ``program`` takes from a macro call: those it reads before it sets them, when
    a G65/G66 of the workspace calls it, or when it returns with M99 and no M98 of the
    workspace calls it (a macro whose caller is elsewhere); and in any program, those the
    evaluator assumed given (read before set in a program that ends with M30)."""
    if program is None:
        return frozenset()
    facts = view.facts
    assumed = facts.assumed_arguments.get(program.first_line) if facts is not None else None
    found = {n for n, _ in assumed} if assumed else set()
    number = program.number
    macro = number is not None and (
        number in called.by_macro_call
        or (bool(program.returns) and number not in called.by_subprogram_call)
    )
    if macro:
        blocks = view.doc.blocks
        found.update(locals_read_before_set(blocks, program.first_line, program.end_line))
    return frozenset(found)


def _variable_token(
    line: int, span: Span, number: int, written: bool, arguments: frozenset[int]
) -> SemanticToken:
    kind = classify(number)
    modifiers: set[TokenModifier] = {TokenModifier.MODIFICATION} if written else set()
    kind_name = TokenType.VARIABLE
    if number in arguments:
        kind_name = TokenType.PARAMETER
    elif kind.kind in _COMMON_KINDS:
        modifiers.add(TokenModifier.COMMON)
    elif kind.kind in _SYSTEM_KINDS:
        modifiers |= {TokenModifier.SYSTEM, TokenModifier.DEFAULT_LIBRARY}
        if kind.read_only:
            modifiers.add(TokenModifier.READONLY)
    return SemanticToken(line, span.start, span.end, kind_name, frozenset(modifiers))


def _expression_tokens(
    line: int, statement: Statement, arguments: frozenset[int]
) -> Iterator[SemanticToken]:
    """The functions and variables of a statement's expressions. A variable is one when its
    number is written (``#[...]`` is left alone: the variables inside it are tokens)."""
    targets = {id(a.target) for a in assignments_in(statement)}
    for top in top_expressions(statement):
        for node in subexpressions(top):
            if isinstance(node, Call):
                span = node.name_span
                yield SemanticToken(line, span.start, span.end, TokenType.FUNCTION, _LIBRARY)
            elif isinstance(node, Var):
                number = number_of(node)
                if number is not None:
                    written = id(node) in targets
                    yield _variable_token(line, node.span, number, written, arguments)


def _word_tokens(
    line: int, code: str, statement: Statement, taken: Sequence[SemanticToken]
) -> Iterator[SemanticToken]:
    """The keywords and word operators of a macro statement, read from its code (the nodes keep
    no columns for them), outside the tokens already found, the NC words of an IF and the
    text a DPRNT prints."""
    if isinstance(statement, NcStatement | ProgramStart):
        return
    skip = [(t.start, t.end) for t in taken]
    if isinstance(statement, IfNc):
        skip.append((statement.words.span.start, statement.words.span.end))
    span = statement.span
    words = _LETTERS.finditer(code, span.start, span.end)
    if isinstance(statement, Print):
        words = itertools.islice(words, 1)  # the keyword; the rest is what it prints
    for m in words:
        if any(start < m.end() and m.start() < end for start, end in skip):
            continue
        word = m.group().upper()
        if word in CONTROL_WORDS:
            yield SemanticToken(line, m.start(), m.end(), TokenType.KEYWORD)
        elif word in OPERATOR_WORDS:
            yield SemanticToken(line, m.start(), m.end(), TokenType.OPERATOR)


def block_tokens(
    block: Block, arguments: frozenset[int], targets: Sequence[tuple[Span, TokenType]] = ()
) -> list[SemanticToken]:
    """The tokens of one block, in order, none overlapping. ``targets`` are the constant targets
    the index found on the line: GOTO labels and the programs calls name."""
    parsed = block.parsed
    line = block.line
    found: list[SemanticToken] = []
    if parsed.seq_span is not None:
        span = parsed.seq_span
        found.append(SemanticToken(line, span.start, span.end, TokenType.LABEL, _DECLARATION))
    statements = statements_of(parsed.statement)
    for statement in statements:
        if isinstance(statement, ProgramStart):
            span = statement.span
            found.append(
                SemanticToken(line, span.start, span.end, TokenType.NAMESPACE, _DECLARATION)
            )
        elif type(statement) is not PlainNc:  # numbers only: no node is built for it
            found.extend(_expression_tokens(line, statement, arguments))
    for span, kind in targets:
        found.append(SemanticToken(line, span.start, span.end, kind))
    if any(not isinstance(s, NcStatement | ProgramStart) for s in statements):
        code = cut_comments(block.text).code
        for statement in statements:
            found.extend(_word_tokens(line, code, statement, tuple(found)))
    return _without_overlaps(found)


def _targets_by_line(program: Program) -> dict[int, list[tuple[Span, TokenType]]]:
    by_line: dict[int, list[tuple[Span, TokenType]]] = {}
    for jump in program.jumps:
        if jump.target is not None:
            by_line.setdefault(jump.line, []).append((jump.target_span, TokenType.LABEL))
    for call in program.calls:
        if call.program is not None and call.program_span is not None:
            by_line.setdefault(call.line, []).append((call.program_span, TokenType.NAMESPACE))
    return by_line


def _without_overlaps(tokens: list[SemanticToken]) -> list[SemanticToken]:
    out: list[SemanticToken] = []
    for token in sorted(tokens, key=lambda t: (t.start, -t.end)):
        if token.end <= token.start:
            continue
        if out and token.start < out[-1].end:
            continue  # inside one already kept (the outer one wins)
        out.append(token)
    return out


# The tokens of a line by what they depend on: its parse (one per distinct text), its program's
# arguments and the targets the index found on it. Kept from request to request, so that after
# an edit only the lines that changed are read again; the parse is kept with its tokens, for an
# id of a parse no longer cached may be another's.
_LineKey = tuple[int, frozenset[int], tuple[tuple[Span, TokenType], ...]]
LINE_TOKENS: TableKey[_LineKey, tuple[object, tuple[SemanticToken, ...]]] = TableKey(
    "ide.semantic.line_tokens", cache=True
)
# Enough for the lines of the programs one edits by hand; a posted file bigger than this has its
# tokens worked out again on each request (its lines are mostly plain words: cheap to redo).
MAX_LINE_TOKENS = 65_536


def line_tokens(
    block: Block,
    arguments: frozenset[int],
    targets: Sequence[tuple[Span, TokenType]] = (),
    worked_out: dict[_LineKey, tuple[object, tuple[SemanticToken, ...]]] | None = None,
) -> list[SemanticToken]:
    """:func:`block_tokens`, from the tokens of the same line worked out before if any (in
    ``worked_out``, the current database's table when not given)."""
    if worked_out is None:
        worked_out = database.current().table(LINE_TOKENS)
    parsed = block.parsed
    key = (id(parsed), arguments, tuple(targets))
    entry = worked_out.get(key)
    if entry is None or entry[0] is not parsed:
        made = tuple(block_tokens(block, arguments, targets))
        entry = kept(worked_out, key, (parsed, made), MAX_LINE_TOKENS)
    tokens = entry[1]
    line = block.line
    if tokens and tokens[0].line != line:
        return [SemanticToken(line, t.start, t.end, t.type, t.modifiers) for t in tokens]
    return list(tokens)


def semantic_tokens(view: View, first: int = 0, last: int | None = None) -> list[SemanticToken]:
    """The tokens of the lines ``first``..``last`` (inclusive; None: to the end)."""
    blocks = view.doc.blocks
    stop = len(blocks) if last is None else min(len(blocks), last + 1)
    called = CalledPrograms.of(view)
    out: list[SemanticToken] = []
    program: Program | None = None
    arguments: frozenset[int] = frozenset()
    targets: dict[int, list[tuple[Span, TokenType]]] = {}
    worked_out = database.current().table(LINE_TOKENS)
    for line in range(max(0, first), stop):
        if program is None or not program.contains(line):
            program = view.index.program_at(line)
            arguments = _arguments_of(view, program, called)
            targets = _targets_by_line(program) if program is not None else {}
        out.extend(line_tokens(blocks[line], arguments, targets.get(line, ()), worked_out))
    return out


__all__ = (
    "CalledPrograms",
    "SemanticToken",
    "block_tokens",
    "line_tokens",
    "semantic_tokens",
)
