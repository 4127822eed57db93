"""The probing and tool-setting cycles vendors install on the control, known by program number.

A shop program calls them (``G65 P9814 D50. Z-10.``) and the programs stay on the control, not
beside the shop's files: a call of one is no mistake, and its arguments have a documented
meaning. Only Renishaw's packages are here, the ones the public material names.

Sources, for every entry:

* [IP] Renishaw, *Inspection Plus software for machining centres*, programming manuals
  H-2000-6031-0C-A (Fanuc, 1995-2003), H-2000-6222-0A-B (Haas, 2008) and H-2500-0071-02-B
  (Fanuc GUI, derivative of H-2000-6492-02-B, 2013). Only their title pages were seen: the
  cycle numbers and letters below are not checked against their pages (unverified).
* [ZAP] zappettiniconsulting.com wiki, "Okuma Renishaw output variables": the cycle names of
  O9811, O9812, O9814, O9815, O9816, O9819, O9820 and O9821 (secondary).
* [CORPUS] Renishaw's macros for Haas NGC in ``shared/corpus`` (jpaullee/renishaw_macros):
  O9810 "PROTECTED POSITION", O9811 "XYZ MEASURE", O9814 "BORE BOSS MEASURE" on their O lines;
  O9023 calls O9832 "(PROBE ON)", O9833 "(FLASH OFF)", O9855 "(OTS ON)", O9856 "(FLASH OTS
  OFF)", O9814 with D, Z, R, T, W, Q, O9812 with X or Y, Z, R, T, W, Q, O9815 and O9816 with
  X, Y, I, J, Q, O9802 and O9803 with D.
* [CPS] Autodesk's Fusion post processors for Fanuc and Haas controls (the public post
  library's ``.cps`` files, ``onCyclePoint`` "probing-*" and ``getProbingArguments``): the
  letters they write for O9810-O9816, O9819, O9823 and O9843 and what each carries (secondary:
  a CAM vendor's reading of the manual).
* [IMD] industrialmonitordirect.com, "Resolving Renishaw OTS probe already triggered alarm on
  FANUC 31i": O9855/O9856 switch the tool setter on and off, O9858 is the broken tool cycle.

An entry's ``verified`` says which of these name it. The argument meanings are those [CPS]
writes where it writes the cycle; the others are [IP] as remembered, unverified.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType


@dataclass(frozen=True, slots=True)
class VendorCycle:
    number: int
    package: str
    name: str
    # Each argument letter and what it means to the cycle, in the order the sources give.
    arguments: tuple[tuple[str, str], ...]
    verified: str  # which sources name the cycle (see the module's documentation)


INSPECTION_PLUS = "Renishaw Inspection Plus"
TOOL_SETTING = "Renishaw tool setting"
_MANUAL_IP = "Renishaw Inspection Plus programming manual H-2000-6031 / H-2000-6222"
_MANUAL_TS = "Renishaw tool setting software (manual number unverified)"

# The letters most measuring cycles of Inspection Plus share: [CPS], but E and U ([IP],
# unverified).
_RESULT = (
    ("Q", "overtravel past the expected surface"),
    ("S", "work offset to update (54-59 for G54-G59, 154.01- for G54.1 P1-)"),
    ("T", "tool offset to update (length for Z, else diameter)"),
    ("H", "tolerance of the size: out of it, the cycle stops with a message"),
    ("M", "tolerance of the position: out of it, the cycle stops with a message"),
    ("B", "tolerance of the angle"),
    ("F", "feedback: the fraction of the error put in the tool offset"),
    ("V", "null band: an error below it leaves the tool offset as it is"),
    ("W", "print the results (1; 2 starts a new component)"),
    ("E", "experience value: an adjustment added to the result"),
    ("U", "upper tolerance: out of it, the tool offset is not updated"),
)
_POSITION = "the surface's expected position"
_BOSS_DEPTH = "the depth to measure a boss at (absent: a bore)"
_CLEARANCE = "radial clearance (negative: an internal boss or web)"
# O9815 and O9816 take the same words.
_CORNER = (
    ("X", "the corner's expected position"),
    ("Y", "the corner's expected position"),
    ("I", "distance of the touches along X from the corner"),
    ("J", "distance of the touches along Y from the corner"),
    *_RESULT,
)

_CYCLES = (
    VendorCycle(
        9801,
        INSPECTION_PLUS,
        "calibrate the probe's length",
        (("Z", "the reference surface"), ("T", "the probe's tool offset")),
        "unverified",
    ),
    VendorCycle(
        9802,
        INSPECTION_PLUS,
        "calibrate the stylus's X/Y offset in a bore",
        (("D", "the bore's diameter"),),
        "CORPUS",
    ),
    VendorCycle(
        9803,
        INSPECTION_PLUS,
        "calibrate the stylus ball's radius in a ring gauge",
        (("D", "the ring gauge's diameter"),),
        "CORPUS",
    ),
    VendorCycle(
        9810,
        INSPECTION_PLUS,
        "protected positioning: a move that stops when the probe touches",
        (("X", "target"), ("Y", "target"), ("Z", "target"), ("F", "feed")),
        "CORPUS, CPS",
    ),
    VendorCycle(
        9811,
        INSPECTION_PLUS,
        "single surface measurement in X, Y or Z",
        (("X", _POSITION), ("Y", _POSITION), ("Z", _POSITION), *_RESULT),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9812,
        INSPECTION_PLUS,
        "web or pocket measurement",
        (
            ("X", "the width, measured in X"),
            ("Y", "the width, measured in Y"),
            ("Z", "the depth to measure a web at (absent: a pocket)"),
            ("R", _CLEARANCE),
            *_RESULT,
        ),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9814,
        INSPECTION_PLUS,
        "bore or boss measurement",
        (("D", "the nominal diameter"), ("Z", _BOSS_DEPTH), ("R", _CLEARANCE), *_RESULT),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9815,
        INSPECTION_PLUS,
        "internal corner find",
        _CORNER,
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9816,
        INSPECTION_PLUS,
        "external corner find",
        _CORNER,
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9819,
        INSPECTION_PLUS,
        "bores or bosses on a pitch circle (PCD)",
        (
            ("A", "angle of the first feature"),
            ("B", "number of features"),
            ("C", "the pitch circle's diameter"),
            ("D", "the features' diameter"),
            ("K", "the depth to measure bores at"),
            ("Z", "the depth to measure bosses at"),
            ("R", "radial clearance"),
            *_RESULT,
        ),
        "ZAP, CPS",
    ),
    VendorCycle(
        9820,
        INSPECTION_PLUS,
        "stock allowance",
        (("X", _POSITION), ("Y", _POSITION), ("Z", _POSITION), *_RESULT),
        "ZAP (arguments unverified)",
    ),
    VendorCycle(
        9821,
        INSPECTION_PLUS,
        "angled single surface measurement",
        (
            ("A", "the surface normal's angle"),
            ("D", "the distance to the surface"),
            ("X", _POSITION),
            ("Y", _POSITION),
            *_RESULT,
        ),
        "ZAP (arguments unverified)",
    ),
    VendorCycle(
        9823,
        INSPECTION_PLUS,
        "bore or boss measured at three points (a partial circle)",
        (
            ("A", "angle of the first point"),
            ("B", "angle of the second point"),
            ("C", "angle of the third point"),
            ("D", "the nominal diameter"),
            ("Z", _BOSS_DEPTH),
            ("R", _CLEARANCE),
            *_RESULT,
        ),
        "CPS",
    ),
    VendorCycle(9832, INSPECTION_PLUS, "switch the spindle probe on", (), "CORPUS"),
    VendorCycle(9833, INSPECTION_PLUS, "switch the spindle probe off", (), "CORPUS"),
    VendorCycle(
        9834,
        INSPECTION_PLUS,
        "feature to feature: the distance between the last two features measured",
        (),
        "unverified (called after O9814 in CORPUS)",
    ),
    VendorCycle(
        9843,
        INSPECTION_PLUS,
        "angle of a surface, measured in X or Y",
        (
            ("X", "the surface's expected position, measured in X"),
            ("Y", "the surface's expected position, measured in Y"),
            ("D", "distance between the two touches"),
            ("A", "the surface's nominal angle"),
            *_RESULT,
        ),
        "CPS",
    ),
    VendorCycle(
        9851,
        TOOL_SETTING,
        "measure a tool's length (T) or diameter (K)",
        (("T", "the tool offset to set"), ("K", "the calibration or measuring mode")),
        "unverified (called with T or K in CORPUS)",
    ),
    VendorCycle(
        9852,
        TOOL_SETTING,
        "calibrate the tool setter",
        (("S", "the calibration tool's diameter"), ("K", "the mode")),
        "unverified (called with S and K in CORPUS)",
    ),
    VendorCycle(
        9853,
        TOOL_SETTING,
        "tool setting cycle (its function unverified)",
        (("B", "the mode"), ("T", "the tool offset"), ("D", "the diameter offset")),
        "unverified (called with B, T and D in CORPUS)",
    ),
    VendorCycle(9855, TOOL_SETTING, "switch the tool setter on", (), "CORPUS, IMD"),
    VendorCycle(9856, TOOL_SETTING, "switch the tool setter off", (), "CORPUS, IMD"),
    VendorCycle(
        9858,
        TOOL_SETTING,
        "broken tool detection",
        (("T", "the tool to check"), ("H", "the tolerance")),
        "IMD (arguments unverified)",
    ),
)

CYCLES: Mapping[int, VendorCycle] = MappingProxyType({cycle.number: cycle for cycle in _CYCLES})


def known_cycle(number: int | None) -> VendorCycle | None:
    """The vendor cycle a program number is, or None."""
    return None if number is None else CYCLES.get(number)


def manual_of(cycle: VendorCycle) -> str:
    return _MANUAL_IP if cycle.package == INSPECTION_PLUS else _MANUAL_TS


def describe(cycle: VendorCycle) -> str:
    """One line naming a cycle: ``O9814, Renishaw Inspection Plus: bore or boss measurement``."""
    return f"O{cycle.number}, {cycle.package}: {cycle.name}"
