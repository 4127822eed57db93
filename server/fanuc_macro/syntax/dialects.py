"""Forms of other controls' dialects that a FANUC control rejects, recognised by their look.

When a block does not parse, the checker says which dialect it comes from, when it can tell,
rather than only "unexpected character". Two levels:

* a block: :func:`recognise` looks at the rejected block alone (``S1=500`` is Citizen's
  spindle selection wherever it stands, ``VC1=0`` Okuma's, ``H1=0.216`` a wire EDM's register);
  a form FANUC rejects that no known dialect has is "not FANUC (dialect not recognised)";
* a file: :func:`file_dialect` finds the marks that only another control's programs carry
  (Syntec's ``%@MACRO`` header, Siemens' ``PROC``/``DEF``, LinuxCNC's ``o<name> sub``, DDCS's
  ``IF #1==0 GOTO`` without brackets). In such a file every rejected block is that dialect's,
  whatever it looks like alone: a block ``ELSE`` is Siemens' in a Siemens file, not Haas's.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..lazy_regex import LazyPattern
from ..translation import Text, tr

SYNTEC = "LNC/Syntec"
SIEMENS = "Siemens Sinumerik"
LINUXCNC = "LinuxCNC"
DDCS = "DDCS"
OKUMA = "Okuma OSP"
WIRE_EDM = tr("wire EDM")
PHILIPS = "Philips (CNC 432 / System 3000)"
MITSUBISHI = "Mitsubishi/Citizen"
CNC_SIMULATOR = tr("CNC Simulator Pro")  # a product's name: said as it is
# A form FANUC rejects that no dialect this checker knows has (C comparisons, 'Q1=12'): said so,
# rather than pinned on a control it may not come from.
NOT_FANUC = tr("not FANUC (dialect not recognised)")
PLAIN = ""  # not a dialect's form: a plain syntax error (MB001), said in FANUC's terms


@dataclass(frozen=True, slots=True)
class Dialect:
    name: str
    message: str


# Patterns on the block's code (comments cut out) and, for forms whose parentheses the block
# reader takes for comments, on the raw line. Most specific first: the first match names it.
_RAW_PATTERNS: tuple[tuple[LazyPattern, str, Text], ...] = (
    (
        LazyPattern(r"^\s*%\s*@MACRO\b", re.I),
        SYNTEC,
        tr("'%@MACRO' opens a Syntec/LNC macro file (Pascal-like statements), not a FANUC program"),
    ),
    (
        LazyPattern(r"^\s*(N\d+\s*)?(IF|WHILE)\s*\(.*\)\s*(THEN|DO)\b", re.I),
        SYNTEC,
        tr(
            "'IF (...) THEN ... END_IF' / 'WHILE (...) DO ... END_WHILE' are Syntec/LNC statements;"
            " FANUC writes IF [...] GOTO n and WHILE [...] DOm ... ENDm"
        ),
    ),
    (
        LazyPattern(r"^\s*(N\d+\s*)?(WAIT|ALARM|SLEEP|MSG)\s*\(", re.I),
        SYNTEC,
        tr(
            "a Syntec/LNC function call such as WAIT() or ALARM(n); FANUC raises an alarm with "
            "#3000=n (MESSAGE)"
        ),
    ),
    (
        LazyPattern(r"^\s*(N\d+\s*)?(IF|WHILE)\s*#\d+\s*(==|!=|<=|>=|<|>)", re.I),
        DDCS,
        tr(
            "'IF #n==0 GOTO' without brackets, with C comparisons, is DDCS syntax; FANUC writes "
            "IF [#n EQ 0] GOTO"
        ),
    ),
)

# Okuma OSP user task (ICAM's Okuma pre-processor syntax page, help.icam.com, [S]: common
# variables VC1..., 'GOTO NLBL', 'IF [VC1 LT 5] N10' branching without GOTO, CALL / RTS /
# MODIN / MODOUT; VS variables as the issue names them, unverified against an Okuma manual).
_OKUMA_VARIABLE = LazyPattern(r"(?<![A-Z#])V[CS]\d+", re.I)
_OKUMA_SEQUENCE_NAME = LazyPattern(r"^\s*(/\d?\s*)?N[A-Z][A-Z0-9]*(?![A-Z0-9])", re.I)

_PATTERNS: tuple[tuple[LazyPattern, str, Text], ...] = (
    (
        _OKUMA_VARIABLE,
        OKUMA,
        tr(
            "'{found_text}' is an Okuma OSP (user task) variable; FANUC's variables are "
            "numbered #n "
            "(#100-#199, #500-#999 for commons)"
        ),
    ),
    (
        LazyPattern(r"\bGOTO\s*N[A-Z][A-Z0-9]*", re.I),
        OKUMA,
        tr(
            "'{found_text}' jumps to an Okuma OSP sequence name; FANUC jumps to a number: "
            "GOTO n to Nn"
        ),
    ),
    (
        # The sequence name ends the block: no GOTO or THEN after the condition.
        LazyPattern(r"^\s*(N\w+\s+)?IF\s*\[(?!.*\b(GOTO|THEN))[^;]*\]\s*N\w+\s*;?\s*$", re.I),
        OKUMA,
        tr(
            "'IF [...] NLOOP' branches to a sequence name the Okuma OSP way; FANUC writes "
            "IF [...] GOTO n"
        ),
    ),
    (
        LazyPattern(r"^\s*(N\w+\s+)?(CALL\s+O\w+|RTS\b|MODIN\b|MODOUT\b)", re.I),
        OKUMA,
        tr(
            "CALL / RTS / MODIN / MODOUT are Okuma OSP subprogram statements; FANUC calls with "
            "M98 P<program> or G65 P<program> and returns with M99"
        ),
    ),
    (
        _OKUMA_SEQUENCE_NAME,
        OKUMA,
        tr("'{found_text}' is an Okuma OSP sequence name; a FANUC sequence number is N and digits"),
    ),
    (
        # Sodick, Mitsubishi and other wire EDM controls set offset and condition registers in
        # the program ('H000=+00000000', 'H1=0.216', 'E001='): unverified per maker.
        LazyPattern(r"^\s*(N\d+\s*)?[EH]\d+\s*=", re.I),
        WIRE_EDM,
        tr(
            "'{found_text}' sets a wire EDM's offset or machining-condition register; "
            "FANUC sets an "
            "offset with G10 or a #variable (#2001-, #10001-)"
        ),
    ),
    (
        LazyPattern(r"#<[^>\n]*>"),
        LINUXCNC,
        tr(
            "named parameter '#<...>' is LinuxCNC syntax; FANUC variables are numbered "
            "(#1, #100, ...)"
        ),
    ),
    (
        LazyPattern(
            r"^\s*o\s*(<[^>]*>|\d+)\s*(sub|endsub|call|if|elseif|else|endif|while|endwhile|do"
            r"|repeat|endrepeat|return|break|continue)\b",
            re.I,
        ),
        LINUXCNC,
        tr("'o<name> sub/call/if/while' (O-word) is LinuxCNC syntax, not FANUC"),
    ),
    (
        LazyPattern(r"\bEND_(IF|WHILE|FOR|REPEAT|CASE)\b", re.I),
        SYNTEC,
        tr(
            "'END_IF' / 'END_WHILE' close Syntec/LNC statements; FANUC has IF [...] GOTO n and "
            "WHILE [...] DOm ... ENDm"
        ),
    ),
    (
        LazyPattern(r":="),
        SYNTEC,
        tr("':=' assignment is Syntec/LNC syntax; FANUC assigns with '='"),
    ),
    (
        LazyPattern(r"^\s*(N\d+\s*)?(PROC|DEF|EXTERN)\s+[A-Z_]", re.I),
        SIEMENS,
        tr("'PROC' / 'DEF' declarations are Siemens Sinumerik (840D) syntax, not FANUC"),
    ),
    (
        LazyPattern(
            r"\bGOTO[FBC]\b|\bEND(FOR|WHILE|LOOP)\b|\bSTOPRE\b|\$(AA|AC|A|P|TC|MC|MN|SC|SN)_\w+\s*\[",
            re.I,
        ),
        SIEMENS,
        tr(
            "GOTOF/GOTOB labels, FOR/ENDFOR, STOPRE and $A_... system variables are Siemens "
            "Sinumerik syntax, not FANUC"
        ),
    ),
    (
        LazyPattern(r"^\s*(N\d+\s*)?R\d+\s*=", re.I),
        SIEMENS,
        tr(
            "'R20=...' arithmetic parameters are Siemens Sinumerik syntax; FANUC's variables are #n"
        ),
    ),
    (
        LazyPattern(r"^\s*\$\d"),
        MITSUBISHI,
        tr("'$n' path selection is Mitsubishi/Citizen syntax, not FANUC"),
    ),
    (
        LazyPattern(r"^\s*!\s*\d*\s*L\d", re.I),
        MITSUBISHI,
        tr("'!L' path wait is Mitsubishi/Citizen syntax, not FANUC"),
    ),
    (
        # An S word of its own ('M3 S1=500'), not the end of a name ('VS1=', 'POS1=').
        LazyPattern(r"(?<![A-Z#])S\d+\s*=", re.I),
        MITSUBISHI,
        tr("'S1=...' style spindle selection is Mitsubishi/Citizen syntax, not FANUC"),
    ),
    (
        LazyPattern(r"^\s*N\d+\s+@\d{3}\s+[RK]", re.I),
        SIEMENS,
        tr(
            "'@100 K...' jumps and '@1xx R... K...' tests are old Sinumerik (810/820) codes, "
            "not FANUC"
        ),
    ),
    (LazyPattern(r"@\d+"), SYNTEC, tr("'@n' variables are LNC/Syntec syntax, not FANUC")),
)

# Forms more than one control writes, or none.
_WEAK_PATTERNS: tuple[tuple[LazyPattern, str, Text], ...] = (
    (
        LazyPattern(r"//"),
        PLAIN,
        tr(
            "'//' does not start a comment on FANUC (Syntec/LNC and DDCS write comments so): FANUC "
            "comments are '( ... )'"
        ),
    ),
    (
        LazyPattern(r"<=|>=|==|!=|&&|\|\||<(?!>)|(?<!<)>"),
        NOT_FANUC,
        tr("FANUC compares with EQ NE GT GE LT LE only ('<', '>=', '==' ... give alarm PS0114)"),
    ),
    (
        LazyPattern(r"\b(LTE|GTE|NEQ)\b", re.I),
        NOT_FANUC,
        tr("FANUC compares with EQ NE GT GE LT LE only ('LTE', 'GTE' give alarm PS0114)"),
    ),
    (
        # 'Q1=12', 'POS=5', 'TEMP=10': a value assigned to a word or a name.
        LazyPattern(r"^\s*(N\d+\s*)?[A-Z]\w*\s*=", re.I),
        NOT_FANUC,
        tr(
            "'{found_text}' assigns a value to an address or a name: FANUC assigns only to "
            "variables "
            "(#n = ...)"
        ),
    ),
)

_UNBRACKETED = LazyPattern(r"([A-MP-Z])\s*(-?#\d+(?:\.\d*)?\s*[-+*/]\s*[.#\d\[][^A-Z]*)", re.I)


def recognise(code: str, text: str | None = None) -> Dialect | None:
    """The dialect a rejected block is written in, when a form only that dialect has says so."""
    raw = code if text is None else text
    for pattern, name, message in _RAW_PATTERNS:
        if pattern.search(raw):
            return Dialect(name, message)
    for pattern, name, message in _PATTERNS:
        m = pattern.search(code)
        if m is not None:
            return Dialect(name, _with_found(message, m))
    return None


def _with_found(message: Text, m: re.Match[str]) -> Text:
    """The message with the text that matched in place of '{found_text}'."""
    if "found_text" not in message.template:
        return message
    return Text(message.template, {"found_text": m.group(0).strip().lstrip("/").strip()})


def recognise_weak(code: str) -> Dialect | None:
    """Forms several controls write (or none): C comparisons, '//', X#1+1. without brackets."""
    for pattern, name, message in _WEAK_PATTERNS:
        m = pattern.search(code)
        if m is not None:
            return Dialect(name, _with_found(message, m))
    m = _UNBRACKETED.search(code)
    if m is not None:
        letter, expression = m.group(1).upper(), m.group(2).strip()
        return Dialect(
            MITSUBISHI,
            tr(
                "an expression after an address must be in brackets on FANUC: write "
                "{letter}[{expression_text}], not {letter}{expression_text}",
                letter=letter,
                expression_text=expression,
            ),
        )
    return None


