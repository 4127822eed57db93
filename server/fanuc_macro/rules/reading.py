"""MB0xx: reading the text. Syntax errors, comments, end of block, case, encoding."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from ..syntax.tree import ParsedLine, ProgramStart
from .context import LineFinding, RuleContext

FAMILY = "reading"
register(
    RuleInfo("MB001", "syntax-error", Severity.ERROR,
             "The block does not follow FANUC Macro B syntax.", FAMILY),
    RuleInfo("MB003", "nested-comment", Severity.WARNING,
             "Parentheses nested in a comment: FANUC ends the comment at the first ')'.", FAMILY),
    RuleInfo("MB004", "unclosed-comment", Severity.WARNING,
             "A comment is opened with '(' and not closed on its line.", FAMILY),
    RuleInfo("MB005", "text-after-eob", Severity.ERROR,
             "Program text after the end-of-block ';' on the same line.", FAMILY),
    RuleInfo("MB006", "lowercase", Severity.WARNING,
             "Lowercase letters outside comments; FANUC program text is uppercase.", FAMILY),
    RuleInfo("MB007", "encoding", Severity.INFORMATION,
             "The file is not UTF-8; it was read in another encoding.", FAMILY),
    RuleInfo("MB008", "unknown-function", Severity.ERROR,
             "A name used as a function that FANUC does not have.", FAMILY),
    RuleInfo("MB009", "tape-mark-not-alone", Severity.WARNING,
             "'%' shares its line with program text, which the control does not read as "
             "written.", FAMILY),
    RuleInfo("MB010", "no-program-number", Severity.INFORMATION,
             "The program text starts without an O number.", FAMILY),
    RuleInfo("MB011", "block-too-long", Severity.WARNING,
             "A line longer than the analysis reads in one block: it is not analysed.", FAMILY),
    RuleInfo("MB012", "expression-too-deep", Severity.WARNING,
             "A block nested deeper than the analysis follows: it is not analysed.", FAMILY),
    RuleInfo("MB013", "file-too-large", Severity.INFORMATION,
             "A document larger than the analysis reads: the blocks after the limit are not "
             "checked.", FAMILY),
)  # fmt: skip

_NOTE_CODES = {
    "nested-comment": "MB003",
    "unclosed-comment": "MB004",
    "text-after-eob": "MB005",
    "too-long": "MB011",
    "too-deep": "MB012",
}


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    if ctx.doc.decode_note:
        yield _encoding(ctx, ctx.doc.decode_note)
    yield from _no_program_number(ctx)
    if ctx.doc.unread_note is not None and ctx.doc.unread_from is not None:
        yield make("MB013", ctx.doc.unread_note, ctx.doc.unread_from, 0, 0)  # a line unread


def _encoding(ctx: RuleContext, note: str) -> Diagnostic:
    """MB007 stands on the first line, where a file diagnostic is suppressed; it points at the
    first text the encoding concerns. On input a control may drop such characters: "When a
    file containing lowercase letters, kana characters, and several special characters ... is
    read, those letters and characters are ignored" (FANUC B-63524EN/01, 16i/18i-TB, p.649,
    memory card files)."""
    for block in ctx.doc.blocks:
        text = block.parsed.text
        if text.isascii():
            continue
        col = next(i for i, ch in enumerate(text) if ord(ch) > 127)
        end = col
        while end < len(text) and ord(text[end]) > 127:
            end += 1
        shown = text[col:end]
        return make(
            "MB007",
            f"{note}; the first non-ASCII text is {shown!r} on line {block.line + 1}",
            0,
            0,
            0,
            related=[Related(block.line, col, end, f"non-ASCII text {shown!r}")],
        )
    return make("MB007", note, 0, 0, 0)


def _no_program_number(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB010 on the first block of program text when no O number comes before it; a hint when
    the file's name gives the number (``O8501.NC``), which then stands for the program."""
    programs = ctx.index.programs
    if programs and programs[0].named_by_file is not None and programs[0].number is not None:
        program = programs[0]
        line = program.first_line
        text = ctx.doc.blocks[line].parsed.text
        yield make(
            "MB010",
            f"program number {program.number} taken from the file name "
            f"{program.named_by_file!r} (the file has no O line): calls of "
            f"O{program.number:04d} reach it here, and on the control it must be stored as "
            f"O{program.number:04d}",
            line,
            0,
            len(text.rstrip()),
            severity=Severity.HINT,
        )
        return
    for block in ctx.doc.blocks:
        parsed = block.parsed
        if isinstance(parsed.statement, ProgramStart):
            return
        has_text = parsed.statement is not None or parsed.seq is not None
        if parsed.problem is not None or any(n.kind == "text-after-eob" for n in parsed.notes):
            return  # the first text is rejected: its own diagnostic says what it is
        if has_text:
            code = parsed.text.strip()
            yield make(
                "MB010",
                f"the program starts here ({code[:30]!r}) without an O number: a control "
                "stores programs under their O number, so loading this file into memory "
                "needs a number keyed in (or fails), and a file of several programs cannot "
                "be told apart",
                block.line,
                0,
                len(parsed.text.rstrip()),
            )
            return


def check_line(parsed: ParsedLine) -> Iterable[LineFinding]:
    if (
        parsed.problem is None
        and not parsed.notes
        and not parsed.has_lowercase
        and not parsed.tape_mark
    ):
        return ()  # most blocks
    return list(_check_line(parsed))


def _check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    if parsed.tape_mark and (parsed.statement is not None or parsed.seq is not None):
        yield _tape_mark_not_alone(parsed)
    problem = parsed.problem
    if problem is not None and problem.dialect is None:
        code = "MB008" if problem.unknown_function else "MB001"
        yield LineFinding(code, problem.message, problem.span.start, problem.span.end)
    for note in parsed.notes:
        yield LineFinding(_NOTE_CODES[note.kind], note.message, note.span.start, note.span.end)
    if parsed.has_lowercase and problem is None:
        col = next(
            (i for i, ch in enumerate(parsed.text) if ch.islower() and _outside(parsed, i)),
            None,
        )
        if col is not None:
            yield LineFinding(
                "MB006",
                f"lowercase {parsed.text[col]!r} at column {col + 1}: FANUC program text is "
                "uppercase; the control may reject it",
                col,
                col + 1,
            )


def _tape_mark_not_alone(parsed: ParsedLine) -> LineFinding:
    """MB009: '%' and program text on one line.

    FANUC B-63524EN/01 (16i/18i-TB operator's manual) p.649, memory card files: "A file
    starts with % or LF ... In a read operation, data between the first % and the next LF is
    skipped", and "A file always ends with %". So text after a leading '%' is not read; what
    the control does with a block written before the closing '%' without its own end of block
    is not documented there (unverified)."""
    text = parsed.text
    mark = text.index("%")
    code = text.replace("%", " ")
    for comment in parsed.comments:
        width = comment.span.end - comment.span.start
        code = code[: comment.span.start] + " " * width + code[comment.span.end :]
    words = code.strip().rstrip(";").strip()
    before = not text[:mark].replace(";", "").strip()
    if before:
        why = (
            f"the control skips what follows '%' up to the end of the line, so {words!r} is "
            "not read: put '%' on a line of its own"
        )
    else:
        why = (
            f"'%' ends the data where it stands, and {words!r} before it has no end of block "
            "of its own: put '%' on a line of its own"
        )
    return LineFinding("MB009", f"'%' shares its line with {words!r}: {why}", mark, mark + 1)


def _outside(parsed: ParsedLine, col: int) -> bool:
    return all(not (c.span.start <= col < c.span.end) for c in parsed.comments)
