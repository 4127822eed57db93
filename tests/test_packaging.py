"""What the packages ship and declare: the wheel and the sdist (``python -m build``, its build
requirements from PyPI) and the .vsix (``vsce package`` as ``npm run package`` calls it), each
built from a copy of the files it is made of, in a temporary folder."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VSCE = ROOT / "node_modules" / ".bin" / "vsce"
URL = "https://github.com/fanuc-macro/fanuc-macro"


def _copy(names: list[str], into: Path) -> None:
    for name in names:
        source = ROOT / name
        target = into / name
        target.parent.mkdir(parents=True, exist_ok=True)
        if source.is_dir():
            ignored = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
            shutil.copytree(source, target, ignore=ignored)
        else:
            shutil.copy2(source, target)


def test_wheel_and_sdist_ship_the_licence_and_declare_it_without_warnings(
    tmp_path: Path,
) -> None:
    pytest.importorskip("build")
    source = tmp_path / "source"
    _copy(["pyproject.toml", "README.md", "LICENSE", "server/fanuc_macro"], source)
    done = subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(tmp_path / "dist"), str(source)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    said = done.stdout + done.stderr
    assert not re.search(r"licen[cs]e", "\n".join(re.findall(r"(?im)^.*warn.*$", said)), re.I)
    assert "project.license" not in said

    [wheel] = (tmp_path / "dist").glob("*.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        info = next(n.split("/")[0] for n in names if n.endswith(".dist-info/METADATA"))
        assert f"{info}/licenses/LICENSE" in names
        licence = archive.read(f"{info}/licenses/LICENSE").decode()
        metadata = archive.read(f"{info}/METADATA").decode()
    assert licence == (ROOT / "LICENSE").read_text("utf-8")
    assert "Copyright (c) 2026 the fanuc-macro authors" in licence
    headers = metadata.split("\n\n", 1)[0].splitlines()
    assert "License-Expression: MIT" in headers and "License-File: LICENSE" in headers
    assert "Author: the fanuc-macro authors" in headers
    for url in (f"Homepage, {URL}", f"Issues, {URL}/issues"):
        assert f"Project-URL: {url}" in headers
    for classifier in (
        "Programming Language :: Python :: 3.10",
        "Programming Language :: Python :: 3.13",
        "Operating System :: OS Independent",
        "Intended Audience :: Manufacturing",
    ):
        assert f"Classifier: {classifier}" in headers
    requires = [h for h in headers if h.startswith("Requires-Dist: ")]
    assert [h for h in requires if "numpy" in h] == [
        'Requires-Dist: numpy>=1.26; extra == "test"'  # not needed to run, only to test
    ]

    [sdist] = (tmp_path / "dist").glob("*.tar.gz")
    with tarfile.open(sdist) as archive:
        top = archive.getnames()[0].split("/")[0]
        member = archive.extractfile(f"{top}/LICENSE")
        assert member is not None and member.read().decode() == licence


@pytest.mark.skipif(
    shutil.which("node") is None or not VSCE.exists(), reason="node or vsce is not installed"
)
def test_vsix_ships_the_licence_and_the_icon(tmp_path: Path) -> None:
    manifest = json.loads((ROOT / "package.json").read_text("utf-8"))
    assert manifest["license"] == "MIT"
    assert manifest["repository"]["url"] == f"{URL}.git"
    assert manifest["bugs"]["url"] == f"{URL}/issues"
    # The files the .vscodeignore lets in (the client built by esbuild stands in as a stub).
    shipped = [
        "package.json",
        ".vscodeignore",
        "README.md",
        "LICENSE",
        manifest["icon"],
        "language-configuration.json",
        "grammars",
        "snippets",
        "l10n",
        "docs/rules.md",
        "media/walkthrough",
        "samples",
        *(p.name for p in ROOT.glob("package.nls*.json")),
    ]
    folder = tmp_path / "extension"
    _copy(shipped, folder)
    for stub in ("client/out/extension.js", "client/out/webview/toolpath.js"):
        (folder / stub).parent.mkdir(parents=True, exist_ok=True)
        (folder / stub).write_text("// built by esbuild\n")
    # The flags of `npm run package`.
    flags = manifest["scripts"]["package"].split("vsce package", 1)[1].split()
    vsix = tmp_path / "fanuc-macro.vsix"
    done = subprocess.run(
        [str(VSCE), "package", *flags, "--out", str(vsix)],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    with zipfile.ZipFile(vsix) as archive:
        names = set(archive.namelist())
        vsix_manifest = archive.read("extension.vsixmanifest").decode()
    # vsce ships the LICENSE file as LICENSE.txt and names it the licence, the icon the icon.
    assert {"extension/LICENSE.txt", f"extension/{manifest['icon']}"} <= names, sorted(names)
    assert "<License>extension/LICENSE.txt</License>" in vsix_manifest
    assert f"<Icon>extension/{manifest['icon']}</Icon>" in vsix_manifest
    assert f'"Microsoft.VisualStudio.Services.Links.Support" Value="{URL}/issues"' in vsix_manifest
