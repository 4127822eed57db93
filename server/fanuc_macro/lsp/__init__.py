"""The language server (fanuc-macro-ls): LSP over stdio on top of the analysis package.

The layer translates only: documents in, the package's diagnostics, facts and index out as
protocol types. :mod:`.server` makes the server. :mod:`.handlers` holds the handlers, top-level
functions registered from tables. :mod:`.engine` is the analysis job and the workspace's
documents, and :mod:`.scheduler` runs them on one worker thread. :mod:`.documents` keeps the
open texts, and :mod:`.folders` reads the workspace folders. :mod:`.features`,
:mod:`.navigation` and :mod:`.presentation` word the results. :mod:`.convert` converts
positions and diagnostics, and :mod:`.commands` runs the server's commands.
"""

from ..code_cache import install_code_cache

# Before server.py imports lsprotocol: its attrs classes are built from cached code.
install_code_cache("server")
