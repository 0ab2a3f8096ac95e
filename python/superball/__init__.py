"""superball: collisions of aligned balls in Frémond's theory, from Python.

A stack of bodies 1 (top) … n (bottom) collides with velocities U⁻; the
dissipation is a quadratic pseudo-potential of the relative velocities
D_ij(U) = U_i − U_j of the pairs, with a symmetric positive semi-definite
matrix M (diagonal K_ij, couplings α between two pairs), plus
impenetrability on the adjacent contacts.  With K = DᵀMD and
A = diag(m) + K, the velocities after the collision W = U⁺ solve

    A W = diag(m) U⁻ − K U⁻ + Cᵀλ,   w = C W ≥ 0,  λ ≥ 0,  wᵀλ = 0,

(λ = −R the reactions on the contacts, C the contact incidence), a linear
complementarity problem with exactly one solution.  The *evolution case* is
the set of contacts that stay closed; the *superball* is U₁⁺ > |U₁⁻|.

This package is a thin front over the C++ libraries of the `superball`
command (same answers, same messages):

- :class:`Scene` — a scene (``Scene.load(path)``, ``Scene.from_dict(...)``,
  ``Scene(bodies=..., K=..., ...)``, ``scene.with_value("K.3-4", 7)``);
- :func:`solve` — one collision in double, long double, MPFR floats of N
  digits, exact rationals, or ``auto`` (the cheapest certified);
- :func:`sweep` and :func:`switch_points` — one parameter varied, on all
  cores, without the GIL; where the evolution case changes, exactly;
- :func:`derive`, :func:`derive_all` — an evolution case, or every case in
  worker processes, solved symbolically (GiNaC), with its conditions exact
  and asymptotic, as text, LaTeX, exact values, NumPy functions and SymPy;
- :func:`audit`, :func:`verify`, :func:`explore` — the paper's printed
  conditions checked, derived conditions checked against exact solutions,
  and a search for the superball in a case.

Bad input raises :class:`InputError` (a ``ValueError``) with the command
line's one-line message; any other failure raises :class:`Error`.
"""

from __future__ import annotations

import html as _html
import json as _json
import numbers as _numbers
import sys as _sys
from dataclasses import dataclass, field
from fractions import Fraction
from typing import AbstractSet, Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _progress, _superball
from ._options import _checkpoint_option, _int_option, _selection, _str_option

__all__ = [
    "Error", "InputError", "Scene", "Result", "solve", "ExactRange", "linspace", "SweepResult", "DropSweepResult", "sweep",
    "SwitchPoint", "switch_points", "Condition", "Derivation", "derive", "derive_all", "audit", "verify", "explore",
    "DEFAULT_RTOL", "STATUSES", "map", "MapResult", "BoundaryPoint", "MapCurve", "MapAxis", "Overlay", "DerivedZero", "OverlayMatch",
    "DropMapResult", "drop", "DropResult", "DropEvent", "DropApex", "DropRest", "gaps_to_zero", "GapLimit", "GapLimitStep",
]

Error = _superball.Error
Error.__doc__ = "A failure of superball that is not bad input (an internal error: a bug to be reported)."
Error.__module__ = "superball"
InputError = _superball.InputError
InputError.__doc__ = ("Bad input: a scene, a parameter, an option.  A ValueError (and a superball.Error) whose "
                      "message is the command line's one line, e.g. 'x.toml:3:8: body[1].mass: must be > 0 (got -1)'.")
InputError.__module__ = "superball"

#: The version of the libraries the module is built from (``superball --version``).
__version__: str = _superball.__version__
#: The default ``rtol`` of ``precision="auto"``: six significant digits of every velocity, certified.
DEFAULT_RTOL: float = _superball.default_rtol
#: A solve's status, by the code the sweep arrays hold (``SweepResult.status_codes``).
STATUSES: Tuple[str, ...] = ("success", "numerical-issue", "no-convergence")

Number = Union[int, float, Fraction, str]


# ---------------------------------------------------------------------------
# Scenes


def _number_text(value: Any, what: str) -> str:
    """The spelling of a number as a scene file reads it (exactly as written)."""
    if isinstance(value, bool):
        raise InputError(f"{what}: expected a number, got {value!r}")
    if isinstance(value, str):
        return value
    try:
        if isinstance(value, Fraction):
            return f"{value.numerator}/{value.denominator}"
        if isinstance(value, _numbers.Integral):
            return str(int(value))
    except ValueError:  # Python's own limit on int to decimal text
        raise InputError(f"{what}: a number of more digits than Python writes as text "
                         f"(sys.get_int_max_str_digits(): {_sys.get_int_max_str_digits()})") from None
    if isinstance(value, _numbers.Real):
        x = float(value)
        if x == float("inf"):
            return "inf"
        return repr(x)  # the shortest decimal that reads back as x: 0.001 is read as 1/1000
    try:  # decimal.Decimal and other exact types
        return str(Fraction(value))
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected a number, got {value!r}") from None


def _check_scene(scene: Any, function: str) -> None:
    if not isinstance(scene, Scene):
        raise InputError(f"{function}: expected a superball.Scene, got {type(scene).__name__}")


def _scene_number(value: Any) -> Any:
    """A number of a scene as a scene file spells it (exact); anything else as it is,
    for the scene reader to refuse naming the field ("must be a number …")."""
    if isinstance(value, (bool, str, list, tuple, dict)) or value is None:
        return value
    if isinstance(value, (_numbers.Number, Fraction)) or hasattr(value, "as_integer_ratio"):
        try:
            return _number_text(value, "number")
        except InputError:  # not a real number (complex), or too long: refused by the reader, naming the field
            return value
    return value


_SCENE_KEYS = ("title", "fall_speed", "drop_height", "g", "bodies", "K", "alpha", "coupling", "flight", "drop")


def _coupling_value(c: Any) -> Any:
    """A coupling as a scene file's {pairs = [p, q], value = v}, from a dict, (p, q, v), ((p, q), v) or ("p/q", v)."""
    if isinstance(c, Mapping):
        pairs, value = c.get("pairs"), c.get("value")
        rest = {k: v for k, v in c.items() if k not in ("pairs", "value")}
    elif isinstance(c, (tuple, list)) and len(c) == 3:
        pairs, value, rest = [c[0], c[1]], c[2], {}
    elif isinstance(c, (tuple, list)) and len(c) == 2:
        pairs, value, rest = c[0], c[1], {}
    else:
        return c  # refused by the reader, naming the field
    if isinstance(pairs, str):
        pairs = pairs.split("/")
    out = {"pairs": [str(p) for p in pairs] if isinstance(pairs, (list, tuple)) else pairs, "value": _scene_number(value), **rest}
    return {k: v for k, v in out.items() if v is not None}


