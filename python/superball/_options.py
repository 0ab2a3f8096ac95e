"""How the module's functions read their keywords before the library checks them: a
wrong type is an InputError naming the keyword; values are the library's to refuse."""
from __future__ import annotations

import numbers as _numbers
from typing import Any, Dict, Mapping, Optional

from . import _superball

InputError = _superball.InputError


# The range of the C++ integer each int argument crosses as: int, except a seed (uint64).
_INT_RANGES = {"seed": (0, 2**64 - 1)}


def _int_option(value: Any, name: str) -> int:
    """An int argument; anything else (a bool, a float, a string), or an int the library's
    integer cannot hold, is an InputError naming it (the library's own rule then checks the value)."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
        raise InputError(f"{name}: expected an int, got {value!r}")
    low, high = _INT_RANGES.get(name, (-2**31, 2**31 - 1))
    if not low <= int(value) <= high:
        raise InputError(f"{name}: {int(value)} is out of range (from {low} to {high})")
    return int(value)


def _str_option(value: Any, name: str) -> str:
    if not isinstance(value, str):
        raise InputError(f"{name}: expected a string, got {value!r}")
    return value


def _list_text(value: Any, sep: str = ",") -> Optional[str]:
    if value is None:
        return None
    if isinstance(value, (str, int)):
        return str(value)
    return sep.join(str(v) for v in value)


def _selection(case: Any, alphas: Any, bodies: Optional[int], pairs: Any, coupling: Any, obstacle: str, scaling: Any, order: int,
               closed: Any, all: bool, scene: Any) -> Dict[str, Any]:
    """The keywords of derive, verify and explore as the C++ selection options take them (None: not given)."""
    if isinstance(scaling, Mapping):
        scaling = ",".join(f"{k}={v}" for k, v in scaling.items())
    if coupling is not None and not isinstance(coupling, str):
        coupling = ",".join(c if isinstance(c, str) else "/".join(c) for c in coupling)
    return {"case": None if case is None else str(case), "alphas": _list_text(alphas), "bodies": None if bodies is None else _int_option(bodies, "bodies"), "pairs": _list_text(pairs),
            "coupling": coupling, "obstacle": obstacle, "scaling": scaling, "order": _int_option(order, "order"), "closed": _list_text(closed),
            "all": bool(all), "scene": None if scene is None else str(scene)}


def _checkpoint_option(value: Any, name: str) -> str:
    """The folder of ``checkpoint=`` (a str or a path-like) as the library takes it; None: "" (no checkpoint)."""
    import os

    if value is None:
        return ""
    if not isinstance(value, (str, os.PathLike)):
        raise InputError(f"{name}: checkpoint: expected a folder (a str or a path), got {value!r}")
    folder = os.fspath(value)
    if not isinstance(folder, str) or not folder:
        raise InputError(f"{name}: checkpoint: expected a folder name, got {value!r}")
    return folder
