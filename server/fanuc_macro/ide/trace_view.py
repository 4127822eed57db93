"""The trace view's text: a header, one row per motion block (where it is, its code and words,
where the tool goes, the spindle speed and the feed in force, the cycle time when it
begins), the values the
block read under its row, a canned cycle's moves, where the path is not known, and the
summary.  Each row of a block says which line of which file it leads to, for the editor's
links and Go to Definition.  The columns fit beside a program (``MAX_COLUMN``), and the
values wrap under the row (``VALUES_WIDTH``).

Values are written at the control's precision: words and positions to the least increment
(0.001), macro variables as the control's display shows them (8 significant digits)."""

from __future__ import annotations

import unicodedata
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from textwrap import wrap
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from ..evaluator.values import fmt, fmt_address
from ..translation import Text, joined, render, tr, tr_n

if TYPE_CHECKING:
    from .trace import Trace

__all__ = ("TraceRow", "TraceView", "view_of_trace")

# Addresses whose values are integers on a FANUC control (no decimal point).
INTEGER_ADDRESSES = frozenset("DGHLMNOPST")

# A column is padded to the widest of its cells, up to this many characters.
MAX_COLUMN = 34
# The values a block read are written under its row, in lines of at most this many characters.
VALUES_WIDTH = 60
VALUES_INDENT = "    "


@dataclass(frozen=True)
class TraceRow:
    """A row of the view that leads to a block: ``line`` in the view (0-based), the block's
    ``source_line`` (0-based) in ``path`` (a URI; None: the traced document), the columns of
    its link (``O0003 line 33``) if it has one, and what the link opens."""

    line: int
    source_line: int
    path: str | None
    link: tuple[int, int] | None
    label: str


@dataclass(frozen=True)
class TraceView:
    text: str
    rows: tuple[TraceRow, ...]


def _word(address: str, value: Any) -> str:
    """A word's value as the control writes it: ``49.816``, ``-60.``; ``G1`` without a point."""
    if value is None:
        return "<vacant>"
    if isinstance(value, str):
        return value
    text = fmt_address(float(value))
    if address.upper() in INTEGER_ADDRESSES and text.endswith("."):
        return text[:-1]
    return text


def _program(program: Any) -> str:
    """``O3331`` from 3331, "3331" or "O3331"; a name such as ``<THREAD>`` as it is."""
    if program is None or program == "":
        return ""
    text = str(program).strip()
    return f"O{text.zfill(4)}" if text.isdigit() else text


def _words(words: Mapping[str, Any] | None) -> str:
    return " ".join(f"{a}{_word(a, v)}" for a, v in (words or {}).items())


def _position(position: Mapping[str, Any] | None) -> str:
    """``X51. Z5.964``; ``?`` when no axis is known."""
    known = [
        f"{axis}{_word(axis, value)}"
        for axis, value in (position or {}).items()
        if isinstance(value, int | float) and not isinstance(value, bool)
    ]
    return " ".join(known) or "?"


def _macro_value(value: Any) -> str:
    if value is None:
        return "<vacant>"
    if isinstance(value, str):
        return f"({value})"
    return fmt(float(value))


def _values(values: Mapping[str, Any] | None) -> str:
    return " ".join(
        f"{name if name.startswith('#') else '#' + name}={_macro_value(value)}"
        for name, value in (values or {}).items()
    )


def _scalar(value: Any, locale: str = "en") -> str:
    if isinstance(value, Text):
        return render(value, locale)
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    if isinstance(value, int | float):
        return f"{value:.6g}"
    return str(value)


def _is_scalar(value: Any) -> bool:
    return not isinstance(value, Mapping | list | tuple)


