"""Which machine a program is written for, a lathe or a mill, read from its own codes.

Several G codes mean one thing on a lathe and another on a mill (G code system A of the
0i-TF against the 0i-MF): ``G90`` is the turning cycle on a lathe and absolute programming on a
mill, ``G92`` the threading cycle or the coordinate system setting, ``G91`` incremental
programming on a mill and nothing on a system A lathe, ``U``/``W`` the lathe's incremental
axes. A program read as the wrong machine gets wrong verdicts, so when the controller setting
does not say the machine (controller ``0i-F``), each document is read as the machine its own
blocks show, from marks only one machine's programs have:

- a mill's: ``M06`` tool change, ``G43``/``G44`` with ``H`` (tool length compensation),
  ``G91``, a ``Y`` move, the drilling cycles a system A lathe does not have (``G81``,
  ``G82``, ``G86``; ``G73`` with ``Z``), ``G90`` with no axis or with a move code (on a lathe
  it is a cycle that needs its X and Z), ``G41``/``G42`` with ``D``; with lathes of G code
  system B or C (setting machine.gCodeSystem), ``G90`` and ``G91`` are no mill's marks;
- a lathe's: ``G96`` constant surface speed, ``G50`` with words (spindle clamp, coordinate
  system), ``U``/``W`` words, ``G70``-``G73`` with ``P`` and ``Q``, the
  two-block ``G76``'s first block (no axis), ``G32``, ``G92`` with ``F``, a four-digit ``T``
  (tool and offset, ``T0101``), ``G77``-``G79`` with an axis (the cycles of G code systems B
  and C; no G code of a mill).

Sources: FANUC Series 0i-F Plus Operator's Manual, common to lathe and machining centre
(B-64694EN), "G code list" of the lathe (system A) and of the machining centre; "Tool length
compensation", "Tool function (T function)". A mill-turn program shows both: it gets no
verdict that depends on the machine (``MachineGuess.kind`` None), as does a program that shows
neither (a macro of arithmetic alone).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from collections.abc import Set as AbstractSet
from dataclasses import dataclass, replace
from types import MappingProxyType

from ..config import SYSTEM_A, Config
from ..database import Derived
from ..line_maps import LineMap
from ..syntax.marks import constant_value
from ..syntax.parser import statements_of
from ..syntax.tree import Document, NcStatement, ParsedLine, PlainNc
from ..translation import tr, tr_n
from .index import ProgramIndex
from .knowledge import G_CODES

LATHE = "lathe"
MILL = "mill"
# The machines in a sentence, in the user's language.
_MACHINE_WORD: Mapping[str, str] = MappingProxyType({LATHE: tr("lathe"), MILL: tr("mill")})

# Words that make a block a call or a setting whose letters are arguments or data, not axes.
_NOT_AXES_G = frozenset({4.0, 10.0, 65.0, 66.0, 66.1})
_NOT_AXES_M = frozenset({98.0, 99.0})
_MOVES = frozenset({0.0, 1.0, 2.0, 3.0})
# Kinds of marks one machine must have more than the other when both show.
MARGIN = 2
# A mill's marks in G code system A, which a lathe of system B or C has too.
G91_MARK = tr("G91 (incremental programming)")
G90_MARK = tr("G90 without a turning cycle's X and Z (absolute programming)")
_SYSTEM_A_ONLY = frozenset({G91_MARK, G90_MARK})


@dataclass(frozen=True, slots=True)
class Mark:
    """One sign of a machine: which (``LATHE`` or ``MILL``), what it is, where (0-based)."""

    machine: str
    what: str
    line: int


@dataclass(frozen=True, slots=True)
class MachineGuess:
    """What a document's codes say of its machine: ``kind`` ``LATHE``, ``MILL`` or None
    (neither shown, or both), with the first marks of each machine found."""

    kind: str | None
    marks: tuple[Mark, ...]

    @property
    def reason(self) -> str:
        """Why, in a sentence's tail: "G43 H (tool length compensation) on line 12"."""
        if not self.marks:
            return tr("no code of the program is a lathe's or a mill's alone")
        lathe = [m for m in self.marks if m.machine == LATHE]
        mill = [m for m in self.marks if m.machine == MILL]
        if self.kind is None:
            return tr(
                "it has marks of both: {lathe_mark} on line {lathe_line} (a lathe's) and "
                "{mill_mark} on line {mill_line} (a mill's)",
                lathe_mark=lathe[0].what,
                lathe_line=lathe[0].line + 1,
                mill_mark=mill[0].what,
                mill_line=mill[0].line + 1,
            )
        own, other = (lathe, mill) if self.kind == LATHE else (mill, lathe)
        text = tr("{mark} on line {line}", mark=own[0].what, line=own[0].line + 1)
        if len(own) > 1:
            text = tr_n(
                "{marks} and {count} more kind of mark",
                "{marks} and {count} more kinds of mark",
                len(own) - 1,
                marks=text,
            )
        if other:
            text = tr(
                "{marks}; a {machine}'s mark, {mark} on line {line}, is taken for an option of "
                "the machine",
                marks=text,
                machine=_MACHINE_WORD[other[0].machine],
                mark=other[0].what,
                line=other[0].line + 1,
            )
        return text