def _scene_value(d: Mapping[str, Any], what: str) -> Dict[str, Any]:
    """The keywords of :class:`Scene` as the tree of a scene file (title, body, dissipation, flight),
    numbers spelled exactly: the library builds and checks the scene from it (no TOML text)."""
    unknown = [k for k in d if k not in _SCENE_KEYS]
    if unknown:
        raise InputError(f"{what}: unknown key '{unknown[0]}' (expected one of: {', '.join(_SCENE_KEYS)})")
    v: Dict[str, Any] = {}
    if d.get("title") is not None:
        v["title"] = d["title"]
    for key in ("fall_speed", "drop_height", "g"):
        if d.get(key) is not None:
            v[key] = _scene_number(d[key])
    bodies = d.get("bodies")
    if bodies is not None:
        if isinstance(bodies, (str, Mapping, AbstractSet)) or not isinstance(bodies, Iterable):  # a set has no order
            raise InputError(f"{what}: bodies: expected a list of masses, or of {{'mass': …, 'velocity': …}}, got {bodies!r}")
        bodies = list(bodies)
        v["body"] = bodies if len(bodies) > _superball.max_scene_bodies else [  # too many: refused before one is read
            {k: _scene_number(x) for k, x in b.items()} if isinstance(b, Mapping) else {"mass": _scene_number(b)} for b in bodies]
    dissipation: Dict[str, Any] = {}
    for key in ("K", "alpha"):
        if d.get(key):
            m = d[key]
            # keys as given: two spellings of one key (2 and "2") are refused by the reader as given twice
            dissipation[key] = {p: _scene_number(x) for p, x in m.items()} if isinstance(m, Mapping) else m
    if d.get("coupling"):
        c = d["coupling"]
        dissipation["coupling"] = [_coupling_value(x) for x in c] if isinstance(c, (list, tuple)) and len(c) <= _superball.max_scene_bodies else c
    if dissipation:
        v["dissipation"] = dissipation
    flight = d.get("flight")
    if flight is True:
        v["flight"] = {}
    elif isinstance(flight, Mapping):
        v["flight"] = {k: _scene_number(x) for k, x in flight.items()}
    elif flight not in (None, False):
        v["flight"] = flight
    drop = d.get("drop")
    if drop is True:
        v["drop"] = {}
    elif isinstance(drop, Mapping):
        v["drop"] = {k: _scene_number(x) for k, x in drop.items()}
    elif drop not in (None, False):
        v["drop"] = drop
    return v


