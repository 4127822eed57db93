"""The call hierarchy: programs as items, the M98/G65/G66 calls between them across the
workspace. A call runs the program its document has of that number, else the first other
document's (``number_uses.resolve``, the evaluator's order); a computed ``P#1`` is no edge.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..program.index import Call, Program
from ..syntax.tree import Document
from .data import Range, SymbolKind
from .number_uses import CALL_KINDS, calls_in, documents_of, resolve
from .view import Indexed, View, call_at, first_comment


@dataclass(frozen=True)
class CallItem:
    """One program: ``key`` and ``first_line`` name it again when the client asks for its
    calls."""

    key: str
    first_line: int
    name: str
    detail: str
    kind: SymbolKind
    range: Range  # the program's lines
    selection: Range  # its O line (its first line when it has none)


@dataclass(frozen=True)
class CallEdge:
    """A program that calls the item (incoming) or that the item calls (outgoing), with the
    calls: their ranges are in the caller's document."""

    item: CallItem
    ranges: tuple[Range, ...]


def item_of(key: str, doc: Document, program: Program) -> CallItem:
    blocks = doc.blocks
    last = max(program.first_line, min(program.end_line, len(blocks)) - 1)
    header = program.header_line if program.header_line is not None else program.first_line
    head = blocks[header] if header < len(blocks) else None
    span_end = len(head.text) if head is not None else 0
    if head is not None and head.statement is not None and program.header_line is not None:
        selection = Range.of(header, head.statement.span.start, header, head.statement.span.end)
    else:
        selection = Range.of(header, 0, header, span_end)
    last_text = blocks[last].text if last < len(blocks) else ""
    name = program.display_name
    if program.number is not None and program.name:
        name += f" <{program.name}>"
    return CallItem(
        key,
        program.first_line,
        name,
        first_comment(doc, program),
        SymbolKind.SUBPROGRAM if program.returns else SymbolKind.MAIN_PROGRAM,
        Range.of(program.first_line, 0, last, len(last_text)),
        selection,
    )


def prepare_call_hierarchy(view: View, line: int, column: int) -> list[CallItem]:
    """The program called at ``line``, ``column`` when a call is there, else the program that
    holds the line."""
    program = view.index.program_at(line)
    found = view.hit_at(line, column)
    call = call_at(program, line)
    if found is not None and call is not None and call.program is not None:
        hit = found[1]
        if (
            hit.kind == "word"
            and hit.word is not None
            and (hit.word.address == "P" or hit.word.span == call.span)
        ):
            documents = documents_of(view)
            callee = resolve(documents, view.key, call.program)
            if callee is not None:
                key, target = callee
                return [item_of(key, documents[key][0], target)]
    if program is None:
        return []
    return [item_of(view.key, view.doc, program)]


def _program(documents: Mapping[str, Indexed], key: str, first_line: int) -> Program | None:
    entry = documents.get(key)
    if entry is None:
        return None
    return next((p for p in entry[1].programs if p.first_line == first_line), None)


def call_range(call: Call) -> Range:
    """The call's words: ``M98`` to its ``P`` word (either may come first)."""
    spans = [call.span] + ([call.program_span] if call.program_span is not None else [])
    start = min(s.start for s in spans)
    end = max(s.end for s in spans)
    return Range.of(call.line, start, call.line, end)


def incoming_calls(documents: Mapping[str, Indexed], key: str, first_line: int) -> list[CallEdge]:
    """The programs that call the program at ``first_line`` of ``key``, by document and line."""
    target = _program(documents, key, first_line)
    if target is None or target.number is None:
        return []
    number = target.number
    edges: list[CallEdge] = []
    for doc_key in sorted(documents):
        doc, index = documents[doc_key]
        runs = resolve(documents, doc_key, number)
        if runs is None or runs[0] != key or runs[1] is not target:
            continue
        by_caller: dict[int, tuple[Program, list[Range]]] = {}
        for caller, call in calls_in(index):
            if call.program == number:
                by_caller.setdefault(caller.first_line, (caller, []))[1].append(call_range(call))
        for _, (caller, ranges) in sorted(by_caller.items()):
            edges.append(CallEdge(item_of(doc_key, doc, caller), tuple(ranges)))
    return edges


def outgoing_calls(documents: Mapping[str, Indexed], key: str, first_line: int) -> list[CallEdge]:
    """The programs the program at ``first_line`` of ``key`` calls, in the order of its first
    call of each; a call of a program found nowhere is left out."""
    source = _program(documents, key, first_line)
    if source is None:
        return []
    by_callee: dict[tuple[str, int], tuple[Program, list[Range]]] = {}
    for call in source.calls:
        if call.kind not in CALL_KINDS or call.program is None:
            continue
        callee = resolve(documents, key, call.program)
        if callee is None:
            continue
        callee_key, program = callee
        entry = by_callee.setdefault((callee_key, program.first_line), (program, []))
        entry[1].append(call_range(call))
    return [
        CallEdge(item_of(callee_key, documents[callee_key][0], program), tuple(ranges))
        for (callee_key, _), (program, ranges) in by_callee.items()
    ]