def summary_lines(summary: Any, indent: str = "  ", locale: str = "en") -> list[str]:
    """Indented ``key: value`` lines, nested objects indented further; in ``locale`` the
    keys the summary is known to have are said in words, the translated values too."""
    if not isinstance(summary, Mapping):
        return [] if summary is None else [f"{indent}{_scalar(summary, locale)}"]
    lines: list[str] = []
    for key, value in summary.items():
        if locale != "en" and key in SUMMARY_KEYS:
            key = render(SUMMARY_KEYS[key], locale)
        if isinstance(value, Mapping | list | tuple) and not value:
            none = render(tr("(none)"), locale)
            lines.append(f"{indent}{key}: {none}")
        elif isinstance(value, Mapping):
            lines.append(f"{indent}{key}:")
            lines.extend(summary_lines(value, f"{indent}  ", locale))
        elif isinstance(value, list | tuple) and all(_is_scalar(v) for v in value):
            lines.append(f"{indent}{key}: {', '.join(_scalar(v, locale) for v in value)}")
        elif isinstance(value, list | tuple):
            lines.append(f"{indent}{key}:")
            for item in value:
                nested = summary_lines(item, f"{indent}    ", locale)
                if nested:
                    nested[0] = f"{indent}  - {nested[0].lstrip()}"
                lines.extend(nested)
        else:
            lines.append(f"{indent}{key}: {_scalar(value, locale)}")
    return lines


# The summary's keys (``trace --format json`` writes them as they are) in words, for a user
# who reads another language than English.
SUMMARY_KEYS: Mapping[str, str] = MappingProxyType(
    {
        "motions": tr("motions"),
        "by_code": tr("by code"),
        "blocks_executed": tr("blocks executed"),
        "stopped": tr("stopped"),
        "stop_message": tr("why it stopped"),
        "findings": tr("findings"),
        "read_in_part": tr("files read in part"),
        "threads": tr("threads"),
        "line": tr("line"),
        "kind": tr("kind"),
        "message": tr("message"),
        "last_line_read": tr("last line read"),
        "program": tr("program"),
        "code": tr("code"),
        "passes": tr("passes"),
        "lead": tr("lead"),
        "side": tr("side"),
        "thread": tr("thread"),
        "identified": tr("identified"),
        "known_from": tr("known from"),
        "pitch_diameter": tr("pitch diameter"),
        "root_diameter": tr("root diameter"),
        "crest_diameter": tr("crest diameter"),
        "nose_radius": tr("nose radius"),
        "nose_radius_known": tr("nose radius known"),
        "limits": tr("limits"),
        "verdict": tr("verdict"),
        "area": tr("area"),
        "largest_pass": tr("largest pass"),
        "index": tr("index"),
        "passes_in_air": tr("passes in the air"),
        "blank": tr("blank"),
        "blank_from": tr("blank from"),
    }
)


def _source_line(line: Any) -> int | None:
    """The 0-based line of a 1-based ``line`` (a number, or the text of one)."""
    if isinstance(line, int) and not isinstance(line, bool):
        number = line
    elif isinstance(line, str) and line.strip().isdigit():
        number = int(line)
    else:
        return None
    return number - 1 if number >= 1 else None


def _path(record: Mapping[str, Any]) -> str | None:
    path = record.get("path")
    return path if isinstance(path, str) and path else None


def _move(move: Mapping[str, Any], locale: str = "en") -> str:
    kind = str(move.get("kind") or "move")
    text = f"{kind:<6} {_position(move.get('start'))} -> {_position(move.get('end'))}"
    if move.get("centre") is not None:
        clockwise = move.get("clockwise")
        turn = " CW" if clockwise is True else " CCW" if clockwise is False else ""
        centre = render(tr("centre {position}", position=_position(move.get("centre"))), locale)
        text += f"  {centre}{turn}"
    return text


def display_width(text: str) -> int:
    """The columns ``text`` takes in a monospaced editor: a wide (Chinese) character two."""
    if text.isascii():
        return len(text)
    return sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text)


