"""The language server (fanuc-macro-ls): LSP over stdio on top of the analysis package.

The layer translates only: documents in, the package's diagnostics, facts and index out as
protocol types. :mod:`.server` makes the server. :mod:`.handlers` holds the handlers, top-level
functions registered from tables. :mod:`.engine` is the analysis job and the workspace's
documents, and :mod:`.scheduler` runs them on one worker thread. :mod:`.documents` keeps the
open texts, and :mod:`.folders` reads the workspace folders. :mod:`.features`,
:mod:`.navigation` and :mod:`.presentation` word the results. :mod:`.convert` converts
positions and diagnostics, and :mod:`.commands` runs the server's commands.
"""

import gc
import os
import sys


def _started_as_server(argv: list[str]) -> bool:
    """Whether the command line runs the language server: ``fanuc-macro-ls`` or
    ``python -m fanuc_macro.lsp.server``."""
    script = os.path.basename(argv[1]) if len(argv) > 1 else ""
    return script.lower().startswith("fanuc-macro-ls") or argv[1:3] == [
        "-m",
        "fanuc_macro.lsp.server",
    ]


def run_on_the_c_allocator() -> None:
    """Start the language server again on the C allocator (``PYTHONMALLOC=malloc``), before it
    imports anything. Python's own allocator gives an arena of 1 MiB back only when no object
    in it lives, so a few long-lived objects made while a big document was analysed keep its
    memory after the document is closed (20 MB after 5,000 typed lines); glibc's ``malloc``
    returns it (``engine.release_memory``). An allocator the user set is kept; Windows, where
    ``exec`` starts another process, keeps Python's."""
    argv = getattr(sys, "orig_argv", [])
    if "PYTHONMALLOC" in os.environ or sys.platform == "win32" or not sys.executable:
        return
    if not _started_as_server(argv):
        return
    os.environ["PYTHONMALLOC"] = "malloc"
    try:
        os.execv(sys.executable, [sys.executable, *argv[1:]])
    except OSError:  # the interpreter cannot be started again: go on with Python's allocator
        del os.environ["PYTHONMALLOC"]


def pause_the_collector() -> None:
    """No cyclic garbage collection from the server's start until ``initialize`` is answered
    (:func:`resume_the_collector`). The start makes some 55,000 objects that live as long as
    the process (lsprotocol's 570 classes, pygls' 600 typed overloads, cattrs' hooks) and no
    garbage cycle: the collector ran 120 times over the growing heap, for nothing. Nothing is
    frozen out of later collections (``gc.freeze``): the collection at the resumption scans
    what the start made once, and frees what it finds."""
    if gc.isenabled() and _started_as_server(getattr(sys, "orig_argv", [])):
        gc.disable()


def resume_the_collector() -> None:
    """The collector back on, after one full collection, if it is paused: what the start made
    is then in the oldest generation, as if collected as it grew. Called once a server
    (``AnsweringProtocol.resume_collector``), before anything else could pause it."""
    if not gc.isenabled():
        gc.collect()
        gc.enable()


run_on_the_c_allocator()
pause_the_collector()

# Imported in the process started again only (it loads pathlib and re). Before server.py
# imports lsprotocol: its attrs classes are built from cached code.
from ..code_cache import install_code_cache  # noqa: E402

install_code_cache("server")
