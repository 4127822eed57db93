"""What names an N label or an O program number: the label and the GOTOs, M99 P and profile
cycles that reach it in its program; the O line and the M98/G65/G66 calls of a program across
the workspace. Rename, document highlight and the call hierarchy share them.

A label or program is named here by its number, which the text states: a computed target
(``GOTO#1``, ``M98 P#1``) names nothing the text alone can follow.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from ..config import Config
from ..program.index import Call, Program, ProgramIndex
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Block, Document, IfNc, NcStatement, Span, Word
from .locate import Hit
from .view import Indexed, View, call_at

CALL_KINDS = frozenset({"M98", "G65", "G66", "G66.1"})  # calls of a program number
# The lathe's cycles that name a profile N(ns)..N(nf) by P and Q (as the evaluator reads them).
PROFILE_CYCLES = frozenset({70.0, 71.0, 72.0, 73.0})


@dataclass(frozen=True)
class NumberUse:
    """One place that names a label or a program: ``span`` is the number's text on ``line``
    (the digits after N, O, P or Q, or the GOTO's target); ``kind`` what names it there."""

    key: str
    line: int
    span: Span
    kind: str  # "label", "goto", "m99", "profile", "m97"; "program", "call"
    call: Call | None = None
    width: int = 0  # the digits a new number must be written in (M98 P0013331: 4), 0: any


@dataclass(frozen=True)
class Named:
    """What a position names: a label of a program, or a program number."""

    kind: str  # "label" or "program"
    number: int
    span: Span  # the number's text under the cursor
    program: Program | None = None  # the label's program; the program named (when found)


@dataclass(frozen=True)
class Unnamed:
    """A position that names a label or program the text cannot follow, and why."""

    reason: str


def documents_of(view: View) -> dict[str, Indexed]:
    """The view's document and the workspace's others, by key, in key order (deterministic)."""
    found: dict[str, Indexed] = {view.key: (view.doc, view.index)}
    for key in sorted(view.workspace):
        if key != view.key:
            found[key] = view.workspace[key]
    return found


def digits_span(text: str, span: Span) -> Span:
    """The digits of a number word (``N0010``, ``P3331``, ``O12``) within ``span``."""
    start = span.start
    while start < span.end and not text[start].isdigit():
        start += 1
    end = start
    while end < span.end and text[end].isdigit():
        end += 1
    return Span(start, end) if end > start else span


def _word_digits(block: Block, word: Word) -> Span:
    return digits_span(block.text, word.value.span)


def nc_parts(block: Block) -> Iterator[NcStatement]:
    """The NC words of a block: its NC statement, the NC half of a mixed block, an IF's NC."""
    for statement in statements_of(block.statement):
        if isinstance(statement, NcStatement):
            yield statement
        elif isinstance(statement, IfNc):
            yield statement.words


def _code(nc: NcStatement, address: str) -> set[float]:
    found: set[float] = set()
    for word in nc.words:
        if word.address == address:
            value = constant_value(word.value)
            if value is not None:
                found.add(value)
    return found


def word_number(word: Word | None) -> int | None:
    if word is None:
        return None
    value = constant_value(word.value)
    return int(value) if value is not None and value == int(value) else None


def label_words(block: Block, config: Config) -> Iterator[tuple[str, Word]]:
    """The words of a block that name a label of its program: M99 P (in a main program it
    jumps there; FANUC 0i-F operator's manual, "M99 P" in subprogram control, unverified for
    other series), Haas M97 P (a local subprogram call), and on a lathe the P and Q of
    G70-G73 (the profile's first and last blocks)."""
    for nc in nc_parts(block):
        m_codes = _code(nc, "M")
        if 99.0 in m_codes or 97.0 in m_codes:
            p = nc.find("P")
            if p is not None and word_number(p) is not None:
                yield ("m99" if 99.0 in m_codes else "m97"), p
        if config.is_lathe and _code(nc, "G") & PROFILE_CYCLES:
            for address in ("P", "Q"):
                word = nc.find(address)
                if word is not None and word_number(word) is not None:
                    yield "profile", word


def computed_label_words(block: Block, config: Config) -> bool:
    """A word that names a label by a computed value (``M99 P#1``, ``G70 P#1 Q#2``)."""
    for nc in nc_parts(block):
        m_codes = _code(nc, "M")
        names = 99.0 in m_codes or 97.0 in m_codes
        profile = config.is_lathe and bool(_code(nc, "G") & PROFILE_CYCLES)
        addresses = ("P",) if names else ("P", "Q") if profile else ()
        for address in addresses:
            word = nc.find(address)
            if word is not None and constant_value(word.value) is None:
                return True
    return False


def named_at(view: View, line: int, hit: Hit) -> Named | Unnamed | None:
    """The label or program ``hit`` names, why it names none the text can follow, or None
    when it is no label, jump, return or call at all."""
    block = view.block(line)
    if block is None:
        return None
    program = view.index.program_at(line)
    if hit.kind == "label" and program is not None and block.parsed.seq is not None:
        seq_span = block.parsed.seq_span or hit.span
        return Named("label", block.parsed.seq, digits_span(block.text, seq_span), program)
    if hit.kind == "goto" and hit.goto is not None:
        value = constant_value(hit.goto.target)
        if value is None:
            return Unnamed(
                "a computed GOTO: where it jumps is known only when the program runs, "
                "so no label can be renamed from it"
            )
        if value != int(value) or program is None:
            return Unnamed("the GOTO's target is not a whole sequence number")
        return Named("label", int(value), digits_span(block.text, hit.goto.target.span), program)
    if hit.kind == "program":
        header = program if program is not None and program.header_line == line else None
        if header is None or header.number is None:
            return Unnamed("this program has a name, not a number")
        seq = block.statement.span if block.statement is not None else hit.span
        return Named("program", header.number, digits_span(block.text, seq), header)
    if hit.kind == "word" and hit.word is not None:
        word = hit.word
        call = call_at(program, line)
        if (
            call is not None
            and call.kind in CALL_KINDS
            and (word.address == "P" or word.span == call.span)
        ):
            if call.program is None or call.program_span is None:
                return Unnamed(f"the {call.kind} calls a computed program number (P#...)")
            entry = view.program_entry(call.program)
            callee = entry[2] if entry is not None else None
            return Named("program", call.program, call_digits(block.text, call), callee)
        for _, label_word in label_words(block, view.config):
            if label_word is word and program is not None:
                number = word_number(word)
                assert number is not None  # label_words gives constant whole numbers only
                return Named("label", number, _word_digits(block, word), program)
        if word.address == "P" and computed_label_words(block, view.config):
            return Unnamed("a computed P: the label it names is known only when it runs")
    return None


def call_digits(text: str, call: Call) -> Span:
    """The digits of a call's program number: ``M98 P0013331`` -> ``3331`` (the leading digits
    are the repeat count)."""
    assert call.program_span is not None
    span = digits_span(text, call.program_span)
    if (
        call.kind == "M98"
        and span.end - span.start > 4
        and call.program == int(text[span.end - 4 : span.end])
    ):
        return Span(span.end - 4, span.end)
    return span


def label_uses(view: View, program: Program, number: int) -> list[NumberUse]:
    """The label N``number`` of ``program`` and everything in the program that names it."""
    out: list[NumberUse] = []
    blocks = view.doc.blocks
    for line in program.labels.get(number, []):
        block = blocks[line]
        if block.parsed.seq_span is not None:
            out.append(
                NumberUse(view.key, line, digits_span(block.text, block.parsed.seq_span), "label")
            )
    for jump in program.jumps:
        if jump.target == number and jump.constant is not None:
            text = blocks[jump.line].text
            out.append(NumberUse(view.key, jump.line, digits_span(text, jump.target_span), "goto"))
    for line in _label_word_lines(view, program):
        block = blocks[line]
        for kind, word in label_words(block, view.config):
            if word_number(word) == number:
                out.append(NumberUse(view.key, line, _word_digits(block, word), kind))
    out.sort(key=lambda use: (use.line, use.span.start))
    return out


def _label_word_lines(view: View, program: Program) -> list[int]:
    """The lines of ``program`` that may hold a word naming a label: its returns and M97 calls
    (the index keeps them), and on a lathe the blocks whose text has a G7 (a profile cycle)."""
    lines = set(program.returns)
    lines.update(call.line for call in program.calls if call.kind == "M97")
    if view.config.is_lathe:
        blocks = view.doc.blocks
        for line in range(program.first_line, min(program.end_line, len(blocks))):
            text = blocks[line].text
            if "7" in text and ("G" in text or "g" in text):
                lines.add(line)
    return sorted(lines)


def defined_in(documents: Mapping[str, Indexed], number: int) -> list[tuple[str, Program]]:
    """Every program numbered ``number`` in the documents, in their order."""
    return [
        (key, program)
        for key, (_, index) in documents.items()
        for program in index.programs
        if program.number == number
    ]


def resolve(
    documents: Mapping[str, Indexed], from_key: str, number: int
) -> tuple[str, Program] | None:
    """The program a call of O``number`` in ``from_key`` runs: its own document's first, then
    the first other document's (the evaluator's order)."""
    own = documents.get(from_key)
    if own is not None:
        program = own[1].by_number(number)
        if program is not None:
            return from_key, program
    for key, (_, index) in documents.items():
        if key != from_key:
            program = index.by_number(number)
            if program is not None:
                return key, program
    return None


def calls_in(index: ProgramIndex) -> Iterator[tuple[Program, Call]]:
    for program in index.programs:
        for call in program.calls:
            if call.kind in CALL_KINDS and call.program is not None:
                yield program, call


def program_uses(
    documents: Mapping[str, Indexed], key: str, program: Program, only: str | None = None
) -> list[NumberUse]:
    """The O line of ``program`` (in ``key``) and every call in the documents that runs it;
    ``only``: in that document alone."""
    out: list[NumberUse] = []
    number = program.number
    if number is None:
        return out
    for doc_key, (doc, index) in documents.items():
        if only is not None and doc_key != only:
            continue
        runs = resolve(documents, doc_key, number)
        if runs is None or runs[0] != key or runs[1] is not program:
            continue  # the calls here run another program of that number
        if doc_key == key and program.header_line is not None:  # (key's own resolves to it)
            block = doc.blocks[program.header_line]
            statement = block.statement
            if statement is not None:
                span = digits_span(block.text, statement.span)
                out.append(NumberUse(doc_key, program.header_line, span, "program"))
        for _, call in calls_in(index):
            if call.program != number or call.program_span is None:
                continue
            text = doc.blocks[call.line].text
            span = call_digits(text, call)
            # After a repeat count (M98 P0013331) the program is the last four digits.
            assert call.program_span is not None
            after_count = span != digits_span(text, call.program_span)
            out.append(
                NumberUse(doc_key, call.line, span, "call", call, width=4 if after_count else 0)
            )
    return out


def doc_text(doc: Document, line: int) -> str:
    return doc.blocks[line].text if 0 <= line < len(doc.blocks) else ""


__all__ = (
    "CALL_KINDS",
    "Named",
    "NumberUse",
    "Unnamed",
    "calls_in",
    "defined_in",
    "documents_of",
    "label_uses",
    "label_words",
    "named_at",
    "program_uses",
    "resolve",
    "word_number",
)
