"""Renumber N labels: one program's sequence numbers rewritten in steps, in the order of its
blocks, with every reference to them: ``GOTO n``, ``M99 Pn`` and, on a lathe, the profile's
``P``/``Q`` of ``G70``-``G73``.

What the edit cannot follow it refuses, with the reason as the action's disabled reason: a
computed jump (``GOTO #1``: which label it reaches is known only when it runs), a reference to
an N number the program does not have or has twice, a block with a syntax error (its jumps are
unknown), a number past ``MAX_SEQUENCE_NUMBER``, and an ``M99 P`` between programs: in a
program that is called, where it returns to the caller's N number, or in a program it calls,
returning to one of its own. A program's ``M99 P`` is taken for its own label only when no
program of the workspace calls it (it runs as a main program).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ..program.index import Program
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Goto, IfGoto, IfNc, NcStatement, Num, Span
from ..translation import tr
from .data import ActionKind, CodeAction, DocumentEdit, Range, TextEdit
from .view import View

# FANUC reads at most five digits after N (N1-N99999): FANUC Series 0i-F Operator's Manual
# (B-64604EN), "Sequence number" (unverified against the manual's text; 30i options allow
# eight digits, not assumed here).
MAX_SEQUENCE_NUMBER = 99_999
DEFAULT_STEP = 10
TITLE = "Renumber N labels"
_DIGITS = re.compile(r"[0-9.]+$")
# The profile cycles of a lathe whose P and Q are the profile's first and last N numbers.
_PROFILE_CYCLES = frozenset((70.0, 71.0, 72.0, 73.0))


class _Refused(Exception):
    pass


@dataclass(frozen=True)
class _Reference:
    line: int
    span: Span  # the number's columns
    target: int
    what: str  # "GOTO 30", "M99 P30": for a refusal's message


def _caller(view: View, program: Program) -> str | None:
    """Where a program of the document or the workspace calls this one, or None."""
    if program.number is None:
        return None
    indexes = [(view.key, view.index)]
    indexes.extend((key, index) for key, (_, index) in view.workspace.items() if key != view.key)
    for key, index in indexes:
        for other in index.programs:
            call = next((c for c in other.calls if c.program == program.number), None)
            if call is not None:
                if key == view.key:
                    return tr(
                        "{program} calls it on line {line}",
                        program=other.display_name,
                        line=call.line + 1,
                    )
                return tr(
                    "{program} calls it on line {line} of {file}",
                    program=other.display_name,
                    line=call.line + 1,
                    file=key.rsplit("/", 1)[-1],
                )
    return None


def _m99_p(nc: NcStatement) -> bool:
    return nc.find("P") is not None and any(
        w.address == "M" and constant_value(w.value) == 99.0 for w in nc.words
    )


def _returns_into(view: View, program: Program) -> None:
    """Refuses when a program this one calls returns into it with ``M99 P``: to one of this
    program's N numbers, which the edit of this program alone would not follow."""
    for call in program.calls:
        entry = None if call.program is None else view.program_entry(call.program)
        if entry is None:
            continue
        _, doc, callee = entry
        for line in callee.returns:
            statements = statements_of(doc.blocks[line].parsed.statement)
            if any(isinstance(s, NcStatement) and _m99_p(s) for s in statements):
                raise _Refused(
                    tr(
                        "{program}, which it calls, returns to one of its N numbers (M99 P on "
                        "line {line})",
                        program=callee.display_name,
                        line=line + 1,
                    )
                )


def _references(view: View, program: Program) -> list[_Reference]:
    """Every constant reference to an N number in the program; a computed one is refused."""
    _returns_into(view, program)
    caller = _caller(view, program)
    found: list[_Reference] = []
    blocks = view.doc.blocks
    for line in range(program.first_line, min(program.end_line, len(blocks))):
        parsed = blocks[line].parsed
        if parsed.problem is not None:
            raise _Refused(tr("line {line} has a syntax error", line=line + 1))
        for statement in statements_of(parsed.statement):
            nc = statement.words if isinstance(statement, IfNc) else statement
            if isinstance(statement, Goto | IfGoto):
                goto = statement if isinstance(statement, Goto) else statement.goto
                value = constant_value(goto.target)
                if not isinstance(goto.target, Num) or value is None or value != int(value):
                    raise _Refused(tr("the jump on line {line} is computed", line=line + 1))
                found.append(_Reference(line, goto.target.span, int(value), f"GOTO {value:g}"))
            elif isinstance(nc, NcStatement):
                if caller is not None and _m99_p(nc):
                    # A subprogram's M99 P returns to an N number of the program that called it.
                    raise _Refused(
                        tr(
                            "M99 P on line {line} returns to its caller ({caller})",
                            line=line + 1,
                            caller=caller,
                        )
                    )
                found.extend(_word_references(view, line, nc))
    return found


