"""Settings of an analysis: the controller, the machine's limits, rules on and off."""

from __future__ import annotations

import fnmatch
import math
import os
from dataclasses import dataclass, field
from pathlib import PurePath
from typing import Any

from .diagnostics import Severity
from .syntax.limits import MAX_LINE_LENGTH, ReadLimits

# "0i-F": a 0i-F whose machine, lathe (0i-TF) or mill (0i-MF), each document's codes show
# (program.machine_kind); the others say the machine.
CONTROLLERS = ("0i-F", "0i-TF", "0i-MF", "16i-T", "16i-M", "18i-T", "18i-M", "30i")
BY_PROGRAM = "0i-F"
ATAN_RANGES = ("0-360", "-180-180")
# The lathe's G code systems (program.g_code_systems): A, the 0i-TF default, or B or C.
G_CODE_SYSTEMS = ("A", "B", "C")
SYSTEM_A = "A"

# A machine limit nobody set: nothing is above it, so the rules that compare with it stay quiet.
# A limit is the machine builder's (spindle and chuck rating, servo speed), not FANUC's: no
# default can be right for every machine, and a wrong one reports good programs.
NOT_SET = math.inf


@dataclass(frozen=True)
class Config:
    controller: str = BY_PROGRAM
    max_spindle_speed: float = NOT_SET  # rpm (setting machine.maxSpindleSpeed)
    max_threading_feed: float = NOT_SET  # mm/min: S x lead must stay under it
    max_depth_per_pass: float = 0.5  # mm, radius, for a threading pass
    disabled: frozenset[str] = frozenset()
    # The rules reported, as code prefixes ("MB6": MB600-MB699; "MB": all), None: all. What
    # ``disabled`` names is dropped all the same (select, then ignore, as ruff reads them).
    selected: tuple[str, ...] | None = None
    # Rules dropped in some files only: each (folder, glob, codes); a glob without "/" is a
    # file name anywhere below the folder, one with "/" a path from it.
    per_file_ignores: tuple[tuple[str, str, frozenset[str]], ...] = ()
    severities: dict[str, Severity] = field(default_factory=dict)
    # Blocks the evaluator may execute from one entry program: the bound every verdict on an
    # unfinished run (MB703, MB707, MB708) comes from, so the same input gives the same result
    # on any machine. Measured: the longest run of a corpus program takes 995 blocks, of a seed
    # program or its variants 1,683, of a test fixture 60,026 (a call repeated 10,000 times);
    # 300,000 take 0.2 s of macro statements, 0.7 s of motion blocks (docs/benchmarks.md).
    step_budget: int = 300_000
    # Seconds per analysis after which the evaluator gives up whatever the step budget says: a
    # safety net for a slow or overloaded machine, never a verdict (the run is incomplete).
    time_limit: float = 10.0
    # ATAN's result: 0 to 360 degrees, or -180 to 180 with parameter 6004#0 (NAT) set.
    atan_signed: bool = False
    # The extended common variables #200-#499 (an option on 0i-F / 30i) are on the machine.
    extended_commons: bool = False
    # What the analysis reads of a document: the rest gets a diagnostic (MB011, MB013), not an
    # analysis. By default any realistic file is read whole: hand-written programs of any size
    # and posted files past a million blocks (about 30 characters a block); the step budget,
    # cancellation and progress bound the work. Lower them for a machine short of memory.
    max_line_length: int = MAX_LINE_LENGTH  # characters of one block
    max_blocks: int = 2_000_000
    max_file_size: int = 64_000_000  # characters (bytes, for ASCII program text)
    # Hovers show values at the least input increment (0.001 mm, 0.0001 inch); with this set,
    # in full (the 8 digits the control keeps). No verdict depends on it.
    hover_full_precision: bool = False
    # The bar the Toolpath view draws on a lathe, in the program's unit (setting
    # view.stockDiameter): the program's when not set (a stock removal cycle's start, a blank).
    stock_diameter: float = NOT_SET
    # The cycle time's machine (evaluator/cycle_time.py): each axis's rapid traverse rate in
    # mm/min (parameter 1420 on the control; the machine builder's). The defaults are a
    # small lathe's or machining centre's usual figures, not any one machine's (unverified).
    rapid_rate_x: float = 20_000.0
    rapid_rate_y: float = 20_000.0
    rapid_rate_z: float = 24_000.0
    # Seconds a tool change takes (a lathe's T, a mill's M06): a turret's index or a changer's
    # swap, chip to chip; 2 s is a usual figure, not any one machine's (unverified).
    tool_change_seconds: float = 2.0
    # Seconds the M codes the machine waits for take (a door, a bar feeder, a chuck):
    # ((code, seconds), ...), sorted by code; no M code takes time unless it is named here.
    m_code_seconds: tuple[tuple[float, float], ...] = ()
    # Set when the machine was read from the document (controller 0i-F): why it is a lathe or
    # a mill, or why neither could be told; then ``machine_known`` is False, the document is
    # read as a lathe (the 0i-TF) and the verdicts that depend on the machine are not given.
    machine_note: str = ""
    machine_known: bool = True
    # (document, first line, lathe?) of each program of a file that holds both a lathe's and
    # a mill's programs: each runs as its own machine.
    program_machines: tuple[tuple[str, int, bool], ...] = ()
    # The lathe's G code system, A, B or C (parameters GSB, GSC: No. 3401#6, #7): a lathe
    # program's codes are read in it (program.g_code_systems); a mill has one system.
    g_code_system: str = SYSTEM_A
    # The codes the control's parameters make calls (machine.customCalls): each a
    # CustomCallSetting, read and checked by read_custom_calls.
    custom_calls: tuple[CustomCallSetting, ...] = ()
    # Programs kept on the control, not beside the files (machine.programsOnControl): ranges
    # of program numbers, first and last included.
    programs_on_control: tuple[tuple[int, int], ...] = ()
    # What the settings above could not read, each a sentence naming the value: the front
    # ends show them (log, stderr); the analysis uses only what was read.
    setting_problems: tuple[str, ...] = field(default=(), compare=False)

    @property
    def read_limits(self) -> ReadLimits:
        return ReadLimits(self.max_line_length, self.max_blocks, self.max_file_size)

    @property
    def is_lathe(self) -> bool:
        """Whether codes are read as a lathe's (a 0i-F not resolved for a document: yes)."""
        return self.controller.endswith(("T", "TF")) or self.controller == BY_PROGRAM

    @property
    def machine_by_program(self) -> bool:
        """Whether each document's codes say its machine (controller 0i-F)."""
        return self.controller == BY_PROGRAM

    @property
    def value_range(self) -> tuple[float, float]:
        """The smallest and largest magnitude a macro variable holds; past the largest the
        control raises PS0111 CALCULATED DATA OVERFLOW. 0i/16i/18i: 10^-29 to 10^47 (FANUC
        0i-F Custom Macro manual, "Range of variable values"). 30i/31i/32i compute in double
        precision: the IEEE 754 range (unverified against the 30i manual)."""
        if self.controller.startswith("30i"):
            return 2.2250738585072014e-308, 1.7976931348623157e308
        return 1e-29, 1e47

    @property
    def four_digit_programs(self) -> bool:
        """0i/16i program numbers have four digits (M98 P0013331 = 1 x O3331)."""
        return self.controller != "30i"

    @classmethod
    def from_settings(cls, settings: dict[str, Any] | None) -> Config:
        """Read the ``fanuc-macro`` settings object of the editor (unknown keys are ignored)."""
        if not settings:
            return cls()
        machine = settings.get("machine") or {}
        threading = settings.get("threading") or {}
        rules = settings.get("rules") or {}
        analysis = settings.get("analysis") or {}
        hover = settings.get("hover") or {}
        view = settings.get("view") or {}
        cycle = settings.get("cycleTime") or {}
        severities: dict[str, Severity] = {}
        for code, value in (rules.get("severity") or {}).items():
            try:
                severities[str(code).upper()] = Severity(str(value).lower())
            except ValueError:
                continue
        controller = str(settings.get("controller") or BY_PROGRAM)
        default = cls()
        custom_calls, call_problems = read_custom_calls(machine.get("customCalls"))
        on_control, range_problems = read_program_ranges(machine.get("programsOnControl"))
        system, system_problems = read_g_code_system(machine.get("gCodeSystem"))
        m_seconds, m_problems = read_m_code_seconds(cycle.get("mCodeSeconds"))
        return cls(
            selected=_selected(rules),
            per_file_ignores=_per_file_ignores(rules.get("perFileIgnores")),
            controller=controller if controller in CONTROLLERS else BY_PROGRAM,
            max_spindle_speed=_number(machine.get("maxSpindleSpeed"), default.max_spindle_speed),
            max_threading_feed=_number(machine.get("maxThreadingFeed"), default.max_threading_feed),
            max_depth_per_pass=_number(
                threading.get("maxDepthPerPass"), default.max_depth_per_pass
            ),
            disabled=frozenset(str(c).upper() for c in rules.get("disabled") or ()),
            severities=severities,
            step_budget=int(_number(analysis.get("stepBudget"), default.step_budget)),
            time_limit=_number(analysis.get("timeLimit"), default.time_limit),
            atan_signed=str(machine.get("atanRange") or "0-360") == "-180-180",
            extended_commons=machine.get("extendedCommons") is True,
            max_line_length=int(_number(analysis.get("maxLineLength"), default.max_line_length)),
            max_blocks=int(_number(analysis.get("maxBlocks"), default.max_blocks)),
            max_file_size=int(_number(analysis.get("maxFileSize"), default.max_file_size)),
            hover_full_precision=hover.get("fullPrecision") is True,
            stock_diameter=_number(view.get("stockDiameter"), default.stock_diameter),
            rapid_rate_x=_number(cycle.get("rapidRateX"), default.rapid_rate_x),
            rapid_rate_y=_number(cycle.get("rapidRateY"), default.rapid_rate_y),
            rapid_rate_z=_number(cycle.get("rapidRateZ"), default.rapid_rate_z),
            tool_change_seconds=_number(
                cycle.get("toolChangeSeconds"), default.tool_change_seconds
            ),
            m_code_seconds=m_seconds,
            g_code_system=system,
            custom_calls=custom_calls,
            programs_on_control=on_control,
            setting_problems=(*call_problems, *range_problems, *system_problems, *m_problems),
        )


