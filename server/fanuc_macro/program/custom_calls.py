"""Blocks that call a program through a code the control's parameters set up (``M165`` calling
O9022, a T code calling O9000): what the settings make of a block's words.

The text alone cannot say which codes call: the parameters of the machine do, and the settings
name them (``machine.customCalls``, read by :func:`fanuc_macro.config.read_custom_calls`). So
these calls are not in the program index, which is of the text alone. The evaluator, the rules
and the editor's answers ask here, with the settings.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from ..config import CustomCallSetting
from ..line_maps import LineMap
from ..syntax.marks import constant_value
from ..syntax.tree import Document, IfNc, Mixed, NcStatement, ParsedLine, PlainNc, Statement, Word
from .index import Call
from .knowledge import M_CODES


def calling_word(
    nc: NcStatement, settings: Sequence[CustomCallSetting]
) -> tuple[Word, CustomCallSetting] | None:
    """The first word of ``nc`` that a setting makes call, with the setting."""
    if not settings:
        return None
    for word in nc.words:
        for setting in settings:
            if word.address != setting.address:
                continue
            if setting.number is None or constant_value(word.value) == setting.number:
                return word, setting
    return None


def nc_part(statement: Statement | None) -> NcStatement | None:
    """The NC words of a statement: a block, the NC part of a mixed one, a Haas ``IF`` block's."""
    if isinstance(statement, Mixed):
        return statement.nc
    if isinstance(statement, IfNc):
        return statement.words
    return statement if isinstance(statement, NcStatement) else None


def custom_call_of(
    line: int, statement: Statement | None, settings: Sequence[CustomCallSetting]
) -> Call | None:
    """The call a block makes through a custom code, as the index would hold a ``G65`` or
    ``M98``: its words but the code are the arguments of a macro call (the FANUC Custom Macro
    chapter, "Macro call using a G code / an M code": the same argument specification as G65;
    L the repeat count, unverified); a subprogram call takes none."""
    nc = nc_part(statement)
    if nc is None:
        return None
    found = calling_word(nc, settings)
    if found is None:
        return None
    word, setting = found
    arguments: tuple[Word, ...] = ()
    repeat: int | None = 1
    if setting.macro:
        arguments = tuple(w for w in nc.words if w is not word and w.address != "L")
        l_word = nc.find("L")
        if l_word is not None:
            l_value = constant_value(l_word.value)
            repeat = int(l_value) if l_value is not None and l_value == int(l_value) else None
    return Call(
        line, setting.kind, word.span, setting.program, word.span, repeat, arguments, setting.code
    )


def called_by_code(number: int | None, settings: Sequence[CustomCallSetting]) -> bool:
    """Whether a program is one the settings' codes call: inside it, the control reads the same
    codes as plain codes, so that a call does not call itself (unverified: shared reference
    macro-b.md 5.4, background knowledge)."""
    return number is not None and any(s.program == number for s in settings)


# The words a macro call's arguments use that a block of an M code alone never takes.
_ARGUMENT_LETTERS = frozenset("ABCDEIJKQRUVW")


def _m_call_candidate(parsed: ParsedLine) -> tuple[float, int, int] | None:
    """An M code (not a standard one) with P and an argument word, no G code: the M code and
    its word's columns."""
    statement = parsed.statement
    if type(statement) is PlainNc:
        codes = statement.codes
        if not any(a == "M" for a, _ in codes) or any(a == "G" for a, _ in codes):
            return None
    if not isinstance(statement, NcStatement | PlainNc):
        return None
    m_word: Word | None = None
    has_p = has_argument = False
    for word in statement.words:
        address = word.address
        if address == "G":
            return None
        if address == "M":
            value = constant_value(word.value)
            if m_word is not None or value is None or f"M{value:02g}" in M_CODES:
                return None
            if value in (97.0, 98.0, 99.0):
                return None
            m_word = word
        elif address == "P":
            has_p = True
        elif address in _ARGUMENT_LETTERS:
            has_argument = True
    if m_word is None or not (has_p and has_argument):
        return None
    value = constant_value(m_word.value)
    assert value is not None
    return value, m_word.span.start, m_word.span.end


# Blocks that look like a macro call through an M code (the rules' MB409): few, and kept from
# edit to edit.
m_call_candidates: LineMap[tuple[float, int, int]] = LineMap(_m_call_candidate)


def unset_m_calls(
    doc: Document, settings: Sequence[CustomCallSetting]
) -> Iterator[tuple[int, float, int, int]]:
    """The blocks that read as a macro call through an M code the settings do not set up:
    line, M code, the M word's columns. Their other words are the macro's arguments, not NC
    words to check."""
    found = m_call_candidates(doc)
    for line, (value, start, end) in zip(found.lines, found.values, strict=True):
        statement = doc.blocks[line].parsed.statement
        if isinstance(statement, NcStatement | PlainNc) and calling_word(statement, settings):
            continue
        yield line, value, start, end
