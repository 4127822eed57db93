"""The quick fixes the rules work out (the editor's code actions) applied to a file's text,
for ``check --fix``, ``--diff`` and ``--unsafe-fixes``. A fix a rule marks safe changes nothing of
what the control does but the mistake (a comment closed); the others change the program as the
message suggests, and are applied only when asked. The files are analysed again after each
round of fixes, and checked as fixed."""

from __future__ import annotations

import codecs
import difflib
import re
from collections.abc import Sequence
from dataclasses import dataclass

from ..diagnostics import Fix, FixEdit
from ..syntax.lines import decode_bytes
from ..workspace import Workspace

# Rounds of analysis and fixes per file: a fix may uncover another (an END inserted lets the
# loop's own check run), and rounds stop when nothing is left to fix.
MAX_ROUNDS = 10
_LINE_BREAK = re.compile(r"(\r\n|\r|\n)")


@dataclass(frozen=True)
class Fixed:
    """One file's fixes: its new bytes (None: unchanged, or not fixable), how many fixes were
    applied, and why the file could not be fixed ("" when it could)."""

    key: str
    data: bytes | None
    applied: int
    refused: str = ""


def encoded_back(data: bytes) -> tuple[str, str, bool] | None:
    """The text of ``data``, its encoding and whether it began with a byte order mark, when
    the text encodes back to the same bytes; None when it would not (a file read in part in
    another encoding, a tape's leader): such a file is not rewritten."""
    decoded = decode_bytes(data)
    if decoded.note is not None:
        return None
    bom = decoded.encoding == "utf-8" and data.startswith(codecs.BOM_UTF8)
    try:
        again = decoded.text.encode(decoded.encoding)
    except (UnicodeEncodeError, LookupError):
        return None
    if (codecs.BOM_UTF8 if bom else b"") + again != data:
        return None
    return decoded.text, decoded.encoding, bom


def _chosen(fixes: Sequence[Fix], unsafe: bool) -> Fix | None:
    """The fix to apply of a diagnostic's: the preferred one, else the first, if allowed."""
    allowed = [f for f in fixes if f.safe or unsafe]
    preferred = [f for f in allowed if f.preferred]
    chosen = preferred or allowed
    return chosen[0] if chosen else None


def _offsets(text: str) -> tuple[list[int], str]:
    """Where each line starts in ``text``, and the line end most used (LF when none)."""
    parts = _LINE_BREAK.split(text)
    starts = [0]
    ends: dict[str, int] = {}
    at = 0
    for n, part in enumerate(parts):
        at += len(part)
        if n % 2:
            starts.append(at)
            ends[part] = ends.get(part, 0) + 1
    return starts, max(ends, key=lambda e: ends[e]) if ends else "\n"


def apply_fixes(text: str, fixes: Sequence[Fix]) -> tuple[str, int]:
    """``text`` with ``fixes`` applied, each whole or not at all: a fix any of whose edits
    overlaps an edit already taken waits for the next round. The count applied. An edit's
    "\\n" is the file's own line end."""
    starts, line_end = _offsets(text)

    def offset(line: int, column: int) -> int:
        return starts[min(line, len(starts) - 1)] + column

    taken: list[tuple[int, int, str]] = []
    applied = 0
    for fix in fixes:
        spans = [(offset(e.line, e.column), offset(e.end_line, e.end_column), e) for e in fix.edits]
        if any(_overlap(a, b, c, d) for a, b, _e in spans for c, d, _t in taken):
            continue
        taken.extend((a, b, _text(e, line_end)) for a, b, e in spans)
        applied += 1
    for start, end, new in sorted(taken, key=lambda t: (t[0], t[1]), reverse=True):
        text = text[:start] + new + text[end:]
    return text, applied


def _overlap(a: int, b: int, c: int, d: int) -> bool:
    """Whether the edits of [a, b) and [c, d) touch the same text, or insert at one place."""
    return max(a, c) < min(b, d) or a == c


def _text(edit: FixEdit, line_end: str) -> str:
    return edit.text.replace("\n", line_end) if line_end != "\n" else edit.text


def fix_file(workspace: Workspace, key: str, data: bytes, unsafe: bool) -> Fixed:
    """The fixes of ``key`` (read in ``workspace`` with the files it calls), round after
    round until none is left; the workspace holds the fixed text after."""
    read = encoded_back(data)
    if read is None:
        return Fixed(key, None, 0, "its bytes do not read back the same: not rewritten")
    text, encoding, bom = read
    applied = 0
    for _round in range(MAX_ROUNDS):
        analysis = workspace.analyse(key)
        fixes = [f for d in analysis.diagnostics if (f := _chosen(d.fixes, unsafe)) is not None]
        if not fixes:
            break
        text, count = apply_fixes(text, fixes)
        if not count:
            break
        applied += count
        workspace.add_text(key, text)
    if not applied:
        return Fixed(key, None, 0)
    return Fixed(key, (codecs.BOM_UTF8 if bom else b"") + text.encode(encoding), applied)


def unified_diff(key: str, before: bytes, after: bytes) -> str:
    """The change of one file as ``diff -u`` shows it."""
    old = (encoded_back(before) or ("", "", False))[0]
    new = (encoded_back(after) or ("", "", False))[0]
    return "".join(
        difflib.unified_diff(old.splitlines(keepends=True), new.splitlines(keepends=True), key, key)
    )
