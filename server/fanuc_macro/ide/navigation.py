"""Definitions, references and the outline of a document (programs, labels, loops)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from ..program.custom_calls import called_by_code, custom_call_of
from ..program.index import Call, Program, ProgramIndex
from ..program.variables import classify
from ..syntax.parser import statements_of
from ..syntax.tree import Assign, Document, ProgramStart, Span, Var, While
from .data import Location, Range, Symbol, SymbolKind
from .locate import assignments_in, goto_target, number_of, uses
from .view import View, call_at, comment_of, first_comment, lines_of


def block_call(view: View, program: Program | None, line: int) -> Call | None:
    """The call the block at ``line`` makes: a ``G65``/``M98``/``G66`` of the index, or a code
    the settings' ``machine.customCalls`` make call (not inside the program it calls, where
    the code is a plain code)."""
    call = call_at(program, line)
    settings = view.config.custom_calls
    if call is not None or not settings or program is None:
        return call
    if called_by_code(program.number, settings):
        return None
    return custom_call_of(line, view.doc.blocks[line].statement, settings)


def definition(view: View, line: int, column: int) -> list[Location]:
    """Where what is at ``line``, ``column`` is defined: the label a GOTO jumps to, the program
    a call runs, the assignments of a local or system variable in its program, those of a
    common variable that reach it (:func:`_common_definitions`). Empty when nothing is."""
    found = view.hit_at(line, column)
    if found is None:
        return []
    block, hit = found
    program = view.index.program_at(block.line)
    if hit.kind == "goto" and hit.goto is not None and program is not None:
        target = goto_target(hit.goto)
        label = program.label_line(target, block.line) if target is not None else None
        if label is None:
            return []
        seq_span = view.doc.blocks[label].parsed.seq_span
        if seq_span is None:
            return [view.location(view.key, label)]
        return [view.location(view.key, label, seq_span.start, seq_span.end)]
    if hit.kind == "word" and hit.word is not None:
        call = block_call(view, program, block.line)
        if (
            call is not None
            and call.program is not None
            and ((hit.word.address == "P" and call.code is None) or hit.word.span == call.span)
        ):
            entry = view.program_entry(call.program)
            if entry is None:
                return []
            key, _, callee = entry
            header = callee.header_line if callee.header_line is not None else callee.first_line
            return [view.location(key, header)]
        return []
    if hit.kind == "var" and hit.var is not None:
        n = number_of(hit.var)
        if n is None:
            return []
        if classify(n).kind in COMMON_KINDS:
            return _common_definitions(view, block.line, hit.var, n)
        first, end = lines_of(program, view.doc)
        return [
            view.location(view.key, use.line, use.var.span.start, use.var.span.end)
            for use in uses(view.doc.blocks, first, end)
            if use.assign is not None and number_of(use.var) == n
        ]
    return []


# Common variables (#100-#199, #500-#999, and the extended #200-#499): shared by every program,
# so the value a program reads may have been set by the program that called it, or by any.
COMMON_KINDS = frozenset({"common", "retained", "extended-common"})


def _common_definitions(view: View, line: int, var: Var, n: int) -> list[Location]:
    """The assignments of common variable ``n`` that reach its use ``var`` on ``line``: those
    of its program that run before it (above it, or below it in a loop or before a jump back);
    when there are none, those of the programs that call it, before their call, and of their
    callers in turn; when there are none either, every assignment of it in the workspace. The
    target of an assignment is its own definition."""
    doc = view.doc
    if any(assign.target is var for assign in _assignments_on(doc, line)):
        return [view.location(view.key, line, var.span.start, var.span.end)]
    program = view.index.program_at(line)
    found = _reaching(view, view.key, doc, program, line, n, set())
    if found:
        return found
    return [
        view.location(key, use.line, use.var.span.start, use.var.span.end)
        for key, other, _index in _documents(view)
        for use in uses(other.blocks, 0, len(other.blocks))
        if use.assign is not None and number_of(use.var) == n
    ]


def _reaching(
    view: View,
    key: str,
    doc: Document,
    program: Program | None,
    line: int,
    n: int,
    seen: set[int],
) -> list[Location]:
    """The assignments of ``n`` that reach ``line`` of ``program`` (see
    :func:`_common_definitions`); ``seen``: the programs whose callers were looked at."""
    found = [
        view.location(key, use.line, use.var.span.start, use.var.span.end)
        for first, end in _before(program, doc, line)
        for use in uses(doc.blocks, first, end)
        if use.assign is not None and number_of(use.var) == n
    ]
    if found or program is None or program.number is None or program.number in seen:
        return found
    seen.add(program.number)
    for caller_key, caller_doc, caller_index in _documents(view):
        for caller in caller_index.programs:
            for call in caller.calls:
                if call.program == program.number and call.kind != "M97":
                    found += _reaching(view, caller_key, caller_doc, caller, call.line, n, seen)
    return list(dict.fromkeys(found))


def _before(program: Program | None, doc: Document, line: int) -> list[tuple[int, int]]:
    """The stretches of lines whose blocks may run before ``line`` in its program: the lines
    above it; and, from ``line`` itself, the body of a WHILE loop that holds it (its END goes
    back to the WHILE) and the lines up to a GOTO that jumps back above it."""
    first, _end = lines_of(program, doc)
    stretches = [(first, line)]
    if program is None:
        return stretches
    for loop in program.loops:
        if loop.end_line is not None and loop.do_line <= line <= loop.end_line:
            stretches.append((line, loop.end_line + 1))
    for jump in program.jumps:
        if jump.line >= line and jump.target is not None:
            target = program.label_line(jump.target, jump.line)
            if target is not None and target <= line:
                stretches.append((line, jump.line + 1))
    return stretches


def _assignments_on(doc: Document, line: int) -> list[Assign]:
    return [
        assign
        for statement in statements_of(doc.blocks[line].statement)
        for assign in assignments_in(statement)
    ]


def _documents(view: View) -> list[tuple[str, Document, ProgramIndex]]:
    """The document and every other of the workspace, with their program indexes."""
    return [
        (view.key, view.doc, view.index),
        *((key, doc, index) for key, (doc, index) in view.workspace.items() if key != view.key),
    ]


def references(
    view: View,
    line: int,
    column: int,
    include_declaration: bool,
    open_views: Sequence[View] = (),
) -> list[Location] | None:
    """Every read and write of a variable: in its program for locals, in every open document
    for common and system variables (they are shared by all programs). None when no variable
    is at ``line``, ``column``."""
    found = view.hit_at(line, column)
    if found is None or found[1].kind != "var" or found[1].var is None:
        return None
    block, hit = found
    assert hit.var is not None
    n = number_of(hit.var)
    if n is None:
        return None
    local = 1 <= n <= 33
    targets: list[tuple[View, int, int]] = []
    if local:
        first, end = lines_of(view.index.program_at(block.line), view.doc)
        targets.append((view, first, end))
    else:
        targets.append((view, 0, len(view.doc.blocks)))
        for other in open_views:
            if other.key != view.key:
                targets.append((other, 0, len(other.doc.blocks)))
    out: list[Location] = []
    for target, first, end in targets:
        for use in uses(target.doc.blocks, first, end):
            if number_of(use.var) != n:
                continue
            if use.assign is not None and not include_declaration:
                continue
            out.append(target.location(target.key, use.line, use.var.span.start, use.var.span.end))
    return out


def document_symbols(view: View) -> list[Symbol]:
    """The programs of the document, each with the labels jumped to and its loops, nested."""
    out: list[Symbol] = []
    blocks = view.doc.blocks

    def whole(first: int, last: int) -> Range:
        return Range.of(first, 0, last, len(view.text(view.key, last)))

    for program in view.index.programs:
        last = max(program.first_line, min(program.end_line, len(blocks)) - 1)
        header = program.header_line if program.header_line is not None else program.first_line
        head_block = blocks[header]
        statement = head_block.statement
        selection = (
            statement.span if isinstance(statement, ProgramStart) else Span(0, len(head_block.text))
        )
        children: list[_Node] = []
        targets = {j.target for j in program.jumps if j.target is not None}
        for seq, seq_lines in program.labels.items():
            if seq not in targets:
                continue
            for ln in seq_lines:
                span = blocks[ln].parsed.seq_span or Span(0, 0)
                children.append(
                    _Node(
                        ln,
                        ln,
                        Symbol(
                            name=f"N{seq}",
                            detail=comment_of(blocks[ln]),
                            kind=SymbolKind.LABEL,
                            range=whole(ln, ln),
                            selection=Range.of(ln, span.start, ln, span.end),
                        ),
                    )
                )
        for loop in program.loops:
            end = loop.end_line if loop.end_line is not None else loop.do_line
            do_block = blocks[loop.do_line]
            do_statement = next(
                (s for s in statements_of(do_block.statement) if isinstance(s, While)), None
            )
            span = do_statement.span if do_statement is not None else Span(0, len(do_block.text))
            children.append(
                _Node(
                    loop.do_line,
                    end,
                    Symbol(
                        name=" ".join(do_block.source(span).split()),
                        detail=f"lines {loop.do_line + 1}-{end + 1}",
                        kind=SymbolKind.LOOP,
                        range=whole(loop.do_line, end),
                        selection=Range.of(loop.do_line, span.start, loop.do_line, span.end),
                    ),
                )
            )
        name = program.display_name
        if program.number is not None and program.name:
            name += f" <{program.name}>"
        out.append(
            Symbol(
                name=name,
                detail=first_comment(view.doc, program),
                kind=SymbolKind.SUBPROGRAM if program.returns else SymbolKind.MAIN_PROGRAM,
                range=whole(program.first_line, last),
                selection=Range.of(header, selection.start, header, selection.end),
                children=_nest(children),
            )
        )
    return out


@dataclass
class _Node:
    start: int
    end: int
    symbol: Symbol
    children: list[_Node] = field(default_factory=list)

    @property
    def is_loop(self) -> bool:
        return self.symbol.kind is SymbolKind.LOOP

    def build(self) -> Symbol:
        if not self.children:
            return self.symbol
        inner = tuple(child.build() for child in self.children)
        s = self.symbol
        return Symbol(s.name, s.detail, s.kind, s.range, s.selection, inner)


def _nest(nodes: list[_Node]) -> tuple[Symbol, ...]:
    """Labels and loops as a tree: each inside the innermost loop whose lines hold it."""
    nodes.sort(key=lambda node: (node.start, -node.end))
    roots: list[_Node] = []
    stack: list[_Node] = []  # open loops
    for node in nodes:
        while stack and node.start > stack[-1].end:
            stack.pop()
        (stack[-1].children if stack else roots).append(node)
        if node.is_loop:
            stack.append(node)
    return tuple(node.build() for node in roots)
