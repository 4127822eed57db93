"""Settings of an analysis: the controller, the machine's limits, rules on and off."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .blocks import MAX_LINE_LENGTH, ReadLimits
from .diagnostics import Severity

CONTROLLERS = ("0i-TF", "0i-MF", "16i-T", "16i-M", "18i-T", "18i-M", "30i")
ATAN_RANGES = ("0-360", "-180-180")


@dataclass(frozen=True)
class Config:
    controller: str = "0i-TF"
    max_spindle_speed: float = 4000.0  # rpm
    max_threading_feed: float = 10000.0  # mm/min: S x pitch must stay under it
    max_depth_per_pass: float = 0.5  # mm, radius, for a threading pass
    disabled: frozenset[str] = frozenset()
    severities: dict[str, Severity] = field(default_factory=dict)
    step_budget: int = 500_000  # blocks the evaluator may execute from one entry
    time_budget: float = 0.8  # seconds of evaluation per document
    # ATAN's result: 0 to 360 degrees, or -180 to 180 with parameter 6004#0 (NAT) set.
    atan_signed: bool = False
    # What the analysis reads of a document: the rest gets a diagnostic (MB011, MB013), not an
    # analysis. About 2 s for a typical program on a 2-core EPYC VM, whatever its size.
    max_line_length: int = MAX_LINE_LENGTH  # characters of one block
    max_blocks: int = 25_000
    max_file_size: int = 600_000  # characters (bytes, for ASCII program text)

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
            time_budget=_number(analysis.get("timeBudget"), default.time_budget),
            atan_signed=str(machine.get("atanRange") or "0-360") == "-180-180",
            max_line_length=int(_number(analysis.get("maxLineLength"), default.max_line_length)),
            max_blocks=int(_number(analysis.get("maxBlocks"), default.max_blocks)),
            max_file_size=int(_number(analysis.get("maxFileSize"), default.max_file_size)),
        )


def _number(value: Any, default: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
        return default
    return float(value)
