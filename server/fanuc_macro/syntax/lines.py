"""Text to lines: decoding, line ends, comments, end of block and tape marks.

This is the layer below the grammar. It takes what the control itself strips before it reads a
block's words: ``( ... )`` comments (FANUC ends one at the first ``)``), the end-of-block ``;``
and the tape mark ``%``. Comments are replaced by spaces so that the grammar's columns stay the
columns of the line.
"""

from __future__ import annotations

import codecs
import re
from dataclasses import dataclass

# What the analysis reads: defined apart, for the settings (re-exported here).
from .limits import MAX_LINE_LENGTH as MAX_LINE_LENGTH
from .limits import READ_WHOLE as READ_WHOLE
from .limits import ReadLimits as ReadLimits
from .tree import Comment, LineNote, shared_span

_LINE_BREAK = re.compile(r"\r\n|\r|\n")
_BLANK_TAIL = re.compile(r"[ \t;%]*")


@dataclass(frozen=True, slots=True)
class DecodedText:
    text: str
    encoding: str
    note: str | None  # set when the bytes were not clean UTF-8


def _kana_count(text: str) -> int:
    return sum(1 for ch in text if "\u3040" <= ch <= "\u30ff")


def _halfwidth_kana_count(text: str) -> int:
    return sum(1 for ch in text if "\uff61" <= ch <= "\uff9f")


def _rare_hanzi_count(text: str) -> int:
    """Ideographs outside GB2312, the everyday Chinese set.

    Shift-JIS kanji read as GB18030 land mostly in GBK's extension rows: rare characters that
    no Chinese comment would be written in.
    """
    rare = 0
    for ch in text:
        if "\u4e00" <= ch <= "\u9fff":
            try:
                ch.encode("gb2312")
            except UnicodeEncodeError:
                rare += 1
    return rare


# What is looked at to tell a program text from a binary file: the start, as git does.
_SNIFF = 8000
# Control bytes that a program text may hold: tab, line ends, form feed, the tape reader's
# DC1-DC4 (ISO 840 device controls), and SUB, the end-of-file mark of DOS files.
_TEXT_CONTROLS = frozenset(b"\t\n\v\f\r\x11\x12\x13\x14\x1a")
_CONTROL_BYTES = bytes(b for b in range(32) if b not in _TEXT_CONTROLS)
_BINARY_SHARE = 0.05  # of the bytes looked at: control bytes no text holds
BINARY = "binary"  # ``DecodedText.encoding`` of bytes that are not program text


def not_text_reason(data: bytes) -> str | None:
    """Why ``data`` is not a program text, or None when it may be one: NUL bytes, or many other
    control bytes, in its first 8,000 bytes (after a punched tape's leader of NULs, the blank
    tape that carries only feed holes); a UTF-16 or UTF-32 byte order mark."""
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        return "it is UTF-32 text (save it as UTF-8 or ASCII)"
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return "it is UTF-16 text (save it as UTF-8 or ASCII)"
    leader = len(data) - len(data.lstrip(b"\0"))
    sample = data[leader : leader + _SNIFF].rstrip(b"\0")
    nul = sample.find(0)
    if nul >= 0:
        return (
            f"it holds NUL bytes (the first at byte {leader + nul + 1}): a binary file, or "
            "text saved as UTF-16"
        )
    controls = len(sample) - len(sample.translate(None, _CONTROL_BYTES))
    if controls > len(sample) * _BINARY_SHARE:
        return f"{controls} of its first {len(sample):,} bytes are control codes: a binary file"
    return None


def decode_bytes(data: bytes) -> DecodedText:
    """Decode a program file. UTF-8 first; then GB18030 or Shift-JIS (common in comments).

    Both legacy encodings accept most byte strings, so the choice is made on what the text
    looks like: Japanese comments have kana, Chinese ones do not; GB18030 bytes read as
    Shift-JIS turn into half-width katakana.

    Bytes that are not a program text (:func:`not_text_reason`) are not read: the text is
    empty, the encoding :data:`BINARY`, and the note says why.
    """
    reason = not_text_reason(data)
    if reason is not None:
        return DecodedText("", BINARY, f"not a program text: {reason}; the file is not analysed")
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    try:
        return DecodedText(data.decode("utf-8"), "utf-8", None)
    except UnicodeDecodeError:
        pass
    candidates: list[tuple[int, str, str]] = []
    for encoding in ("gb18030", "shift_jis"):
        try:
            text = data.decode(encoding)
        except UnicodeDecodeError:
            continue
        score = _kana_count(text) * 3 - _halfwidth_kana_count(text) * 5
        if encoding == "gb18030":
            score -= _kana_count(text) * 4  # kana decoded from GB bytes are unlikely
            score -= _rare_hanzi_count(text) * 2
        candidates.append((score, encoding, text))
    if candidates:
        candidates.sort(key=lambda c: -c[0])
        _, encoding, text = candidates[0]
        return DecodedText(text, encoding, f"file is not UTF-8; read as {encoding.upper()}")
    text = data.decode("latin-1")
    return DecodedText(text, "latin-1", "file is not UTF-8, GB18030 or Shift-JIS; read as Latin-1")


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


def cut_comments(line: str) -> LineCode:
    """Separate comments, EOB and tape marks from code, keeping columns."""
    if "(" not in line and ";" not in line and "%" not in line and ")" not in line:
        return LineCode(line, (), False, ())
    chars = list(line)
    comments: list[Comment] = []
    notes: list[LineNote] = []
    tape_mark = False
    i = 0
    n = len(line)
    balanced_closes: dict[int, int] | None = None  # worked out when a comment holds a '('
    while i < n:
        ch = line[i]
        if ch == "(":
            close = line.find(")", i + 1)
            if close < 0:
                comments.append(Comment(line[i + 1 :], shared_span(i, n), closed=False))
                notes.append(
                    LineNote(
                        "unclosed-comment",
                        "comment opened with '(' is not closed with ')' on this line",
                        shared_span(i, n),
                    )
                )
                for k in range(i, n):
                    chars[k] = " "
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
                            "parentheses nested in a comment: FANUC ends the comment at the "
                            f"first ')' (column {close + 1}) and reads "
                            f"{line[close + 1 : end + 1]!r} as program text",
                            shared_span(i, end + 1),
                        )
                    )
            comments.append(Comment(line[i + 1 : end], shared_span(i, end + 1)))
            for k in range(i, end + 1):
                chars[k] = " "
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
                    f"text after the end of block ';': {line[i + 1 : tail_end].strip()!r}",
                    shared_span(i + 1, tail_end),
                )
            )
            for k in range(i + 1, tail_end):
                chars[k] = " "
            i = tail_end
            continue
        elif ch == "%":
            tape_mark = True
            chars[i] = " "
        i += 1
    return LineCode("".join(chars), tuple(comments), tape_mark, tuple(notes))
