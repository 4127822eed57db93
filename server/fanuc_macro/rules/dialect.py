"""MB002: forms of other controls' dialects (Haas, Mitsubishi/Citizen, LinuxCNC, LNC/Syntec,
Okuma, wire EDM registers): those the block reader names in rejected blocks, and Haas-only codes
in blocks FANUC's grammar reads."""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from types import MappingProxyType

from ..diagnostics import Diagnostic, Related, RuleDoc, RuleInfo, Severity, make
from ..line_maps import LineMap
from ..per_line import PerLine
from ..program.knowledge import FUNCTIONS, KEYWORDS
from ..syntax import dialects
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import (
    Assign,
    BareCond,
    BlockIf,
    Document,
    IfGoto,
    IfNc,
    NcStatement,
    Num,
    ParsedLine,
    PlainNc,
    ProgramStart,
    Unary,
    Var,
    While,
    Word,
)
from ..syntax.walk import all_line_variables, line_variables
from ..translation import Text, tr, tr_n
from .context import LineFinding

FAMILY = "dialect"

# The family's rules, by code: what diagnostics.make gives each diagnostic (its name,
# severity and tags). Each rule's documentation, MBxxx_DOC, is beside the function that
# finds it; docs/rules.md is generated from them (python3 scripts/rules_doc.py).
# fmt: off
MB002 = RuleInfo("MB002", "not-fanuc", Severity.ERROR,
                 "A form another control accepts and a FANUC control rejects.", FAMILY)
# fmt: on


def check_line(parsed: ParsedLine) -> Iterable[LineFinding]:
    whole = parsed.statement
    if type(whole) is PlainNc and no_foreign_code(parsed):
        return []
    if isinstance(whole, NcStatement) and parsed.problem is None:
        found = _plain_nc(parsed, whole)  # most blocks: their words, without the walks
        if found is not None:
            return found
    if parsed.problem is None and (type(whole) is Assign or type(whole) is NcStatement):
        # The next most: an assignment, NC words with brackets. As _check_line, at once.
        found = list(_nc_codes(whole)) if type(whole) is NcStatement else []
        return found + _haas_variables(parsed, all_line_variables(parsed))
    return list(_check_line(parsed))


def no_foreign_code(parsed: ParsedLine) -> bool:
    """Of a line of words of numbers (``PlainNc``): whether it has no G or M code of another
    control's, the only thing this family finds in such a line."""
    statement = parsed.statement
    assert type(statement) is PlainNc
    return all(value not in _FOREIGN_CODES for _, value in statement.codes)


def _plain_nc(parsed: ParsedLine, statement: NcStatement) -> list[LineFinding] | None:
    """The findings of a block of NC words whose values are numbers, #n or -#n, from one look
    at each word; None for any other block."""
    has_p = has_h = False
    codes: list[tuple[Word, float]] = []
    found: list[LineFinding] = []
    for word in statement.words:
        address = word.address
        if address == "P":
            has_p = True
        elif address == "H":
            has_h = True
        value = word.value
        if type(value) is Num:
            if (address == "G" or address == "M") and value.value in _FOREIGN_CODES:
                codes.append((word, value.value))
            continue
        if type(value) is Unary:
            value = value.operand
        if type(value) is not Var or value.index is not None:
            return None
        finding = _variable_finding(parsed, value)
        if finding is not None:
            found.append(finding)
    if codes:  # the codes' findings come before the variables'
        return [*_code_findings(codes, has_p, has_h), *found]
    return found


