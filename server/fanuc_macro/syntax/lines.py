"""Text to lines: decoding, line ends, comments, end of block and tape marks.

This is the layer below the grammar. It takes what the control itself strips before it reads a
block's words: ``( ... )`` comments (FANUC ends one at the first ``)``), the end-of-block ``;``
and the tape mark ``%``. Comments are replaced by spaces so that the grammar's columns stay the
columns of the line.
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

# What the analysis reads: defined apart, for the settings (re-exported here).
from ..translation import tr
from .limits import MAX_LINE_LENGTH as MAX_LINE_LENGTH
from .limits import READ_WHOLE as READ_WHOLE
from .limits import ReadLimits as ReadLimits
from .tree import Comment, LineNote, shared_span

_LINE_BREAK = re.compile(r"\r\n|\r|\n")
_BLANK_TAIL = re.compile(r"[ \t;%]*")


# What is looked at to tell a program text from a binary file: the start, as git does.
_SNIFF = 8000
# Control bytes that a program text may hold: tab, line ends, form feed, the tape reader's
# DC1-DC4 (ISO 840 device controls), and SUB, the end-of-file mark of DOS files.
_TEXT_CONTROLS = frozenset(b"\t\n\v\f\r\x11\x12\x13\x14\x1a")
_CONTROL_BYTES = bytes(b for b in range(32) if b not in _TEXT_CONTROLS)
_BINARY_SHARE = 0.05  # of the bytes looked at: control bytes no text holds
BINARY = "binary"  # ``DecodedText.encoding`` of bytes that are not program text


# What a punched tape's leader and trailer are in a file: NUL bytes, the blank tape that carries
# only feed holes, with line ends and spaces among them. The tape reader disregards NUL in ISO
# code (YASNAC LX3 manual, table of function characters: "NUL ... Disregarded in ISO"; FANUC's
# own tape code table unverified), and reads nothing before the first end of block after a
# reset (the label skip: Mitsubishi M700V manual, "Significant data section").
_LEADER_BYTES = b"\0\r\n \t"


def tape_leader_bounds(data: bytes) -> tuple[int, int]:
    """``(start, end)``: ``data[:start]`` is a punched tape's leader, up to its last NUL byte,
    and ``data[end:]`` its trailer, from its first NUL byte; ``(0, len(data))`` for a file
    without NUL bytes around its text."""
    head = len(data) - len(data.lstrip(_LEADER_BYTES))
    start = data.rfind(0, 0, head) + 1
    if head == len(data):  # nothing but leader
        return start, start
    tail = len(data.rstrip(_LEADER_BYTES))
    nul = data.find(0, tail)
    return start, len(data) if nul < 0 else nul


def not_text_reason(data: bytes) -> str | None:
    """Why ``data`` is not a program text, or None when it may be one: NUL bytes, or many other
    control bytes, in its first 8,000 bytes (after a punched tape's leader of NULs, the blank
    tape that carries only feed holes); a UTF-16 or UTF-32 byte order mark."""
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        return tr("it is UTF-32 text (save it as UTF-8 or ASCII)")
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return tr("it is UTF-16 text (save it as UTF-8 or ASCII)")
    start, end = tape_leader_bounds(data)
    sample = data[start : min(end, start + _SNIFF)]
    nul = sample.find(0)
    if nul >= 0:
        return tr(
            "it holds NUL bytes (the first at byte {byte}): a binary file, or text saved as UTF-16",
            byte=start + nul + 1,
        )
    controls = len(sample) - len(sample.translate(None, _CONTROL_BYTES))
    if controls > len(sample) * _BINARY_SHARE:
        return tr(
            "{controls} of its first {size:,} bytes are control codes: a binary file",
            controls=controls,
            size=len(sample),
        )
    return None


@dataclass(frozen=True, slots=True)
class DecodedText:
    text: str
    encoding: str
    # Set when the reading is in doubt (lines in two encodings, an encoding unclear, bytes no
    # encoding reads) or the bytes are not a program text; None for a clean reading.
    note: str | None


# The encodings a file that is not UTF-8 is read in, the first preferred on a tie: those of
# the shops that write comments in their own script (GB18030, which holds GBK and GB2312, in
# China; Shift-JIS in Japan; Windows-1252, which holds Latin-1's letters, in Western Europe
# and the Americas).
_LEGACY = ("gb18030", "shift_jis", "cp1252")
_NAMES: Mapping[str, str] = MappingProxyType(
    {
        "utf-8": "UTF-8",
        "gb18030": "GB18030",
        "shift_jis": "Shift-JIS",
        "cp1252": "Windows-1252",
        "latin-1": "Latin-1",
    }
)
# A reading is taken as the file's encoding, without a note, when at most this share of its
# non-ASCII characters is seldom written in that encoding's script.
_UNUSUAL_SHARE = 0.1
_NON_ASCII = re.compile(r"[^\x00-\x7f]+")
# Windows-1252's characters in 0x80-0x9F that Western text holds (the euro, quotes, dashes,
# ellipsis, bullet); the others (Š, ‰, ˆ, ...) come up mostly when other bytes are read so.
_WESTERN_PUNCTUATION = frozenset("€‘’“”–—…•")


def _is_kana(ch: str) -> bool:
    return "\u3040" <= ch <= "\u30ff"


def _in_gb2312(ch: str) -> bool:
    """GB2312 is the everyday Chinese set (with Cyrillic, Greek and full-width forms): the
    characters outside it that GB18030 bytes give are mostly other encodings' bytes (a
    Shift-JIS kanji, a Western letter before an ASCII one)."""
    try:
        ch.encode("gb2312")
    except UnicodeEncodeError:
        return False
    return True


def _jis_level_1(ch: str) -> bool:
    """A kanji of JIS X 0208's first level, the common ones (Shift-JIS 889F-9872); Western
    letters before an ASCII one read as Shift-JIS land in the second level."""
    code = ch.encode("shift_jis")
    return len(code) < 2 or code < b"\x98\x9f"


def _unusual_count(run: str, encoding: str, halfwidth_kana_unusual: bool) -> int:
    """How many characters of ``run`` (non-ASCII characters side by side) are seldom written in
    ``encoding``'s script: the sign that the bytes are in another encoding. Half-width
    katakana, which older Japanese controls and files use, are also what GB18030 bytes read as
    Shift-JIS turn into: unusual when GB18030 reads the bytes too."""
    if encoding == "gb18030":
        # Kana are in GB2312, but Chinese comments do not hold them: GB18030 kana are other
        # bytes (Shift-JIS half-width katakana).
        return sum(1 for ch in run if _is_kana(ch) or not _in_gb2312(ch))
    if encoding == "shift_jis":
        return sum(
            1
            for ch in run
            if ("\uff61" <= ch <= "\uff9f" and halfwidth_kana_unusual)
            or ("\u4e00" <= ch <= "\u9fff" and not _jis_level_1(ch))
        )
    # Western text has its accented letters and signs one or two at a time; longer runs,
    # and pairs that are UTF-8 bytes ("Ã©" for "é"), are another encoding's characters.
    if len(run) > 2 or _is_utf8(run.encode("cp1252")):
        return len(run)
    # Bytes 0x80-0x9F are Windows-1252's characters above U+00FF.
    return sum(1 for ch in run if ch > "\xff" and ch not in _WESTERN_PUNCTUATION)


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


@dataclass(frozen=True, slots=True)
class _Reading:
    encoding: str
    text: str
    unusual: int  # non-ASCII characters seldom written in the encoding's script
    non_ascii: int

    @property
    def clear(self) -> bool:
        return self.unusual <= self.non_ascii * _UNUSUAL_SHARE


def _reading(data: bytes, encoding: str, halfwidth_kana_unusual: bool = True) -> _Reading | None:
    """``data`` read in ``encoding``, or None when it has bytes the encoding does not hold."""
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError:
        return None
    unusual = non_ascii = 0
    for run in _NON_ASCII.findall(text):
        non_ascii += len(run)
        unusual += _unusual_count(run, encoding, halfwidth_kana_unusual)
    return _Reading(encoding, text, unusual, non_ascii)


def _best_reading(data: bytes) -> _Reading | None:
    """The legacy encoding whose reading of ``data`` has the smallest share of unusual
    characters (the first of ``_LEGACY`` on a tie); None when none reads all its bytes."""
    chinese = _reading(data, "gb18030")
    japanese = _reading(data, "shift_jis", halfwidth_kana_unusual=chinese is not None)
    readings = [r for r in (chinese, japanese, _reading(data, "cp1252")) if r is not None]
    if not readings:
        return None
    return min(readings, key=lambda r: r.unusual / max(r.non_ascii, 1))


def decode_bytes(data: bytes) -> DecodedText:
    """Decode a program file: UTF-8 (with or without a byte order mark), else the legacy
    encoding whose reading looks most like text of its script: GB18030, Shift-JIS or
    Windows-1252. Comments are the only non-ASCII text of a program, so the choice is made on
    what they look like: kana for Japanese, everyday hanzi (or Cyrillic) for GB18030, accented
    letters one at a time for Western text.

    A clean reading carries no note. The note says what is in doubt: lines in UTF-8 beside
    lines in a legacy encoding (each line is then read in its own); a reading in which many
    characters are unusual (the encoding is unclear); bytes that none of the encodings reads
    (read as Latin-1, byte for byte).

    Bytes that are not a program text (:func:`not_text_reason`) are not read: the text is
    empty, the encoding :data:`BINARY`, and the note says why. The NUL bytes of a punched
    tape's leader and trailer (:func:`tape_leader_bounds`) are read as spaces.
    """
    reason = not_text_reason(data)
    if reason is not None:
        return DecodedText(
            "",
            BINARY,
            tr("not a program text: {reason}; the file is not analysed", reason=reason),
        )
    start, end = tape_leader_bounds(data)
    if (start, end) != (0, len(data)):
        # The NULs of a punched tape's leader and trailer are read as spaces: blank, as the
        # control takes them, in the file's own columns.
        data = data[:start].replace(b"\0", b" ") + data[start:end] + data[end:].replace(b"\0", b" ")
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    try:
        return DecodedText(data.decode("utf-8"), "utf-8", None)
    except UnicodeDecodeError:
        pass
    lines = data.split(b"\n")  # no legacy encoding has a line feed inside a character
    foreign = [n for n, line in enumerate(lines) if not line.isascii() and not _is_utf8(line)]
    best = _best_reading(b"\n".join(lines[n] for n in foreign))
    if best is None:
        return DecodedText(data.decode("latin-1"), "latin-1", _unreadable_note(lines, foreign))
    encoding = best.encoding
    utf8 = [n for n, line in enumerate(lines) if _utf8_rather(line, encoding)]
    if utf8:
        texts = [line.decode("utf-8" if n in utf8 else encoding) for n, line in enumerate(lines)]
        name = _NAMES[encoding]
        return DecodedText(
            "\n".join(texts),
            encoding,
            tr(
                "file mixes encodings: {utf8_lines} in UTF-8, {other_lines} in {encoding}; each "
                "line is read in its own, but an editor or a transfer program reads the file in "
                "one and shows the other lines garbled",
                utf8_lines=_lines(utf8),
                other_lines=_lines(foreign),
                encoding=name,
            ),
        )
    text = data.decode(encoding)
    if best.clear:
        return DecodedText(text, encoding, None)
    return DecodedText(
        text,
        encoding,
        tr(
            "file is not UTF-8 and its encoding is unclear: read as {encoding}, in which "
            "{unusual} of its {non_ascii} non-ASCII characters are seldom written; if its "
            "comments show garbled, the file is in another encoding",
            encoding=_NAMES[encoding],
            unusual=best.unusual,
            non_ascii=best.non_ascii,
        ),
    )


def _utf8_rather(line: bytes, encoding: str) -> bool:
    """A line in UTF-8 in a file in ``encoding``: valid UTF-8 with non-ASCII characters, that
    ``encoding`` reads as unusual text or not at all (short legacy text can be valid UTF-8 by
    chance, and then reads as usual text in its own encoding)."""
    if line.isascii() or not _is_utf8(line):
        return False
    reading = _reading(line, encoding)
    return reading is None or reading.unusual > 0


def _lines(numbers: list[int]) -> str:
    """'line 3' or '4 lines (the first: line 3)', 1-based."""
    if len(numbers) == 1:
        return tr("line {line}", line=numbers[0] + 1)
    return tr("{count} lines (the first: line {line})", count=len(numbers), line=numbers[0] + 1)


def _unreadable_note(lines: list[bytes], foreign: list[int]) -> str:
    for n in foreign:
        if all(_reading(lines[n], e) is None for e in _LEGACY):
            where = tr("line {line} holds bytes that none of them reads", line=n + 1)
            break
    else:
        where = tr("its lines are in more than one of them")
    return tr(
        "file is not text in UTF-8, GB18030, Shift-JIS or Windows-1252 ({where}); read as "
        "Latin-1, byte for byte",
        where=where,
    )


def split_lines(text: str) -> list[str]:
    """Lines of a program; CRLF, CR and LF all end a line (the control's EOB is LF)."""
    lines = text.split("\n") if "\r" not in text else _LINE_BREAK.split(text)
    if len(lines) > 1 and lines[-1] == "":
        lines.pop()
    return lines


@dataclass(frozen=True, slots=True)
class LineCode:
    """A line with its comments cut out: what the grammar parses."""

    code: str  # same length as the line; comments, ";" and "%" are spaces
    comments: tuple[Comment, ...]
    tape_mark: bool
    notes: tuple[LineNote, ...]


def _balanced_closes(line: str) -> dict[int, int]:
    """Each '(' of the line that a ')' balances, and that ')': one pass, where a scan from each
    '(' took quadratic time on "(()(()(()..."."""
    closes: dict[int, int] = {}
    opened: list[int] = []
    for k, ch in enumerate(line):
        if ch == "(":
            opened.append(k)
        elif ch == ")" and opened:
            closes[opened.pop()] = k
    return closes


# Where code gives way to a comment, an end of block or a tape mark.
_CUT_AT = re.compile(r"[(;%]")


def cut_comments(line: str) -> LineCode:
    """Separate comments, EOB and tape marks from code, keeping columns."""
    if "(" not in line and ";" not in line and "%" not in line and ")" not in line:
        return LineCode(line, (), False, ())
    if ";" not in line and "%" not in line:
        # Most commented lines: one "(" and its ")", the comment cut out at once.
        i = line.find("(")
        if i < 0:
            return LineCode(line, (), False, ())
        close = line.find(")", i + 1)
        if close >= 0 and line.find("(", i + 1) < 0:
            code = line[:i] + " " * (close + 1 - i) + line[close + 1 :]
            comment = Comment(line[i + 1 : close], shared_span(i, close + 1))
            return LineCode(code, (comment,), False, ())
    return _cut_comments(line)


def _cut_comments(line: str) -> LineCode:
    """:func:`cut_comments` of any line: the comments, end-of-block marks and tape marks in
    turn."""
    chars = list(line)
    comments: list[Comment] = []
    notes: list[LineNote] = []
    tape_mark = False
    i = 0
    n = len(line)
    balanced_closes: dict[int, int] | None = None  # worked out when a comment holds a '('
    while i < n:
        # The code between is kept as it is: on to the next character that ends it.
        found = _CUT_AT.search(line, i)
        if found is None:
            break
        i = found.start()
        ch = line[i]
        if ch == "(":
            close = line.find(")", i + 1)
            if close < 0:
                comments.append(Comment(line[i + 1 :], shared_span(i, n), closed=False))
                notes.append(
                    LineNote(
                        "unclosed-comment",
                        tr("comment opened with '(' is not closed with ')' on this line"),
                        shared_span(i, n),
                    )
                )
                chars[i:n] = " " * (n - i)
                break
            end = close
            if line.find("(", i + 1, close) >= 0:
                if balanced_closes is None:
                    balanced_closes = _balanced_closes(line)
                balanced = balanced_closes.get(i)
                if balanced is not None and balanced > close:
                    # FANUC ends the comment at the first ")" and reads the rest as program
                    # text. Real files do this by mistake, so take the comment to the ")" that
                    # balances it and say so, instead of reporting the stray text as syntax.
                    end = balanced
                    notes.append(
                        LineNote(
                            "nested-comment",
                            tr(
                                "parentheses nested in a comment: FANUC ends the comment at "
                                "the first ')' (column {column}) and reads {program_text} as "
                                "program text",
                                column=close + 1,
                                program_text=repr(line[close + 1 : end + 1]),
                            ),
                            shared_span(i, end + 1),
                        )
                    )
            comments.append(Comment(line[i + 1 : end], shared_span(i, end + 1)))
            chars[i : end + 1] = " " * (end + 1 - i)
            i = end + 1
            continue
        if ch == ";":
            chars[i] = " "
            rest = line.find("(", i + 1)
            tail_end = n if rest < 0 else rest
            blank = _BLANK_TAIL.match(line, i + 1, tail_end)
            assert blank is not None  # it may match nothing
            if blank.end() == tail_end:
                # Only more end-of-block marks, tape marks and spaces up to the next comment:
                # blank them all in one step (one at a time took quadratic time on ";;;;...").
                for k in range(i + 1, tail_end):
                    if line[k] in ";%":
                        tape_mark = tape_mark or line[k] == "%"
                        chars[k] = " "
                i = tail_end
                continue
            # Everything after the EOB belongs to no block the control would read as one.
            notes.append(
                LineNote(
                    "text-after-eob",
                    tr(
                        "text after the end of block ';': {program_text}",
                        program_text=repr(line[i + 1 : tail_end].strip()),
                    ),
                    shared_span(i + 1, tail_end),
                )
            )
            chars[i + 1 : tail_end] = " " * (tail_end - i - 1)
            i = tail_end
            continue
        elif ch == "%":
            tape_mark = True
            chars[i] = " "
        i += 1
    return LineCode("".join(chars), tuple(comments), tape_mark, tuple(notes))