class Scene:
    """A scene: the bodies, the fall, the matrix M of dissipation (paper §1–§3).

    Bodies are numbered 1 (top) … n (bottom).  Bodies without a velocity of
    their own fall at −a, a = ``fall_speed`` or √(2 g h) with h =
    ``drop_height``.  M is given by its declared entries: ``K`` (diagonal,
    ``{"1-2": 7, …}``), ``alpha`` (the paper's α₁…α₇ for 4 bodies,
    ``{2: -100}``) and ``coupling`` (``[("1-3", "2-4", 3)]`` or
    ``[{"pairs": ["1-3", "2-4"], "value": 3}]``).  ``flight=True`` (or a dict
    of ``[flight]``'s keys) asks for the flight after the collision;
    ``drop=True`` (or a dict: ``until``, ``max_events``) for the whole drop
    (:func:`drop`), the bodies released ``drop_height`` over the obstacle and
    each ``{"mass": …, "gap": …}`` above the body below it.

    Numbers are read exactly as written: ints, ``Fraction``, strings
    (``"1/3"``, ``"5e6"``) and floats by their shortest decimal (``0.001`` is
    1/1000).  A mass ``float("inf")`` or ``"inf"`` is a fixed obstacle (bottom
    body only).  Every check of a scene file applies (the same loader);
    errors raise :class:`InputError`.

    >>> s = Scene(bodies=[0.001, 10, 15, {"mass": 5e6, "velocity": 0}], fall_speed=3.13209,
    ...           K={"1-2": 7, "1-3": 7, "1-4": 1500, "2-3": 10, "2-4": 13, "3-4": 10}, alpha={2: -100})
    """

    __slots__ = ("_scene",)

    def __init__(self, bodies: Optional[Sequence[Any]] = None, *, title: Optional[str] = None, fall_speed: Optional[Number] = None,
                 drop_height: Optional[Number] = None, g: Optional[Number] = None, K: Optional[Mapping[str, Number]] = None,
                 alpha: Optional[Mapping[Union[int, str], Number]] = None, coupling: Optional[Sequence[Any]] = None,
                 flight: Union[bool, Mapping[str, Number], None] = None, drop: Union[bool, Mapping[str, Any], None] = None,
                 _scene: Any = None) -> None:
        if _scene is not None:
            self._scene = _scene
            return
        d = {"title": title, "fall_speed": fall_speed, "drop_height": drop_height, "g": g, "bodies": bodies, "K": K,
             "alpha": alpha, "coupling": coupling, "flight": flight, "drop": drop}
        origin = title if isinstance(title, str) and title else "<scene>"
        self._scene = _superball.Scene.from_value(_scene_value(d, "Scene"), origin)

    @classmethod
    def load(cls, path: Any) -> "Scene":
        """Read a scene file (TOML, docs/SCENES.md); ``"-"`` reads standard input."""
        return cls(_scene=_superball.Scene.load(str(path)))

    @classmethod
    def from_toml(cls, text: str, origin: str = "<string>") -> "Scene":
        """Read a scene from TOML text; ``origin`` names it in messages."""
        return cls(_scene=_superball.Scene.parse(text, origin))

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Scene":
        """A scene from a dict with the keyword arguments of :class:`Scene` as keys
        (``{"bodies": [...], "fall_speed": 3.13209, "K": {...}, "alpha": {...}}``)."""
        if not isinstance(d, Mapping):
            raise InputError(f"Scene.from_dict: expected a dict, got {type(d).__name__}")
        title = d.get("title")
        origin = title if isinstance(title, str) and title else "<dict>"
        return cls(_scene=_superball.Scene.from_value(_scene_value(d, "Scene.from_dict"), origin))

    def with_value(self, key: str, value: Number) -> "Scene":
        """A copy with the parameter ``key`` set to ``value``.

        ``key`` names it as the command line does: ``K.3-4`` (diagonal of M),
        ``alpha.2``, ``coupling.1-2/1-4``, ``mass.1``, ``velocity.4``,
        ``drop_height``, ``fall_speed``, ``g``.  The scene loader's checks
        apply (a mass ≤ 0, g ≤ 0 … raise :class:`InputError`).
        """
        return Scene(_scene=self._scene.with_value(key, _number_text(value, key)))

    def to_toml(self, comment: str = "") -> str:
        """The scene as a scene file (reads back to the same exact values)."""
        return self._scene.to_toml(comment)

    @property
    def title(self) -> str:
        """The scene's title (its ``title`` key; empty when it has none)."""
        return self._scene.title

    @property
    def origin(self) -> str:
        """The file it came from, or the label it was given."""
        return self._scene.origin

    @property
    def bodies(self) -> int:
        """The number of bodies n."""
        return self._scene.bodies

    @property
    def masses(self) -> List[Union[Fraction, float]]:
        """The masses, exact (``inf`` for a fixed obstacle)."""
        return [float("inf") if m == "inf" else Fraction(m) for m in self._scene.masses]

    @property
    def velocities(self) -> List[Optional[Fraction]]:
        """The velocities given before the collision, per body, exact (None: the body falls at −a)."""
        return self._scene.velocities

    @property
    def fall_speed(self) -> Optional[Fraction]:
        """a, when the scene gives it (else None: a = √(2 g h) from ``drop_height``)."""
        return self._scene.fall_speed

    @property
    def drop_height(self) -> Optional[Fraction]:
        """h, when the scene gives it."""
        return self._scene.drop_height

    @property
    def g(self) -> Fraction:
        """g (9.81 unless given)."""
        return self._scene.g

    @property
    def K(self) -> Dict[str, Fraction]:
        """The diagonal of M as declared: ``{"1-2": Fraction(7), …}``."""
        return self._scene.matrix["K"]

    @property
    def alpha(self) -> Dict[int, Fraction]:
        """The couplings the paper names α₁ … α₇ (4 bodies): ``{2: Fraction(-100)}``."""
        return self._scene.matrix["alpha"]

    @property
    def couplings(self) -> Dict[str, Fraction]:
        """The other couplings (off-diagonal entries of M) as declared: ``{"1-2/2-3": Fraction(3)}``."""
        return self._scene.matrix["coupling"]

    @property
    def keys(self) -> List[str]:
        """The keys of the values the scene holds, as :meth:`with_value`, :func:`sweep` and :func:`map` take them:
        ``["K.1-2", …, "alpha.2", "mass.1", …, "velocity.4", "fall_speed"]``; a drop scene's gaps too
        (``"gap.1"`` … ``"gap.{n-2}"``)."""
        return self._scene.keys

    @property
    def flight(self) -> bool:
        """Whether the scene asks for the flight after the collision ([flight])."""
        return self._scene.flight

    @property
    def drop(self) -> bool:
        """Whether the scene asks for the whole drop ([drop]: :func:`drop`)."""
        return self._scene.drop

    def __repr__(self) -> str:
        fall = f"fall_speed={float(self.fall_speed):.6g}" if self.fall_speed is not None else (
            f"drop_height={float(self.drop_height):.6g}, g={float(self.g):.6g}" if self.drop_height is not None else "no fall")
        return (f"<superball.Scene {self.origin!r}: {self.bodies} bodies, {fall}, {len(self.K)} K, "
                f"{len(self.alpha) + len(self.couplings)} couplings>")

    def _repr_html_(self) -> str:
        e = _html.escape

        def num(x: Any) -> str:
            return "∞" if x == float("inf") else e(str(x))

        bodies = "".join(f"<tr><td>{i + 1}</td><td>{num(m)}</td><td>{'−a' if v is None else num(v)}</td></tr>"
                         for i, (m, v) in enumerate(zip(self.masses, self.velocities)))
        fall = (f"a = {num(self.fall_speed)}" if self.fall_speed is not None else
                f"h = {num(self.drop_height)}, g = {num(self.g)}" if self.drop_height is not None else "")
        entries = [f"K<sub>{e(p.replace('-', ''))}</sub> = {num(x)}" for p, x in self.K.items()]
        entries += [f"α<sub>{k}</sub> = {num(x)}" for k, x in self.alpha.items()]
        entries += [f"M<sub>{e(p)}</sub> = {num(x)}" for p, x in self.couplings.items()]
        return (f"<div><b>{e(self.origin)}</b>{': ' + e(self.title) if self.title else ''}<br>{fall}"
                f"<table><tr><th>body</th><th>mass (kg)</th><th>U⁻ (m/s)</th></tr>{bodies}</table>"
                f"M: {', '.join(entries) or 'none declared'}<br>keys: {e(', '.join(self.keys))}</div>")


# ---------------------------------------------------------------------------
# One collision


def _fraction_or_none(text: str) -> Optional[Fraction]:
    return None if "sqrt" in text else Fraction(text)


