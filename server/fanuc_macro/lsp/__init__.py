"""The language server (fanuc-macro-ls): LSP over stdio on top of the analysis package.

The layer translates only: documents in, the package's analysis and facts out as protocol types.
"""

from __future__ import annotations

__all__ = ["main"]


def main() -> int:
    """Entry point, without importing the server before it is needed (``--version`` is fast)."""
    from .server import main as server_main

    return server_main()
