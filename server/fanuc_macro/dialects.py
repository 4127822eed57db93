"""Forms of other controls' dialects that a FANUC control rejects, recognised by their look.

When a block does not parse, the checker says which dialect it comes from, when it can tell,
rather than only "unexpected character".
"""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Dialect:
    name: str
    message: str


_PATTERNS: tuple[tuple[re.Pattern[str], str, str], ...] = (
    (
        re.compile(r"#<\w*>"),
        "LinuxCNC",
        "named parameter '#<...>' is LinuxCNC syntax; FANUC variables are numbered (#1, #100, ...)",
    ),
    (
        re.compile(r"^\s*o\d+\s+(sub|endsub|call|if|while|do)\b", re.I),
        "LinuxCNC",
        "'o<number> sub/call/if' is LinuxCNC syntax, not FANUC",
    ),
    (
        re.compile(r"^\s*\$\d"),
        "Mitsubishi/Citizen",
        "'$n' path selection is Mitsubishi/Citizen syntax, not FANUC",
    ),
    (
        re.compile(r"^\s*!\s*\d*\s*L\d", re.I),
        "Mitsubishi/Citizen",
        "'!L' path wait is Mitsubishi/Citizen syntax, not FANUC",
    ),
    (
        re.compile(r"[A-Z]\d+\s*=", re.I),
        "Mitsubishi/Citizen",
        "'S1=...' style spindle selection is Mitsubishi/Citizen syntax, not FANUC",
    ),
    (re.compile(r"@\d+"), "LNC/Syntec", "'@n' variables are LNC/Syntec syntax, not FANUC"),
    (
        re.compile(r"<=|>=|==|!=|&&|\|\||<|>"),
        "not FANUC",
        "FANUC compares with EQ NE GT GE LT LE only ('<', '>=', '==' ... give alarm PS0114)",
    ),
    (
        re.compile(r"\b(LTE|GTE|NEQ)\b", re.I),
        "not FANUC",
        "FANUC compares with EQ NE GT GE LT LE only ('LTE', 'GTE' give alarm PS0114)",
    ),
    (
        re.compile(r"[A-MP-Z]\s*-?#\d+(\.\d*)?\s*[-+*/]\s*[.#\d\[]", re.I),
        "Mitsubishi/Citizen",
        "an expression after an address must be in brackets on FANUC: write X[#1+1.], not X#1+1.",
    ),
)


def recognise(code: str, column: int) -> Dialect | None:
    """The dialect a rejected block seems to be written in, if its text says so."""
    for pattern, name, message in _PATTERNS:
        if pattern.search(code):
            return Dialect(name, message)
    return None
