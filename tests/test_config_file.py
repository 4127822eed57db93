"""The configuration file: found nearest first, extended, checked key by key with the file and
line named, its schema agreeing with the loader; and the command line reading it under its own
options (command line > file > defaults), through a subprocess."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from cli_runner import run
from fanuc_macro.config_file import (
    KEYS,
    ConfigFileError,
    find_config_file,
    json_schema,
    load_config_file,
)

ROOT = Path(__file__).resolve().parents[1]
SPINDLE = "O1000\nG97 S5000 M03\nG00 X10. Z2.\nM30\n"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_the_nearest_file_is_found_looking_up_and_a_pyproject_needs_its_table(
    tmp_path: Path,
) -> None:
    write(tmp_path / "fanuc-macro.toml", "[machine]\ncontroller = '0i-TF'\n")
    write(tmp_path / "jobs" / "pyproject.toml", "[project]\nname = 'x'\n")  # not ours
    program = write(tmp_path / "jobs" / "a" / "o1000.nc", SPINDLE)
    assert find_config_file(program) == (tmp_path / "fanuc-macro.toml").resolve()
    write(tmp_path / "jobs" / "pyproject.toml", "[tool.fanuc-macro.machine]\ncontroller = '30i'\n")
    assert find_config_file(program) == (tmp_path / "jobs" / "pyproject.toml").resolve()
    assert load_config_file(tmp_path / "jobs" / "pyproject.toml").settings == {"controller": "30i"}
    write(tmp_path / "jobs" / "a" / "fanuc-macro.toml", "")
    assert find_config_file(program) == (tmp_path / "jobs" / "a" / "fanuc-macro.toml").resolve()


def test_extend_reads_the_parent_first_and_the_nearer_file_wins(tmp_path: Path) -> None:
    write(
        tmp_path / "shop.toml",
        "[machine]\ncontroller = '0i-TF'\nmax-spindle-speed = 8000\n\n"
        "[rules]\nignore = ['MB403']\n",
    )
    child = write(
        tmp_path / "lathe" / "fanuc-macro.toml",
        "extend = '../shop.toml'\n[machine]\nmax-spindle-speed = 3000\n",
    )
    found = load_config_file(child)
    assert found.settings == {
        "controller": "0i-TF",
        "machine": {"maxSpindleSpeed": 3000},
        "rules": {"disabled": ["MB403"]},
    }
    assert str(found.origins["machine.max-spindle-speed"]).endswith("fanuc-macro.toml:3")
    assert str(found.origins["machine.controller"]).endswith("shop.toml:2")
    assert str(found.origins["rules.ignore"]).endswith("shop.toml:6")
    assert found.files == [child.resolve(), (tmp_path / "shop.toml").resolve()]


def test_rules_are_named_by_code_or_name_and_kept_as_codes(tmp_path: Path) -> None:
    file = write(
        tmp_path / "fanuc-macro.toml",
        '[rules]\nignore = ["mb006", "call-target-missing"]\nseverity = { MB403 = "hint" }\n',
    )
    rules = load_config_file(file).settings["rules"]
    assert rules == {"disabled": ["MB006", "MB403"], "severity": {"MB403": "hint"}}


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[machine]\ncontroler = '0i-TF'\n", ":2: machine.controler is not a key of [machine]"),
        ("[machine]\n\nmax-spindle-speed = 'fast'\n", ":3: machine.max-spindle-speed: 'fast' is"),
        ("[machine]\nmax-spindle-speed = -5\n", ":2: machine.max-spindle-speed: -5 is not above"),
        ("[machine]\ncontroller = '0i-XX'\n", ":2: machine.controller: '0i-XX' is not one of"),
        ("[rules]\nignore = ['MB999']\n", ":2: rules.ignore: 'MB999' is not a rule"),
        ("[rules]\nseverity = { MB403 = 'loud' }\n", ":2: rules.severity: 'loud' is not a"),
        ("[machin]\ncontroller = '0i-TF'\n", ":1: 'machin' is not a table of it"),
        ("[machine\ncontroller = 1\n", "not TOML: "),
        ("machine.controller = 7\n", ":1: machine.controller: 7 is not a string"),
    ],
)
def test_a_bad_file_is_named_with_its_line_and_key(tmp_path: Path, text: str, message: str) -> None:
    file = write(tmp_path / "fanuc-macro.toml", text)
    with pytest.raises(ConfigFileError) as caught:
        load_config_file(file)
    assert str(file.resolve()) in str(caught.value)
    assert message in str(caught.value)


def test_an_extend_loop_is_an_error_not_a_hang(tmp_path: Path) -> None:
    write(tmp_path / "a.toml", "extend = 'b.toml'\n")
    write(tmp_path / "b.toml", "extend = 'a.toml'\n")
    with pytest.raises(ConfigFileError, match="extend makes a loop"):
        load_config_file(tmp_path / "a.toml")


def test_the_schema_is_valid_and_agrees_with_the_loader(tmp_path: Path) -> None:
    schema = json_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    good = {
        "machine": {"controller": "0i-MF", "max-spindle-speed": 8000, "custom-calls": {"T": 9000}},
        "rules": {"ignore": ["MB403"]},
        "analysis": {"max-blocks": 100},
        "format": {"space-between-words": "always"},
    }
    assert list(validator.iter_errors(good)) == []
    bad = [
        {"machine": {"controller": "0i-XX"}},
        {"machine": {"max-spindle-speed": "fast"}},
        {"machine": {"unknown": 1}},
        {"analysis": {"max-blocks": 0}},
        {"rules": {"ignore": "MB403"}},
    ]
    for number, table in enumerate(bad):
        assert list(validator.iter_errors(table)), table
        lines = [
            f"[{section}]\n" + "".join(f"{k} = {json.dumps(v)}\n" for k, v in body.items())
            for section, body in table.items()
        ]
        file = write(tmp_path / f"bad{number}" / "fanuc-macro.toml", "".join(lines))
        with pytest.raises(ConfigFileError):
            load_config_file(file)
    assert {k.dotted for k in KEYS} == {
        f"{section}.{name}"
        for section, body in schema["properties"].items()
        if section != "extend"
        for name in body["properties"]
    }


def test_the_published_schema_is_the_one_the_keys_give() -> None:
    published = json.loads((ROOT / "docs" / "fanuc-macro.schema.json").read_text("utf-8"))
    assert published == json_schema(), "run: fanuc-macro config --format schema"


def test_every_editor_setting_of_the_analysis_has_a_key_of_the_file() -> None:
    package = json.loads((ROOT / "package.json").read_text("utf-8"))
    properties = {
        name: value
        for section in package["contributes"]["configuration"]
        for name, value in section["properties"].items()
    }
    editor_only = {"server.path", "trace.server", "language", "analysis.debounceMs",
                   "analysis.progressDelayMs"}  # fmt: skip
    settings = {name.removeprefix("fanuc-macro.") for name in properties} - editor_only
    assert settings == {k.setting for k in KEYS if k.editor}


def test_check_reads_the_nearest_file_and_the_command_line_wins(tmp_path: Path) -> None:
    write(tmp_path / "fanuc-macro.toml", "[machine]\nmax-spindle-speed = 8000\n")
    write(tmp_path / "lathe" / "fanuc-macro.toml", "extend = '../fanuc-macro.toml'\n"
          "[machine]\nmax-spindle-speed = 3000\n")  # fmt: skip
    write(tmp_path / "lathe" / "o1000.nc", SPINDLE)
    write(tmp_path / "mill" / "o1000.nc", SPINDLE)
    result = run(tmp_path, "check", "--format", "json", ".")
    found = json.loads(result.stdout)
    assert [(f["path"], f["code"]) for f in found if f["code"] == "MB602"] == [
        (str(Path("lathe") / "o1000.nc"), "MB602")
    ]
    assert "3000" in next(f["message"] for f in found if f["code"] == "MB602")
    result = run(tmp_path, "check", "--format", "json", "--max-spindle-speed", "4000", ".")
    assert sorted(f["path"] for f in json.loads(result.stdout) if f["code"] == "MB602") == [
        str(Path("lathe") / "o1000.nc"),
        str(Path("mill") / "o1000.nc"),
    ]
    result = run(tmp_path, "check", "--format", "json", "--isolated", ".")
    assert [f for f in json.loads(result.stdout) if f["code"] == "MB602"] == []


def test_config_prints_each_value_and_where_it_came_from(tmp_path: Path) -> None:
    write(tmp_path / "fanuc-macro.toml", "[machine]\ncontroller = '0i-TF'\n\n[rules]\n"
          "ignore = ['MB403']\n")  # fmt: skip
    result = run(tmp_path, "config", "--format", "json", "--disable", "MB006", "--max-blocks", "9")
    assert result.returncode == 0, result.stderr
    shown = json.loads(result.stdout)
    settings = shown["settings"]
    assert shown["files"] == ["fanuc-macro.toml"]  # from the folder it ran in
    assert settings["machine.controller"]["value"] == "0i-TF"
    assert settings["machine.controller"]["from"].endswith("fanuc-macro.toml:2")
    assert settings["analysis.max-blocks"] == {"value": 9, "from": "--max-blocks"}
    assert settings["rules.ignore"]["value"] == ["MB006", "MB403"]
    assert settings["rules.ignore"]["from"].endswith("fanuc-macro.toml:5 and --disable")
    assert settings["analysis.step-budget"]["from"] == "default"
    assert settings["machine.max-spindle-speed"] == {"value": None, "from": "default"}
    text = run(tmp_path, "config").stdout
    assert 'controller = "0i-TF"  # ' in text
    assert "# max-spindle-speed: not set, not checked  # default" in text


def test_a_bad_file_ends_the_run_with_its_message_and_no_traceback(tmp_path: Path) -> None:
    write(tmp_path / "fanuc-macro.toml", "[machine]\nmax-spindle-speed = 'fast'\n")
    write(tmp_path / "o1000.nc", SPINDLE)
    for command in (["check", "o1000.nc"], ["trace", "o1000.nc"], ["config"]):
        result = run(tmp_path, *command)
        assert result.returncode == 2, (command, result.stderr)
        assert "fanuc-macro.toml:2: machine.max-spindle-speed: 'fast' is not a number" in (
            result.stderr
        )
        assert "Traceback" not in result.stderr


def test_select_extend_select_and_per_file_ignores_from_the_file(tmp_path: Path) -> None:
    # MB602 (spindle over the limit) in both files; MB403 (M98 of a missing program) in both.
    program = "O1000\nG97 S5000 M03\nM98 P2000\nM30\n"
    write(tmp_path / "probe" / "o1000.nc", program)
    write(tmp_path / "o1001.nc", program.replace("O1000", "O1001"))
    write(
        tmp_path / "fanuc-macro.toml",
        "[machine]\nmax-spindle-speed = 3000\n[rules]\nselect = ['MB6']\n"
        "extend-select = ['call-target-missing']\n"
        "per-file-ignores = { 'probe/*.nc' = ['MB602'] }\n",
    )
    found = json.loads(run(tmp_path, "check", "--format", "json", ".").stdout)
    assert sorted((f["path"], f["code"]) for f in found) == [
        ("o1001.nc", "MB403"),
        ("o1001.nc", "MB602"),
        (str(Path("probe") / "o1000.nc"), "MB403"),
    ]
    # The command line: --select replaces the file's choice (its extend-select too), --ignore
    # adds to its ignore, --severity changes a rule's severity.
    result = run(
        tmp_path, "check", "--format", "json", "--select", "MB602", "--severity",
        "MB602=hint", "o1001.nc",
    )  # fmt: skip
    assert [(f["code"], f["severity"]) for f in json.loads(result.stdout)] == [("MB602", "hint")]
    result = run(tmp_path, "check", "--format", "json", "--ignore", "MB403,MB602", "o1001.nc")
    assert json.loads(result.stdout) == []


def test_a_bad_rule_option_is_a_usage_error_naming_the_nearest_rule(tmp_path: Path) -> None:
    write(tmp_path / "o1000.nc", SPINDLE)
    result = run(tmp_path, "check", "--select", "MB60Z", "o1000.nc")
    assert result.returncode == 2
    assert "'MB60Z' is not a rule's code or name, a prefix of codes or ALL" in result.stderr
    result = run(tmp_path, "check", "--severity", "MB602=loud", "o1000.nc")
    assert result.returncode == 2 and "not RULE=LEVEL" in result.stderr


def test_the_files_table_excludes_and_adds_extensions_to_the_walk(tmp_path: Path) -> None:
    write(tmp_path / "fanuc-macro.toml", "[files]\nexclude = ['old']\nextensions = ['pgm']\n")
    write(tmp_path / "old" / "o1000.nc", SPINDLE)
    write(tmp_path / "jobs" / "o2000.pgm", SPINDLE.replace("O1000", "O2000"))
    write(tmp_path / "jobs" / "o3000.nc", SPINDLE.replace("O1000", "O3000"))
    result = run(tmp_path, "check", "--format", "json", "--max-spindle-speed", "3000", ".")
    paths = sorted({f["path"] for f in json.loads(result.stdout)})
    assert paths == [str(Path("jobs") / "o2000.pgm"), str(Path("jobs") / "o3000.nc")]
    assert "2 files checked" in result.stderr
    isolated = run(tmp_path, "check", "--isolated", "--format", "json", ".")
    assert "2 files checked" in isolated.stderr  # old/o1000.nc and jobs/o3000.nc, no .pgm