MB002_DOC = RuleDoc(
    "MB002",
    reports="""
A form that another control accepts and a FANUC control rejects, with the
dialect named: Haas (`M97 P`, `G103`, `G154 P`, `M109 P`, `IF [...] <NC words>`,
`IF [...] THEN M31`, block `IF`/`ELSE`/`ENDIF`, a bare value as a condition, `#30001.116`, the
settings `#20000`–`#29999`), Mitsubishi/Citizen (`$1`, `!L1`, `S1=500`, `X#1+1.` without
brackets), LinuxCNC (`#<NAME>`, `o100 sub`, `o<name> call`), LNC/Syntec (`%@MACRO`, `@100`,
`:=`, `IF (...) THEN ... END_IF`, `WAIT()`), Siemens Sinumerik (`PROC`, `DEF REAL`, `GOTOF`,
`FOR ... ENDFOR`, `R20=5`, `$AA_IW`), DDCS (`IF #1==0 GOTO5` without brackets), Okuma OSP
(`VC1`, `VS1` variables, sequence names `NLOOP`, `GOTO NEND`, `IF [...] NLOOP`, `CALL O...`,
`RTS`) and wire EDM registers (`H1=0.216`, `H000=+00000000`, `E001=`). A form FANUC rejects
that no dialect here has is named "not FANUC (dialect not recognised)": C-style comparisons
(`<`, `>=`, `==`, `LTE`), a value assigned to an address or a name (`Q1=12`, `TEMP=10`).

A file that carries a mark only another control's programs have (Syntec's `%@MACRO` header,
Siemens' `PROC` or `DEF` or R parameters, LinuxCNC's O-word subroutine, DDCS's `IF` without
brackets, Okuma's `VC1=` or `GOTO NLOOP` or `CALL O...`, a wire EDM's `H1=` register, Philips'
`%PM` header, CNC Simulator Pro's `$Mill` directives) is read as
that control's program: one MB002 on its first line (past a tape mark and empty lines) names
the control and the line of the mark, and counts the blocks FANUC rejects; it is information,
a statement about the file (right, perhaps, for its control), not an error (an error for a
dialect not recognised: the file may be a broken FANUC program). The editor lists
each of them as a related place, with what FANUC rejects in it, instead of one diagnostic a
block, syntax errors, comment or end-of-block warnings (a `;` comment of Siemens or LinuxCNC, a
`(` of a Syntec expression). A block `ELSE` in a Siemens file is Siemens', not Haas's. At least 5
blocks in one control's forms read the same way (two of Haas's local subroutine calls
`M97 P<n>`: a program built on them is Haas's), and so do at least 5 blocks with a comment
after `;` (`G0 Z10.0 ; Retract`: LinuxCNC, Mach3, Fagor and proLIGHT start comments with `;`,
where FANUC ends the block and reads the words as the next one). A FANUC
program with a few foreign blocks (no such mark) keeps one MB002 a block. A file without such a
mark most of whose blocks (at least 5, and half of them or more; three in four with an O
program number, which says the file is meant for FANUC) FANUC rejects is read the same way, as
the program of another control whose dialect is not recognised (Heidenhain's `BEGIN PGM`,
Okuma's named variables, an editor's template): a FANUC program with mistakes has a few such
blocks among many. In a file read as another control's, FANUC's map of variable numbers
(MB302-MB304: that control numbers its own) and its end of record (MB014) are not applied,
and the verdicts of the run (MB501-MB999) past its first block FANUC rejects are not
reported: FANUC stops there with an alarm, and the run without the blocks it cannot read
(their F, their variables) is of no control.
""",
    why="""
A FANUC control raises an alarm on the block: PS0125 for an
`IF` without `GOTO`/`THEN`, PS0114 for `<`, `LTE` and unbracketed address expressions, PS0115
for a variable number with a decimal part, an address or format alarm for `$`, `!`, `@`. A
program copied from a Haas or a Citizen stops at the first such block, possibly in the middle
of a cycle.
""",
    example="""
```nc
O0044 (PART COUNTER - HAAS FORMS)
IF [#1 EQ #2] S#20 F#30
IF [FIX[#3901/5.] EQ [#3901/5.]] THEN M31
M97 P100
M30
```
""",
    fix="""
Rewrite in FANUC form: `IF [...] GOTO n` around the NC block, `THEN` only
with one macro assignment, `M98 P<program>` with the subroutine as its own O program, `[ ]`
around an address expression (`X[#814+.1]`), `EQ NE GT GE LT LE` for comparisons, numbered
variables instead of names, `G54.1 P` for `G154 P`, offsets through `G10` or `#2001`–.
""",
    not_reported="""
A code that is Haas's only with its `P` when it stands without
one (`M97`, `M109` alone are machine builders' M codes on FANUC); `#10000`–`#19999`, which are
FANUC's tool offsets as well as Haas's commons; the other Haas G codes: `G47` (engraving on a
Haas, a tool offset on a FANUC mill), `G187` (a FANUC machine may make it a custom macro call);
and, in another control's file, its rejected blocks one by one: they are the related places of
its one MB002. G103 as a FANUC custom G code (set by
parameters 6050-6059) is reported all the same: that setting is not in the program.
""",
)


