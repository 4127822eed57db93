"""Between the package's positions (code points) and the protocol's (client code units), and from
package diagnostics to LSP diagnostics.

The package counts columns in characters. LSP counts UTF-16 code units unless the client and
server agreed on another encoding, so a character outside the Basic Multilingual Plane counts
twice. Lines here are split as LSP splits them: on CRLF, CR and LF only (``str.splitlines``
would also split on form feeds and U+2028, and shift every line after them).
"""

from __future__ import annotations

import json
import re
from array import array
from collections.abc import Callable, Sequence
from types import MappingProxyType
from typing import overload

from lsprotocol import types

from ..diagnostics import Diagnostic, Severity, Tag

LINE_BREAK = re.compile(r"\r\n|\r|\n")
SOURCE = "fanuc-macro"

UTF8 = types.PositionEncodingKind.Utf8.value
UTF16 = types.PositionEncodingKind.Utf16.value
UTF32 = types.PositionEncodingKind.Utf32.value


def line_starts(text: str) -> array[int]:
    """Where each line of ``text`` begins, as LSP numbers them: CRLF, CR and LF each end a
    line, and a final line break opens an empty line. An array of machine integers: 8 bytes a
    line, where a list of ints held about 36 (its slot and an int object for each offset)."""
    return array("q", [0, *(m.end() for m in LINE_BREAK.finditer(text))])


class TextLines(Sequence[str]):
    """The lines of a text as :func:`line_starts` numbers them, cut from the text when asked for:
    a list of lines is a second copy of a document's text, one string per line (about 130
    bytes a line: 13 MB for 100,000 blocks), while the text and its line starts are kept for
    the edits anyway (:class:`~.documents.OpenDocument`) and are shared here."""

    __slots__ = ("_starts", "_text")

    def __init__(self, text: str, starts: Sequence[int]) -> None:
        self._text = text
        self._starts = starts  # never mutated: an edit makes a new list

    def __len__(self) -> int:
        return len(self._starts)

    @overload
    def __getitem__(self, index: int) -> str: ...

    @overload
    def __getitem__(self, index: slice) -> list[str]: ...

    def __getitem__(self, index: int | slice) -> str | list[str]:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        starts = self._starts
        count = len(starts)
        if index < 0:
            index += count
        if not 0 <= index < count:
            raise IndexError(index)
        end = starts[index + 1] if index + 1 < count else len(self._text)
        # The slice ends with its line break alone: a line holds no CR or LF.
        return self._text[starts[index] : end].rstrip("\r\n")


class Codec:
    """Column conversion for one position encoding."""

    def __init__(self, encoding: object = UTF16) -> None:
        name = str(getattr(encoding, "value", encoding))  # an lsprotocol enum or its value
        self.encoding = name if name in (UTF8, UTF16, UTF32) else UTF16

    def units(self, text: str) -> int:
        if self.encoding == UTF32 or text.isascii():
            return len(text)
        if self.encoding == UTF16:
            return len(text.encode("utf-16-le", "surrogatepass")) // 2
        return len(text.encode("utf-8", "surrogatepass"))

    def to_client(self, line: str, column: int) -> int:
        """Code-point column -> client units; past the end of the line counts one per column."""
        column = max(0, column)
        if column <= len(line):
            return self.units(line[:column])
        return self.units(line) + column - len(line)

    def from_client(self, line: str, units: int) -> int:
        """Client units -> code-point column, clamped to the line; a split pair goes before."""
        if units <= 0:
            return 0
        if self.encoding == UTF32 or line.isascii():
            return min(units, len(line))
        count = 0
        for i, ch in enumerate(line):
            width = self._width(ch)
            if count + width > units:
                return i
            count += width
        return len(line)

    def _width(self, ch: str) -> int:
        code = ord(ch)
        if self.encoding == UTF16:
            return 2 if code > 0xFFFF else 1
        if code < 0x80:
            return 1
        if code < 0x800:
            return 2
        if code < 0x10000:
            return 3
        return 4


class Lines:
    """The lines of one analysed text, with conversions of positions in it."""

    def __init__(self, lines: Sequence[str], codec: Codec) -> None:
        self.lines = lines
        self.codec = codec

    def text(self, line: int) -> str:
        return self.lines[line] if 0 <= line < len(self.lines) else ""

    def position(self, line: int, column: int) -> types.Position:
        line = max(0, line)
        return types.Position(line=line, character=self.codec.to_client(self.text(line), column))

    def range(self, line: int, column: int, end_line: int, end_column: int) -> types.Range:
        return types.Range(
            start=self.position(line, column), end=self.position(end_line, end_column)
        )

    def column(self, position: types.Position) -> int:
        return self.codec.from_client(self.text(position.line), position.character)


