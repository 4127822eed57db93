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

from ..translation import tr


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
    ("Q", tr("overtravel past the expected surface")),
    ("S", tr("work offset to update (54-59 for G54-G59, 154.01- for G54.1 P1-)")),
    ("T", tr("tool offset to update (length for Z, else diameter)")),
    ("H", tr("tolerance of the size: out of it, the cycle stops with a message")),
    ("M", tr("tolerance of the position: out of it, the cycle stops with a message")),
    ("B", tr("tolerance of the angle")),
    ("F", tr("feedback: the fraction of the error put in the tool offset")),
    ("V", tr("null band: an error below it leaves the tool offset as it is")),
    ("W", tr("print the results (1; 2 starts a new component)")),
    ("E", tr("experience value: an adjustment added to the result")),
    ("U", tr("upper tolerance: out of it, the tool offset is not updated")),
)
_POSITION = tr("the surface's expected position")
_BOSS_DEPTH = tr("the depth to measure a boss at (absent: a bore)")
_CLEARANCE = tr("radial clearance (negative: an internal boss or web)")
# O9815 and O9816 take the same words.
_CORNER = (
    ("X", tr("the corner's expected position")),
    ("Y", tr("the corner's expected position")),
    ("I", tr("distance of the touches along X from the corner")),
    ("J", tr("distance of the touches along Y from the corner")),
    *_RESULT,
)

_CYCLES = (
    VendorCycle(
        9801,
        INSPECTION_PLUS,
        tr("calibrate the probe's length"),
        (("Z", tr("the reference surface")), ("T", tr("the probe's tool offset"))),
        "unverified",
    ),
    VendorCycle(
        9802,
        INSPECTION_PLUS,
        tr("calibrate the stylus's X/Y offset in a bore"),
        (("D", tr("the bore's diameter")),),
        "CORPUS",
    ),
    VendorCycle(
        9803,
        INSPECTION_PLUS,
        tr("calibrate the stylus ball's radius in a ring gauge"),
        (("D", tr("the ring gauge's diameter")),),
        "CORPUS",
    ),
    VendorCycle(
        9810,
        INSPECTION_PLUS,
        tr("protected positioning: a move that stops when the probe touches"),
        (("X", tr("target")), ("Y", tr("target")), ("Z", tr("target")), ("F", tr("feed"))),
        "CORPUS, CPS",
    ),
    VendorCycle(
        9811,
        INSPECTION_PLUS,
        tr("single surface measurement in X, Y or Z"),
        (("X", _POSITION), ("Y", _POSITION), ("Z", _POSITION), *_RESULT),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9812,
        INSPECTION_PLUS,
        tr("web or pocket measurement"),
        (
            ("X", tr("the width, measured in X")),
            ("Y", tr("the width, measured in Y")),
            ("Z", tr("the depth to measure a web at (absent: a pocket)")),
            ("R", _CLEARANCE),
            *_RESULT,
        ),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9814,
        INSPECTION_PLUS,
        tr("bore or boss measurement"),
        (("D", tr("the nominal diameter")), ("Z", _BOSS_DEPTH), ("R", _CLEARANCE), *_RESULT),
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9815,
        INSPECTION_PLUS,
        tr("internal corner find"),
        _CORNER,
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9816,
        INSPECTION_PLUS,
        tr("external corner find"),
        _CORNER,
        "ZAP, CORPUS, CPS",
    ),
    VendorCycle(
        9819,
        INSPECTION_PLUS,
        tr("bores or bosses on a pitch circle (PCD)"),
        (
            ("A", tr("angle of the first feature")),
            ("B", tr("number of features")),
            ("C", tr("the pitch circle's diameter")),
            ("D", tr("the features' diameter")),
            ("K", tr("the depth to measure bores at")),
            ("Z", tr("the depth to measure bosses at")),
            ("R", tr("radial clearance")),
            *_RESULT,
        ),
        "ZAP, CPS",
    ),
    VendorCycle(
        9820,
        INSPECTION_PLUS,
        tr("stock allowance"),
        (("X", _POSITION), ("Y", _POSITION), ("Z", _POSITION), *_RESULT),
        "ZAP (arguments unverified)",
    ),
    VendorCycle(
        9821,
        INSPECTION_PLUS,
        tr("angled single surface measurement"),
        (
            ("A", tr("the surface normal's angle")),
            ("D", tr("the distance to the surface")),
            ("X", _POSITION),
            ("Y", _POSITION),
            *_RESULT,
        ),
        "ZAP (arguments unverified)",
    ),
    VendorCycle(
        9823,
        INSPECTION_PLUS,
        tr("bore or boss measured at three points (a partial circle)"),
        (
            ("A", tr("angle of the first point")),
            ("B", tr("angle of the second point")),
            ("C", tr("angle of the third point")),
            ("D", tr("the nominal diameter")),
            ("Z", _BOSS_DEPTH),
            ("R", _CLEARANCE),
            *_RESULT,
        ),
        "CPS",
    ),
    VendorCycle(9832, INSPECTION_PLUS, tr("switch the spindle probe on"), (), "CORPUS"),
    VendorCycle(9833, INSPECTION_PLUS, tr("switch the spindle probe off"), (), "CORPUS"),
    VendorCycle(
        9834,
        INSPECTION_PLUS,
        tr("feature to feature: the distance between the last two features measured"),
        (),
        "unverified (called after O9814 in CORPUS)",
    ),
    VendorCycle(
        9843,
        INSPECTION_PLUS,
        tr("angle of a surface, measured in X or Y"),
        (
            ("X", tr("the surface's expected position, measured in X")),
            ("Y", tr("the surface's expected position, measured in Y")),
            ("D", tr("distance between the two touches")),
            ("A", tr("the surface's nominal angle")),
            *_RESULT,
        ),
        "CPS",
    ),
    VendorCycle(
        9851,
        TOOL_SETTING,
        tr("measure a tool's length (T) or diameter (K)"),
        (("T", tr("the tool offset to set")), ("K", tr("the calibration or measuring mode"))),
        "unverified (called with T or K in CORPUS)",
    ),
    VendorCycle(
        9852,
        TOOL_SETTING,
        tr("calibrate the tool setter"),
        (("S", tr("the calibration tool's diameter")), ("K", tr("the mode"))),
        "unverified (called with S and K in CORPUS)",
    ),
    VendorCycle(
        9853,
        TOOL_SETTING,
        tr("tool setting cycle (its function unverified)"),
        (("B", tr("the mode")), ("T", tr("the tool offset")), ("D", tr("the diameter offset"))),
        "unverified (called with B, T and D in CORPUS)",
    ),
    VendorCycle(9855, TOOL_SETTING, tr("switch the tool setter on"), (), "CORPUS, IMD"),
    VendorCycle(9856, TOOL_SETTING, tr("switch the tool setter off"), (), "CORPUS, IMD"),
    VendorCycle(
        9858,
        TOOL_SETTING,
        tr("broken tool detection"),
        (("T", tr("the tool to check")), ("H", tr("the tolerance"))),
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
    # The package is a product's name, the same in every language.
    return tr(
        "O{number}, {product_text}: {name}",
        number=cycle.number,
        product_text=cycle.package,
        name=cycle.name,
    )