def _check_line(parsed: ParsedLine) -> Iterator[LineFinding]:
    problem = parsed.problem
    if problem is not None and problem.dialect is not None:
        yield LineFinding(
            "MB002",
            tr("{dialect}: {message}", dialect=problem.dialect, message=problem.message),
            problem.span.start,
            problem.span.end,
        )
    for statement, statement_variables in zip(
        statements_of(parsed.statement), line_variables(parsed), strict=True
    ):
        span = statement.span
        if isinstance(statement, IfNc):
            yield LineFinding(
                "MB002",
                tr(
                    "Haas: 'IF [...] THEN <NC words>' is not FANUC; FANUC's IF takes GOTO n, or "
                    "THEN with one macro statement (alarm PS0125)"
                )
                if statement.has_then
                else tr(
                    "Haas: 'IF [...] <NC words>' is not FANUC; FANUC's IF takes GOTO n, or THEN "
                    "with one macro statement (alarm PS0125)"
                ),
                span.start,
                span.end,
            )
        elif isinstance(statement, BlockIf):
            yield LineFinding(
                "MB002",
                tr(
                    "Haas NGC: block {keyword} (IF ... THEN / ELSE / ENDIF on their own lines) "
                    "is not FANUC 0i/16i/30i; use IF [...] GOTO n",
                    keyword=statement.keyword,
                ),
                span.start,
                span.end,
            )
        elif isinstance(statement, NcStatement):
            yield from _nc_codes(statement)
        if isinstance(statement, (IfGoto, While)) and isinstance(statement.cond, BareCond):
            c = statement.cond
            yield LineFinding(
                "MB002",
                tr(
                    "Haas NGC: a bare value as a condition is not FANUC; compare it, e.g. [#1 NE 0]"
                ),
                c.span.start,
                c.span.end,
            )
        yield from _haas_variables(parsed, statement_variables)


def _haas_variables(parsed: ParsedLine, variables: Iterable[Var]) -> list[LineFinding]:
    found: list[LineFinding] = []
    for var in variables:
        number = var.number
        if number is None or (number < 20000 and number == int(number)):
            continue  # most variables: no Haas number
        finding = _variable_finding(parsed, var)
        if finding is not None:
            found.append(finding)
    return found


def _variable_finding(parsed: ParsedLine, var: Var) -> LineFinding | None:
    """Haas NGC variable numbers: a decimal part, the settings #20000-#29999."""
    number = var.number
    if number is None:
        return None
    if number != int(number):
        written = parsed.text[var.span.start + 1 : var.span.end].strip()
        return LineFinding(
            "MB002",
            tr(
                "Haas NGC: #{number_text} (a variable number with a decimal part) is not FANUC "
                "(alarm PS0115)",
                number_text=written,
            ),
            var.span.start,
            var.span.end,
        )
    if 20000 <= number <= 29999:
        n = int(number)
        return LineFinding(
            "MB002",
            tr(
                "Haas NGC: #{number} reads Haas setting {setting} (#20000-#29999 are the "
                "settings); FANUC has no settings variables (alarm PS0115 on most controls)",
                number=n,
                setting=n - 20000,
            ),
            var.span.start,
            var.span.end,
        )
    return None