def _words(parsed: ParsedLine) -> list[tuple[str, float | None, str]]:
    """The NC words of a line: address, constant value (None: computed), text as written; of a
    block with brackets, the value of G and M words only and the text of T words only (what
    the marks read)."""
    found: list[tuple[str, float | None, str]] = []
    if type(parsed.statement) is PlainNc:
        for letter, number in parsed.statement.pairs():
            try:
                found.append((letter.upper(), float(number), number))
            except ValueError:
                continue
        return found
    text = parsed.text
    for statement in statements_of(parsed.statement):
        if isinstance(statement, NcStatement):
            for word in statement.words:
                address = word.address
                if address == "G" or address == "M":
                    found.append((address, constant_value(word.value), ""))
                elif address == "T":
                    written = text[word.span.start + 1 : word.span.end].strip()
                    found.append((address, constant_value(word.value), written))
                else:
                    found.append((address, None, ""))
    return found


_ADDRESSES = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZ")
_FOUR_DIGIT_T = re.compile(r"T(\d{4})(?![\d.])")


def _four_digit_t(words_text: str) -> bool:
    """Whether upper-case NC words hold a T of four digits, a tool and offset number."""
    return any(t[:2] != "00" for t in _FOUR_DIGIT_T.findall(words_text))


# The marks a line may show, made once: a line's marks are kept for every line.
_M06_MARK = (MILL, tr("M06 (tool change)"))
_TOOL_LENGTH_MARK = (MILL, tr("G43/G44 H (tool length compensation)"))
_Y_MARK = (MILL, tr("a Y axis word"))
_DRILLING_MARK = (MILL, tr("a drilling cycle a lathe does not have (G81, G82, G86, G73 Z)"))
_CUTTER_COMPENSATION_MARK = (MILL, tr("G41/G42 D (cutter compensation with an offset number)"))
_G96_MARK = (LATHE, tr("G96 (constant surface speed)"))
_G50_MARK = (LATHE, tr("G50 with S, X or Z (spindle clamp, coordinate system)"))
_UW_MARK = (LATHE, tr("a U or W word (incremental X or Z)"))
_PROFILE_CYCLE_MARK = (LATHE, tr("a multiple repetitive cycle (G70-G73 with P and Q)"))
_G76_FIRST_MARK = (LATHE, tr("G76's first block (threading cycle parameters)"))
_G32_MARK = (LATHE, tr("G32 (threading)"))
_G77_TO_G79_MARK = (
    LATHE,
    tr("G77, G78 or G79 with X or Z (a lathe cycle of G code system B or C)"),
)
_G92_F_MARK = (LATHE, tr("G92 with F (threading cycle)"))
_FOUR_DIGIT_T_MARK = (LATHE, tr("a four-digit T (tool and offset number)"))


