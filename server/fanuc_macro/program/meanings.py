"""What a variable stands for in a thread program: from its comment or a known module's table.

The threading rules need to know which variable is the tool nose radius or the thread height.
Two sources, in this order:
1. the comment on the assignment, by the words below (English, upper case on the control, or
   Chinese as the seed papers write them);
2. the parameter tables of the known modules: the symmetric thread module O3331 (external) and
   O3330 (internal) with their main programs' #100-#104 (Deng Ronggang's paper, tables 2 and
   3), and the fitting-method arc thread sub-programs O3/O4 (Ren Guozhu et al.): see
   ``papers.py``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..lazy_regex import LazyPattern
from ..line_maps import LineMap
from ..syntax.tree import Assign, Document, ParsedLine
from ..translation import tr
from .index import ProgramIndex
from .papers import DENG_MOLYBDENUM, REN_ARC_THREAD, Paper

# Role -> words that name it in a comment. The first role with a matching word wins, so the
# more specific come first: "刀尖圆弧半径" (nose radius) holds "圆弧半径" (arc radius).
ROLE_WORDS: Mapping[str, tuple[str, ...]] = MappingProxyType({
    "nose_radius": ("NOSE RADIUS", "TOOL RADIUS", "刀尖圆弧半径", "刀尖半径", "刀具半径"),
    "groove_radius": ("GROOVE RADIUS", "圆弧槽的半径", "圆弧半径", "槽半径"),
    "thread_height": ("THREAD HEIGHT", "THREAD DEPTH", "牙高", "牙深"),
    "ap_max": ("MAX DEPTH", "FIRST DEPTH", "最大切削深度"),
    "ap_min": ("MIN DEPTH", "FINISH ALLOWANCE", "最小切削深度"),
    "minor_diameter": ("MINOR DIAMETER", "小径"),
    "nominal_diameter": ("NOMINAL DIAMETER", "MAJOR DIAMETER", "THREAD DIAMETER", "公称直径",
                         "螺纹外径", "大径"),
    "pitch": ("PITCH", "LEAD", "螺距", "导程"),
    "thread_length": ("THREAD LENGTH", "标注长度", "螺纹长度"),
})  # fmt: skip

# Known modules' parameter tables: program number -> {variable: role}.
_ARC_THREAD_ROLES: Mapping[int, str] = MappingProxyType(
    {1: "nominal_diameter", 3: "pitch", 4: "groove_radius", 18: "nose_radius"}
)
KNOWN_MODULES: Mapping[int, Mapping[int, str]] = MappingProxyType(
    {
        3331: MappingProxyType({3: "nose_radius", 4: "thread_height", 5: "ap_max", 6: "ap_min"}),
        3330: MappingProxyType(
            {3: "nose_radius", 4: "thread_height", 5: "ap_max", 6: "ap_min", 11: "minor_diameter"}
        ),
        3: _ARC_THREAD_ROLES,
        4: _ARC_THREAD_ROLES,
    }
)
_NO_ROLES: Mapping[int, str] = MappingProxyType({})
# The seed papers' parameter tables (paper 000, tables 2 and 3; paper 002, section 2.2).
_SYMMETRIC_SUB: Mapping[int, tuple[str, str]] = MappingProxyType(
    {
        1: (tr("δ2, run-out (slow-down) length = P"), ""),
        2: (tr("δ1, run-in (speed-up) length = 2P + P + FIX[L/P]·P − L"), ""),
        3: (
            tr("r, tool nose radius"),
            tr("in theory P/(8·sin60°) external, P/(16·sin60°) internal"),
        ),
        4: (
            tr("h, thread height, radius"),
            tr("7H/8 − r + es/2 + Td2/4 (internal 6H/8 − r + EI/2 + TD2/4)"),
        ),
        5: (tr("ap(max), first depth of cut, radius"), tr("coefficient·√h")),
        6: (
            tr("ap(min), minimum depth of cut and finish allowance, radius"),
            tr("coefficient·√ap(max)"),
        ),
        7: (tr("n, rough pass counter"), ""),
        8: (tr("ap(n), depth of pass n, radius"), tr("ap(max)·(√n − √(n−1))")),
        9: (tr("Σap(n), total depth after pass n, radius"), ""),
        10: (tr("u, side offset of the pass"), tr("(h + r − ap(min) − Σap(n))·tan30° − r·tan30°")),
        11: (tr("D1, minor diameter of the internal thread"), tr("D − 2·(5/8)·sin60°·P")),
        12: (tr("n', spring (idle) passes at full depth"), ""),
    }
)
_SYMMETRIC_MAIN: Mapping[int, tuple[str, str]] = MappingProxyType(
    {
        100: (tr("d / D, nominal diameter of the thread"), ""),
        101: (tr("P, pitch (at most 2/3 of the insert width)"), ""),
        102: (tr("L, thread length, cut from right to left"), ""),
        103: (
            tr("es / EI, fundamental deviation, entered as a magnitude (GB/T 197 = ISO 965-1)"),
            "",
        ),
        104: (tr("Td2 / TD2, pitch-diameter tolerance (GB/T 197 = ISO 965-1)"), ""),
    }
)
_ARC_THREAD: Mapping[int, tuple[str, str]] = MappingProxyType(
    {
        1: (tr("thread outer diameter"), ""),
        2: (tr("thread length including the run-out δ2"), ""),
        3: (tr("pitch (lead)"), ""),
        4: (tr("R, radius of the arc groove of this layer"), ""),
        5: (tr("diameter of the groove's centre for this layer"), ""),
        6: (tr("δ1, run-in length (Z of the groove centre)"), ""),
        7: (tr("number of cuts per layer"), ""),
        10: (tr("right edge angle of the sector"), tr("ASIN[((#5 − #1)/2)/#4]")),
        11: (tr("tangency correction"), tr("ASIN[#18/(#4 − #18)]")),
        12: (tr("Δα, angle between two cuts"), ""),
        13: (tr("M code of the spindle direction (3 for this left-hand thread)"), ""),
        14: (tr("angle of the tool centre tangent to the right edge"), ""),
        15: (tr("angle of the last cut (left edge of the sector)"), ""),
        16: (tr("α, angle of the tool centre of this cut"), ""),
        18: (tr("r, tool nose radius"), ""),
        19: (tr("spindle speed of this layer"), ""),
        20: (tr("tool number"), ""),
        21: (tr("tool offset number"), ""),
        22: (tr("X of the start and retract point of each cut"), ""),
        24: (tr("X of the overall start and return point"), ""),
        26: (tr("Z of the overall start and return point"), ""),
    }
)


@dataclass(frozen=True)
class ModuleTable:
    """A known module's parameter table: which module, the paper and where in it."""

    module: str
    paper: Paper
    where: str  # "table 3", "section 2.2"
    meanings: Mapping[int, tuple[str, str]]  # variable -> its name, what the table adds


