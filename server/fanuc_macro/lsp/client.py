"""What the client can show, as it says in ``initialize``: read by the features."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class CompletionSupport:
    snippets: bool = False
    markdown: bool = False
    builtin_snippets: bool = False  # the client has the snippets already (VS Code extension)