SEVERITY = MappingProxyType(
    {
        Severity.ERROR: types.DiagnosticSeverity.Error,
        Severity.WARNING: types.DiagnosticSeverity.Warning,
        Severity.INFORMATION: types.DiagnosticSeverity.Information,
        Severity.HINT: types.DiagnosticSeverity.Hint,
    }
)


# The rules' tags (diagnostics.Tag) in the protocol's terms.
TAG = MappingProxyType(
    {
        Tag.UNNECESSARY: types.DiagnosticTag.Unnecessary,
        Tag.DEPRECATED: types.DiagnosticTag.Deprecated,
    }
)


def rule_url(code: str, locale: str = "en") -> str:
    """The section of docs/rules.md that documents ``code`` (of docs/rules.zh-cn.md for a
    Chinese reader)."""
    # Imported here: the server answers initialize before it loads the analysis.
    from ..rules_doc import rule_url as url

    return url(code, locale)


def _json_safe(data: dict[str, object]) -> dict[str, object]:
    out: dict[str, object] = {}
    for key, value in data.items():
        try:
            json.dumps(value)
        except (TypeError, ValueError):
            value = str(value)
        out[str(key)] = value
    return out


Resolver = Callable[[str], "tuple[str, Lines] | None"]


def to_lsp_diagnostic(
    diag: Diagnostic,
    key: str,
    uri: str,
    lines: Lines,
    resolve: Resolver | None = None,
    locale: str = "en",
) -> types.Diagnostic:
    """One package diagnostic in the protocol's terms.

    ``key`` is the document's name in the package, ``uri`` the client's name for it. A related
    place in another document is converted with that document's lines and client URI, which
    ``resolve`` gives for a package key. The rule's link is to the page in ``locale``.
    """
    related: list[types.DiagnosticRelatedInformation] = []
    for r in diag.related:
        r_uri, r_lines = uri, lines
        if r.uri is not None and r.uri != key:
            found = resolve(r.uri) if resolve is not None else None
            r_uri, r_lines = found if found is not None else (r.uri, Lines((), lines.codec))
        related.append(
            types.DiagnosticRelatedInformation(
                location=types.Location(
                    uri=r_uri, range=r_lines.range(r.line, r.column, r.line, r.end_column)
                ),
                message=r.message,
            )
        )
    tags = [TAG[tag] for tag in sorted(diag.tags)] if diag.tags else None
    data: dict[str, object] = {"code": diag.code}
    if diag.data:
        data.update(_json_safe(diag.data))
    return types.Diagnostic(
        range=lines.range(diag.line, diag.column, diag.end_line, diag.end_column),
        message=diag.message,
        severity=SEVERITY.get(diag.severity, types.DiagnosticSeverity.Warning),
        code=diag.code,
        code_description=types.CodeDescription(href=rule_url(diag.code, locale)),
        source=SOURCE,
        related_information=related or None,
        tags=tags,
        data=data,
    )


class ConvertedDiagnostics:
    """The protocol's form of one document's diagnostics, kept from one analysis to the next:
    after an edit most diagnostics are the ones before, on the same lines, and converting each
    again (ranges in the client's units, related places, the rule's link) is most of the cost
    of publishing them."""

    def __init__(self) -> None:
        self._last: dict[object, types.Diagnostic] = {}

    def convert(
        self,
        diags: Sequence[Diagnostic],
        key: str,
        uri: str,
        lines: Lines,
        resolve: Resolver | None = None,
        locale: str = "en",
    ) -> list[types.Diagnostic]:
        kept: dict[object, types.Diagnostic] = {}
        out: list[types.Diagnostic] = []
        for diag in diags:
            if any(r.uri is not None and r.uri != key for r in diag.related):
                # A place in another document: its lines are not this one's to compare.
                out.append(to_lsp_diagnostic(diag, key, uri, lines, resolve, locale))
                continue
            # What the converted form depends on: the diagnostic (its data apart, which it
            # does not compare), the lines its ranges are on, the client's name and units.
            text = lines.text
            identity = (
                diag,
                repr(diag.data) if diag.data else None,
                text(diag.line),
                text(diag.end_line),
                tuple(text(r.line) for r in diag.related),
                uri,
                lines.codec.encoding,
                locale,
            )
            converted = self._last.get(identity)
            if converted is None:
                converted = to_lsp_diagnostic(diag, key, uri, lines, resolve, locale)
            kept[identity] = converted
            out.append(converted)
        self._last = kept
        return out
