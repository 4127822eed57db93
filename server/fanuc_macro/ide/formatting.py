"""Formatting: a document's or a range's blocks rewritten as a FANUC programmer writes them
(addresses and keywords in upper case, spaces by the settings, no trailing whitespace), never
changing what a block means.

A block is rewritten alone: never joined with another or split, its words never reordered, its
numbers' text never touched (``10.`` stays ``10.``), its comments byte for byte as they were.
Each rewritten block is parsed again and kept only when its syntax tree, columns aside, is the
original's (``same_meaning``); a block with a syntax error is left as it is. Line ends are not
part of a block: an edit never touches them, so CRLF stays CRLF.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field, fields, is_dataclass
from itertools import pairwise

from ..config import FormatSettings
from ..syntax.lines import decode_bytes, not_text_reason, split_lines, tape_leader_bounds
from ..syntax.parser import default_parser, statements_of
from ..syntax.tree import Assign, IfThen, NcStatement, ParsedLine, Print, Span
from .data import Position, Range, TextEdit

# Fields of the syntax tree that say where a thing is written or how its letter was cased,
# not what it means.
_PLACE_FIELDS = frozenset(("span", "name_span", "id_span", "address_lowercase"))
_NAME = re.compile(r"<[^>\n]*>")  # O<NAME> (30i): a name, kept as written
_ASSIGNMENT_GAP = re.compile(r"[ \t]*=[ \t]*")
_BLANK = re.compile(r"[ \t]*")
_LINE_END = re.compile(r"\r\n|\r|\n")


@dataclass(frozen=True)
class FormatOptions:
    """The settings and what the editor asks for each request (LSP ``FormattingOptions``)."""

    settings: FormatSettings = field(default_factory=FormatSettings)
    trim_trailing_whitespace: bool = True
    insert_final_newline: bool = False
    trim_final_newlines: bool = False


# What rewrites one parsed line: ``format_line``, or a test's on purpose faulty one.
Rewrite = Callable[[ParsedLine, FormatOptions], str]


# ---- what a line means -----------------------------------------------------------------------


def _shape(node: object) -> object:
    """A node as a comparable value without its columns."""
    if isinstance(node, NcStatement):  # a PlainNc too: its words, built from its code
        return ("NcStatement", tuple(_shape(w) for w in node.words))
    if isinstance(node, Print):  # the keyword in any case; the format as written
        return ("Print", node.keyword, node.text[len(node.keyword) :])
    if isinstance(node, tuple):
        return tuple(_shape(item) for item in node)
    if is_dataclass(node) and not isinstance(node, type):
        return (
            type(node).__name__,
            *(_shape(getattr(node, f.name)) for f in fields(node) if f.name not in _PLACE_FIELDS),
        )
    return node


def line_meaning(parsed: ParsedLine) -> object:
    """What a parsed line says, columns and the case of address letters aside: block skip, N
    number, statement, comments (their text exactly), tape mark, problem, notes' kinds."""
    return (
        parsed.tape_mark,
        parsed.skip,
        parsed.seq,
        _shape(parsed.statement),
        tuple((c.text, c.closed) for c in parsed.comments),
        None if parsed.problem is None else parsed.problem.message,
        parsed.failed_assignment,
        tuple(note.kind for note in parsed.notes),
    )


def same_meaning(original: ParsedLine, formatted: ParsedLine) -> bool:
    return line_meaning(original) == line_meaning(formatted)


# ---- one line --------------------------------------------------------------------------------


def _kept_as_written(parsed: ParsedLine) -> list[Span]:
    """Columns no rewrite touches: comments, DPRNT/BPRNT formats (printed as written), program
    names in angle brackets, and what follows an end of block ';' or a tape mark '%'."""
    text = parsed.text
    kept = [c.span for c in parsed.comments]
    code = list(text)
    for span in kept:
        code[span.start : span.end] = " " * (span.end - span.start)
    code_text = "".join(code)
    for statement in statements_of(parsed.statement):
        if isinstance(statement, Print):  # its keyword is cased as any other
            kept.append(Span(statement.span.start + len(statement.keyword), statement.span.end))
    kept.extend(Span(m.start(), m.end()) for m in _NAME.finditer(code_text))
    ends = [i for i in (code_text.find(";"), code_text.find("%")) if i >= 0]
    if ends:
        kept.append(Span(min(ends), len(text)))
    return kept