# The values of the G and M codes _nc_codes looks closer at (M97, M98, G103, G154, M109).
_FOREIGN_CODES = frozenset({97.0, 98.0, 103.0, 109.0, 154.0})


def _nc_codes(statement: NcStatement) -> Iterator[LineFinding]:
    """M98 H, M97 P and Haas-only G and M codes among a block's NC words."""
    has_p = has_h = False
    codes: list[tuple[Word, float]] = []
    for word in statement.words:
        address = word.address
        if address == "P":
            has_p = True
        elif address == "H":
            has_h = True
        elif address == "G" or address == "M":
            value = word.value
            number = value.value if type(value) is Num else constant_value(value)
            if number in _FOREIGN_CODES:
                assert number is not None
                codes.append((word, number))
    return _code_findings(codes, has_p, has_h)


def _code_findings(
    codes: list[tuple[Word, float]], has_p: bool, has_h: bool
) -> Iterator[LineFinding]:
    """The findings of the G and M words ``codes`` of a block (with their values) that has a P
    word or an H word."""
    for word, code in codes:
        if word.address == "M" and code == 98.0 and has_h and not has_p:
            yield LineFinding(
                "MB002",
                tr(
                    "Mitsubishi/Citizen: M98 H<n> (a call to a sequence "
                    "number) is not FANUC; FANUC's M98 takes P<program>"
                ),
                word.span.start,
                word.span.end,
            )
        # A bare M97 is an ordinary M code on FANUC; with P it is Haas's local call.
        if word.address == "M" and code == 97.0 and has_p:
            yield LineFinding(
                "MB002",
                tr("Haas: M97 (local subroutine at an N number) is not FANUC; use M98 P<program>"),
                word.span.start,
                word.span.end,
            )
        haas = _haas_code(word.address, code, has_p)
        if haas is not None:
            yield LineFinding("MB002", haas, word.span.start, word.span.end)


def _haas_code(address: str, value: float | None, has_p: bool) -> Text | None:
    """Haas-only G and M codes (Haas mill operator's manual 96-8000 and the reference's 7:
    G103 look-ahead, G154 P work offsets, M109 user input; [S HAAS], [C jpaullee]). FANUC has
    none of them as standard: an unknown G code raises PS0010 IMPROPER G-CODE, unless a
    parameter (6050-6059) makes it a custom macro call; buffering is suppressed by the M codes
    of parameters 3411-3432 (macro-b.md 7, [M FANUC-16iTB-buf]). #20000-#29999 as Haas NGC
    settings: macro-b.md 2.1 [C], unverified against Haas's manual."""
    if address == "G" and value == 103.0:
        return tr(
            "Haas: G103 (block look-ahead limit) is not FANUC: FANUC raises PS0010 IMPROPER "
            "G-CODE (unless a parameter makes G103 a macro call); FANUC stops look-ahead with "
            "an M code that suppresses buffering (parameters 3411-3432)"
        )
    if address == "G" and value == 154.0 and has_p:
        return tr(
            "Haas: G154 P<n> (additional work offsets) is not FANUC (PS0010 IMPROPER G-CODE); "
            "FANUC selects them with G54.1 P<n>"
        )
    if address == "M" and value == 109.0 and has_p:
        return tr(
            "Haas: M109 P<n> (interactive input of a character into #n) is not FANUC; on FANUC "
            "M109 is whatever the machine builder made it"
        )
    return None


# ---- a file of another control's dialect --------------------------------------------------------


def _dialect_mark(parsed: ParsedLine) -> tuple[str, str] | None:
    return dialects.file_mark(parsed.text)


_dialect_marks: PerLine[tuple[str, str] | None] = PerLine(_dialect_mark)


def _file_mark(parsed: ParsedLine) -> tuple[str, str] | None:
    # A mark of another dialect is a block FANUC rejects.
    return None if parsed.problem is None else _dialect_marks(parsed)


