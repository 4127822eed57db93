"""The language server in a real editor: headless Neovim starts it, shows its diagnostics and
asks for a hover (tests/nvim/init.lua writes what it got to a JSON file)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
INIT = ROOT / "tests" / "nvim" / "init.lua"
NVIM = shutil.which("nvim")


@pytest.mark.skipif(NVIM is None, reason="nvim (Neovim) is not on PATH")
def test_neovim_shows_diagnostics_and_hover(tmp_path: Path) -> None:
    assert NVIM is not None
    out = tmp_path / "result.json"
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(
            p for p in (str(ROOT / "server"), os.environ.get("PYTHONPATH", "")) if p
        ),
        "FANUC_NVIM_OUT": str(out),
        "FANUC_NVIM_SEED": str(SEEDS / "o2_arc_thread_roughing.nc"),
        "FANUC_NVIM_ROOT": str(SEEDS),
        "FANUC_NVIM_PYTHON": sys.executable,
        "FANUC_NVIM_TIMEOUT": "60000",
        # "N22 G54 S#19 M#1": the hover asks about #1 (0-based line 29, column 14).
        "FANUC_NVIM_HOVER_LINE": "29",
        "FANUC_NVIM_HOVER_COL": "14",
        "XDG_STATE_HOME": str(tmp_path / "state"),  # Neovim's LSP log goes there
        "XDG_DATA_HOME": str(tmp_path / "data"),
        "XDG_CACHE_HOME": str(tmp_path / "cache"),
    }
    done = subprocess.run(
        [NVIM, "--headless", "-n", "-i", "NONE", "--noplugin", "-u", str(INIT)],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=150,
    )
    assert out.exists(), f"nvim wrote no result (rc {done.returncode}): {done.stderr[-2000:]}"
    result = json.loads(out.read_text("utf-8"))
    assert "error" not in result, result
    assert result["got_diagnostics"], result
    mb601 = [d for d in result["diagnostics"] if d["code"] == "MB601"]
    assert {d["lnum"] for d in mb601} == {29, 63}, result["diagnostics"]
    assert all(d["source"] == "fanuc-macro" and "93.82" in d["message"] for d in mb601)
    assert "#1" in result["hover"] and "93.82" in result["hover"], result
