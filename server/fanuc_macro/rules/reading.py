"""MB0xx: reading the text. Syntax errors, comments, end of block, case, encoding."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from types import MappingProxyType

from ..diagnostics import (
    Diagnostic,
    Fix,
    FixEdit,
    Related,
    RuleDoc,
    RuleInfo,
    Severity,
    make,
)
from ..line_maps import LineMap
from ..program.knowledge import FUNCTIONS, KEYWORDS
from ..syntax.parser import MAX_DIGITS
from ..syntax.tree import ParsedLine, ProgramStart
from ..translation import Text, joined, tr, tr_n
from .context import LineFinding, RuleContext

FAMILY = "reading"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB001 = RuleInfo("MB001", "syntax-error", Severity.ERROR,
                 "The block does not follow FANUC Macro B syntax.", FAMILY)
MB003 = RuleInfo("MB003", "nested-comment", Severity.WARNING,
                 "Parentheses nested in a comment: FANUC ends the comment at the first ')'.",
                 FAMILY)
MB004 = RuleInfo("MB004", "unclosed-comment", Severity.WARNING,
                 "A comment is opened with '(' and not closed on its line.", FAMILY)
MB005 = RuleInfo("MB005", "text-after-eob", Severity.ERROR,
                 "Program text after the end-of-block ';' on the same line.", FAMILY)
MB006 = RuleInfo("MB006", "lowercase", Severity.WARNING,
                 "Lowercase letters outside comments; FANUC program text is uppercase.", FAMILY)
MB007 = RuleInfo("MB007", "encoding", Severity.INFORMATION,
                 "The file's encoding is in doubt (lines in two encodings, an encoding unclear, "
                 "bytes no encoding reads), or, not being text, the file is not read.", FAMILY)
MB008 = RuleInfo("MB008", "unknown-function", Severity.ERROR,
                 "A name used as a function that FANUC does not have.", FAMILY)
MB009 = RuleInfo("MB009", "tape-mark-not-alone", Severity.WARNING,
                 "'%' shares its line with program text, which the control does not read as "
                 "written.", FAMILY)
MB010 = RuleInfo("MB010", "no-program-number", Severity.INFORMATION,
                 "The program text starts without an O number.", FAMILY)
MB011 = RuleInfo("MB011", "block-too-long", Severity.WARNING,
                 "A line longer than the analysis reads in one block: it is not analysed.", FAMILY)
MB012 = RuleInfo("MB012", "expression-too-deep", Severity.WARNING,
                 "A block nested deeper than the analysis follows: it is not analysed.", FAMILY)
MB013 = RuleInfo("MB013", "file-too-large", Severity.INFORMATION,
                 "A document larger than the analysis reads: the blocks after the limit are not "
                 "checked.", FAMILY)
MB014 = RuleInfo("MB014", "after-end-of-record", Severity.WARNING,
                 "Blocks after the '%' that ends the file's data, which the control never reads "
                 "in.", FAMILY)
# fmt: on


_NOTE_CODES = MappingProxyType(
    {
        "nested-comment": "MB003",
        "unclosed-comment": "MB004",
        "text-after-eob": "MB005",
        "too-long": "MB011",
        "too-deep": "MB012",
    }
)


MB013_DOC = RuleDoc(
    "MB013",
    reports="""
A document larger than the analysis reads: more than 2,000,000 blocks
(setting `fanuc-macro.analysis.maxBlocks`, `--max-blocks`) or more than 64,000,000 characters
(setting `fanuc-macro.analysis.maxFileSize`, `--max-file-size`; a line longer than
`maxLineLength` counts for that much). It stands on the first line not read and says how many
blocks were analysed of how many, and which limit stopped the reading. The lines after it are
not checked at all: no rule sees them, and the evaluator does not run them.
""",
    why="""
It does not come from the program: a program this large
(a CAM surface path, typically) runs like any other. By default any realistic file is read
whole (a 10 MB program of 500,000 blocks gets its diagnostics in about 6 s on a 2-core EPYC
VM); lower limits keep the analysis of a huge file within a few seconds on a machine short of
time or memory, in the editor on every change as on the command line.
""",
    example="""
The example assumes `"fanuc-macro.analysis.maxBlocks": 8`.

```nc
%
O9303 (PASSES)
G00 X50. Z2.
#1=0
WHILE[#1LT3]DO1
G01 X[50.-#1] Z-20. F0.2
#1=#1+1
END1
G00 X60. Z2.
M30
%
```
""",
    fix="""
Raise the setting if the whole file must be checked and a longer analysis is
acceptable, or check the program in parts.
""",
    not_reported="""
Documents within both limits. What the unread part may settle is
not reported either: in a program that goes on past the limit, a `DO` without its `END`
(MB201), a `GOTO` to a label not found (MB101), a `G66` without `G67` (MB406), a program
without its end (MB407), and in the whole file a call of a program not found (MB403); the run
of such a program stops unfinished at the limit, so no verdict that needs a whole run is given.