class Result:
    """One collision solved (``superball solve``): every field of its ``--json``.

    Velocities are in m/s, top body first; ``reactions[c]`` is the reaction
    R (N s, ≤ 0) on contact (c+1, c+2), 0 where the contact opens.  In exact
    arithmetic ``velocities_after_exact`` and ``reactions_exact`` are
    :class:`fractions.Fraction` (``None`` when the fall speed a = √(2 g h) is
    irrational: then ``velocities_after_text`` has ``"p/q*sqrt(a²)"``).
    Momentum is conserved and kinetic energy does not increase:
    Σ mᵢU⁺ᵢ = Σ mᵢU⁻ᵢ (finite bodies, no obstacle) and
    E⁺ = E⁻ − dissipation ≤ E⁻.
    """

    __slots__ = ("_p", "_cache", "_before")

    def __init__(self, presented: Any, before: Optional[List[Optional[Fraction]]] = None) -> None:
        self._p = presented
        self._cache: Dict[str, Any] = {}
        self._before = before

    # plain fields
    origin = property(lambda self: self._p.origin, doc="The scene's file or label.")
    title = property(lambda self: self._p.title, doc="The scene's title.")
    precision = property(lambda self: self._p.precision, doc="The arithmetic of the answer: double, long-double, digits:N, exact.")
    precision_requested = property(lambda self: self._p.requested or self._p.precision, doc="'auto' when chosen by certification.")
    error_bound = property(lambda self: self._p.error_bound if self._p.requested else None,
                           doc="auto: certified bound on max|U⁺ − exact U⁺| / max|U⁺| (None otherwise).")
    escalation = property(lambda self: list(self._p.escalation), doc="auto: what was tried, e.g. ['double: case not certain', 'exact'].")
    warnings = property(lambda self: list(self._p.warnings),
                        doc="Why an answer of an explicit double, long-double or digits:N cannot be trusted (its case not "
                            "certified, or its certified bound says nothing); [] when it can, and always for auto and exact.")
    status = property(lambda self: self._p.status, doc="'success', 'numerical-issue' or 'no-convergence'.")
    case = property(lambda self: self._p.case, doc="The evolution case: the paper's name for 4 bodies ('3.3'), else '{2-3,3-4}'.")
    closed_contacts = property(lambda self: tuple(self._p.closed_contacts), doc="The contacts that stay closed, e.g. ('2-3',).")
    superball = property(lambda self: self._p.superball, doc="U₁⁺ > |U₁⁻|: the top body leaves faster than it came.")
    bodies = property(lambda self: self._p.bodies, doc="n.")
    pivots = property(lambda self: self._p.pivots, doc="Principal pivots of the complementarity solve.")
    exact = property(lambda self: self._p.exact, doc="Whether the arithmetic is exact (rationals).")
    kinetic_energy_before = property(lambda self: self._p.kinetic_energy_before, doc="E⁻ = ½ Σ mᵢ(U⁻ᵢ)² over finite bodies (J).")
    kinetic_energy_after = property(lambda self: self._p.kinetic_energy_after, doc="E⁺ (J).")
    dissipation = property(lambda self: self._p.dissipation, doc="P·X = 2XᵀMX + R·X ≥ 0, X = D(U⁺+U⁻)/2 (J): E⁻ − E⁺.")
    momentum_before = property(lambda self: self._p.momentum_before, doc="Σ mᵢU⁻ᵢ over finite bodies (kg m/s).")
    momentum_after = property(lambda self: self._p.momentum_after, doc="Σ mᵢU⁺ᵢ over finite bodies (kg m/s).")
    residual_motion = property(lambda self: self._p.residual_motion, doc="Largest relative residual of the equations of motion.")
    residual_complementarity = property(lambda self: self._p.residual_complementarity, doc="Largest relative violation of w ≥ 0, λ ≥ 0, wλ = 0.")
    contacts = property(lambda self: tuple(f"{c + 1}-{c + 2}" for c in range(self._p.bodies - 1)), doc="('1-2', '2-3', …).")

    @property
    def masses(self) -> np.ndarray:
        """Masses (kg), float64, ``inf`` for a fixed obstacle."""
        return self._p.masses

    @property
    def velocities_before(self) -> np.ndarray:
        """U⁻ (m/s), float64, shape (n,)."""
        return self._p.before

    @property
    def velocities_after(self) -> np.ndarray:
        """U⁺ (m/s), float64, shape (n,): the answer rounded to double."""
        return self._p.after

    @property
    def velocities_after_text(self) -> List[str]:
        """U⁺ in the solve's own arithmetic, as text (exact: ``"p/q"``)."""
        return list(self._p.after_text)

    @property
    def velocities_after_exact(self) -> Optional[List[Optional[Fraction]]]:
        """U⁺ as Fractions when the arithmetic is exact, else None."""
        if not self._p.exact:
            return None
        if "v" not in self._cache:
            self._cache["v"] = [_fraction_or_none(t) for t in self._p.after_text]
        return self._cache["v"]

    @property
    def velocities_before_exact(self) -> List[Optional[Fraction]]:
        """U⁻ exactly, whatever the arithmetic of the solve: −a for a falling body, its velocity otherwise
        (``None`` for a falling body when a = √(2 g h) is irrational)."""
        return list(self._before) if self._before is not None else [None] * self.bodies

    @property
    def ratio(self) -> Union[Fraction, float, None]:
        """U₁⁺/a (U₁⁺/|U₁⁻|; the superball is ratio > 1): a Fraction when the arithmetic is exact and a is
        rational, else a float in the solve's answer; None when U₁⁻ = 0."""
        u1 = self.velocities_before_exact[0]
        after = self.velocities_after_exact
        if u1 is not None and after is not None and after[0] is not None:
            return after[0] / abs(u1) if u1 != 0 else None
        before = float(u1) if u1 is not None else float(self.velocities_before[0])
        return float(self.velocities_after[0]) / abs(before) if before != 0 else None

    @property
    def reactions(self) -> np.ndarray:
        """R on each contact (N s, ≤ 0), float64, shape (n−1,)."""
        return self._p.reactions

    @property
    def reactions_exact(self) -> Optional[List[Optional[Fraction]]]:
        """R as Fractions when the arithmetic is exact, else None."""
        if not self._p.exact:
            return None
        return [_fraction_or_none(t) for t in self._p.reaction_text]

    def to_dict(self) -> Dict[str, Any]:
        """Every field, exactly as ``superball solve --json`` writes them."""
        return self._p.to_dict()

    def to_text(self) -> str:
        """The report of ``superball solve``."""
        return self._p.to_text()

    def __repr__(self) -> str:
        v = ", ".join(f"{x:.6g}" for x in self.velocities_after)
        return f"<superball.Result {self.origin!r} {self.precision} {self.status}: U+ = [{v}], case {self.case}, superball {self.superball}>"

    def _repr_html_(self) -> str:
        e = _html.escape
        exact = self.exact or self.precision != "double"
        rows = []
        for i in range(self.bodies):
            m = self.masses[i]
            cells = [str(i + 1), "∞" if np.isinf(m) else f"{m:.6g}", f"{self.velocities_before[i]:.6g}", f"{self.velocities_after[i]:.6g}"]
            if exact:
                cells.append(e(self.velocities_after_text[i]))
            rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
        head = ["body", "mass (kg)", "U⁻ (m/s)", "U⁺ (m/s)"] + (["U⁺ exact"] if exact else [])
        closed = ", ".join(self.closed_contacts) or "none"
        reactions = ", ".join(f"R<sub>{c}</sub> = {r:.6g}" for c, r in zip(self.contacts, self.reactions))
        return (f"<div><b>{e(self.origin)}</b>{': ' + e(self.title) if self.title else ''}<br>"
                f"precision {e(self.precision)}, status {e(self.status)}<table><tr>"
                + "".join(f"<th>{h}</th>" for h in head) + "</tr>" + "".join(rows) + "</table>"
                f"case <b>{e(self.case)}</b> (closed contacts: {e(closed)}); reactions (N s): {reactions}<br>"
                f"kinetic energy (J): before {self.kinetic_energy_before:.8g}, after {self.kinetic_energy_after:.8g}, "
                f"dissipated {self.dissipation:.8g}<br>superball: <b>{'yes' if self.superball else 'no'}</b></div>")


