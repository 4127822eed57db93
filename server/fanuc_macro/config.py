"""Settings of an analysis: the controller, the machine's limits, rules on and off."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from .diagnostics import Severity
from .syntax.limits import MAX_LINE_LENGTH, ReadLimits

CONTROLLERS = ("0i-TF", "0i-MF", "16i-T", "16i-M", "18i-T", "18i-M", "30i")
ATAN_RANGES = ("0-360", "-180-180")

# A machine limit nobody set: nothing is above it, so the rules that compare with it stay quiet.
# A limit is the machine builder's (spindle and chuck rating, servo speed), not FANUC's: no
# default can be right for every machine, and a wrong one reports good programs.
NOT_SET = math.inf


@dataclass(frozen=True)
class Config:
    controller: str = "0i-TF"
    max_spindle_speed: float = NOT_SET  # rpm (setting machine.maxSpindleSpeed)
    max_threading_feed: float = NOT_SET  # mm/min: S x lead must stay under it
    max_depth_per_pass: float = 0.5  # mm, radius, for a threading pass
    disabled: frozenset[str] = frozenset()
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
    # analysis. About 2 s for a typical program on a 2-core EPYC VM, whatever its size.
    max_line_length: int = MAX_LINE_LENGTH  # characters of one block
    max_blocks: int = 25_000
    max_file_size: int = 600_000  # characters (bytes, for ASCII program text)
    # Hovers show values at the least input increment (0.001 mm, 0.0001 inch); with this set,
    # in full (the 8 digits the control keeps). No verdict depends on it.
    hover_full_precision: bool = False

    @property
    def read_limits(self) -> ReadLimits:
        return ReadLimits(self.max_line_length, self.max_blocks, self.max_file_size)

    @property
    def is_lathe(self) -> bool:
        return self.controller.endswith("T") or self.controller.endswith("TF")

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
        severities: dict[str, Severity] = {}
        for code, value in (rules.get("severity") or {}).items():
            try:
                severities[str(code).upper()] = Severity(str(value).lower())
            except ValueError:
                continue
        controller = str(settings.get("controller") or "0i-TF")
        default = cls()
        return cls(
            controller=controller if controller in CONTROLLERS else "0i-TF",
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
        )


def _number(value: Any, default: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
        return default
    return float(value)


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


def _choice(value: Any, choices: tuple[str, ...], default: str) -> str:
    return value if isinstance(value, str) and value in choices else default