On the command line the limits are `--max-blocks`, `--max-file-size` and `--max-line-length`
(and `--step-budget`, `--time-limit` for the run).
""",
)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    if ctx.doc.decode_note:
        yield _encoding(ctx, ctx.doc.decode_note)
    yield from _no_program_number(ctx)
    if ctx.doc.unread_note is not None and ctx.doc.unread_from is not None:
        yield make(MB013, ctx.doc.unread_note, ctx.doc.unread_from, 0, 0)  # a line unread
    yield from _after_end_of_record(ctx)


def _tape_mark(parsed: ParsedLine) -> bool | None:
    return True if parsed.tape_mark else None


# The lines of a '%': few, kept from edit to edit.
_tape_marks: LineMap[bool] = LineMap(_tape_mark, every_line=True)


MB014_DOC = RuleDoc(
    "MB014",
    reports="""
Blocks after the `%` that ends a file's data, up to the next program's `O` line: once per such
stretch, at its first block, with the number of blocks and the jumps elsewhere in the file
(`GOTO`) that land on a sequence number in it; and programs after the file's last `%`, which
no mark closes, with a call of them from the programs before it. A `%` ends the data when
program text stands before it; a `%` before any program text starts it.
""",
    why="""
The control reads a file in from the `%` that starts its data to the `%` that ends it (FANUC
16i/18i-TB operator's manual B-63524EN, input from a memory card; the same for the other
input paths, unverified): what stands after the end is never loaded. A sub program or a
label kept there for a jump is not in the control's memory, and the jump stops the program
with alarm PS0060 SEQUENCE NUMBER NOT FOUND.
""",
    example="""
```nc
%
O1000 (DRILL, A RETRY AT THE END)
#1=0
IF [#1 EQ 0] GOTO 10
M30
%
N10 G00 X0 Y0
M30
```
""",
    fix="""
Move the blocks before the closing `%` (before `M30`, or in a program of their own with an
`O` number).
""",
    not_reported="""
What follows the closing `%` when it starts with an `O` line and a later `%` closes it:
another program, as in files that hold several programs each between its own marks, which
are loaded one by one (programs after the file's last `%` are reported, with a call of
them). Comments and empty lines after the `%`. A file read as another control's program
(MB002), whose own marks may use `%` otherwise. The checker's run still reads such blocks (so
the verdicts of the run treat them as loaded).
""",
)


def _after_end_of_record(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB014: the blocks after a closing '%' and before the next O line."""
    marks = _tape_marks(ctx.doc).lines
    programs = ctx.index.programs
    if not marks or not programs:
        return
    blocks = ctx.doc.blocks
    start = next((n for n in range(len(blocks)) if _holds_block(blocks[n].parsed)), None)
    headers = [p.header_line for p in programs if p.header_line is not None]
    after = -1  # the stretches found end here: a later mark inside one is no new end
    for mark in marks:
        if start is None or mark <= after or mark < start:
            continue  # an opening '%', or one within a stretch already reported
        first = next(
            (n for n in range(mark + 1, len(blocks)) if _holds_block(blocks[n].parsed)), None
        )
        if first is None:
            return
        if isinstance(blocks[first].parsed.statement, ProgramStart):
            if mark != marks[-1]:
                continue  # another program between its own marks: loaded on its own
            # Programs after the last '%', which no mark closes: never read in.
            yield from _programs_not_loaded(ctx, mark, first)
            return
        end = next((h for h in headers if h > first), len(blocks))
        after = end
        held = [n for n in range(first, end) if _holds_block(blocks[n].parsed)]
        landing = _jumps_into(ctx, first, end)
        where = (
            tr("line {line}", line=first + 1)
            if len(held) == 1
            else tr("lines {first}-{last}", first=first + 1, last=held[-1] + 1)
        )
        text: Text = tr_n(
            "{count} block after the '%' on line {mark}, which ends the file's data ({where}): "
            "the control never reads it in",
            "{count} blocks after the '%' on line {mark}, which ends the file's data ({where}): "
            "the control never reads them in",
            len(held),
            mark=mark + 1,
            where=where,
        )
        if landing:
            text = tr(
                "{message}; {more}",
                message=text,
                more=tr_n(
                    "{jumps} jumps to a sequence number there, which the control does not find "
                    "(alarm PS0060)",
                    "{jumps} jump to a sequence number there, which the control does not find "
                    "(alarm PS0060)",
                    len(landing),
                    jumps=_listed(landing),
                ),
            )
        yield make(MB014, text, first, 0, len(blocks[first].text.rstrip()))


def _listed(landing: list[Text]) -> Text:
    """The first three jumps, "A, B and C", "A, B, C and 2 more"."""
    if len(landing) == 1:
        return landing[0]
    if len(landing) > 3:
        return tr("{jumps} and {more} more", jumps=joined(", ", landing[:3]), more=len(landing) - 3)
    return tr("{jumps} and {last}", jumps=joined(", ", landing[:-1]), last=landing[-1])