def solve(scene: Scene, precision: str = "auto", rtol: Optional[float] = None) -> Result:
    """Solve the collision of ``scene`` (paper §2–§3; ``superball solve``).

    ``precision``: ``"auto"`` (default: double, then long double, then exact
    rationals, the first whose evolution case is certain and whose velocity
    error is certified below ``rtol`` relative to max|U⁺|, default
    :data:`DEFAULT_RTOL`), ``"double"``, ``"long-double"``, ``"digits:N"``
    (MPFR floats of at least N decimal digits, 10 ≤ N ≤ 10000) or ``"exact"`` (CLN
    rationals).  ``rtol`` applies to ``"auto"`` only.

    The solver finds the unique solution of the complementarity problem
    w = q + Nλ, w ≥ 0, λ ≥ 0, wᵀλ = 0 (N = C A⁻¹ Cᵀ) by principal pivoting
    and checks it against the equations of motion; ``Result.status`` says
    how it ended.  The GIL is released while it solves.
    """
    _check_scene(scene, "solve")
    if rtol is not None and (isinstance(rtol, bool) or not isinstance(rtol, _numbers.Real)):
        raise InputError(f"solve: rtol: expected a number, got {rtol!r}")
    return Result(_superball.solve(scene._scene, _str_option(precision, "precision"), None if rtol is None else float(rtol)),
                  scene._scene.velocities_before)


# ---------------------------------------------------------------------------
# Sweeps


class ExactRange:
    """``steps`` equally spaced exact values from ``start`` to ``stop``, ends
    included: x_k = start + (stop − start)·k/(steps − 1), as the command line's
    ``--vary KEY=START:STOP:STEPS``.  ``np.asarray(r)`` gives them as float64."""

    __slots__ = ("start", "stop", "steps", "_values")

    def __init__(self, start: Number, stop: Number, steps: int) -> None:
        self.start, self.stop, self.steps = start, stop, int(steps)
        self._values = _superball.Values.linspace(_number_text(start, "start"), _number_text(stop, "stop"), self.steps)

    def __len__(self) -> int:
        return self.steps

    def __array__(self, dtype: Any = None) -> np.ndarray:
        a = self._values.as_doubles()
        return a if dtype is None else a.astype(dtype)

    def fractions(self) -> List[Fraction]:
        """The values, exact."""
        return [Fraction(t) for t in self._values.as_text()]

    def __repr__(self) -> str:
        return f"linspace({self.start!r}, {self.stop!r}, {self.steps})"


def linspace(start: Number, stop: Number, steps: int) -> ExactRange:
    """Exact equally spaced values (see :class:`ExactRange`), for :func:`sweep` and :func:`switch_points`."""
    return ExactRange(start, stop, steps)


def _values(values: Any) -> Any:
    """The library's exact values for what a user passes: an ExactRange, a
    NumPy array or sequence of floats (each double taken exactly), or of
    ints, Fractions and strings (read as a scene file reads numbers)."""
    if isinstance(values, ExactRange):
        return values._values
    if isinstance(values, range):
        return _superball.Values.from_text([str(v) for v in values])
    a = np.asarray(values)
    if a.ndim != 1:
        raise InputError(f"values: expected a one-dimensional sequence, got shape {a.shape}")
    if a.dtype.kind == "f":
        return _superball.Values.from_doubles(a.astype(np.float64, copy=False))
    if a.dtype.kind in "iu":
        return _superball.Values.from_text([str(int(v)) for v in a])
    texts = []
    for v in values:
        texts.append(str(Fraction(v)) if isinstance(v, float) else _number_text(v, "values"))
    return _superball.Values.from_text(texts)


@dataclass(frozen=True, repr=False)
class SweepResult:
    """The velocities after the collision along one parameter.

    ``values``: float64 (N,); ``velocities``: float64 (N, n), row k the
    U⁺ at ``values[k]``; ``cases``: the evolution case per value (NumPy
    str array: the paper's name for 4 bodies, else ``"{2-3,3-4}"``);
    ``case_codes``: int32 (N,), the number of each value's case in
    ``case_list`` (the distinct cases, in the order met) and
    ``closed_list`` (their closed contacts); ``status_codes``: int8
    (0 success, see :data:`STATUSES`); ``status``: the names.  ``psd``:
    bool (N,), M positive semi-definite at the value; where it is not, the
    value is not solved (as in a map): NaN velocities, case ``""``, case
    and status code −1.
    """

    key: str
    precision: str
    values: np.ndarray
    velocities: np.ndarray
    cases: np.ndarray
    case_codes: np.ndarray
    case_list: Tuple[str, ...]
    closed_list: Tuple[Tuple[str, ...], ...]
    status_codes: np.ndarray
    psd: Optional[np.ndarray] = None
    scene: Optional["Scene"] = field(default=None, compare=False)
    exact_values: Any = field(default=None, compare=False)  #: the library's exact values (for switch_points())

    @property
    def ratio(self) -> np.ndarray:
        """U₁⁺/a per value (U₁⁺/|U₁⁻|, float64; the superball is ratio > 1), with U₁⁻ exact at each value
        (NaN where it is 0)."""
        if self.scene is None:
            raise Error("SweepResult.ratio: the sweep's scene is not known")
        keys_of_the_fall = ("velocity.1", "fall_speed", "drop_height", "g")
        if self.key not in keys_of_the_fall:
            u1 = self.scene._scene.velocities_before[0]
            before = np.full(len(self), np.nan if u1 is None else float(u1))
        else:  # U₁⁻ changes with the value
            exact = [Fraction(t) for t in self.exact_values.as_text()]
            before = np.array([float(b) if b is not None else np.nan for b in
                               (self.scene._scene.with_value(self.key, _number_text(x, self.key)).velocities_before[0] for x in exact)])
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(before != 0, self.velocities[:, 0] / np.abs(before), np.nan)

    def switch_points(self, bits: int = 64, threads: int = 0) -> List["SwitchPoint"]:
        """Where the evolution case changes between this sweep's values (``superball sweep --switch-points``):
        :func:`switch_points` of the same scene, key and exact values."""
        if self.scene is None or self.exact_values is None:
            raise Error("SweepResult.switch_points: the sweep's scene is not known")
        return _switch_points(self.scene, self.key, self.exact_values, bits, threads)

    def __repr__(self) -> str:
        cases = ", ".join(self.case_list) or "none"
        span = f"{self.values[0]:.6g} … {self.values[-1]:.6g}" if len(self) else "no value"
        return (f"<superball.SweepResult {self.key} = {span} ({len(self)} values, {self.precision}): cases {cases}; "
                f"{'all' if self.ok else int(np.sum(self.status_codes == 0))} solved with success>")

    def _repr_html_(self) -> str:
        e = _html.escape
        rows = "".join(f"<tr><td>{e(c)}</td><td>{e(', '.join(cl) or 'none')}</td><td>{int(np.sum(self.case_codes == k))}</td></tr>"
                       for k, (c, cl) in enumerate(zip(self.case_list, self.closed_list)))
        span = f"{self.values[0]:.6g} to {self.values[-1]:.6g}" if len(self) else "no value"
        return (f"<div><b>sweep of {e(self.key)}</b> from {span} ({len(self)} values, {e(self.precision)})"
                f"<table><tr><th>case</th><th>closed contacts</th><th>values</th></tr>{rows}</table>"
                f"status: {'every value success' if self.ok else e(', '.join(sorted(set(self.status))))}</div>")

    @property
    def status(self) -> np.ndarray:
        """The status names ("" where M is not PSD and the value is not solved)."""
        return np.asarray(STATUSES + ("",), dtype=object)[self.status_codes].astype(str)

    @property
    def ok(self) -> bool:
        """Whether every value solved with status success (and M is PSD at every value)."""
        return bool(np.all(self.status_codes == 0))

    def closed(self, k: int) -> Tuple[str, ...]:
        """The contacts closed at ``values[k]`` (() where it is not solved)."""
        code = int(self.case_codes[k])
        return self.closed_list[code] if code >= 0 else ()

    def __len__(self) -> int:
        return len(self.values)