# The marks of another control's dialect: after an edit only the edited lines are looked at
# again.
file_marks: LineMap[tuple[str, str]] = LineMap(_file_mark)


# A file without a program number most of whose blocks FANUC rejects is another control's
# program even without a mark of a dialect known here (Heidenhain's BEGIN PGM, Okuma's named
# variables): a FANUC program with mistakes has a few such blocks among many (the corpus's
# worst, NC Code Checker's collection of macro errors: 13 of 47; a Swiss-type lathe's program in
# Citizen's dialect, 34 of 160).
MOSTLY_REJECTED = 0.5
MIN_REJECTED = 5
# A file with a program number is meant for FANUC: only three blocks in four make it another's
# (an editor's template behind an O line; the fixtures' collection of syntax errors: 18 of 34).
NEARLY_ALL_REJECTED = 0.75
UNRECOGNISED = tr("another control (its dialect not recognised)")


def unrecognised_dialect(doc: Document, rejected: list[int]) -> dialects.FileDialect | None:
    """Another control's program whose dialect has no mark known here, from the lines of
    ``doc`` FANUC rejects (``rejected``, ascending): most of its blocks."""
    if len(rejected) < MIN_REJECTED:
        return None
    numbered = any(isinstance(b.parsed.statement, ProgramStart) for b in doc.blocks)
    lines = set(rejected)
    lines.update(
        b.line for b in doc.blocks if b.parsed.statement is not None or b.parsed.problem is not None
    )
    if len(rejected) < (NEARLY_ALL_REJECTED if numbered else MOSTLY_REJECTED) * len(lines):
        return None
    mark = tr("{count} of its {total} blocks", count=len(rejected), total=len(lines))
    return dialects.FileDialect(UNRECOGNISED, mark, rejected[0])


# The dialects the line rules name in an MB002 ("Haas: ..."), by the control they are of.
_NAMED = MappingProxyType(
    {
        "Haas": "Haas",
        "Haas NGC": "Haas",
        dialects.MITSUBISHI: dialects.MITSUBISHI,
        dialects.SYNTEC: dialects.SYNTEC,
        dialects.SIEMENS: dialects.SIEMENS,
        dialects.LINUXCNC: dialects.LINUXCNC,
        dialects.DDCS: dialects.DDCS,
        dialects.OKUMA: dialects.OKUMA,
        dialects.WIRE_EDM: dialects.WIRE_EDM,
    }
)
# Blocks in one control's forms that make a file that control's program: a FANUC program with
# a stray form or two keeps one MB002 a block (the corpus: at most 3 in a FANUC-looking file;
# a Haas NGC program, 9; a Citizen lathe's, 34).
MIN_DIALECT_BLOCKS = 5
# Haas's local subroutine calls (M97 P<n>): a program built on them is Haas's from two on, its
# flow jumping to N numbers FANUC would take for M codes of the machine builder.
HAAS_LOCAL_CALL = "Haas: M97 "
MIN_LOCAL_CALLS = 2


def _named_dialect(finding: LineFinding) -> str | None:
    if finding.code != "MB002":
        return None
    name = finding.message.partition(": ")[0]
    return _NAMED.get(name)


# Controls whose comments run from ';' to the end of the line (LinuxCNC, Mach3, Fagor, Light
# Machines' proLIGHT): on FANUC ';' ends the block, and words after it are the next block's.
SEMICOLON_COMMENTS = tr("a control whose comments follow ';' (LinuxCNC, Mach3, Fagor, proLIGHT)")
# Macro B's words: after ';' they are a FANUC block, not a comment.
_MACRO_WORDS = frozenset(KEYWORDS) | frozenset(FUNCTIONS)
_WORD = re.compile(r"[A-Za-z]{3,}")