class _Writer:
    """The view's lines and the rows that lead to blocks, in the order of the text, in the
    language of ``locale``."""

    def __init__(self, locale: str = "en") -> None:
        self.out: list[str] = []
        self.rows: list[TraceRow] = []
        self.locale = locale

    def say(self, text: str) -> str:
        return render(text, self.locale)

    def lead(self, at: int, source: int, path: str | None, label: str, link: bool) -> None:
        """The lines from ``at`` on lead to the block; the first one links to it if ``link``."""
        for line in range(at, len(self.out)):
            span = (0, len(label)) if link and line == at else None
            self.rows.append(TraceRow(line, source, path, span, label))


def _block(m: Mapping[str, Any], locale: str = "en") -> str:
    program = _program(m.get("program"))
    line = "" if m.get("line") is None else render(tr("line {line}", line=m["line"]), locale)
    return f"{program} {line}".strip() if program else line


def _to(m: Mapping[str, Any]) -> str:
    """Where the block leaves the tool (where it came from is the row above's)."""
    if "start" not in m and "end" not in m:
        return ""
    return _position(m.get("end"))


def _spindle(m: Mapping[str, Any]) -> str:
    """The spindle speed in force: rpm in G97, the surface speed in G96; ``-`` not known."""
    rpm = m.get("speed")
    if isinstance(rpm, int | float) and not isinstance(rpm, bool):
        return _word("S", rpm)
    surface = m.get("surface_speed")
    if isinstance(surface, int | float) and not isinstance(surface, bool):
        return f"{_word('S', surface)} G96"
    return "-"


def _feed(m: Mapping[str, Any]) -> str:
    """The feed a cut goes at (the block's F, else the one in force); ``-`` for a rapid."""
    feed = (m.get("words") or {}).get("F")
    return "-" if feed is None else _word("F", feed)


def _clock(m: Mapping[str, Any]) -> str:
    """The cycle time when the block begins, minutes and seconds to 0.1 s (``6:12.4``)."""
    clock = m.get("clock")
    if not isinstance(clock, int | float) or isinstance(clock, bool):
        return "-"
    minutes, tenths = divmod(round(clock * 10.0), 600)
    return f"{minutes}:{tenths // 10:02d}.{tenths % 10}"


# The row's columns: a title and its cell.  The block's F is its own column, not a word.
_COLUMNS: tuple[tuple[str, Callable[[Mapping[str, Any]], str]], ...] = (
    (tr("block"), _block),
    (tr("code"), lambda m: str(m.get("code") or "")),
    (tr("words"), lambda m: _words({a: v for a, v in (m.get("words") or {}).items() if a != "F"})),
    (tr("to"), _to),
    ("S", _spindle),
    ("F", _feed),
    (tr("time"), _clock),
)


def _motion_rows(writer: _Writer, motions: Sequence[Mapping[str, Any]]) -> None:
    say, locale = writer.say, writer.locale
    titles = tuple(say(title) for title, _ in _COLUMNS)
    cells = [(_block(m, locale), *(cell(m) for _, cell in _COLUMNS[1:])) for m in motions]
    widths = [
        min(MAX_COLUMN, max(display_width(title), *(display_width(c[i]) for c in cells)))
        for i, title in enumerate(titles)
    ]

    def row(cell: tuple[str, ...]) -> str:
        return "  ".join(
            text + " " * (size - display_width(text))
            for text, size in zip(cell, widths, strict=True)
        ).rstrip()

    writer.out.append(row(titles))
    for m, cell in zip(motions, cells, strict=True):
        at = len(writer.out)
        writer.out.append(row(cell))
        values = _values(m.get("values"))
        if values:
            writer.out.extend(
                wrap(
                    values,
                    VALUES_WIDTH,
                    initial_indent=VALUES_INDENT,
                    subsequent_indent=VALUES_INDENT,
                    break_long_words=False,
                    break_on_hyphens=False,
                )
            )
        if m.get("centre") is not None:
            centre = say(tr("centre {position}", position=_position(m["centre"])))
            writer.out.append(f"{VALUES_INDENT}{centre}")
        moves = m.get("moves") or []
        if moves:
            count = tr_n("{count} move", "{count} moves", len(moves))
            if m.get("cycle"):
                count = tr("{moves} ({cycle})", moves=count, cycle=m["cycle"])
            said = say(tr("{moves}:", moves=count))
            writer.out.append(f"{VALUES_INDENT}{said}")
        writer.out.extend(f"      {_move(move, locale)}" for move in moves)
        source = _source_line(m.get("line"))
        if source is not None:
            writer.lead(at, source, _path(m), cell[0], link=True)


