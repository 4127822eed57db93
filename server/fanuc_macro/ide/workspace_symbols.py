"""Workspace symbols: every O program (its first comment as the detail) and N label of the
workspace's documents whose name holds the query, in the order of the documents' keys and lines.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..syntax.tree import Span
from .data import Location, Range, SymbolKind
from .view import Indexed, comment_of, first_comment

# How many symbols one answer holds at most: a workspace of programs numbered N10, N20, ... on
# every block has hundreds of thousands of labels, and a client filters as it is typed.
MAX_SYMBOLS = 2000


@dataclass(frozen=True)
class WorkspaceSymbol:
    name: str
    detail: str
    kind: SymbolKind
    location: Location  # the program's O line, or the label's N word
    container: str  # the program of a label; "" for a program


def workspace_symbols(documents: Mapping[str, Indexed], query: str) -> list[WorkspaceSymbol]:
    """The programs and labels whose name holds ``query`` (case-insensitive): the programs
    first, then the labels, each by document key and line."""
    wanted = query.strip().upper()
    out: list[WorkspaceSymbol] = []
    labels: list[WorkspaceSymbol] = []
    for key in sorted(documents):
        doc, index = documents[key]
        blocks = doc.blocks
        found: list[WorkspaceSymbol] = []
        for program in index.programs:
            name = program.display_name
            if program.number is not None and program.name:
                name += f" <{program.name}>"
            header = program.header_line if program.header_line is not None else program.first_line
            if header < len(blocks) and wanted in name.upper():
                block = blocks[header]
                span = block.statement.span if block.statement is not None else Span(0, 0)
                out.append(
                    WorkspaceSymbol(
                        name,
                        first_comment(doc, program),
                        SymbolKind.SUBPROGRAM if program.returns else SymbolKind.MAIN_PROGRAM,
                        Location(key, Range.of(header, span.start, header, span.end)),
                        "",
                    )
                )
            for seq, lines in sorted(program.labels.items()):
                label = f"N{seq}"
                if wanted not in label:
                    continue
                for line in lines:
                    block = blocks[line]
                    span = block.parsed.seq_span or Span(0, 0)
                    found.append(
                        WorkspaceSymbol(
                            label,
                            comment_of(block),
                            SymbolKind.LABEL,
                            Location(key, Range.of(line, span.start, line, span.end)),
                            program.display_name,
                        )
                    )
        found.sort(key=lambda s: s.location.range.start)
        labels.extend(found[: MAX_SYMBOLS - len(labels)])
    return (out + labels)[:MAX_SYMBOLS]