def _selected(rules: dict[str, Any]) -> tuple[str, ...] | None:
    """``rules.select`` and ``rules.extendSelect`` (codes or prefixes, "ALL") as prefixes;
    None when every rule is reported."""
    select = rules.get("select")
    extend = rules.get("extendSelect") or ()
    if not isinstance(select, list) and not extend:
        return None
    chosen = [str(c).upper() for c in (select if isinstance(select, list) else ["ALL"])]
    chosen += [str(c).upper() for c in extend]
    if "ALL" in chosen:
        return None
    return tuple(sorted(set(chosen)))


def _per_file_ignores(value: Any) -> tuple[tuple[str, str, frozenset[str]], ...]:
    """``rules.perFileIgnores``: ``[[folder, glob, [codes]], ...]`` as the configuration file
    gives them (the folder: the file's own)."""
    if not isinstance(value, list):
        return ()
    found: list[tuple[str, str, frozenset[str]]] = []
    for item in value:
        if isinstance(item, list | tuple) and len(item) == 3 and isinstance(item[2], list):
            found.append((str(item[0]), str(item[1]), frozenset(str(c).upper() for c in item[2])))
    return tuple(found)


def ignored_in(config: Config, uri: str) -> frozenset[str]:
    """The codes ``config.per_file_ignores`` drops in the file ``uri`` (a path or a file:
    URI)."""
    if not config.per_file_ignores:
        return frozenset()
    path = _path_of(uri)
    codes: set[str] = set()
    for folder, glob, named in config.per_file_ignores:
        try:
            relative = path.relative_to(folder)
        except ValueError:
            continue
        target = relative.name if "/" not in glob else relative.as_posix()
        if fnmatch.fnmatchcase(target, glob):
            codes |= named
    return frozenset(codes)


