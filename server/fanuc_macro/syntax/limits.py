"""How much of a program the analysis reads. It imports nothing: the settings need it, and the
language server reads its settings before it loads the syntax."""

from __future__ import annotations

from dataclasses import dataclass

# FANUC's manuals cited here give no limit on the
# length of a block; a longer line is almost surely not a program (a corrupt or binary file),
# and reading it would cost time and memory for nothing.
MAX_LINE_LENGTH = 1024


@dataclass(frozen=True, slots=True)
class ReadLimits:
    """Lines longer than ``max_line_length`` are not analysed, nor the blocks past
    ``max_blocks`` or ``max_characters`` of a document (None: no such limit). A diagnostic says
    what was left out (MB011, MB013)."""

    max_line_length: int = MAX_LINE_LENGTH
    max_blocks: int | None = None
    max_characters: int | None = None


READ_WHOLE = ReadLimits()  # every block of the document; the limit on one line only
