"""fanuc-macro: static analysis for FANUC Custom Macro B programs."""

__version__ = "0.1.0"