@dataclass(frozen=True)
class DropSweepResult:
    """The drops of a scene with a [drop] table along one parameter (``superball sweep`` of a drop scene).

    ``values``: float64 (N,); ``ratio``: the top body's apex ratio at each
    value (``DropResult.top_apex_ratio``, float64); ``labels``: the sequence
    of collisions of each drop (NumPy str array, the command's ``label``:
    ``CONTACTS:CASE`` per collision in time order, a run of k equal ones as
    ``TOKEN*k``, docs/DROP.md); ``events``: int32, the number of collisions;
    ``end``: why each run ended (``"apex"``, ``"rest"``, ``"max-events"``, …).
    No switch points: a drop has no exact solution of one collision to bisect.
    """

    key: str
    precision: str
    values: np.ndarray
    ratio: np.ndarray
    labels: np.ndarray
    events: np.ndarray
    end: Tuple[str, ...]

    @property
    def ok(self) -> bool:
        """Whether every run ran its course: none ended on max_events, an unsolved collision or (exact) an irrational time (the command's exit 0)."""
        return all(_superball.drop_finished(e) for e in self.end)

    def __len__(self) -> int:
        return len(self.values)

    def __repr__(self) -> str:
        span = f"{self.values[0]:.6g} to {self.values[-1]:.6g}" if len(self) else "no value"
        return (f"<superball.DropSweepResult {self.key} = {span} ({len(self)} values, {self.precision}): "
                f"{len(set(self.labels.tolist()))} labels; top apex ratio {np.min(self.ratio):.6g} to {np.max(self.ratio):.6g}>")


def sweep(scene: Scene, key: str, values: Any, precision: str = "double", threads: int = 0, progress: Any = None,
          checkpoint: Any = None) -> Union[SweepResult, DropSweepResult]:
    """Solve ``scene`` at every value of the parameter ``key`` (``superball sweep``).

    ``key`` as in :meth:`Scene.with_value` (``"K.3-4"``).  ``values``: a
    :func:`linspace` (exact, as the command line), a NumPy array or sequence
    of floats (each double exactly), or ints, Fractions, strings.  The range
    is checked first: values where M is not positive semi-definite (decided
    exactly) are marked in ``psd`` and not solved; any other inadmissible
    value, or M PSD at no value, raises :class:`InputError` before anything
    is solved.  Solved on ``threads`` threads (0: all cores) with
    the GIL released; the result does not depend on ``threads``, bit for bit.
    ``progress``: a callable ``(phase, done, total)`` told after each block
    of 2¹⁶ values, True/False, or None (a bar on standard error when it is a
    terminal); Ctrl-C stops the sweep (KeyboardInterrupt) between two blocks.
    ``SweepResult.switch_points()`` bisects its case changes exactly.
    ``checkpoint``: a folder (``superball sweep --checkpoint``) where each
    block of values is written as soon as it is solved; the same call made
    again (same scene, key, values and precision) solves only the blocks
    not there, and the result is the same.

    A scene with a [drop] table gives a :class:`DropSweepResult` instead:
    each value's whole drop (:func:`drop`), its top apex ratio and its
    sequence of collisions, as ``superball sweep`` prints them (keys as
    above plus ``gap.i``; precision double or long-double; no checkpoint).
    """
    _check_scene(scene, "sweep")
    v = _values(values)
    if scene.drop:
        x, ratio, labels, events, end = _superball.drop_sweep(scene._scene, _str_option(key, "key"), v, _str_option(precision, "precision"),
                                                              _int_option(threads, "threads"), _progress.resolve(progress, "sweep"),
                                                              _checkpoint_option(checkpoint, "sweep"))
        return DropSweepResult(str(key), str(precision), x, ratio, np.array(labels, dtype=str), events, tuple(end))
    x, u, codes, (names, closed), status, psd = _superball.sweep(scene._scene, _str_option(key, "key"), v, _str_option(precision, "precision"),
                                                            _int_option(threads, "threads"), _progress.resolve(progress, "sweep"),
                                                            _checkpoint_option(checkpoint, "sweep"))
    cases = np.array(list(names) + [""], dtype=str)[codes]
    return SweepResult(str(key), str(precision), x, u, cases, codes, tuple(names), tuple(tuple(c) for c in closed), status, psd, scene, v)


@dataclass(frozen=True)
class SwitchPoint:
    """A change of evolution case between two parameter values, bracketed
    exactly: the case is ``case_below`` just below ``value`` and
    ``case_above`` just above; ``high − low`` is the width left by bisection
    on the exact solution."""

    key: str
    value: float
    low: Fraction
    high: Fraction
    width: float
    case_below: str
    case_above: str
    closed_below: Tuple[str, ...]
    closed_above: Tuple[str, ...]
    text: str  #: the middle of the bracket, 17 significant digits, as the command line prints it


def switch_points(scene: Scene, key: str, values: Any, bits: int = 64, threads: int = 0) -> List[SwitchPoint]:
    """Where the evolution case changes along ``key`` (``superball sweep --switch-points``).

    Between consecutive ``values`` (monotone) whose cases differ, the change
    is bisected on the exact solution (CLN rationals) until the bracket is
    narrower than 2^-bits of the step; a third case inside a bracket is
    found too.  In increasing value, each starting in the case the previous
    one ended in.  GIL released; ``threads`` as in :func:`sweep`.
    """
    _check_scene(scene, "switch_points")
    return _switch_points(scene, key, _values(values), bits, threads)


