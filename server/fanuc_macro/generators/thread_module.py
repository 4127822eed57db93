"""The thread module generator, loaded when a thread module is first asked for: a build of the
package may come without it."""

from __future__ import annotations

import importlib
from collections.abc import Callable

# The generator's refusals of a designation that does not say its side, or says the other one:
# a front end words them with its own way of saying the side.
from ..threads.designation import SideConflict, SideUndecided

__all__ = (
    "GENERATOR_MODULE",
    "Generator",
    "NoGenerator",
    "SideConflict",
    "SideUndecided",
    "load_generator",
)

GENERATOR_MODULE = "fanuc_macro.generators.thread_generator"

# generate_module(designation, length in mm, internal or None, *, infeed=..., taper=...)
# -> the module's text
Generator = Callable[..., object]


class NoGenerator(Exception):
    """This build of the package has no thread module generator."""


def load_generator() -> Generator:
    """The generator; :class:`NoGenerator` when the build has none, and any other failure
    to import it as it is."""
    try:
        module = importlib.import_module(GENERATOR_MODULE)
    except ModuleNotFoundError as err:
        if err.name == GENERATOR_MODULE or GENERATOR_MODULE.startswith(f"{err.name}."):
            raise NoGenerator(
                "this version of fanuc-macro has no thread module generator yet"
            ) from err
        raise  # the generator is there, something it imports is not
    generate = getattr(module, "generate_module", None)
    if not callable(generate):
        raise NoGenerator(f"{GENERATOR_MODULE} has no generate_module function")
    return generate  # type: ignore[no-any-return]
