"""Code actions: the fixes offered for diagnostics, and their suppression comment."""

from __future__ import annotations

import re
from collections.abc import Iterable

from ..translation import tr
from .data import ActionKind, CodeAction, DocumentEdit, Position, Problem, Range, TextEdit
from .view import View

_SUPPRESS = re.compile(r"\(\s*fanuc-macro\s*:\s*ignore\b[^)]*\)", re.I)
_RULE_CODE = re.compile(r"MB\d{3}")


def _edit(view: View, edit_range: Range, text: str) -> tuple[DocumentEdit, ...]:
    return (DocumentEdit(view.key, (TextEdit(edit_range, text),)),)


def rule_fixes(view: View, problem: Problem, eol: str = "\n") -> list[CodeAction]:
    """The fixes the rule worked out with the diagnostic asked for: the analysis's diagnostic
    with that code that starts where the problem does. A fix's line ends ("\n") become the
    document's ``eol``."""
    actions: list[CodeAction] = []
    for diag in view.analysis.diagnostics:
        if (diag.line, diag.column, diag.code) != (problem.line, problem.column, problem.code):
            continue
        for fix in diag.fixes:
            edits = tuple(
                TextEdit(
                    Range.of(e.line, e.column, e.end_line, e.end_column),
                    e.text.replace("\n", eol) if eol != "\n" else e.text,
                )
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
        title=tr("Suppress {code} on this line", code=code),
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
        found = rule_fixes(view, problem, eol)
        if (code, line) not in seen and _RULE_CODE.fullmatch(code):
            seen.add((code, line))
            found.append(suppress(view, line, code))
        actions.extend(_fixing(action, problem) for action in found)
    return actions


def _fixing(action: CodeAction, problem: Problem) -> CodeAction:
    return CodeAction(action.title, action.kind, action.edits, (problem,), action.preferred)
