"""The repository's pre-commit hook, run by pre-commit itself (try-repo), and the composite
GitHub Action's steps, run by bash as a runner runs them."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
FAULTY = "O1000\n#1=93.82\nM#1\nM30\n"
GOOD = "O2000\nG00 X10. Z2.\nM30\n"


def _git(cwd: Path, *args: str) -> None:
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", *args],
        cwd=cwd, check=True, capture_output=True,
    )  # fmt: skip


@pytest.mark.timeout(900)
def test_the_pre_commit_hook_fails_a_faulty_program_and_passes_a_good_one(tmp_path: Path) -> None:
    if shutil.which("git") is None or shutil.which("pre-commit") is None:
        pytest.skip("git and pre-commit (the test extra) are needed")
    shop = tmp_path / "shop"
    shop.mkdir()
    (shop / "bad.nc").write_text(FAULTY, encoding="utf-8")
    (shop / "good.nc").write_text(GOOD, encoding="utf-8")
    (shop / "notes.md").write_text("not a program\n", encoding="utf-8")
    _git(shop, "init", "-q")
    _git(shop, "add", ".")
    env = {**os.environ, "PRE_COMMIT_HOME": str(tmp_path / "cache")}

    def hook(*files: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            ["pre-commit", "try-repo", str(ROOT), "fanuc-macro", "--files", *files],
            cwd=shop, env=env, capture_output=True, text=True, timeout=840,
        )  # fmt: skip

    failed = hook("bad.nc", "notes.md")
    assert failed.returncode == 1, failed.stdout + failed.stderr
    assert "bad.nc:3:" in failed.stdout and "MB601" in failed.stdout
    passed = hook("good.nc", "notes.md")
    assert passed.returncode == 0, passed.stdout + passed.stderr


def _shim(folder: Path) -> dict[str, str]:
    """An environment whose ``fanuc-macro`` is this checkout's, as the action installs it."""
    folder.mkdir()
    script = folder / "fanuc-macro"
    server = ROOT / "server"
    script.write_text(
        f'#!/bin/sh\nPYTHONPATH="{server}" exec "{sys.executable}" -m fanuc_macro.cli "$@"\n'
    )
    script.chmod(0o755)
    return {**os.environ, "PATH": f"{folder}{os.pathsep}{os.environ['PATH']}"}


def test_the_action_s_steps_write_sarif_and_annotations_and_fail_on_an_error(
    tmp_path: Path,
) -> None:
    action = yaml.safe_load((ROOT / "action.yml").read_text("utf-8"))
    assert action["runs"]["using"] == "composite"
    steps = {step.get("name", ""): step for step in action["runs"]["steps"]}
    work = tmp_path / "work"
    (work / "programs").mkdir(parents=True)
    (work / "programs" / "o1000.nc").write_text(FAULTY, encoding="utf-8")
    (work / "programs" / "o2000.nc").write_text(GOOD, encoding="utf-8")
    env = _shim(tmp_path / "bin")
    env["GITHUB_OUTPUT"] = str(tmp_path / "output")
    inputs = {name: value["default"] for name, value in action["inputs"].items()}
    inputs["paths"] = "programs"

    def run_step(name: str) -> subprocess.CompletedProcess[str]:
        step = steps[name]
        assert step["shell"] == "bash"
        step_env = dict(env)
        for key, value in step.get("env", {}).items():
            step_env[key] = value.replace("${{ inputs.paths }}", inputs["paths"]).replace(
                "${{ inputs.args }}", inputs["args"]
            )
        return subprocess.run(
            ["bash", "-e", "-c", step["run"]], cwd=work, env=step_env,
            capture_output=True, text=True, timeout=120,
        )  # fmt: skip

    checked = run_step("Check the programs (SARIF)")
    assert checked.returncode == 0, checked.stderr
    log = json.loads((work / "fanuc-macro.sarif").read_text("utf-8"))
    assert [r["ruleId"] for r in log["runs"][0]["results"]] == ["MB601"]
    assert "sarif-file=fanuc-macro.sarif" in (tmp_path / "output").read_text("utf-8")
    upload = steps["Upload to code scanning"]
    assert upload["with"]["sarif_file"] == "fanuc-macro.sarif"
    annotated = run_step("Annotate and set the exit status")
    assert annotated.returncode == 1
    assert annotated.stdout.startswith("::error file=programs/o1000.nc,line=3,")
