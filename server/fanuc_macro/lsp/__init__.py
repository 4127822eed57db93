"""The language server (fanuc-macro-ls): LSP over stdio on top of the analysis package.

The layer translates only: documents in, the package's diagnostics, facts and index out as
protocol types. :mod:`.server` wires the protocol, :mod:`.engine` schedules the analyses in a
worker thread, :mod:`.features` words the results, :mod:`.convert` converts positions.
"""

from ..code_cache import install_code_cache

# Before server.py imports lsprotocol: its attrs classes are built from cached code.
install_code_cache("server")