@dataclass(frozen=True)
class TableMeaning:
    """What a table says of one variable: its name, then what the table adds after a colon
    (a formula, a bound), and the table."""

    name: str
    detail: str
    table: ModuleTable


PARAMETER_TABLES: Mapping[int, ModuleTable] = MappingProxyType(
    {
        3331: ModuleTable(
            tr("symmetric thread module, external"), DENG_MOLYBDENUM, tr("table 3"), _SYMMETRIC_SUB
        ),
        3330: ModuleTable(
            tr("symmetric thread module, internal"), DENG_MOLYBDENUM, tr("table 3"), _SYMMETRIC_SUB
        ),
        3: ModuleTable(
            tr("arc thread by the fitting method, roughing layer"),
            REN_ARC_THREAD,
            tr("section 2.2"),
            _ARC_THREAD,
        ),
        4: ModuleTable(
            tr("arc thread by the fitting method, roughing layer"),
            REN_ARC_THREAD,
            tr("section 2.2"),
            _ARC_THREAD,
        ),
    }
)
MAIN_TABLE = ModuleTable(
    tr("main program of the symmetric thread module"),
    DENG_MOLYBDENUM,
    tr("table 2"),
    _SYMMETRIC_MAIN,
)


def _meaning(table: ModuleTable, number: int) -> TableMeaning:
    """The table's text of ``#number``: its name, and what the table adds (a formula)."""
    name, detail = table.meanings[number]
    return TableMeaning(name, detail, table)