def _comment_after_semicolon(parsed: ParsedLine, findings: tuple[LineFinding, ...]) -> bool:
    """Whether a block FANUC rejects for its text after ';' (MB005) has prose there: a word
    that is no Macro B keyword ("; Retract", "; Units: Metric")."""
    if not any(f.code == "MB005" for f in findings):
        return False
    after = parsed.text.partition(";")[2]
    return any(w.upper() not in _MACRO_WORDS for w in _WORD.findall(after))


def dialect_of_blocks(
    per_block: list[tuple[int, ParsedLine, tuple[LineFinding, ...]]],
) -> dialects.FileDialect | None:
    """Another control's program from its blocks: at least :data:`MIN_DIALECT_BLOCKS` in the
    forms of one control (the line rules name it), or with a comment after ';'."""
    counts: dict[str, list[int]] = {}
    local_calls: list[int] = []
    for line, parsed, findings in per_block:
        names = {n for n in map(_named_dialect, findings) if n is not None}
        if _comment_after_semicolon(parsed, findings):
            names.add(SEMICOLON_COMMENTS)
        for name in names:
            counts.setdefault(name, []).append(line)
        if any(f.code == "MB002" and f.message.startswith(HAAS_LOCAL_CALL) for f in findings):
            local_calls.append(line)
    if not counts:
        return None
    name, lines = max(counts.items(), key=lambda item: (len(item[1]), -item[1][0]))
    if len(local_calls) >= MIN_LOCAL_CALLS and name == "Haas":
        return dialects.FileDialect(
            name,
            tr("{count} local subroutine calls M97 P<n>, the first", count=len(local_calls)),
            local_calls[0],
        )
    if len(lines) < MIN_DIALECT_BLOCKS:
        return None
    return dialects.FileDialect(
        name, tr("{count} blocks in its forms, the first", count=len(lines)), lines[0]
    )


def foreign_dialect(doc: Document) -> dialects.FileDialect | None:
    """The other control whose program the document is, from the marks only its programs
    have; None for a FANUC program."""
    marks = [dialects.FileDialect(name, mark, line) for line, (name, mark) in file_marks(doc)]
    return dialects.strongest(marks)


# What a block of another control's program gives when FANUC cannot read it: these findings
# of one block become one MB002 naming the file's dialect.
FOLDED_CODES = frozenset({"MB001", "MB002", "MB003", "MB004", "MB005", "MB008"})
# FANUC's conventions of writing that another control's program need not follow (lower case),
# and FANUC's map of variable numbers (MB302-MB304): another control numbers its own
# (EdingCNC's #4337 is a setting, not a FANUC system variable).
FANUC_STYLE_CODES = frozenset({"MB006", "MB302", "MB303", "MB304"})
# How a FANUC control reads a file in (MB014: the '%' that ends its data), said of FANUC
# programs only: another control's file has its own marks ('%2000' heads a CNC Simulator
# program), and FANUC runs none of it anyway.
FANUC_RECORD_CODES = frozenset({"MB014"})


def in_foreign_file(
    findings: tuple[LineFinding, ...], parsed: ParsedLine, foreign: dialects.FileDialect
) -> tuple[LineFinding, ...]:
    """A block's line findings in a file of the ``foreign`` dialect: without FANUC's
    conventions of writing, and those of a block FANUC rejects folded into one MB002 that
    names the dialect, after the others."""
    folded = [f for f in findings if f.code in FOLDED_CODES]
    kept = [f for f in findings if f.code not in FANUC_STYLE_CODES and f.code not in FOLDED_CODES]
    if folded:
        first = folded[0]
        named = next((f for f in folded if _named_dialect(f) == foreign.name), None)
        # A form of the file's own dialect says what it is; otherwise what FANUC rejects.
        message = named.message if named else _foreign_message(foreign, parsed, first)
        kept.append(LineFinding("MB002", message, first.start, first.end))
    return tuple(kept)