def _gaps(parsed: ParsedLine, options: FormatOptions) -> list[tuple[int, int, str]]:
    """The spaces the settings rewrite: (start, end, new text), none overlapping. They lie
    between the nodes of the statement, blank but for an assignment's "=": never in a comment
    or a column ``_kept_as_written``."""
    text = parsed.text
    settings = options.settings
    words = settings.space_between_words
    assignment = settings.spaces_around_assignment
    found: list[tuple[int, int, str]] = []
    for statement in statements_of(parsed.statement):
        # The words of an NC block (not of a mixed one), and its N number before them.
        alone = type(parsed.statement) is type(statement)
        if words != "keep" and alone and isinstance(statement, NcStatement):
            spans = [w.span for w in statement.words]
            if parsed.seq_span is not None and parsed.seq_span.end <= spans[0].start:
                spans.insert(0, parsed.seq_span)
            space = " " if words == "always" else ""
            for before, after in pairwise(spans):
                if _BLANK.fullmatch(text, before.end, after.start):
                    found.append((before.end, after.start, space))
        if assignment != "keep":
            assign = statement.then if isinstance(statement, IfThen) else statement
            if isinstance(assign, Assign):
                start, end = assign.target.span.end, assign.value.span.start
                if _ASSIGNMENT_GAP.fullmatch(text, start, end):
                    found.append((start, end, " = " if assignment == "always" else "="))
    return found


def format_line(parsed: ParsedLine, options: FormatOptions) -> str:
    """The line as the settings write it (the meaning is checked by the caller)."""
    text = parsed.text
    if parsed.problem is not None:
        return text
    kept = bytearray(len(text))  # 1: a column written as it is
    for span in _kept_as_written(parsed):
        kept[span.start : span.end] = b"\x01" * (span.end - span.start)
    gaps = {start: (end, space) for start, end, space in _gaps(parsed, options)}
    upper = options.settings.upper_case
    out: list[str] = []
    i = 0
    while i < len(text):
        gap = gaps.get(i)
        if gap is not None:
            end, space = gap
            out.append(space)
            if end > i:
                i = end
                continue
        ch = text[i]
        out.append(ch.upper() if upper and "a" <= ch <= "z" and not kept[i] else ch)
        i += 1
    line = "".join(out)
    if options.trim_trailing_whitespace:
        last = parsed.comments[-1] if parsed.comments else None
        open_to_end = last is not None and not last.closed and last.span.end == len(text)
        if not open_to_end:  # an unclosed comment's spaces are its text
            line = line.rstrip(" \t")
    return line


# ---- a document ------------------------------------------------------------------------------


def _edit(line: int, old: str, new: str) -> TextEdit:
    """The smallest edit of one line from ``old`` to ``new``."""
    prefix = 0
    most = min(len(old), len(new))
    while prefix < most and old[prefix] == new[prefix]:
        prefix += 1
    suffix = 0
    while suffix < most - prefix and old[-1 - suffix] == new[-1 - suffix]:
        suffix += 1
    return TextEdit(
        Range.of(line, prefix, line, len(old) - suffix), new[prefix : len(new) - suffix]
    )


def formatted_line(text: str, options: FormatOptions, rewrite: Rewrite = format_line) -> str:
    """One line formatted, or as it is when it has a syntax error or the rewrite would change
    what it means."""
    parser = default_parser()
    parsed = parser.parse_line(text)
    if parsed.problem is not None:
        return text
    new = rewrite(parsed, options)
    if new == text or not same_meaning(parsed, parser.parse_line(new)):
        return text
    return new


