"""Renaming an N label (with the GOTOs, M99 P and profile cycles that reach it) or an O program
number (with its calls across the workspace), refused where the text cannot follow every use.

Numbers are what the control reads, so a rename is of a number to another number: a variable
``#n`` is an address, not a name, and is never renamed.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..program.index import Program
from .data import DocumentEdit, Range, TextEdit
from .number_uses import (
    CALL_KINDS,
    Named,
    NumberUse,
    Unnamed,
    defined_in,
    documents_of,
    label_uses,
    label_words,
    named_at,
    program_uses,
    resolve,
    word_number,
)
from .view import Indexed, View

# The numbers FANUC accepts (FANUC Series 0i-F operator's manual B-64604EN, "Program number"
# and "Sequence number": O1-O9999, N1-N99999; the 8-digit program number option of the 30i is
# not assumed. Unverified against every series' manual.)
LIMITS: Mapping[str, tuple[str, int]] = MappingProxyType(
    {"label": ("N", 99999), "program": ("O", 9999)}
)


@dataclass(frozen=True)
class RenameTarget:
    """What can be renamed at a position: ``range`` its number's text, ``placeholder`` the
    number as the new name is typed (``N10`` is ``10``)."""

    kind: str  # "label" or "program"
    number: int
    range: Range
    placeholder: str


@dataclass(frozen=True)
class Refusal:
    message: str


_VARIABLE = (
    "#{n} is a variable number, an address of the control's memory, not a name: variables "
    "are not renamed (find its uses with Find All References)"
)


def prepare_rename(view: View, line: int, column: int) -> RenameTarget | Refusal | None:
    """What a rename at ``line``, ``column`` would change, a refusal that says why it would not
    be safe, or None when nothing there has a name."""
    found = view.hit_at(line, column)
    if found is None:
        return None
    _, hit = found
    if hit.kind == "var" and hit.var is not None:
        number = hit.var.number
        shown = "[...]" if number is None else f"{number:g}"
        return Refusal(_VARIABLE.format(n=shown))
    named = named_at(view, line, hit)
    if named is None:
        return None
    if isinstance(named, Unnamed):
        return Refusal(f"cannot rename: {named.reason}")
    problem = _unsafe(view, named)
    if problem is not None:
        return Refusal(problem)
    return RenameTarget(
        named.kind,
        named.number,
        Range.of(line, named.span.start, line, named.span.end),
        str(named.number),
    )


def rename(view: View, line: int, column: int, new_name: str) -> tuple[DocumentEdit, ...] | Refusal:
    """The edits that renumber what is at ``line``, ``column`` to ``new_name`` (``20``,
    ``N20`` for a label; ``1234``, ``O1234`` for a program), or why they are refused."""
    target = prepare_rename(view, line, column)
    if target is None:
        return Refusal("nothing to rename here: put the cursor on an N label, a GOTO or a call")
    if isinstance(target, Refusal):
        return target
    found = view.hit_at(line, column)
    assert found is not None
    named = named_at(view, line, found[1])
    assert isinstance(named, Named)
    new = parse_number(target.kind, new_name)
    if isinstance(new, Refusal):
        return new
    if new == named.number:
        return ()
    uses = _uses(view, named)
    if named.kind == "label":
        assert named.program is not None
        if new in named.program.labels:
            where = named.program.labels[new][0] + 1
            return Refusal(
                f"N{new} is already a label of {named.program.display_name} (line {where})"
            )
    else:
        taken = defined_in(documents_of(view), new)
        if taken:
            key, program = taken[0]
            return Refusal(f"O{new:04d} is already a program ({key}, {program.display_name})")
    edits: dict[str, list[TextEdit]] = {}
    for use in uses:
        old = view.text(use.key, use.line)[use.span.start : use.span.end]
        edits.setdefault(use.key, []).append(
            TextEdit(
                Range.of(use.line, use.span.start, use.line, use.span.end),
                _written(old, new, use.width),
            )
        )
    return tuple(
        DocumentEdit(key, tuple(sorted(edits[key], key=lambda e: e.range.start)))
        for key in sorted(edits)
    )


_NUMBER = re.compile(r"\s*([NOno])?\s*(\d+)\s*")


def parse_number(kind: str, new_name: str) -> int | Refusal:
    """The new number typed for a label (``20`` or ``N20``) or a program (``O20``)."""
    letter, limit = LIMITS[kind]
    m = _NUMBER.fullmatch(new_name)
    what = "a sequence number" if kind == "label" else "a program number"
    if m is None or (m.group(1) is not None and m.group(1).upper() != letter):
        return Refusal(f"'{new_name}' is not {what}: type {letter}1 to {letter}{limit}")
    number = int(m.group(2))
    if not 1 <= number <= limit:
        return Refusal(f"{letter}{number} is out of range: {what} is {letter}1 to {letter}{limit}")
    return number


def _written(old: str, new: int, width: int = 0) -> str:
    """``new`` as the old number was written: ``0010`` stays four digits wide; ``width``: the
    digits it must take (the program after M98's repeat count)."""
    if len(old) > 1 and old.startswith("0"):
        width = max(width, len(old))
    return f"{new:0{width}d}" if width else str(new)


def _uses(view: View, named: Named) -> list[NumberUse]:
    if named.kind == "label":
        assert named.program is not None
        return label_uses(view, named.program, named.number)
    documents = documents_of(view)
    found = resolve(documents, view.key, named.number)
    if found is None:
        return []
    return program_uses(documents, found[0], found[1])


def _unsafe(view: View, named: Named) -> str | None:
    """Why renaming ``named`` could miss a use the text cannot show, if it could."""
    documents = documents_of(view)
    if named.kind == "label":
        program = named.program
        assert program is not None
        lines = program.labels.get(named.number, [])
        if not lines:
            return f"cannot rename: {program.display_name} has no label N{named.number}"
        if len(lines) > 1:
            shown = ", ".join(str(ln + 1) for ln in lines)
            return (
                f"cannot rename: N{named.number} labels several blocks of "
                f"{program.display_name} (lines {shown}); which one a GOTO reaches depends on "
                "where it is"
            )
        computed = next((j for j in program.jumps if j.constant is None), None)
        if computed is not None:
            return (
                f"cannot rename: {program.display_name} has a computed GOTO (line "
                f"{computed.line + 1}) that may jump to N{named.number}"
            )
        # In a main program M99 P jumps to its own label; in a called one it returns to the
        # caller's: which one it names depends on how the program is run.
        if program.number is not None and _is_called(documents, view.key, program):
            for line in program.returns:
                for kind, word in label_words(view.doc.blocks[line], view.config):
                    if kind == "m99" and word_number(word) == named.number:
                        return (
                            f"cannot rename: {program.display_name} is called as a subprogram "
                            f"and its M99 P{named.number} (line {line + 1}) returns to the "
                            "caller's label, not this one"
                        )
        # A subprogram this program calls may return here with M99 P: it is called from
        # other programs too, where its P names their labels, so it cannot be renamed with it.
        for call in program.calls:
            if call.kind not in CALL_KINDS or call.program is None:
                continue
            callee = resolve(documents, view.key, call.program)
            if callee is None:
                continue
            callee_key, callee_program = callee
            callee_doc = documents[callee_key][0]
            for line in callee_program.returns:
                block = callee_doc.blocks[line]
                for kind, word in label_words(block, view.config):
                    if kind == "m99" and word_number(word) == named.number:
                        return (
                            f"cannot rename: {callee_program.display_name}, called at line "
                            f"{call.line + 1}, returns to N{named.number} with M99 P (line "
                            f"{line + 1} of {callee_key})"
                        )
        return None
    found = resolve(documents, view.key, named.number)
    if found is None:
        return f"cannot rename: no program O{named.number:04d} in the workspace"
    program = found[1]
    if program.named_by_file is not None:
        return (
            f"cannot rename: O{named.number:04d} has no O line, its number is the file name "
            f"'{program.named_by_file}' (rename the file)"
        )
    defined = defined_in(documents, named.number)
    if len(defined) > 1:
        where = ", ".join(sorted({k for k, _ in defined}))
        return (
            f"cannot rename: O{named.number:04d} is defined {len(defined)} times ({where}); "
            "which one a call runs depends on the document"
        )
    return None


def _is_called(documents: dict[str, Indexed], key: str, program: Program) -> bool:
    assert program.number is not None
    return bool([u for u in program_uses(documents, key, program) if u.kind == "call"])


__all__ = ("LIMITS", "Refusal", "RenameTarget", "parse_number", "prepare_rename", "rename")
