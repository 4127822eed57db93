"""The command line as a user runs it: ``python -m fanuc_macro.cli ...`` in a subprocess, with
this checkout's package, for the CLI tests."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def run(cwd: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "server")
    return subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        encoding="utf-8",
        timeout=120,
    )


def check_text(tmp_path: Path, text: str, *options: str) -> list[dict[str, Any]]:
    """``check --format json`` of ``text`` saved as part.nc: the diagnostics."""
    (tmp_path / "part.nc").write_text(text)
    result = run(tmp_path, "check", "--format", "json", *options, "part.nc")
    assert result.returncode in (0, 1), result.stdout + result.stderr
    found: list[dict[str, Any]] = json.loads(result.stdout)
    return found
