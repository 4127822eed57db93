"""What a variable stands for in a thread program: from its comment or a known module's table.

The threading rules need to know which variable is the tool nose radius or the thread height.
Two sources, in this order:
1. the comment on the assignment, by the words below (English, upper case on the control, or
   Chinese as the seed papers write them);
2. the parameter tables of the known modules: the symmetric thread module O3331 (external) and
   O3330 (internal) with their main programs' #100-#104 (seed paper 000, tables 2 and 3), and
   the fitting-method arc thread sub-programs O3/O4 (seed paper 002).
"""

from __future__ import annotations

from dataclasses import dataclass

from .index import ProgramIndex
from .syntax import Assign, Document

# Role -> words that name it in a comment. The first role with a matching word wins, so the
# more specific come first: "刀尖圆弧半径" (nose radius) holds "圆弧半径" (arc radius).
ROLE_WORDS: dict[str, tuple[str, ...]] = {
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
}  # fmt: skip

# Known modules' parameter tables: program number -> {variable: role}.
KNOWN_MODULES: dict[int, dict[int, str]] = {
    3331: {3: "nose_radius", 4: "thread_height", 5: "ap_max", 6: "ap_min"},
    3330: {3: "nose_radius", 4: "thread_height", 5: "ap_max", 6: "ap_min", 11: "minor_diameter"},
    3: {1: "nominal_diameter", 3: "pitch", 4: "groove_radius", 18: "nose_radius"},
    4: {1: "nominal_diameter", 3: "pitch", 4: "groove_radius", 18: "nose_radius"},
}
INTERNAL_WORDS = ("INTERNAL", "内螺纹", "内孔")
EXTERNAL_WORDS = ("EXTERNAL", "外螺纹")

ROLE_TITLES = {
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


def role_of_comment(comment: str) -> str | None:
    upper = comment.upper()
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
    for program in index.programs:
        table = KNOWN_MODULES.get(program.number or -1, {})
        for var, role in table.items():
            roles[(program.first_line, var)] = Meaning(role, -1, f"module {program.display_name}")
        for line in range(program.first_line, program.end_line):
            block = doc.blocks[line]
            statement = block.statement
            if not isinstance(statement, Assign) or statement.target.number is None:
                continue
            var = int(statement.target.number)
            comment = " ".join(c.text for c in block.parsed.comments)
            said = role_of_comment(comment) if comment else None
            if said is not None:
                key = (program.first_line, var)
                if key not in roles or roles[key].line == -1:
                    roles[key] = Meaning(said, line, "comment")
    return roles


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