def _word_references(view: View, line: int, nc: NcStatement) -> list[_Reference]:
    codes = {(w.address, constant_value(w.value)) for w in nc.words if w.address in "GM"}
    addresses: tuple[str, ...] = ()
    if ("M", 99.0) in codes or ("M", 97.0) in codes:
        addresses = ("P",)
    if view.config.is_lathe and any(("G", g) in codes for g in _PROFILE_CYCLES):
        addresses = ("P", "Q")
    found: list[_Reference] = []
    for word in nc.words:
        if word.address not in addresses:
            continue
        value = constant_value(word.value)
        if not isinstance(word.value, Num) or value is None or value != int(value):
            raise _Refused(
                tr("the {address} on line {line} is computed", address=word.address, line=line + 1)
            )
        found.append(_Reference(line, word.value.span, int(value), f"{word.address}{value:g}"))
    return found


def _renumbered(view: View, program: Program, step: int) -> list[TextEdit]:
    references = _references(view, program)
    labelled = sorted(line for lines in program.labels.values() for line in lines)
    if len(labelled) * step > MAX_SEQUENCE_NUMBER:
        raise _Refused(
            tr(
                "{count} labels in steps of {step} go past N{largest}",
                count=len(labelled),
                step=step,
                largest=MAX_SEQUENCE_NUMBER,
            )
        )
    new_of_line = {line: (k + 1) * step for k, line in enumerate(labelled)}
    blocks = view.doc.blocks
    edits: list[TextEdit] = []
    for reference in references:
        lines = program.labels.get(reference.target)
        if not lines:
            raise _Refused(
                tr(
                    "{reference} on line {line} names no N{target} of this program",
                    reference=reference.what,
                    line=reference.line + 1,
                    target=reference.target,
                )
            )
        if len(lines) > 1:
            raise _Refused(
                tr(
                    "N{target} is on lines {lines}",
                    target=reference.target,
                    lines=", ".join(str(n + 1) for n in lines),
                )
            )
        span = reference.span
        target = str(new_of_line[lines[0]])
        if blocks[reference.line].text[span.start : span.end] != target:
            place = Range.of(reference.line, span.start, reference.line, span.end)
            edits.append(TextEdit(place, target))
    for line, new in new_of_line.items():
        parsed = blocks[line].parsed
        seq_span = parsed.seq_span
        if seq_span is None or parsed.seq == new:
            continue
        digits = _DIGITS.search(parsed.text, seq_span.start, seq_span.end)
        if digits is None:
            raise _Refused(tr("the N number on line {line} is not plain digits", line=line + 1))
        edits.append(TextEdit(Range.of(line, digits.start(), line, digits.end()), str(new)))
    return sorted(edits, key=lambda e: e.range.start)


def renumber_labels(view: View, line: int, step: int = DEFAULT_STEP) -> CodeAction | None:
    """The "Renumber N labels" action of the program holding ``line`` (or the next one): None
    when it has no N numbers or they are already so; disabled, with the reason, when it
    cannot be done."""
    program = view.index.program_at(line)
    if program is None:  # before the first program (a "%" line): the program that follows
        program = next((p for p in view.index.programs if p.first_line > line), None)
    if program is None or not program.labels:
        return None
    title = tr(
        "Renumber N labels of {program} (step {step})", program=program.display_name, step=step
    )
    try:
        if step < 1:
            raise _Refused(tr("the step {step} is not a positive whole number", step=step))
        edits = _renumbered(view, program, step)
    except _Refused as refused:
        reason: str = refused.args[0]
        return CodeAction(
            title=tr("{title}: not possible, {reason}", title=title, reason=reason),
            kind=ActionKind.SOURCE_RENUMBER,
            edits=(),
            disabled=reason,
        )
    if not edits:
        return None
    return CodeAction(
        title=title,
        kind=ActionKind.SOURCE_RENUMBER,
        edits=(DocumentEdit(view.key, tuple(edits)),),
    )


__all__ = ("DEFAULT_STEP", "MAX_SEQUENCE_NUMBER", "TITLE", "renumber_labels")