def _line_marks(parsed: ParsedLine) -> tuple[tuple[str, str], ...] | None:
    """The machine marks of one line: (machine, what) pairs; None for most lines."""
    statement = parsed.statement
    if statement is None or parsed.problem is not None:
        return None
    if type(statement) is PlainNc:
        # Most blocks (CAM output): the G and M codes the parser read, the letters of the text.
        words_text = statement.text().upper()
        codes = statement.codes
        if _MARKING_CODES.isdisjoint(codes):  # nearly all: marked by their words alone
            return _word_marks(words_text, "T" in words_text and _four_digit_t(words_text))
        letters: frozenset[str] | set[str] = _ADDRESSES.intersection(words_text)
        g = {v for a, v in codes if a == "G"}
        m = {v for a, v in codes if a == "M"}
        four_digit_t = "T" in letters and _four_digit_t(words_text)
    else:
        words = _words(parsed)
        if not words:
            return None
        g = set()
        m = set()
        letters = set()
        four_digit_t = False
        for a, v, w in words:  # one loop: most lines have a few words
            letters.add(a)
            if v is None:
                continue
            if a == "G":
                g.add(v)
            elif a == "M":
                m.add(v)
            elif a == "T" and len(w) == 4 and w.isdigit() and w[:2] != "00":
                four_digit_t = True
    if not g.isdisjoint(_NOT_AXES_G) or not m.isdisjoint(_NOT_AXES_M):
        return None  # a call's letters are its arguments; G10's, data; G04's U, a dwell
    if g.isdisjoint(_MARK_G) and 6.0 not in m:  # most blocks: moves, marked by words alone
        return _word_marks(letters, four_digit_t)
    marks: list[tuple[str, str]] = []
    if 6.0 in m:
        marks.append(_M06_MARK)
    if not g.isdisjoint({43.0, 44.0}) and "H" in letters:
        marks.append(_TOOL_LENGTH_MARK)
    if 91.0 in g:
        marks.append((MILL, G91_MARK))
    if "Y" in letters:
        marks.append(_Y_MARK)
    if not g.isdisjoint({81.0, 82.0, 86.0}) or (73.0 in g and "Z" in letters):
        marks.append(_DRILLING_MARK)
    if 90.0 in g and (not g.isdisjoint(_MOVES) or letters.isdisjoint("XZUW")):
        marks.append((MILL, G90_MARK))
    if not g.isdisjoint({41.0, 42.0}) and "D" in letters:
        marks.append(_CUTTER_COMPENSATION_MARK)
    if 96.0 in g:
        marks.append(_G96_MARK)
    if 50.0 in g and not letters.isdisjoint("SXZ"):
        marks.append(_G50_MARK)
    if not letters.isdisjoint("UW"):
        marks.append(_UW_MARK)
    # With P and Q only: a bare G70/G71 is inch/metric input on other controls (ISO dialects,
    # Heidenhain, Fagor); the cycles' first blocks have U or W, marks of their own.
    if not g.isdisjoint({70.0, 71.0, 72.0, 73.0}) and {"P", "Q"} <= letters:
        marks.append(_PROFILE_CYCLE_MARK)
    if 76.0 in g and letters.isdisjoint("XYZ"):
        marks.append(_G76_FIRST_MARK)
    if 32.0 in g:
        marks.append(_G32_MARK)
    if not g.isdisjoint({77.0, 78.0, 79.0}) and not letters.isdisjoint("XZUW"):
        marks.append(_G77_TO_G79_MARK)
    if 92.0 in g and "F" in letters:
        marks.append(_G92_F_MARK)
    if 6.0 not in m and four_digit_t:
        marks.append(_FOUR_DIGIT_T_MARK)
    return tuple(marks) or None


# The G codes that are marks, or make a block's words marks (U of G71 is the lathe's anyway).
_MARK_G = frozenset(
    {32.0, 41.0, 42.0, 43.0, 44.0, 50.0, 70.0, 71.0, 72.0, 73.0, 76.0, 81.0, 82.0, 86.0, 90.0}
    | {77.0, 78.0, 79.0, 91.0, 92.0, 96.0}
)
# The (address, value) codes of a plain block that make its marks more than its words': the
# codes that mark, and those whose block's letters are no axes.
_MARKING_CODES = frozenset(
    [("G", g) for g in _MARK_G | _NOT_AXES_G] + [("M", m) for m in {6.0} | _NOT_AXES_M]
)
_Y = ((MILL, tr("a Y axis word")),)
_UW = ((LATHE, tr("a U or W word (incremental X or Z)")),)
_T = ((LATHE, tr("a four-digit T (tool and offset number)")),)


def _word_marks(
    letters: AbstractSet[str] | str, four_digit_t: bool
) -> tuple[tuple[str, str], ...] | None:
    """The marks of a block without a G or M code that is one: its Y, U/W and T words
    (``letters``: the block's addresses, or its words' text in upper case)."""
    marks = (
        (_Y if "Y" in letters else ())
        + (_UW if "U" in letters or "W" in letters else ())
        + (_T if four_digit_t else ())
    )
    return marks or None