def _foreign_message(foreign: dialects.FileDialect, parsed: ParsedLine, first: LineFinding) -> str:
    """The message of a rejected block in a file of another control's dialect."""
    problem = parsed.problem
    if problem is not None and problem.dialect == foreign.name:
        return tr("{dialect}: {message}", dialect=foreign.name, message=problem.message)
    if first.code == "MB005":
        what = tr("';' ends the block on FANUC, and the comment after it is read as program text")
    elif problem is not None and problem.dialect in (None, dialects.NOT_FANUC):
        what = tr("FANUC rejects this block ({problem})", problem=problem.message)
    else:  # a form of yet another dialect, or a Haas-looking statement: this file's own
        what = tr("FANUC rejects this block")
    return tr(
        "{dialect} program ({mark} on line {line}): {what}",
        dialect=foreign.name,
        mark=foreign.mark,
        line=foreign.line + 1,
        what=what,
    )


def fold_foreign_file(
    blocks: list[tuple[int, ParsedLine, tuple[LineFinding, ...]]],
    foreign: dialects.FileDialect,
    first_line: int,
    first_text: str,
) -> tuple[list[tuple[int, ParsedLine, tuple[LineFinding, ...]]], Diagnostic | None]:
    """The line findings of a file written for another control: the blocks FANUC rejects give
    one MB002 on the file's first line (``first_line``: the first but an empty line or a
    tape mark), which names the control and the
    evidence and lists them as related places, in place of one a block. The other findings of
    each block stay (see :func:`in_foreign_file`)."""
    kept_blocks: list[tuple[int, ParsedLine, tuple[LineFinding, ...]]] = []
    rejected: list[Related] = []
    for line, parsed, findings in blocks:
        kept = in_foreign_file(findings, parsed, foreign)
        for f in kept:
            if f.code == "MB002":
                rejected.append(Related(line, f.start, f.end, f.message))
        kept = tuple(f for f in kept if f.code != "MB002")
        if kept:
            kept_blocks.append((line, parsed, kept))
    if not rejected:
        return kept_blocks, None
    shown = ", ".join(str(r.line + 1) for r in rejected[:8])
    if len(rejected) > 8:
        shown = tr("{lines} and {more} more", lines=shown, more=len(rejected) - 8)
    where = tr_n("line {lines}", "lines {lines}", len(rejected), lines=shown)
    if foreign.name == UNRECOGNISED:
        message = tr(
            "not a FANUC program: {mark} are in forms FANUC rejects ({where}), in the dialect of "
            "another control, not recognised; not reported one by one",
            mark=foreign.mark,
            where=where,
        )
    else:
        message = tr_n(
            "a program written for {dialect} ({mark} on line {line}): FANUC cannot run it as "
            "written; {count} of its blocks is in forms FANUC rejects ({where}), not reported "
            "one by one",
            "a program written for {dialect} ({mark} on line {line}): FANUC cannot run it as "
            "written; {count} of its blocks are in forms FANUC rejects ({where}), not reported "
            "one by one",
            len(rejected),
            dialect=foreign.name,
            mark=foreign.mark,
            line=foreign.line + 1,
            where=where,
        )
    end = len(first_text.rstrip())
    # Of a control named by its marks, a statement about the file, not a mistake in it: it
    # may be right for that control. Of one not recognised, the file may be FANUC's, broken.
    severity = Severity.ERROR if foreign.name == UNRECOGNISED else Severity.INFORMATION
    return kept_blocks, make(
        MB002, message, first_line, 0, end, related=rejected, severity=severity
    )


# The codes of the verdicts of a run (the evaluator's rules), as strings compare.
RUN_VERDICTS = "MB501"


def past_the_stop(diag: Diagnostic, stop_line: int | None) -> bool:
    """Whether ``diag`` is a verdict of the run (MB501-MB999) past the first block FANUC
    rejects in another control's file: FANUC stops there with an alarm, and the run, which
    goes on without the blocks it cannot read (their F, their variables), is of no control."""
    return stop_line is not None and diag.line > stop_line and diag.code >= RUN_VERDICTS