# ---- the dialect of a whole file -------------------------------------------------------------

# Marks that no FANUC program carries, each naming the control whose programs do. A file with
# one of them is that control's program: FANUC-looking blocks in it are checked as usual, and
# every block FANUC rejects is reported as that dialect's.
_FILE_MARKS: tuple[tuple[re.Pattern[str], str, Text], ...] = (
    (re.compile(r"^\s*%\s*@MACRO\b", re.I), SYNTEC, tr("'%@MACRO' header")),
    (re.compile(r"^\s*(N\d+\s*)?PROC\s+\w+", re.I), SIEMENS, tr("'PROC' declaration")),
    (
        re.compile(r"^\s*(N\d+\s*)?DEF\s+(REAL|INT|BOOL|STRING|CHAR|AXIS|FRAME)\b", re.I),
        SIEMENS,
        tr("'DEF' declaration"),
    ),
    (re.compile(r"^\s*(N\d+\s*)?R\d+\s*=", re.I), SIEMENS, tr("R-parameter assignment")),
    (
        re.compile(r"^\s*o\s*(<[^>]*>|\d+)\s*(sub|call)\b", re.I),
        LINUXCNC,
        tr("O-word subroutine"),
    ),
    (
        re.compile(r"^\s*(N\d+\s*)?(IF|WHILE)\s*#\d+\s*(==|!=|<=|>=|<|>)", re.I),
        DDCS,
        tr("IF/WHILE without brackets, with a C comparison"),
    ),
    (
        re.compile(r"^\s*(N\w+\s+)?V[CS]\d+\s*=", re.I),
        OKUMA,
        tr("VC/VS variable assignment"),
    ),
    (re.compile(r"\bGOTO\s*N[A-Z]", re.I), OKUMA, tr("GOTO to a sequence name")),
    (re.compile(r"^\s*(N\w+\s+)?CALL\s+O\w+", re.I), OKUMA, tr("CALL of a subprogram")),
    (re.compile(r"^\s*(N\d+\s*)?[EH]\d+\s*=", re.I), WIRE_EDM, tr("register setting")),
    # Philips CNC 432 / System 3000 files begin with "%PM", the program number an N9xxx block
    # after it (Philips CNC 432 programming manual; unverified beyond the files seen).
    (re.compile(r"^\s*%\s*PM\b", re.I), PHILIPS, tr("'%PM' header")),
    # CNC Simulator Pro's directives, a '$' word at the start of a line ('$Mill', '$AddRegPart
    # 1', '$UseMaterial "Wood"'); not Siemens' '$' system variables, which are read in
    # expressions or assigned (unverified beyond the simulator's files seen).
    (re.compile(r"^\s*\$[A-Za-z]+\b(?!\s*[\[=.])"), CNC_SIMULATOR, tr("'$' directive")),
)
# Strongest first: a Syntec file may hold R words, a LinuxCNC file comparisons.
_FILE_MARK_ORDER: Mapping[str, int] = MappingProxyType(
    {SYNTEC: 0, SIEMENS: 1, LINUXCNC: 2, DDCS: 3, OKUMA: 4, WIRE_EDM: 5, PHILIPS: 6}
    | {CNC_SIMULATOR: 7}
)


@dataclass(frozen=True, slots=True)
class FileDialect:
    name: str
    mark: str  # what in the file says so: "'%@MACRO' header"
    line: int  # 0-based line of the first such mark


def file_mark(text: str) -> tuple[str, str] | None:
    """(dialect, what) when this line is a mark of another control's program files."""
    for pattern, name, what in _FILE_MARKS:
        if pattern.search(text):
            return name, what
    return None


def strongest(marks: list[FileDialect]) -> FileDialect | None:
    """The dialect of a file from the marks found in it (the first of the strongest kind)."""
    if not marks:
        return None
    return min(marks, key=lambda m: (_FILE_MARK_ORDER.get(m.name, 9), m.line))