# The lines with a mark: after an edit only the changed lines are looked at again. A mark may
# stand in a bare line (a Y word, G91), so every line is looked at.
_marks_of: LineMap[tuple[tuple[str, str], ...]] = LineMap(_line_marks, every_line=True)

# The G codes that mean one thing on a lathe (system A) and another on a mill.
_TWO_MEANINGS = frozenset(
    float(code[1:]) for code, info in G_CODES.items() if not info.same_on_both
)


def _line_reads_differ(parsed: ParsedLine) -> bool:
    """Whether a lathe reads the line otherwise than a mill: a G code of two meanings, a U or
    W word (a lathe's incremental axes)."""
    if parsed.statement is None:
        return False
    return any((a == "G" and v in _TWO_MEANINGS) or a in ("U", "W") for a, v, _ in _words(parsed))


# The lines a lathe and a mill read otherwise: after an edit only the changed lines are looked
# at again (a bare line may be one: U, W, G90, G91).
_reads_differ_at: LineMap[bool] = LineMap(_line_reads_differ, every_line=True)


def readings_differ(doc: Document) -> bool:
    """Whether a lathe and a mill read any block of ``doc`` otherwise."""
    return len(_reads_differ_at(doc)) > 0


def guess_machine(
    doc: Document, first: int = 0, end: int | None = None, system: str = SYSTEM_A
) -> MachineGuess:
    """The machine ``doc``'s blocks (lines ``first`` to ``end``, exclusive) show: the first
    mark of each kind, and the verdict. With lathes of G code ``system`` B or C, G90 and G91
    are no mill's marks."""
    seen: dict[tuple[str, str], int] = {}
    found = _marks_of(doc)
    at = found.between(first, len(doc.blocks) if end is None else end)
    lines, values = found.lines[at.start : at.stop], found.values[at.start : at.stop]
    # Most marked lines repeat a few sets of marks (a Y word on every line of a mill's
    # program): each distinct one, at its first line, found in C.
    for on_line in dict.fromkeys(values):
        line = lines[values.index(on_line)]
        for mark in on_line:
            if system != SYSTEM_A and mark[1] in _SYSTEM_A_ONLY:
                continue
            if mark not in seen or line < seen[mark]:
                seen[mark] = line
    marks = tuple(
        sorted(
            (Mark(k[0], k[1], line) for k, line in seen.items()),
            key=lambda m: (m.line, m.machine, m.what),
        )
    )
    lathe = sum(m.machine == LATHE for m in marks)
    mill = len(marks) - lathe
    # A lathe with a Y axis or a Swiss-type's M06, a mill with a four-digit T: one mark of the
    # other machine among several of one is the machine's option, not a mill-turn program.
    if lathe and mill and abs(lathe - mill) < MARGIN:
        kind = None
    elif lathe or mill:
        kind = LATHE if lathe > mill else MILL
    else:
        kind = None
    return MachineGuess(kind, marks)


def mill_reading(config: Config) -> Config:
    """The mill's reading of a document whose machine is not known (``config``'s is the
    lathe's): what both find is reported."""
    return replace(config, controller="0i-MF", machine_known=True)


def machine_text(config: Config) -> str:
    """Which machine an analysis read the document as, and why: a sentence (and the lathe's
    G code system when it is not A)."""
    text = _machine_text(config)
    if config.g_code_system != SYSTEM_A and (config.is_lathe or not config.machine_known):
        return tr(
            "{machine} A lathe's G codes are read in G code system {system}.",
            machine=text,
            system=config.g_code_system,
        )
    return text


def _machine_text(config: Config) -> str:
    if config.machine_note and not config.machine_known:
        return tr(
            "Machine: {note}. Read as a lathe (0i-TF), with only the verdicts a mill's reading "
            "gives too; set fanuc-macro.controller (--controller) to say which.",
            note=config.machine_note,
        )
    if config.machine_note:
        return tr("Machine: {note}.", note=config.machine_note)
    if config.is_lathe:
        return tr(
            "Machine: a lathe, as the controller setting {controller} says.",
            controller=config.controller,
        )
    return tr(
        "Machine: a mill, as the controller setting {controller} says.",
        controller=config.controller,
    )