def _programs_not_loaded(ctx: RuleContext, mark: int, first: int) -> Iterator[Diagnostic]:
    """MB014 for programs after a file's last '%' (no mark closes them): the control reads
    up to that '%' and never loads them; a call from the programs before it finds nothing."""
    after = [p for p in ctx.index.programs if p.first_line >= first]
    numbers = {p.number: p for p in after if p.number is not None}
    calls = [
        (call, numbers[call.program])
        for p in ctx.index.programs
        if p.first_line < mark
        for call in p.calls
        if call.program in numbers
    ]
    names = ", ".join(p.display_name for p in after)
    text: Text = tr_n(
        "{programs} stands after the '%' on line {mark}, which ends the file's data, and no "
        "'%' closes it: the control never reads it in",
        "{programs} stand after the '%' on line {mark}, which ends the file's data, and no "
        "'%' closes them: the control never reads them in",
        len(after),
        programs=names,
        mark=mark + 1,
    )
    if calls:
        call, callee = calls[0]
        text = tr(
            "{message}; {call} P{number} on line {line} calls {program}, which the control "
            "does not find (alarm PS0078)",
            message=text,
            call=call.kind,
            number=callee.number,
            line=call.line + 1,
            program=callee.display_name,
        )
    blocks = ctx.doc.blocks
    yield make(MB014, text, first, 0, len(blocks[first].text.rstrip()))


def _holds_block(parsed: ParsedLine) -> bool:
    return not parsed.tape_mark and (parsed.statement is not None or parsed.seq is not None)


def _jumps_into(ctx: RuleContext, first: int, end: int) -> list[Text]:
    """The jumps from outside lines ``first``-``end`` (exclusive) to a label inside: "GOTO 10
    (line 4)"."""
    found: list[Text] = []
    for program in ctx.index.programs:
        for jump in program.jumps:
            if jump.target is None or first <= jump.line < end:
                continue
            target = program.label_line(jump.target, jump.line)
            if target is not None and first <= target < end:
                found.append(
                    tr("GOTO {target} (line {line})", target=jump.target, line=jump.line + 1)
                )
    return found


MB007_DOC = RuleDoc(
    "MB007",
    reports="""
A file whose encoding is in doubt, read from disk:

- lines in UTF-8 beside lines in another encoding (GB18030, Shift-JIS or Windows-1252), as when
  a comment copied from a UTF-8 file is pasted into a GB18030 one. Each line is read in its own
  encoding; the message names the lines of each.
- a file that is not UTF-8 and whose reading in GB18030, Shift-JIS and Windows-1252 all look
  wrong: more than a tenth of its non-ASCII characters are ones seldom written (ideographs
  outside GB2312 and kana for GB18030, second-level kanji for Shift-JIS, runs of three or more
  accented letters for Windows-1252). The message names the encoding chosen.
- a file with bytes that none of UTF-8, GB18030, Shift-JIS and Windows-1252 reads: it is read
  as Latin-1, byte for byte, and the message names the first line with such bytes.

The message quotes the first non-ASCII text, with its line (the diagnostic's related location
points at it). It is reported on the first line.

A file that is not a program text at all is reported once, here, and not analysed: one that
holds NUL bytes (a binary file, or text saved as UTF-16 without a byte order mark), one whose
first 8,000 bytes are more than 5% control codes other than tab, the line ends, form feed,
DC1-DC4 and SUB, and one that starts with a UTF-16 or UTF-32 byte order mark. NUL bytes
before and after the text, a punched tape's leader and trailer (also when line ends run
through them), do not count: they are read as blank, as the control disregards them.
""",
    why="""
Nothing changes for the motion, since only comments hold
non-ASCII characters. But an editor or a transfer program reads a file in one encoding: in a
file of two encodings the lines of the other show garbled there, and a wrong guess of the
checker garbles the comments it quotes (hover, outline, messages). Bytes no encoding reads are
often a damaged file. On input a control may drop characters it does not have (FANUC's
16i/18i-TB manual, B-63524EN, says kana characters in a memory-card file are ignored when it is
read).
""",
    example="""
A file saved in GB18030, with the third line pasted from a file in UTF-8:

```nc
O4009 (外螺纹 M50X3 主程序)
G00 X100. Z100. (退刀)
(螺纹 精车 M50X3)
M30
```
""",
    fix="""
Save the file in one encoding, preferably UTF-8: retype or re-save the lines
named in the message. A file whose encoding is unclear: save it as UTF-8, or keep comments in
ASCII. A file that is not a program text: leave it out of the folder checked, or save the
program as UTF-8 text.
""",
    not_reported="""
A file in one encoding that a shop normally uses, read cleanly:
UTF-8 (with or without a byte order mark, which includes plain ASCII), GB18030 (GBK and GB2312:
Chinese, and the Cyrillic and Greek they hold), Shift-JIS (Japanese, half-width katakana
included) and Windows-1252 (Latin-1's accented letters and signs: Western European). A
document open in the editor: the editor has already decoded it, so only the files the
workspace reads from disk, and the command line's, are judged. The programs and problems of a
file that is not text: its bytes are not read as a program. A file in an encoding the checker
does not try whose bytes read as usual text in one it does: EUC-KR (Korean) and Windows-1253
(Greek) comments read as everyday GB18030 hanzi, garbled and without a note (Windows-1251,
Russian, reads as runs of accented letters: reported as unclear).
""",
)


def _encoding(ctx: RuleContext, note: str) -> Diagnostic:
    """MB007 stands on the first line, where a file diagnostic is suppressed; it points at the
    first text the encoding concerns (the note, ``syntax.lines.decode_bytes``, says what is in
    doubt). On input a control may drop such characters: "When a
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
            MB007,
            tr(
                "{note}; the first non-ASCII text is {shown_text} on line {line}",
                note=note,
                shown_text=repr(shown),
                line=block.line + 1,
            ),
            0,
            0,
            0,
            related=[
                Related(
                    block.line, col, end, tr("non-ASCII text {shown_text}", shown_text=repr(shown))
                )
            ],
        )
    return make(MB007, note, 0, 0, 0)


MB010_DOC = RuleDoc(
    "MB010",
    reports="""
