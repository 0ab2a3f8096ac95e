"""Progress of long calls: a callable given by the user, or a one-line bar on
standard error when it is a terminal, or nothing."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional

#: progress(phase, done, total): told before the first task of each phase and after each task.
ProgressCallback = Callable[[str, int, int], Any]


class _Bar:
    """A one-line bar on standard error, redrawn in place: ``map: points [#####     ] 32/64``."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __call__(self, phase: str, done: int, total: int) -> None:
        width = 30
        filled = width * done // total if total else width
        sys.stderr.write(f"\r{self.name}: {phase} [{'#' * filled}{' ' * (width - filled)}] {done}/{total}")
        if done == total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def resolve(progress: Any, name: str) -> Optional[ProgressCallback]:
    """What to call for ``progress=``: ``None`` (the default) gives the bar when
    standard error is a terminal, else nothing; ``False`` nothing; ``True`` the
    bar; a callable itself."""
    if progress is None:
        isatty = getattr(sys.stderr, "isatty", None)
        return _Bar(name) if isatty is not None and isatty() else None
    if progress is True:
        return _Bar(name)
    if progress is False:
        return None
    if not callable(progress):
        from . import InputError

        raise InputError(f"progress: expected a callable (phase, done, total), True, False or None, got {progress!r}")
    return progress
