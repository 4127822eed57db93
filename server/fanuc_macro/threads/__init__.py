"""What a thread is (see ARCHITECTURE.md).

:mod:`.designation` reads ISO metric designations, and :mod:`.iso965` holds the ISO 965-1 /
GB/T 197 tolerances. :mod:`.geometry`, :mod:`.profile` and :mod:`.linear` are the
thread-cutting math. :mod:`.module_shape` recognises a thread module by what its formulas
compute. :mod:`.jobs` groups the executed passes into threads, and :mod:`.identify` says what
each thread is.
"""

from __future__ import annotations

from .designation import (
    COARSE_PITCH,
    SideConflict,
    SideUndecided,
    ThreadDesignation,
    ToleranceClass,
    coarse_pitch,
    parse_designation,
)
from .geometry import (
    RoughPass,
    SymmetricThreadPlan,
    ap_max,
    ap_min,
    basic_minor_diameter,
    basic_pitch_diameter,
    count_rough_passes,
    cumulative_depth,
    fundamental_triangle_height,
    nose_radius_ok,
    nose_radius_range,
    paper_internal_minor_diameter,
    pass_depth,
    plan_from_tolerances,
    plan_symmetric_thread,
    rough_passes,
    run_in_out,
    side_offset,
    theoretical_nose_radius,
    thread_height,
)
from .iso965 import (
    TableCell,
    TableValue,
    ThreadTolerances,
    diameter_range,
    fundamental_deviation,
    major_diameter_tolerance,
    minor_diameter_tolerance,
    pitch_diameter_tolerance,
    table_cells,
    tolerances,
)

__all__ = (
    "COARSE_PITCH",
    "RoughPass",
    "SideConflict",
    "SideUndecided",
    "SymmetricThreadPlan",
    "TableCell",
    "TableValue",
    "ThreadDesignation",
    "ThreadTolerances",
    "ToleranceClass",
    "ap_max",
    "ap_min",
    "basic_minor_diameter",
    "basic_pitch_diameter",
    "coarse_pitch",
    "count_rough_passes",
    "cumulative_depth",
    "diameter_range",
    "fundamental_deviation",
    "fundamental_triangle_height",
    "major_diameter_tolerance",
    "minor_diameter_tolerance",
    "nose_radius_ok",
    "nose_radius_range",
    "paper_internal_minor_diameter",
    "parse_designation",
    "pass_depth",
    "pitch_diameter_tolerance",
    "plan_from_tolerances",
    "plan_symmetric_thread",
    "rough_passes",
    "run_in_out",
    "side_offset",
    "table_cells",
    "theoretical_nose_radius",
    "thread_height",
    "tolerances",
)
