"""Code actions: the fixes offered for diagnostics, and their suppression comment."""

from __future__ import annotations

import re
from collections.abc import Iterable

from ..rules import expressions
from ..rules.expressions import logic_fixes, logic_operands
from ..syntax.marks import constant_value
from ..syntax.parser import default_parser, statements_of
from ..syntax.tree import Block, NcStatement, ParsedLine
from .data import ActionKind, CodeAction, DocumentEdit, Position, Problem, Range, TextEdit
from .view import View

_SUPPRESS = re.compile(r"\(\s*fanuc-macro\s*:\s*ignore\b[^)]*\)", re.I)
_RULE_CODE = re.compile(r"MB\d{3}")


def _ends_program(block: Block) -> bool:
    for statement in statements_of(block.statement):
        nc = statement if isinstance(statement, NcStatement) else None
        if nc is not None and any(
            w.address == "M" and constant_value(w.value) in (2.0, 30.0, 99.0) for w in nc.words
        ):
            return True
    return False


def _edit(view: View, edit_range: Range, text: str) -> tuple[DocumentEdit, ...]:
    return (DocumentEdit(view.key, (TextEdit(edit_range, text),)),)


def insert_end(view: View, line: int, eol: str) -> CodeAction | None:
    """MB201: close the DO with END<m> before the program's M99/M30 (or after its last block)."""
    program = view.index.program_at(line)
    if program is None:
        return None
    problem = next(
        (p for p in program.loop_problems if p.kind == "no-end" and p.line == line), None
    )
    if problem is None:
        return None
    n = f"{problem.loop_id:g}"
    blocks = view.doc.blocks
    end = min(program.end_line, len(blocks))
    target = next((ln for ln in range(line + 1, end) if _ends_program(blocks[ln])), None)
    if target is not None:
        position = Position(target, 0)
        text = f"END{n}{eol}"
    else:
        last = max(
            (ln for ln in range(line, end) if blocks[ln].statement is not None), default=line
        )
        position = Position(last, len(blocks[last].text))
        text = f"{eol}END{n}"
    return CodeAction(
        title=f"Insert END{n} to close DO{n}",
        kind=ActionKind.QUICK_FIX,
        edits=_edit(view, Range.at(position), text),
        preferred=True,
    )


def bracket_logic(view: View, line: int, column: int) -> list[CodeAction]:
    """MB305: the comparison rewritten with brackets, the likely intent first (each operand
    compared on its own, preferred), then the control's own reading made explicit. A rewrite
    is offered only when the line it gives parses, keeps within five brackets and no longer
    has that comparison's problem."""
    block = view.block(line)
    if block is None:
        return []
    text = block.text
    actions: list[CodeAction] = []
    for statement in statements_of(block.statement):
        for found in logic_operands(statement):
            compare = found.compare
            if compare.span.start != column:
                continue
            before = _logic_count(block.parsed)
            for i, (what, rewritten) in enumerate(logic_fixes(text, found)):
                fixed = text[: compare.span.start] + rewritten + text[compare.span.end :]
                if not acceptable_fix(fixed, before):
                    continue
                edit_range = Range.of(line, compare.span.start, line, compare.span.end)
                actions.append(
                    CodeAction(
                        title=f"Bracket the condition: {rewritten} ({what})",
                        kind=ActionKind.QUICK_FIX,
                        edits=_edit(view, edit_range, rewritten),
                        preferred=i == 0,
                    )
                )
            return actions
    return actions


def _logic_count(parsed: ParsedLine) -> int:
    return sum(len(logic_operands(s)) for s in statements_of(parsed.statement))


def acceptable_fix(fixed: str, before: int) -> bool:
    """The rewritten line parses, nests no bracket more than five deep (the IF's own and the
    conditions' brackets counted too, to be safe: PS0118), and has fewer MB305 findings."""
    parsed = default_parser().parse_line(fixed)
    if parsed.problem is not None or parsed.statement is None:
        return False
    depth = deepest = 0
    for i, ch in enumerate(fixed):
        if any(c.span.start <= i < c.span.end for c in parsed.comments):
            continue
        if ch == "[":
            depth += 1
            deepest = max(deepest, depth)
        elif ch == "]":
            depth -= 1
    if deepest > expressions.MAX_BRACKET_NESTING:
        return False
    return _logic_count(parsed) < before


def rule_fixes(view: View, problem: Problem) -> list[CodeAction]:
    """The fixes the rule worked out with the diagnostic asked for (MB003, MB004, MB101,
    MB404, MB601): the analysis's diagnostic with that code that starts where the problem
    does."""
    actions: list[CodeAction] = []
    for diag in view.analysis.diagnostics:
        if (diag.line, diag.column, diag.code) != (problem.line, problem.column, problem.code):
            continue
        for fix in diag.fixes:
            edits = tuple(
                TextEdit(Range.of(e.line, e.column, e.end_line, e.end_column), e.text)
                for e in fix.edits
            )
            actions.append(
                CodeAction(
                    title=fix.title,
                    kind=ActionKind.QUICK_FIX,
                    edits=(DocumentEdit(view.key, edits),),
                    preferred=fix.preferred,
                )
            )
    return actions


def suppress(view: View, line: int, code: str) -> CodeAction:
    """A ``(fanuc-macro: ignore CODE)`` comment on the line, or the code added to the one
    there."""
    text = view.text(view.key, line)
    existing = _SUPPRESS.search(text)
    if existing is not None:
        position = Position(line, existing.end() - 1)  # before its ")"
        new = f" {code}"
    else:
        position = Position(line, len(text))
        new = f" (fanuc-macro: ignore {code})"
    return CodeAction(
        title=f"Suppress {code} on this line",
        kind=ActionKind.QUICK_FIX,
        edits=_edit(view, Range.at(position), new),
    )


def code_actions(
    view: View,
    problems: Iterable[Problem],
    eol: str,
) -> list[CodeAction]:
    """The fixes of each problem, then one suppression per code and line. Each action names
    in ``fixes`` the problem it answers (the very object given)."""
    actions: list[CodeAction] = []
    seen: set[tuple[str, int]] = set()
    for problem in problems:
        code, line = problem.code, problem.line
        found: list[CodeAction] = []
        if code == "MB201":
            fix = insert_end(view, line, eol)
            if fix is not None:
                found.append(fix)
        if code == "MB305":
            found.extend(bracket_logic(view, line, problem.column))
        found.extend(rule_fixes(view, problem))
        if (code, line) not in seen and _RULE_CODE.fullmatch(code):
            seen.add((code, line))
            found.append(suppress(view, line, code))
        actions.extend(_fixing(action, problem) for action in found)
    return actions


def _fixing(action: CodeAction, problem: Problem) -> CodeAction:
    return CodeAction(action.title, action.kind, action.edits, (problem,), action.preferred)
