"""Blocks that call a program through a code the control's parameters set up (``M165`` calling
O9022, a T code calling O9000): what the settings make of a block's words.

The text alone cannot say which codes call: the parameters of the machine do, and the settings
name them (``machine.customCalls``, read by :func:`fanuc_macro.config.read_custom_calls`). So
these calls are not in the program index, which is of the text alone. The evaluator, the rules
and the editor's answers ask here, with the settings.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..config import CustomCallSetting
from ..syntax.marks import constant_value
from ..syntax.tree import IfNc, Mixed, NcStatement, Statement, Word
from .index import Call


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