def table_meaning(
    index: ProgramIndex, program_number: int | None, number: int
) -> TableMeaning | None:
    """What a known module's parameter table says of ``#number`` in that program; for #100-#104,
    in a program that calls the symmetric module (M98 P0013331 / P0013330)."""
    if program_number is not None and program_number in PARAMETER_TABLES:
        table = PARAMETER_TABLES[program_number]
        if number in table.meanings:
            return _meaning(table, number)
    if number in _SYMMETRIC_MAIN:
        program = index.by_number(program_number) if program_number is not None else None
        calls = program.calls if program is not None else ()
        if any(c.program in (3330, 3331) for c in calls):
            return _meaning(MAIN_TABLE, number)
    return None


INTERNAL_WORDS = ("INTERNAL", "内螺纹", "内孔")
EXTERNAL_WORDS = ("EXTERNAL", "外螺纹")

ROLE_TITLES: Mapping[str, str] = MappingProxyType(
    {
        "groove_radius": "groove (arc) radius",
        "nose_radius": "tool nose radius",
        "thread_height": "thread height (radius)",
        "ap_max": "first (maximum) depth of cut",
        "ap_min": "minimum depth of cut / finish allowance",
        "minor_diameter": "minor diameter",
        "nominal_diameter": "nominal (major) diameter",
        "pitch": "pitch",
        "thread_length": "thread length",
    }
)


_ANY_ROLE_WORD = LazyPattern("|".join(re.escape(w) for ws in ROLE_WORDS.values() for w in ws))


# Not cached: the line map below asks once per commented assignment of a version, again only
# for the lines an edit changed, and a cache kept every comment's text (about 2.4 MB for a
# 100,000-block program of distinct comments) for 34 substring tests of about 2 µs.
def role_of_comment(comment: str) -> str | None:
    upper = comment.upper()
    if _ANY_ROLE_WORD.search(upper) is None:  # most comments: one scan, not 34
        return None
    for role, words in ROLE_WORDS.items():
        for word in words:
            if word in upper:
                return role
    return None


@dataclass(frozen=True, slots=True)
class Meaning:
    role: str
    line: int  # the assignment that says so (or -1 for a known module's table)
    source: str  # "comment" or "module O3331"


def variable_roles(doc: Document, index: ProgramIndex) -> dict[tuple[int, int], Meaning]:
    """(program first line, variable) -> its role, for every program of the document."""
    roles: dict[tuple[int, int], Meaning] = {}
    said_at = _role_lines(doc)
    for program in index.programs:
        table = KNOWN_MODULES.get(program.number or -1, _NO_ROLES)
        for var, role in table.items():
            roles[(program.first_line, var)] = Meaning(role, -1, f"module {program.display_name}")
        for line, (var, role) in said_at.within(program.first_line, program.end_line):
            key = (program.first_line, var)
            if key not in roles or roles[key].line == -1:
                roles[key] = Meaning(role, line, "comment")
    return roles


def _assigned_role(parsed: ParsedLine) -> tuple[int, str] | None:
    statement = parsed.statement
    if not isinstance(statement, Assign) or statement.target.number is None:
        return None
    comment = " ".join(c.text for c in parsed.comments)
    role = role_of_comment(comment) if comment else None
    return None if role is None else (int(statement.target.number), role)


def _role_line(parsed: ParsedLine) -> tuple[int, str] | None:
    return _assigned_role(parsed) if parsed.comments else None  # no comment, no role


# The assignments whose comment names a role, looked at again only where the document changed.
_role_lines: LineMap[tuple[int, str]] = LineMap(_role_line)


def program_is_internal(doc: Document, first_line: int, end_line: int) -> bool | None:
    """Whether a program's comments say it cuts an internal or an external thread."""
    text = " ".join(
        c.text.upper()
        for ln in range(first_line, min(end_line, first_line + 3))
        for c in doc.blocks[ln].parsed.comments
    )
    if any(w in text for w in INTERNAL_WORDS):
        return True
    if any(w in text for w in EXTERNAL_WORDS):
        return False
    return None
