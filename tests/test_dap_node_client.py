"""The debug adapter through the DAP client VS Code's adapters are tested with: runs
tests/dap/debug_client.test.mjs (@vscode/debugadapter-testsupport's DebugClient) with node,
against ``python -m fanuc_macro.dap`` of this interpreter."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TEST = ROOT / "tests" / "dap" / "debug_client.test.mjs"
CLIENT = ROOT / "node_modules" / "@vscode" / "debugadapter-testsupport"
WAIT_S = 600  # a safety net for a hung run, not a time the test measures


def test_debug_client_drives_the_adapter() -> None:
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed: the DAP client test runs on node")
    if not CLIENT.is_dir():
        pytest.skip("node_modules has no @vscode/debugadapter-testsupport: run `npm ci` first")
    env = dict(os.environ)
    env["FANUC_MACRO_PYTHON"] = sys.executable
    # The adapter imports the fanuc_macro this test imports, installed or not.
    server = str(ROOT / "server")
    env["PYTHONPATH"] = os.pathsep.join(p for p in (server, env.get("PYTHONPATH", "")) if p)
    result = subprocess.run(
        [node, "--test", str(TEST)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=WAIT_S,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    # Every test ran and passed: none was skipped or left out.
    passed = re.search(r"^# pass (\d+)$", result.stdout, re.MULTILINE)
    assert passed is not None and int(passed.group(1)) >= 5, result.stdout
    assert "# fail 0" in result.stdout and "# skipped 0" in result.stdout, result.stdout
