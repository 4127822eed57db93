"""The kinds of semantic tokens (``semantic.py``), apart: the language server declares them
when it starts, before it loads the analysis.

The types are the protocol's standard ones, so that any theme colours them; what a FANUC
variable is beyond that (a common, a system variable, read-only) is a modifier.
"""

from __future__ import annotations

from enum import Enum


class TokenType(str, Enum):
    NAMESPACE = "namespace"  # an O program: its O line, a call's P word
    LABEL = "label"  # an N sequence number, a GOTO's target
    VARIABLE = "variable"
    PARAMETER = "parameter"  # a local a macro reads before it sets it: a call's argument
    FUNCTION = "function"  # SIN, ATAN, ROUND...
    KEYWORD = "keyword"  # IF, GOTO, WHILE, DO, END, THEN...
    OPERATOR = "operator"  # EQ, AND, MOD...


class TokenModifier(str, Enum):
    DECLARATION = "declaration"  # the O line of a program, the N of a block
    READONLY = "readonly"  # a system variable a program cannot write
    DEFAULT_LIBRARY = "defaultLibrary"  # the control's own: system variables, functions
    MODIFICATION = "modification"  # a variable written here
    COMMON = "common"  # #100-#199, #200-#499 (option), #500-#999
    SYSTEM = "system"  # #0 and #1000 on


# The legend, in the order the front end numbers them.
TOKEN_TYPES: tuple[str, ...] = tuple(t.value for t in TokenType)
TOKEN_MODIFIERS: tuple[str, ...] = tuple(m.value for m in TokenModifier)

__all__ = ("TOKEN_MODIFIERS", "TOKEN_TYPES", "TokenModifier", "TokenType")