def _switch_points(scene: Scene, key: str, v: Any, bits: int, threads: int) -> List[SwitchPoint]:
    out = []
    for low, high, middle, width, below, closed_below, above, closed_above in _superball.switch_points(
            scene._scene, _str_option(key, "key"), v, _int_option(bits, "bits"), _int_option(threads, "threads")):
        out.append(SwitchPoint(str(key), float(middle), Fraction(low), Fraction(high), float(width), below, above, tuple(closed_below),
                               tuple(closed_above), middle))
    return out


# ---------------------------------------------------------------------------
# Derivations (_derive.py)

from ._derive import Condition, Derivation, derive, derive_all  # noqa: E402

# ---------------------------------------------------------------------------
# Audit, verification, exploration


def _text_html(title: str, text: str) -> str:
    """A result's report for a notebook: a bold title over the command's text."""
    return f"<div><b>{_html.escape(title)}</b><pre>{_html.escape(text)}</pre></div>"


@dataclass(frozen=True, repr=False)
class AuditResult:
    """The paper's printed conditions (§4.1–§4.3) and claims against the derivation (``superball audit``).

    ``conditions``: per printed condition a dict with ``agreement``
    (``identical-exact``, ``identical-asymptotic`` or ``different``), the
    forms and, for a different one, a ``witness`` point (exact values as
    ``"p/q"``) where the printed condition disagrees with the exact solution;
    ``claims``: per claim in words, ``supported`` and the ``verdict``.
    ``data`` is ``superball audit --json``; ``str()`` the report.
    """

    conditions: List[Dict[str, Any]]
    claims: List[Dict[str, Any]]
    data: Dict[str, Any] = field(repr=False)
    text: str = field(repr=False)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        agreements = [c.get("agreement") for c in self.conditions]
        different = sum(a == "different" for a in agreements)
        supported = sum(bool(c.get("supported")) for c in self.claims)
        return (f"<superball.AuditResult: {len(self.conditions)} printed conditions, {different} different from the derivation; "
                f"{supported} of {len(self.claims)} claims supported>")

    def _repr_html_(self) -> str:
        return _text_html("superball audit", self.text)


def audit(epsilon: Number = Fraction(1, 1000), samples: int = 20000, seed: int = 1) -> AuditResult:
    """Audit every condition and claim the paper prints (§4.1–§4.3) against the derivation,
    with counterexamples solved exactly; points sampled at m₁ = ε·O(1), K₁₄ = O(1)/ε."""
    d, text = _superball.audit(_number_text(epsilon, "epsilon"), _int_option(samples, "samples"), _int_option(seed, "seed"))
    return AuditResult(d["conditions"], d["claims"], d, text)


@dataclass(frozen=True, repr=False)
class VerifyResult:
    """A case's derived conditions against exact solutions (``superball verify``).

    ``epsilons``: float64 (k,); ``exact_agreement`` and
    ``asymptotic_agreement``: float64 (k,), the share of the points at each ε
    where the conjunction of the exact (asymptotic) conditions agrees with
    the exact solution's "case actual and U₁⁺ > a" (drawn and boundary
    points together); ``points``: int64 (k,).  ``exact_agrees``: the exact
    conditions agree at every point (each one and their conjunction) — the
    asymptotic ones are expected to agree only as ε → 0.  ``data``: the
    command's ``--json``; ``str()``: its tables.
    """

    case: str
    exact_agrees: bool
    epsilons: np.ndarray
    points: np.ndarray
    exact_agreement: np.ndarray
    asymptotic_agreement: np.ndarray
    data: Dict[str, Any] = field(repr=False)
    text: str = field(repr=False)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        eps = ", ".join(f"{e:g}" for e in self.epsilons)
        return (f"<superball.VerifyResult case {self.case}: exact conditions agree everywhere: {self.exact_agrees}; "
                f"eps {eps}; {int(self.points.sum())} points>")

    def _repr_html_(self) -> str:
        return _text_html(f"superball verify, case {self.case}", self.text)


def _verify_result(data: Dict[str, Any], text: str, agrees: bool) -> VerifyResult:
    eps, points, exact, asym = [], [], [], []
    for e in data["epsilons"]:
        eps.append(float(Fraction(e["epsilon"])))
        total = agree_exact = agree_asym = 0
        for stage in ("drawn", "boundary"):
            t = e[stage]
            for name, sink in (("exact", "e"), ("asymptotic", "a")):
                c = t[name]
                n = c["holds_true"] + c["holds_false"] + c["fails_true"] + c["fails_false"]
                agree = c["holds_true"] + c["fails_false"]
                if sink == "e":
                    total += n
                    agree_exact += agree
                else:
                    agree_asym += agree
        points.append(total)
        exact.append(agree_exact / total if total else np.nan)
        asym.append(agree_asym / total if total else np.nan)
    return VerifyResult(data["case"], bool(agrees), np.array(eps, dtype=np.float64), np.array(points, dtype=np.int64),
                        np.array(exact, dtype=np.float64), np.array(asym, dtype=np.float64), data, text)


def verify(case: Optional[str] = None, alphas: Any = None, bodies: Optional[int] = None, pairs: Any = None, coupling: Any = None,
           obstacle: str = "infinite", scaling: Any = None, order: int = 0, closed: Any = None, all: bool = False,
           scene: Any = None, epsilons: Optional[Sequence[Number]] = None, samples: int = 4000,
           boundary_pairs: int = 20, seed: int = 1, threads: int = 0, progress: Any = None,
           checkpoint: Any = None) -> Union[VerifyResult, List[VerifyResult]]:
    """Check a case's derived conditions, exact and asymptotic, against exact solutions.

    Points of the regime (m₁ ~ ε, K₁ₙ ~ 1/ε; M ⪰ 0) are drawn for each ε of
    ``epsilons`` (default 10⁻², …, 10⁻⁶), ``samples`` per ε, then
    ``boundary_pairs`` segments per condition are bisected to reach both
    sides of every condition near its boundary; each point is solved exactly
    (rationals) and compared with the conditions.  The case and pattern as
    in :func:`derive`.  Deterministic given ``seed``, whatever ``threads``.
    ``progress``: a callable ``(phase, done, total)`` ("drawn points", then
    "boundaries", per case), True/False, or None (a bar on standard error
    when it is a terminal); Ctrl-C stops it (KeyboardInterrupt) between tasks.
    ``checkpoint``: a folder (``superball verify --checkpoint``) where each
    case is written as soon as it is verified; the same call made again
    verifies only the cases not there (``progress`` is then told of the
    cases too, phase "cases"), and the result is the same.
    """
    eps = [] if epsilons is None else [_number_text(e, "epsilons") for e in epsilons]
    out = [_verify_result(j, text, agrees)
           for j, text, agrees in _superball.verify(_selection(case, alphas, bodies, pairs, coupling, obstacle, scaling, order, closed, all,
                                                               scene), eps, _int_option(samples, "samples"), _int_option(boundary_pairs, "boundary_pairs"), _int_option(seed, "seed"), _int_option(threads, "threads"),
                                                               _progress.resolve(progress, "verify"), _checkpoint_option(checkpoint, "verify"))]
    return out if all else out[0]