def _wrapped(line: str, width: int = VALUES_WIDTH + len(VALUES_INDENT)) -> list[str]:
    """A long line of the summary cut at spaces, its further lines indented under it."""
    if len(line) <= width:
        return [line]
    indent = " " * (len(line) - len(line.lstrip()) + len(VALUES_INDENT))
    return wrap(
        line, width, subsequent_indent=indent, break_long_words=False, break_on_hyphens=False
    )


def _lost_rows(writer: _Writer, lost: Sequence[Mapping[str, Any]]) -> None:
    writer.out.extend(["", writer.say(tr("Where the path is not known"))])
    for place in lost:
        line = (
            writer.say(tr("line {line}", line=place["line"]))
            if isinstance(place.get("line"), int)
            else ""
        )
        block = f"{_program(place.get('program'))} {line}".strip()
        axes = ", ".join(place.get("axes") or [])
        at = len(writer.out)
        reason = writer.say(place.get("reason") or "")
        writer.out.extend(_wrapped(f"  {block}: {axes} {reason}".rstrip()))
        source = _source_line(place.get("line"))
        if source is not None:
            writer.rows.append(TraceRow(at, source, _path(place), (2, 2 + len(block)), block))


def view_of_trace(trace: Trace, source: str, locale: str = "en") -> TraceView:
    """The view of ``trace`` (what :func:`~fanuc_macro.ide.trace.trace` answers) for the
    program ``source`` (a file's path, or an untitled document's URI).  The rows read its
    records as JSON, a key left out or of another type skipped, so a trace read back from a
    file is shown too."""
    motions: Sequence[Mapping[str, Any]] = trace.get("motions") or []
    toolpath: Mapping[str, Any] = trace.get("toolpath") or {}
    summary = trace.get("summary")
    executed = summary.get("blocks_executed") if isinstance(summary, Mapping) else None
    units = toolpath.get("units")
    writer = _Writer(locale)
    say = writer.say
    # The file's name as the title; its folder on a line of its own, the title short.
    folder, cut, name = source.replace("\\", "/").rpartition("/")
    hidden = "://" in source or source.startswith("untitled:")
    writer.out.append(say(tr("Trace of {name}", name=name if cut and not hidden else source)))
    if cut and not hidden and folder:
        writer.out.append(say(tr("in {folder}", folder=source[: len(folder)])))
    counts = [tr_n("{count} motion block", "{count} motion blocks", len(motions))]
    if isinstance(executed, int):
        counts.append(tr_n("{count} block executed", "{count} blocks executed", executed))
    if isinstance(units, str):
        counts.append(tr("positions in {units}", units=units))
    writer.out.append(say(joined(", ", counts)))
    writer.out.append(say(tr("Ctrl+click a row's block, or F12 on the row, to open it.")))
    writer.out.append("")
    if motions:
        _motion_rows(writer, motions)
    else:
        writer.out.append(say(tr("(no motion)")))
    lost = toolpath.get("lost") or []
    if lost:
        _lost_rows(writer, lost)
    said = summary_lines(summary, locale=locale)
    if said:
        heading = say(tr("Summary"))
        writer.out.extend(["", heading, *(w for line in said for w in _wrapped(line))])
    return TraceView("\n".join(writer.out) + "\n", tuple(writer.rows))