def format_lines(
    text: str,
    options: FormatOptions,
    first: int = 0,
    last: int | None = None,
    rewrite: Rewrite = format_line,
) -> list[TextEdit]:
    """The edits that format lines ``first`` to ``last`` (inclusive; None: to the end) of a
    document's text."""
    lines = split_lines(text)
    stop = len(lines) - 1 if last is None else min(last, len(lines) - 1)
    edits: list[TextEdit] = []
    for n in range(max(first, 0), stop + 1):
        old = lines[n]
        new = formatted_line(old, options, rewrite)
        if new != old:
            edits.append(_edit(n, old, new))
    return edits


def format_document(
    text: str, options: FormatOptions, rewrite: Rewrite = format_line
) -> list[TextEdit]:
    """The edits that format a whole document: its lines, and at its end the final newline the
    editor asks for (one, of the document's own line end) and no blank lines after it."""
    lines = split_lines(text)
    if not text:
        return []
    ends_with_eol = text.endswith(("\n", "\r"))
    tail = len(lines)  # the first of the blank lines at the end that go
    if options.trim_final_newlines and ends_with_eol:
        while tail > 1 and not lines[tail - 1].strip(" \t"):
            tail -= 1
    edits = format_lines(text, options, 0, tail - 1, rewrite)
    if tail < len(lines):
        edits.append(TextEdit(Range(Position(tail, 0), Position(len(lines), 0)), ""))
    elif options.insert_final_newline and not ends_with_eol:
        eol_match = _LINE_END.search(text)
        eol = eol_match.group() if eol_match is not None else "\n"
        last = len(lines) - 1
        if edits and edits[-1].range.start.line == last:  # one edit per line: joined
            old = lines[last]
            new = formatted_line(old, options, rewrite) + eol
            edits[-1] = TextEdit(Range.of(last, 0, last, len(old)), new)
        else:
            end = Position(last, len(lines[last]))
            edits.append(TextEdit(Range(end, end), eol))
    return edits


def format_text(text: str, options: FormatOptions, rewrite: Rewrite = format_line) -> str:
    """The document's text formatted: its edits applied (the command line's ``format``)."""
    return apply_edits(text, format_document(text, options, rewrite))


def apply_edits(text: str, edits: list[TextEdit]) -> str:
    """``text`` with edits of distinct places applied (columns in code points)."""
    starts = [0]
    for m in _LINE_END.finditer(text):
        starts.append(m.end())

    def offset(p: Position) -> int:
        if p.line >= len(starts):
            return len(text)
        return starts[p.line] + p.column

    out = text
    for edit in sorted(edits, key=lambda e: (e.range.start, e.range.end), reverse=True):
        out = out[: offset(edit.range.start)] + edit.new_text + out[offset(edit.range.end) :]
    return out


class CannotFormat(Exception):
    """A file the formatter does not write: not a program text, or not written back as it was
    read in the encoding it was read in."""


_BOM = "\ufeff".encode()


def format_file(data: bytes, options: FormatOptions) -> bytes:
    """A program file's bytes formatted, in its own encoding (a UTF-8 byte order mark kept);
    ``data`` itself when nothing changes."""
    reason = not_text_reason(data)
    if reason is not None:
        raise CannotFormat(reason)
    start, end = tape_leader_bounds(data)
    if (start, end) != (0, len(data)):  # a punched tape's leader and trailer of NULs: kept
        return data[:start] + format_file(data[start:end], options) + data[end:]
    decoded = decode_bytes(data)
    bom = _BOM if data.startswith(_BOM) else b""
    if bom + decoded.text.encode(decoded.encoding, "replace") != data:
        raise CannotFormat(f"its text does not encode back to the same {decoded.encoding} bytes")
    formatted = format_text(decoded.text, options)
    return data if formatted == decoded.text else bom + formatted.encode(decoded.encoding)


__all__ = (
    "CannotFormat",
    "FormatOptions",
    "Rewrite",
    "apply_edits",
    "format_document",
    "format_file",
    "format_line",
    "format_lines",
    "format_text",
    "formatted_line",
    "line_meaning",
    "same_meaning",
)
