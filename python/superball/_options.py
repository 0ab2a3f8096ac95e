"""How the module's functions read their keywords before the library checks them: a
wrong type is an InputError naming the keyword; values are the library's to refuse."""
from __future__ import annotations

import numbers as _numbers
from typing import Any, Dict, Mapping, Optional

from . import _superball

InputError = _superball.InputError


def _int_option(value: Any, name: str) -> int:
    """An int argument; anything else (a bool, a float, a string) is an InputError naming it."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
        raise InputError(f"{name}: expected an int, got {value!r}")
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