Program text (a block with words or a macro statement) before any O
number in the file, reported on its first block. It is not reported when that first block is
itself rejected (a program number typed with the digit zero, `00001`, is MB001's).

A file with no O line at all whose name is a program number (`O8501.NC`, `o8501.nc`,
`8501.nc`, `O09010`, `O09010.nc`, `O8501 ROUGH.nc`, `O8501_ROUGH.nc`) is a common way to keep
programs: the checker takes the number from the name, the file is program O8501 for the calls
of the other files (on the command line, the files given together; in the editor, the
workspace), and this diagnostic says so as a hint: `program number 8501 taken from the file
name 'O8501.NC'`. The name gives the number when it is `O` and up to 8 digits, or a bare
number of 1 to 9999 (at most 5 digits, `01000`), alone or followed by a description after a
space (after `O` and digits, also after `_` or `-`).
""",
    why="""
The control keeps programs in memory under their O number.
A file without one is stored under the number keyed in when it is read (or refused, depending
on the control and the input path), and a call `M98 P...` of it works only if that number is
right. Run by DNC it may be fine, which is why this is information.
""",
    example="""
```nc
%
G91 G28 Z0
T01 M06
M30
%
```
""",
    fix="""
Start the program with its number: `O0001 (NAME)` on the line after `%`. A
file named by its number needs nothing: store it on the control under that number.
""",
    not_reported="""
Comments before the O line, and files whose first block is
rejected: that block's own diagnostic comes first. It takes no number from a name that is not
a program number: words around a number (`PART2.nc`, `SAMPLE 3.nc`), a bare number with more
than a description after it (`04_variables.nc`, `2024-01-05.nc`), a number out of range
(`0.nc`, `12345.nc`); nor from the name of a file that has an O line somewhere (the O line
numbers the programs, and the text before it stays a fragment).
""",
    severity_note="hint when the file's name gives the number",
)


def _no_program_number(ctx: RuleContext) -> Iterator[Diagnostic]:
    """MB010 on the first block of program text when no O number comes before it; a hint when
    the file's name gives the number (``O8501.NC``), which then stands for the program."""
    programs = ctx.index.programs
    if programs and programs[0].named_by_file is not None and programs[0].number is not None:
        program = programs[0]
        line = program.first_line
        text = ctx.doc.blocks[line].parsed.text
        yield make(
            MB010,
            tr(
                "program number {number} taken from the file name {file_text} (the file has no "
                "O line): calls of O{number:04d} reach it here, and on the control it must be "
                "stored as O{number:04d}",
                number=program.number,
                file_text=repr(program.named_by_file),
            ),
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
                MB010,
                tr(
                    "the program starts here ({program_text}) without an O number: a control "
                    "stores programs under their O number, so loading this file into memory "
                    "needs a number keyed in (or fails), and a file of several programs cannot "
                    "be told apart",
                    program_text=repr(code[:30]),
                ),
                block.line,
                0,
                len(parsed.text.rstrip()),
            )
            return


def nothing_to_read(parsed: ParsedLine) -> bool:
    """Whether this family finds nothing in the line: most blocks."""
    return (
        parsed.problem is None
        and not parsed.notes
        and not parsed.has_lowercase
        and not parsed.tape_mark
    )


def check_line(parsed: ParsedLine) -> Iterable[LineFinding]:
    if nothing_to_read(parsed):
        return ()
    return list(_check_line(parsed))


MB001_DOC = RuleDoc(
    "MB001",
    reports="""
A block that does not follow FANUC Custom Macro B syntax: unbalanced
brackets, `IF [...]` with neither `GOTO` nor `THEN`, `WHILE [...]` without `DOm`, a stray
character, a variable where an address letter is needed. The message says what was found,
at which column, and what would have been accepted there.
""",
    why="""
The control rejects the block when it reads it, with a
format alarm (PS0114 ILLEGAL EXPRESSION FORMAT, PS0125 MACRO STATEMENT FORMAT ERROR or a
similar one). Macro blocks are read ahead of the motion, so the alarm can stop the program
while the tool is still in the cut, in the middle of a part: the part may be scrapped, or the
cycle has to be restarted by hand from a safe block.
""",
    example="""
```nc
O3001 (PECK DRILL)
#1=#1-#17:
IF[#1GT#2]
G01 Z[#1+#17 F#9
M99
```
""",
    fix="""
Read the message: it gives the column and what is expected there. A `:` typed
for `;`, a missing `GOTO n`, a missing `]` and `#26` written without its address (`G01 #26`,
meant `G01 Z#26`) are the usual causes. The message names the typing mistakes it recognises:
a full-width letter or bracket (`Ｇ91`, `（`), a space that is not ASCII (U+3000, U+00A0,
alone on a line too), a decimal comma (`Z-5,0`), a second decimal point
(`X10.0.0`), a number without its address (`G01X-50. 30.`, or `00001` for `O0001`), an
address without its value (`G01XY0`), an expression or a function after an address without
brackets (`X10.*#1`, `XCOS[45]`: write `X[10.*#1]`), `=` or `<>` in a condition (write `EQ`,
`NE`), a `[` not closed, a misspelt keyword (`WHIL`).
""",
    not_reported="""
Forms of another control's dialect: MB002 names them. Nor what
follows from the rejected block: its N number stays a label, and an assignment in it sets its
variable to an unknown value, so a `GOTO` to it is no missing label (MB101) and a later read
of the variable no vacant one (MB901).

A comment whose text goes on over the next lines without its `(` (after an MB004 line): the
control reads the first of them as a block and stops there with an alarm, so that line gets
one MB001 that says so and names the lines after it, which are not reported one by one. A line
of Macro B words only (`IF`, `GOTO`, `SIN`, ...) or an empty line ends the run: it is reported
as itself. Lines of dots alone (`.....`), which an excerpt of a program puts for the blocks it
leaves out: the first gets one MB001 that says so and names the others. Numbers of more than
12 digits (`X10.64426623359`, CAM output for a control that takes them; FANUC's PS0003 TOO
MANY DIGITS) on more than five lines: the first gets one MB001 that counts and names the others.
""",
)


MB003_DOC = RuleDoc(
    "MB003",
    reports="""
Parentheses nested inside a comment, such as `(TOOL (T0101) BORING BAR)`.
The checker reads the comment to its balancing `)` so that the rest of the file is checked,
and says where FANUC would end it.
""",
    why="""
Comments do not nest on a FANUC control: the first `)` ends
the comment, and what follows is read as program text. Here ` BORING BAR)` becomes words of
the block: the control raises an address or format alarm, or, when the left-over text happens
to be valid words (`(SAFE (Z50.) X100.)` leaves ` X100.)`), it executes a move the programmer
believed was a comment.
""",
    example="""
```nc
O9123 (HELICAL BORE)
(TOOL (T0101) BORING BAR)
M99
```
""",
    fix="""
Do not put parentheses inside a comment: write `(TOOL T0101 BORING BAR)` or
`(TOOL - T0101 - BORING BAR)`. The quick fix in the editor removes the parentheses inside the
comment, `(TOOL (T0101) BORING BAR)` becoming `(TOOL T0101 BORING BAR)`.
""",
    not_reported="""
A `(` inside a comment that no second `)` balances (`(A (B) C`):
the comment ends at the first `)` as FANUC reads it, and the rest is checked as program text
(usually MB001). Square brackets, `#`, `=` and other characters in comments, which carry no
meaning there.
""",
)


MB004_DOC = RuleDoc(
    "MB004",
    reports="""
A comment opened with `(` and not closed with `)` on the same line.
""",
    why="""
The block is not what it looks like: depending on the
control and the transfer software, the comment runs on into the following text or the block
is rejected as a format error. A forgotten `)` is also how a following `(` ... `)` pair ends up
read in the wrong place.
""",
    example="""
```nc
O2000 (FACE AND TURN)
G00 X100. Z100. (RETRACT TO TOOL CHANGE
M30
```
""",
    fix="""
Close the comment on the same line. The quick fix in the editor adds the `)` at the end
of the line (before any trailing blanks), where the comment's text ends as the checker reads it.
""",
    not_reported="""
A `)` with no `(` before it (a syntax error, MB001), and comments
that are closed on their line however long they are. When the comment's text goes on over the
next lines, those lines are one MB001 on the first of them, not one a line (see MB001).
""",
)


MB005_DOC = RuleDoc(
    "MB005",
    reports="""
Program text after the end-of-block `;` on the same line, as in
`G00 X100.; Z100.`. A `;` followed only by a comment, more `;` or `%` is fine.
""",
    why="""
The `;` is how the end of block (the line feed) is displayed
and written on a PC. What follows it on the same line is not part of the block the line
shows: depending on how the file is sent, it becomes a separate block that the program author
did not see as one, or the control rejects the line. The checker does not analyse that text,
so a move or an assignment hidden there is not checked either.
""",
    example="""
```nc
O9001 (WAIT FOR SIGNAL)
G00 X100.; Z100.
M99
```
""",
    fix="""
Put each block on its own line: `G00 X100.` then `Z100.`.
""",
    not_reported="""
A `;` followed only by a comment, more `;` or `%`
(`G00 X100. ; (RETRACT)`, `;;`), and a bare `;` line (an empty block). In a file of another
control that writes `;` comments (Siemens, LinuxCNC, DDCS) the block is reported once as that
dialect's (MB002).
""",
)


MB006_DOC = RuleDoc(
    "MB006",
    reports="""
Lowercase letters outside comments (`g01 x10.`, `G1X#611f#9`,
`#1=sin[#2]`). The checker reads them as uppercase.
""",
    why="""
FANUC program text is uppercase. Many controls reject a
lowercase address or keyword with an alarm when the program is loaded or run; others convert
it on input. A program that works on one machine can stop on another at a block that looked
correct.
""",
    example="""
```nc
O3001 (POCKET FINISH)
G1X#611f#9
M99
```
""",
    fix="""
Write program text in uppercase. Comments may keep lowercase text.
""",
    not_reported="""
Lowercase inside comments, which the control shows as it is, and
lowercase in a file the checker recognises as another control's program (a Siemens or LinuxCNC
file, whose own convention it is: MB002 names the file's dialect at each block FANUC rejects);
a line FANUC rejects for another reason (its own diagnostic comes first). Only the first
lowercase letter of a line is reported, and in a file with lowercase on more than five lines
(a generator's convention) only the first such line: its message counts and names the others.
""",
)


MB008_DOC = RuleDoc(
    "MB008",
    reports="""
A name written like a function (`SQR[`, `TRUNC[`, `INT[`, `MAX[`) that
FANUC does not have. FANUC has `SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP POW
ADP BIN BCD`.
""",
    why="""
The control rejects the block with a format alarm (PS0114)
when it reads it, which stops the program, possibly in the middle of a cycle.
""",
    example="""
```nc
O9010 (BOLT CIRCLE)
#2=SQR[#24*#24+#25*#25]
#5=TRUNC[#1/2]
M99
```
""",
    fix="""
Use the FANUC function: `SQRT` for a square root, `FIX` to truncate, `FUP` to
round up, `ROUND` to round, `ABS`; compare with `GT`/`LT` instead of `MAX`/`MIN`.
""",
    not_reported="""
The FANUC functions, statement words written before a bracket
(`IF[`, `WHILE[`, `GOTO[`, `DPRNT[`), names that end with a FANUC function (`XCOS[45]`: a
function after an address without brackets, which MB001 names), and a name away from where the
block fails. In a file of another control (Syntec, Siemens, DDCS...) the block is reported once
as that dialect's (MB002).
""",
)


MB011_DOC = RuleDoc(
    "MB011",
    reports="""
A line longer than the analysis reads in one block: 1024 characters by
default, the setting `fanuc-macro.analysis.maxLineLength`. The message gives the line's length
and the limit. The block is not analysed: only a block delete and a sequence number at its head
are kept, so that a `GOTO` to it still finds its label.
""",
    why="""
Such a line is almost never a program block: a file saved
without line ends, binary data read as text, a CAM post that wrote a whole path on one line.
FANUC's manuals cited in this project give no limit on the length of a block, so the control's
own verdict on it is not known here; what is known is that the analysis checked nothing on it.
(Reading it would cost time and memory out of proportion: a 1 MB line took 7.5 s and 459 MB.)
""",
    example="""
The example assumes `"fanuc-macro.analysis.maxLineLength": 60`.

```nc
O9301 (SURFACE PASSES)
G01 X1.5 Z-1. X2.5 Z-2. X3.5 Z-3. X4.5 Z-4. X5.5 Z-5. X6.5 Z-6. F0.2
M30
```
""",
    fix="""
Put one block on each line. If the file really has blocks that long, raise the
setting.
""",
    not_reported="""
Long lines within the limit, whatever their comments (a comment counts in the length: a line
over the limit because of its comment is reported). Lines past the part of a big file the
analysis reads (MB013): they are not read at all.
""",
)


MB012_DOC = RuleDoc(
    "MB012",
    reports="""
A block whose expressions nest more than 100 levels deep: each operator,
sign, bracket, function and `AND`/`OR`/`XOR` is a level, so `#1=#2+#2+...` with 101 terms is
101 levels. The message gives the depth and, when the block's brackets nest more than five
deep, says that the control stops there with alarm PS0118. The block is not analysed (its
sequence number is kept).
""",
    why="""
Real blocks stay far below this: FANUC itself allows five
levels of brackets (MB301). A block this deep is generated text or a corrupt file, and the
analysis does not follow it (it would exhaust the interpreter's recursion).
""",
    example="""
```nc
O9302 (GENERATED TERMS)
#2=0.5
#1=#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2+#2
M30
```
""",
    fix="""
Split the expression into several assignments (`#10=...`, `#11=#10+...`),
which is also what the control's bracket limit asks for.
""",
    not_reported="""
Blocks of up to 100 levels: those are analysed, and MB301 reports
more than five brackets.
""",
)


def _check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    if parsed.tape_mark and (parsed.statement is not None or parsed.seq is not None):
        yield _tape_mark_not_alone(parsed)
    problem = parsed.problem
    if problem is not None and problem.dialect is None:
        code = "MB008" if problem.unknown_function else "MB001"
        yield LineFinding(code, problem.message, problem.span.start, problem.span.end)
    for note in parsed.notes:
        start, end = note.span.start, note.span.end
        fixes: tuple[Fix, ...] = ()
        if note.kind == "unclosed-comment":
            fixes = (_close_comment(parsed.text),)
        elif note.kind == "nested-comment":
            fixes = _unnest_comment(parsed.text, start, end)
        yield LineFinding(_NOTE_CODES[note.kind], note.message, start, end, fixes)
    if parsed.has_lowercase and problem is None:
        col = next(
            (i for i, ch in enumerate(parsed.text) if ch.islower() and _outside(parsed, i)),
            None,
        )
        if col is not None:
            yield LineFinding(
                "MB006",
                tr(
                    "lowercase {letter_text} at column {column}: FANUC program text is "
                    "uppercase; the control may reject it",
                    letter_text=repr(parsed.text[col]),
                    column=col + 1,
                ),
                col,
                col + 1,
            )


def _close_comment(text: str) -> Fix:
    """MB004: ``)`` at the end of the line, before its trailing blanks: the comment runs to
    the line's end, so that is where its text ends."""
    return Fix(
        tr("Close the comment with ')' at the end of the line"),
        (FixEdit.insert(0, len(text.rstrip()), ")"),),
        preferred=True,
        safe=True,  # the control reads the comment to the line's end already
    )


def _unnest_comment(text: str, start: int, end: int) -> tuple[Fix, ...]:
    """MB003: the comment from ``start`` to ``end`` (its outer parentheses included) with the
    parentheses inside it left out, as the rule's documentation advises: ``(TOOL (T0101) BAR)``
    becomes ``(TOOL T0101 BAR)``, one comment as FANUC reads it."""
    inner = text[start + 1 : end - 1]
    if not (text[start] == "(" and text[end - 1] == ")"):
        return ()
    flat = inner.replace("(", "").replace(")", "")
    return (
        Fix(
            tr("Remove the parentheses nested in the comment"),
            (FixEdit(0, start, 0, end, f"({flat})"),),
            preferred=True,
            safe=True,  # comment text only: what was meant as comment becomes one
        ),
    )


MB009_DOC = RuleDoc(
    "MB009",
    reports="""
A `%` on the same line as program text: `%O100` at the head of a file,
`M30%` at its end. The message names the text that shares the line.
""",
    why="""
`%` marks the start and the end of the data. When a file is
read in, what follows the leading `%` up to the end of its line is skipped (FANUC 16i/18i-TB
operator's manual B-63524EN, memory card files: "data between the first % and the next LF is
skipped"): `%O100` loads a program without its O number, under whatever number the control
gives it, and a call `M98 P100` then finds nothing. Before the closing `%`, a block has no end
of block of its own; whether the control still runs it is not documented.
""",
    example="""
```nc
%O100
G00 X0 Y0
M30%
```
""",
    fix="""
Put `%` on a line of its own, before the first block and after the last one.
""",
    not_reported="""
A `%` alone, or followed only by a comment or `;`. A `%` inside a comment, which is comment
text, or in text after an end-of-block `;` (that text is MB005's and is not analysed). A `%` on
a line whose program text FANUC rejects, unless the line keeps a sequence number (`%N10 ...`):
the block's own diagnostic (MB001, MB002) is given instead.
""",
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
        message = tr(
            "'%' shares its line with {words_text}: the control skips what follows '%' up to "
            "the end of the line, so {words_text} is not read: put '%' on a line of its own",
            words_text=repr(words),
        )
    else:
        message = tr(
            "'%' shares its line with {words_text}: '%' ends the data where it stands, and "
            "{words_text} before it has no end of block of its own: put '%' on a line of its own",
            words_text=repr(words),
        )
    return LineFinding("MB009", message, mark, mark + 1)


def _outside(parsed: ParsedLine, col: int) -> bool:
    return all(not (c.span.start <= col < c.span.end) for c in parsed.comments)


# ---- a comment run on over several lines ------------------------------------------------------

# Words of Macro B and of its functions: a line made of them is code, not a comment's prose.
_MACRO_WORDS = frozenset(KEYWORDS) | frozenset(FUNCTIONS)
_WORD = re.compile(r"[^\W\d_]{3,}")

# A block's findings, with its line: what run_checks folds.
LineFindings = tuple[int, ParsedLine, tuple[LineFinding, ...]]


def _prose(parsed: ParsedLine) -> bool:
    """Whether a line that does not parse reads as a comment's text: a word of three letters
    or more that no block has (a Chinese character counts as one)."""
    if parsed.problem is None or parsed.statement is not None:
        return False
    return any(not w.isascii() or w.upper() not in _MACRO_WORDS for w in _WORD.findall(parsed.text))


def fold_runaway_comments(blocks: list[LineFindings]) -> list[LineFindings]:
    """A comment whose ``(`` is not closed on its line (MB004) and whose text goes on over the
    next lines: the control ends the comment at the end of the block and reads the next line
    as a block, and stops there with an alarm. That first line keeps one MB001 that says so;
    the lines after it, which the control never reaches, are not reported one by one.

    ``blocks`` are the lines with a finding, in order; a line in between without one (an
    empty line) ends the run. The run ends after a line with ``)``, which closes the text."""
    out: list[LineFindings] = []
    i = 0
    while i < len(blocks):
        line, _, findings = blocks[i]
        out.append(blocks[i])
        i += 1
        if not any(f.code == "MB004" for f in findings):
            continue
        run: list[LineFindings] = []
        while i < len(blocks) and blocks[i][0] == line + 1 + len(run) and _prose(blocks[i][1]):
            run.append(blocks[i])
            i += 1
            if ")" in run[-1][1].text:
                break
        if run:
            out.append(_first_of_run(line, run))
    return out


# Lines with lowercase one by one up to this many; past it, a file written in lowercase (a
# generator's or an editor's convention) gets one MB006 that names the others.
LOWERCASE_LINES = 5


def fold_lowercase(blocks: list[LineFindings]) -> list[LineFindings]:
    """More than :data:`LOWERCASE_LINES` lines with lowercase (MB006): the first keeps one
    MB006 that counts and names the others, whose own MB006 is not given."""
    return _fold_repeated(
        blocks,
        lambda f: f.code == "MB006",
        lambda count, lines: tr(
            "{count} more lines have lowercase (lines {lines}), not reported one by one",
            count=count,
            lines=lines,
        ),
        LOWERCASE_LINES,
    )


# A number of more digits than any FANUC takes (the parser's MAX_DIGITS): CAM output for a
# control that takes them writes it in every block.
_LONG_NUMBER = f"has more than {MAX_DIGITS} digits"


def fold_long_numbers(blocks: list[LineFindings]) -> list[LineFindings]:
    """More than :data:`LOWERCASE_LINES` lines with a number of too many digits (MB001, the
    control's PS0003 TOO MANY DIGITS): one MB001 on the first, naming the others."""
    return _fold_repeated(
        blocks,
        lambda f: f.code == "MB001" and _LONG_NUMBER in f.message,
        lambda count, lines: tr(
            "{count} more lines have numbers of more than {digits} digits (written for a "
            "control that takes them) (lines {lines}), not reported one by one",
            count=count,
            digits=MAX_DIGITS,
            lines=lines,
        ),
        LOWERCASE_LINES,
    )


def _fold_repeated(
    blocks: list[LineFindings],
    match: Callable[[LineFinding], bool],
    what: Callable[[int, str], Text],
    most: int,
) -> list[LineFindings]:
    """One mistake on more than ``most`` lines: the first line's finding counts and names the
    others, whose own is not given (``what`` says so, from their count and their lines)."""
    hit = [n for n, (_, _, findings) in enumerate(blocks) if any(match(f) for f in findings)]
    if len(hit) <= most:
        return blocks
    others = [blocks[n][0] + 1 for n in hit[1:]]
    shown = _line_numbers(others)
    out = list(blocks)
    line, parsed, findings = blocks[hit[0]]
    out[hit[0]] = (
        line,
        parsed,
        tuple(
            f._replace(
                message=tr("{message}; {more}", message=f.message, more=what(len(others), shown))
            )
            if match(f)
            else f
            for f in findings
        ),
    )
    for n in hit[1:]:
        line, parsed, findings = blocks[n]
        out[n] = (line, parsed, tuple(f for f in findings if not match(f)))
    return [b for b in out if b[2]]


# A line of dots alone (a comment after them): what an excerpt of a program puts for the
# blocks it leaves out.
_ELISION = re.compile(r"\s*(\.{3,}|\u2026+)\s*(\([^()]*\)\s*)?")


def fold_elisions(blocks: list[LineFindings]) -> list[LineFindings]:
    """Lines of dots alone (``.....``), an excerpt's mark for blocks left out: the control
    rejects the first and stops there with an alarm. It keeps one MB001 that says so and names
    the others, whose own MB001 is not given (their other findings are)."""
    dots = [
        n
        for n, (_, parsed, findings) in enumerate(blocks)
        if any(f.code == "MB001" for f in findings) and _ELISION.fullmatch(parsed.text)
    ]
    if not dots:
        return blocks
    out = list(blocks)
    others = [blocks[n][0] + 1 for n in dots[1:]]
    line, parsed, findings = blocks[dots[0]]
    start = len(parsed.text) - len(parsed.text.lstrip())
    message = tr(
        "a line of dots, which an excerpt puts for blocks it leaves out: the control rejects "
        "it and stops with an alarm here"
    )
    if others:
        message = tr_n(
            "{message}; {count} more such line ({lines}) not reported one by one",
            "{message}; {count} more such lines ({lines}) not reported one by one",
            len(others),
            message=message,
            lines=_line_numbers(others),
        )
    first = LineFinding("MB001", message, start, len(parsed.text.rstrip()))
    out[dots[0]] = (line, parsed, (first, *(f for f in findings if f.code != "MB001")))
    for n in dots[1:]:
        line, parsed, findings = blocks[n]
        out[n] = (line, parsed, tuple(f for f in findings if f.code != "MB001"))
    return [b for b in out if b[2]]


def _line_numbers(lines: list[int]) -> str:
    """The first eight line numbers, and how many more."""
    if len(lines) > 8:
        return tr(
            "{lines} and {more} more", lines=", ".join(map(str, lines[:8])), more=len(lines) - 8
        )
    return ", ".join(map(str, lines))


def _first_of_run(opened: int, run: list[LineFindings]) -> LineFindings:
    line, parsed, _ = run[0]
    shown = parsed.text.strip()
    shown = shown if len(shown) <= 30 else shown[:27] + "..."
    rest: str = ""
    if len(run) > 2:
        rest = tr("; lines {first}-{last} go on with it too", first=line + 2, last=run[-1][0] + 1)
    elif len(run) == 2:
        rest = tr("; line {line} goes on with it too", line=line + 2)
    message = tr(
        "line {line} goes on with the comment opened on line {opened} without its '(': the "
        "control ends a comment at the end of its block, reads {block} as a block and stops "
        "with an alarm here{rest}; put each line of the comment in ( )",
        line=line + 1,
        opened=opened + 1,
        block=repr(shown),
        rest=rest,
    )
    end = len(parsed.text.rstrip())
    first = LineFinding("MB001", message, len(parsed.text) - len(parsed.text.lstrip()), end)
    return line, parsed, (first,)