def _path_of(uri: str) -> PurePath:
    if uri.startswith("file:"):
        from urllib.parse import unquote, urlparse

        parsed = urlparse(uri)
        return PurePath(os.path.abspath(unquote(parsed.path)))
    return PurePath(os.path.abspath(uri))


def _number(value: Any, default: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
        return default
    return float(value)


def read_m_code_seconds(value: Any) -> tuple[tuple[tuple[float, float], ...], tuple[str, ...]]:
    """``cycleTime.mCodeSeconds`` (``{"M08": 0.5, "M10": 1.5}``, the M optional): each code
    with its seconds, sorted by code, and a sentence for each entry that cannot be read."""
    if value is None:
        return (), ()
    if not isinstance(value, dict):
        return (), (f"cycleTime.mCodeSeconds: {value!r} is not an object of M code: seconds",)
    found: dict[float, float] = {}
    problems: list[str] = []
    for code, seconds in value.items():
        digits = str(code).strip().upper().removeprefix("M")
        what = f"cycleTime.mCodeSeconds: {code!r}"
        if not digits.isdigit():
            problems.append(f"{what} is not an M code (M08, 8)")
        elif isinstance(seconds, bool) or not isinstance(seconds, int | float) or seconds < 0:
            problems.append(f"{what}: {seconds!r} is not a number of seconds")
        else:
            found[float(int(digits))] = float(seconds)
    return tuple(sorted(found.items())), tuple(problems)


# How the formatter spaces what it may: "keep" what is written, "always" one space, "never" none.
SPACING = ("keep", "always", "never")


@dataclass(frozen=True)
class FormatSettings:
    """The formatter's settings (``fanuc-macro.format.*``), apart from the analysis's: a change
    of them analyses nothing again."""

    upper_case: bool = True  # addresses and keywords outside comments (format.upperCase)
    space_between_words: str = "keep"  # "G01 X10." / "G01X10." (format.spaceBetweenWords)
    spaces_around_assignment: str = "keep"  # "#1 = 2" / "#1=2" (format.spacesAroundAssignment)
    renumber_step: int = 10  # the step of "Renumber N labels" (format.renumberStep)

    @classmethod
    def from_settings(cls, settings: dict[str, Any] | None) -> FormatSettings:
        fmt = (settings or {}).get("format")
        if not isinstance(fmt, dict):
            return cls()
        default = cls()
        upper = fmt.get("upperCase")
        return cls(
            upper_case=upper if isinstance(upper, bool) else default.upper_case,
            space_between_words=_choice(fmt.get("spaceBetweenWords"), SPACING, "keep"),
            spaces_around_assignment=_choice(fmt.get("spacesAroundAssignment"), SPACING, "keep"),
            renumber_step=int(_number(fmt.get("renumberStep"), default.renumber_step)),
        )


def read_g_code_system(value: Any) -> tuple[str, tuple[str, ...]]:
    """machine.gCodeSystem ("A", "B", "C", in any case; not set: A) and what could not be read."""
    if value is None or value == "":
        return SYSTEM_A, ()
    text = str(value).strip().upper()
    if text in G_CODE_SYSTEMS:
        return text, ()
    return SYSTEM_A, (
        f"machine.gCodeSystem: {value!r} is not a G code system (A, B or C); system A is used",
    )


def _choice(value: Any, choices: tuple[str, ...], default: str) -> str:
    return value if isinstance(value, str) and value in choices else default


# Calls through parameters: the code a parameter registers calls a program of a fixed range
# (FANUC Custom Macro chapter, "Macro call using a G code / an M code", "Subprogram call using an
# M code / a T code / an S code / a second auxiliary function code"). Per range: the address,
# the first and last program, whether the call is a macro call (G65-like: the words are
# arguments, a new level of locals) and the common variable that receives the code's value.
# Sources: G code -> O9010-O9019 (parameters 6050-6059): zappettini wiki "macro structure" and
# ZapCon1/KnowledgeBase FanucParameters.md (shared reference macro-b.md 5.4, secondary); T code
# -> O9000 (parameter 6001#5 TCS), value in #149, and M code -> O9001-O9003 as subprograms:
# FANUC Power Mate i-D/H Macro Compiler/Executor B-62093E-1/02, 3.1.1-3.1.2. Unverified against
# a 0i/16i/30i manual: M code -> O9020-O9029 macro calls (6080-6089), O9004-O9009 and the
# parameters 6071-6079, S -> O9029 (#147), B -> O9028 (#146). A G code with a decimal point
# and the extended ranges of newer controls are not read (no manual seen).
@dataclass(frozen=True)
class CustomCallRange:
    address: str
    first: int
    last: int
    macro: bool
    value_variable: int | None  # the variable that receives the code's value (T: #149)
    parameters: str  # where the control registers the code, for the messages


CUSTOM_CALL_RANGES = (
    CustomCallRange("G", 9010, 9019, True, None, "parameters 6050-6059"),
    CustomCallRange("M", 9020, 9029, True, None, "parameters 6080-6089"),
    CustomCallRange("M", 9001, 9009, False, None, "parameters 6071-6079"),
    CustomCallRange("T", 9000, 9000, False, 149, "parameter 6001#5 TCS"),
    CustomCallRange("S", 9029, 9029, False, 147, "the S code call"),
    CustomCallRange("B", 9028, 9028, False, 146, "the second auxiliary code call"),
)
# Codes that already call or return: a parameter cannot make them call something else.
_FIXED_CALL_CODES = frozenset({("G", 65), ("G", 66), ("G", 67), ("M", 98), ("M", 99)})


@dataclass(frozen=True)
class CustomCallSetting:
    """One code the control calls a program with: ``M165`` -> O9022 (``number`` None for a
    whole address: every T word calls O9000)."""

    address: str
    number: int | None
    program: int
    macro: bool  # G65-like (the words are arguments); else M98-like
    value_variable: int | None = None

    @property
    def code(self) -> str:
        return self.address if self.number is None else f"{self.address}{self.number}"

    @property
    def kind(self) -> str:
        """What the call is like: ``G65`` or ``M98``."""
        return "G65" if self.macro else "M98"


def _custom_call(code: str, program: object) -> CustomCallSetting | str:
    """One entry of ``machine.customCalls`` read, or why it cannot be."""
    text = code.strip().upper()
    address, digits = text[:1], text[1:]
    what = f"machine.customCalls: {code!r}"
    if address not in "GMTSB" or not address or (digits and not digits.isdigit()):
        return f"{what} is not a code a parameter can register (G<n>, M<n>, T, S or B)"
    number = int(digits) if digits else None
    if (number is None) != (address in "TSB"):
        return f"{what}: a G or M code takes its number (G100, M165); T, S and B stand alone"
    if number is not None and (address, number) in _FIXED_CALL_CODES:
        return f"{what} already calls or returns: a parameter cannot make it call a program"
    if isinstance(program, str):
        program = program.strip().upper().removeprefix("O")
        program = int(program) if program.isdigit() else program
    if isinstance(program, bool) or not isinstance(program, int | float) or program != int(program):
        return f"{what} calls {program!r}, not a program number"
    ranges = [r for r in CUSTOM_CALL_RANGES if r.address == address]
    for r in ranges:
        if r.first <= program <= r.last:
            return CustomCallSetting(address, number, int(program), r.macro, r.value_variable)
    allowed = " or ".join(
        f"O{r.first}" + (f"-O{r.last}" if r.last != r.first else "") + f" ({r.parameters})"
        for r in ranges
    )
    article = "an" if address in "MS" else "a"
    return f"{what} calls O{int(program):04d}: {article} {address} code can call only {allowed}"


def read_custom_calls(value: Any) -> tuple[tuple[CustomCallSetting, ...], tuple[str, ...]]:
    """``machine.customCalls`` (``{"G100": 9010, "M165": 9022, "T": 9000}``): the calls read,
    and a sentence for each entry that cannot be one. One program is called by one code (its
    parameter holds one)."""
    if value is None:
        return (), ()
    if not isinstance(value, dict):
        return (), (f"machine.customCalls: {value!r} is not an object of code: program",)
    calls: list[CustomCallSetting] = []
    problems: list[str] = []
    for code, program in value.items():
        found = _custom_call(str(code), program)
        if isinstance(found, str):
            problems.append(found)
        elif any(c.program == found.program or c.code == found.code for c in calls):
            problems.append(
                f"machine.customCalls: {code!r}: O{found.program:04d} or {found.code} is "
                "already set up (one parameter holds one code)"
            )
        else:
            calls.append(found)
    return tuple(calls), tuple(problems)


def _program_range(item: object) -> tuple[int, int] | None:
    if isinstance(item, bool):
        return None
    if isinstance(item, int) and item >= 0:
        return item, item
    if not isinstance(item, str):
        return None
    ends = [e.strip().upper().removeprefix("O") for e in item.split("-")]
    if len(ends) > 2 or not all(e.isdigit() for e in ends):
        return None
    first, last = int(ends[0]), int(ends[-1])
    return (first, last) if first <= last else None


def read_program_ranges(value: Any) -> tuple[tuple[tuple[int, int], ...], tuple[str, ...]]:
    """``machine.programsOnControl``: numbers and ranges (``9000``, ``"O9000-O9999"``)."""
    if value is None:
        return (), ()
    items = value.split(",") if isinstance(value, str) else value
    if not isinstance(items, list | tuple):
        return (), (f"machine.programsOnControl: {value!r} is not a list of programs",)
    ranges: list[tuple[int, int]] = []
    problems: list[str] = []
    for item in items:
        found = _program_range(item)
        if found is None:
            problems.append(
                f"machine.programsOnControl: {item!r} is not a program number or a range "
                "like O9000-O9999"
            )
        else:
            ranges.append(found)
    return tuple(ranges), tuple(problems)


def on_control(config: Config, number: int) -> bool:
    """Whether the settings say program ``number`` is kept on the control."""
    return any(first <= number <= last for first, last in config.programs_on_control)
