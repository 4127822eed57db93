"""The extension in a real VS Code: tests/browser/run_browser_test.sh in pytest.

It installs code-server, Node.js 24 and playwright-core from the npm registry (cached in
tests/browser/node_modules), chromium from Debian if missing, builds the .vsix and checks in
headless Chromium the language mode, the highlighting, an MB601 diagnostic, a hover, the
extension's workbench parts (no colour swatch on `#101`, the status bar item with the controller,
a rule code's link opening the shipped rules page, the Settings UI's group title), navigation
(rename, document highlight, folding, selection ranges, formatting, workspace symbols, the call
hierarchy), semantic tokens, a code lens,
signature help, the Toolpath view (drawn, a click on a segment reveals its block, the cursor's
block lit), the trace view (a row's values, its link and F12 to the block) and the debugger (a
breakpoint, Debug This Program, the stop's Variables, the Toolpath view lighting the stopped
block), and Insert Arc Thread Program... with its defaults. It takes minutes on a first run, so
it only runs when FANUC_MACRO_BROWSER_TEST=1.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parent / "run_browser_test.sh"
LIMIT_S = 2400  # a first run (npm ci, code-server's native modules, apt) took about 5 minutes

pytestmark = pytest.mark.skipif(
    os.environ.get("FANUC_MACRO_BROWSER_TEST") != "1",
    reason="browser test of the extension in code-server + chromium: "
    "set FANUC_MACRO_BROWSER_TEST=1 to run it (or run tests/browser/run_browser_test.sh)",
)


@pytest.mark.timeout(LIMIT_S + 120)
def test_extension_in_code_server(tmp_path: Path) -> None:
    out = tmp_path / "browser"
    env = {**os.environ, "FANUC_MACRO_PYTHON": sys.executable, "FANUC_MACRO_BROWSER_OUT": str(out)}
    try:
        # timeout sends TERM first: the script then ends code-server itself.
        proc = subprocess.run(
            ["timeout", "-k", "60", str(LIMIT_S), "bash", str(SCRIPT)],
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            check=False,
        )
    finally:
        # The script removes this file once it has ended code-server: if it is still there,
        # the script was killed before its cleanup, so end code-server here.
        pgid_file = out / "code-server.pgid"
        if pgid_file.exists():
            with contextlib.suppress(ProcessLookupError, PermissionError, ValueError):
                os.killpg(int(pgid_file.read_text().strip()), signal.SIGKILL)
    print(proc.stdout)  # shown with -s, -rP, or on failure
    tail = "\n".join(proc.stdout.splitlines()[-60:])
    assert proc.returncode == 0, f"run_browser_test.sh exited {proc.returncode}:\n{tail}"
    assert "PASS diagnostics" in proc.stdout, tail
    assert "PASS hover" in proc.stdout, tail
    ui = ("no colour swatch", "status bar controller", "rule documentation link", "settings title")
    navigation = (
        "rename",
        "document highlight",
        "folding",
        "selection ranges",
        "formatting",
        "workspace symbols",
        "call hierarchy",
    )
    tokens = ("semantic tokens", "code lens", "signature help")
    views = ("toolpath view", "toolpath click", "toolpath cursor", "trace view", "trace link")
    debugger = ("debug", "debug toolpath")
    generators = ("arc thread program", "thread module options")
    for check in (*ui, *navigation, *tokens, *views, *debugger, *generators):
        assert f"PASS {check}:" in proc.stdout, tail