def _by_program(
    config: Config, doc: Document, index: ProgramIndex | None, guess: MachineGuess
) -> Config | None:
    """``config`` for a file of several programs each of which shows one machine, some a
    lathe and some a mill (a folder of programs pasted into one file): each runs as its own.
    The file's features (hover, completion) read it as its first program's machine."""
    if index is None or len(index.programs) < 2 or len({m.machine for m in guess.marks}) < 2:
        return None
    system = config.g_code_system
    each = [(p, guess_machine(doc, p.first_line, p.end_line, system)) for p in index.programs]
    if any(g.kind is None and g.marks for _, g in each):
        return None  # a program of both machines' marks: a mill-turn program
    decided = [(p, g) for p, g in each if g.kind is not None]
    if len({g.kind for _, g in decided}) < 2:
        return None
    lathe = [p.display_name for p, g in decided if g.kind == LATHE]
    mill = [p.display_name for p, g in decided if g.kind == MILL]
    first = decided[0][1]
    controller = "0i-TF" if first.kind == LATHE else "0i-MF"
    note = tr(
        "a lathe for {lathe_programs} and a mill for {mill_programs} (0i-F read as a 0i-TF or "
        "a 0i-MF for each program), from their codes",
        lathe_programs=", ".join(lathe),
        mill_programs=", ".join(mill),
    )
    machines = tuple((doc.uri, p.first_line, g.kind == LATHE) for p, g in decided)
    return replace(config, controller=controller, machine_note=note, program_machines=machines)


# The whole document's guess, kept while the document is the same version: the analysis and
# the workspace's cache of facts both ask for it.
_document_guess: Derived[tuple[Document, str], MachineGuess] = Derived(
    "machine_kind.document_guess",
    lambda arg: arg,
    lambda arg: (guess_machine(arg[0], system=arg[1]), True),
)


def machine_config(config: Config, doc: Document, index: ProgramIndex | None = None) -> Config:
    """``config`` for ``doc``: with controller 0i-F, that of a 0i-TF or a 0i-MF as the
    document's codes show (:func:`guess_machine`; with its ``index``, for each program when
    its programs show different machines), or a lathe's reading without the verdicts that
    depend on the machine when they show neither; any other ``config`` as it is."""
    if not config.machine_by_program:
        return config
    guess = _document_guess(doc.uri, (doc, config.g_code_system))
    each = _by_program(config, doc, index, guess)
    if each is not None:
        return each
    if guess.kind is None:
        note = tr("not known, {reason}", reason=guess.reason)
        return replace(config, controller="0i-TF", machine_note=note, machine_known=False)
    controller = "0i-TF" if guess.kind == LATHE else "0i-MF"
    note = tr(
        "a {machine} (0i-F read as {controller}), from its codes: {reason}",
        machine=_MACHINE_WORD[guess.kind],
        controller=controller,
        reason=guess.reason,
    )
    return replace(config, controller=controller, machine_note=note)


__all__ = (
    "LATHE",
    "MILL",
    "MachineGuess",
    "Mark",
    "guess_machine",
    "machine_config",
    "machine_text",
    "readings_differ",
)


def callers_machine(
    config: Config, callers: Sequence[tuple[Document, ProgramIndex]]
) -> Config | None:
    """``config`` (a document whose own codes show no machine) as the machine of the
    documents whose programs call it, when they show one and the same: a subprogram runs on
    its caller's machine. None when there is none, or they differ."""
    if config.machine_known or not config.machine_note or not callers:
        return None
    kinds: dict[str, list[str]] = {}
    for doc, index in callers:
        guess = _document_guess(doc.uri, (doc, config.g_code_system))
        if guess.kind is not None:
            names = [p.display_name for p in index.programs]
            kinds.setdefault(guess.kind, []).extend(names[:1])
    if len(kinds) != 1:
        return None
    kind, names = next(iter(kinds.items()))
    controller = "0i-TF" if kind == LATHE else "0i-MF"
    shown = ", ".join(names[:3])
    if len(names) > 3:
        shown = tr("{programs} and {more} more", programs=shown, more=len(names) - 3)
    note = tr(
        "a {machine} (0i-F read as {controller}), as the programs that call it show "
        "({programs}); its own codes show neither machine",
        machine=_MACHINE_WORD[kind],
        controller=controller,
        programs=shown,
    )
    return replace(config, controller=controller, machine_note=note, machine_known=True)