@dataclass(frozen=True, repr=False)
class ExploreResult:
    """Is the superball reachable for a pattern in a case (``superball explore``)?

    ``reach``: ``yes`` (a witness: the case actual and U₁⁺ > a, confirmed by
    an exact solve), ``no`` (proved: the conditions clash), ``case
    impossible`` or ``not found``; ``witness``: the best point confirmed
    exactly (name → Fraction, a included), ``ratio``: U₁⁺/a there, exact;
    ``scene``: the witness as a :class:`Scene` (None without one).
    """

    case: str
    reach: str
    ratio: Optional[Fraction]
    witness: Dict[str, Fraction]
    scene: Optional[Scene]
    data: Dict[str, Any] = field(repr=False)
    text: str = field(repr=False)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        ratio = f", U1+/a = {float(self.ratio):.6g} (exact)" if self.ratio is not None else ""
        return f"<superball.ExploreResult case {self.case}: reach {self.reach}{ratio}>"

    def _repr_html_(self) -> str:
        return _text_html(f"superball explore, case {self.case}", self.text)


@dataclass(frozen=True, repr=False)
class PatternTable:
    """``explore(all_patterns=True)``: each α_k (and {α₁, α₆}) against every case.
    ``reach``: a NumPy str array [pattern, case] ("yes", "no (proved)", …);
    ``patterns`` ("alpha1", …, "alpha1,alpha6") and ``cases`` its labels."""

    patterns: List[str]
    cases: List[str]
    reach: np.ndarray
    data: Dict[str, Any] = field(repr=False)
    text: str = field(repr=False)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<superball.PatternTable: {len(self.patterns)} patterns x {len(self.cases)} cases>"

    def _repr_html_(self) -> str:
        e = _html.escape
        head = "".join(f"<th>{e(c)}</th>" for c in self.cases)
        rows = "".join(f"<tr><th>{e(p)}</th>" + "".join(f"<td>{e(str(x))}</td>" for x in row) + "</tr>"
                       for p, row in zip(self.patterns, self.reach))
        return f"<div><b>superball explore --all-patterns</b><table><tr><th></th>{head}</tr>{rows}</table></div>"


def explore(case: Optional[str] = None, alphas: Any = None, bodies: Optional[int] = None, pairs: Any = None, coupling: Any = None,
            closed: Any = None, all: bool = False, scene: Any = None, all_patterns: bool = False, seed: int = 1, starts: int = 24,
            evaluations: int = 1000, box: Tuple[float, float] = (1e-3, 1e3),
            progress: Any = None, checkpoint: Any = None) -> Union[ExploreResult, List[ExploreResult], PatternTable]:
    """Search a witness of the superball in a case (fixed obstacle, a = 1), or prove it impossible.

    The derived exact conditions of the case and the minors of M bound the
    search (a penalty method, Nelder–Mead from ``starts`` points, masses and
    K's in ``box`` on a log scale, couplings t·√(K_p K_q), |t| ≤ 1) for the
    largest U₁⁺/a; the best points are rounded to rationals and solved
    exactly.  Without a witness, it looks for weights w with
    −Σ wᵢNᵢ = Q + (terms ≥ 0), Q ≥ 0 wherever M ⪰ 0: a proof that the
    conditions clash.  ``all_patterns=True`` gives the table of every α_k.
    ``progress``: a callable ``(phase, done, total)`` (phase ``"case 2.2"``
    per case, or ``"cells"`` for the table; the steps are the objective
    evaluations, then one for the exact confirmation and the proofs), told at
    least every 1024 evaluations, True/False, or None (a bar on standard
    error when it is a terminal); Ctrl-C stops it (KeyboardInterrupt) within
    as many evaluations.  The result does not depend on it.
    ``checkpoint``: a folder (``superball explore --checkpoint``) where each
    case (with ``all_patterns``, each cell of the table) is written as soon
    as it is explored; the same call made again explores only those not
    there, and the result is the same.  Between two of them ``progress``
    is told ``("cases", done, total)`` (``"cells"``).
    """
    low, high = box
    folder = _checkpoint_option(checkpoint, "explore")
    options = _selection(case, alphas, bodies, pairs, coupling, "infinite", None, 0, closed, all, scene)
    told = _progress.resolve(progress, "explore")
    if all_patterns:
        (d, text), = _superball.explore(options, True, _int_option(seed, "seed"), _int_option(starts, "starts"), _int_option(evaluations, "evaluations"), float(low), float(high), told, folder)
        patterns = [row["cells"][0]["pattern"] if row["cells"] else ",".join(f"alpha{k}" for k in row["alphas"]) for row in d["rows"]]
        reach = np.array([[cell["reach"] for cell in row["cells"]] for row in d["rows"]], dtype=str)
        return PatternTable(patterns, list(d["cases"]), reach, d, text)
    out = []
    for d, text, witness_scene in _superball.explore(options, False, _int_option(seed, "seed"), _int_option(starts, "starts"), _int_option(evaluations, "evaluations"), float(low), float(high), told, folder):
        witness = {k: Fraction(v) for k, v in (d.get("witness") or {}).items()}
        ratio = Fraction(d["ratio"]) if d.get("ratio") is not None and witness else None
        out.append(ExploreResult(d["case"], d["reach"], ratio, witness, None if witness_scene is None else Scene(_scene=witness_scene), d, text))
    return out if all else out[0]



# ---------------------------------------------------------------------------
# Maps over two parameters (python/superball/_map.py)

from ._map import BoundaryPoint, DerivedZero, DropMapResult, MapAxis, MapCurve, MapResult, Overlay, OverlayMatch, map  # noqa: E402  (uses Scene, defined above)
from ._drop import DropApex, DropEvent, DropRest, DropResult, drop  # noqa: E402  (uses Scene, defined above)
from ._drop_limit import GapLimit, GapLimitStep, gaps_to_zero  # noqa: E402  (uses Scene, defined above)
