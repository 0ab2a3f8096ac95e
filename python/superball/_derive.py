"""Derivations: evolution cases solved symbolically (``superball derive``).

:func:`derive` gives one case, :func:`derive_all` every case of a pattern
(in parallel, in the worker processes the command uses); a
:class:`Derivation` holds the velocities, reactions and :class:`Condition`\\ s,
each evaluated exactly (:meth:`Condition.evaluate`, GiNaC) or over NumPy
arrays (:meth:`Condition.lambdify`) without SymPy.
"""

from __future__ import annotations

import html as _html
import re as _re
import sys as _sys
from dataclasses import dataclass, field, replace as _replace
from fractions import Fraction
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _superball
from ._options import _checkpoint_option, _int_option, _selection

InputError = _superball.InputError
Error = _superball.Error

#: A progress callback: called with (cases done, cases in all).
Progress = Callable[[int, int], Any]

_RELATIONS = (" >= ", " <= ", " > ", " < ")


def _sympy_relation(ascii_text: str, symbols: Sequence[Mapping[str, Any]]) -> Any:
    import sympy  # optional: imported only here

    names = {}
    for s in symbols:
        names[s["name"]] = sympy.Symbol(s["name"], positive=True) if s.get("positive") else sympy.Symbol(s["name"], real=True)
    text = ascii_text.split("  (")[0].strip()  # a note after the relation ("(sign of the denominator not proved)")
    for op, rel in ((">=", sympy.Ge), ("<=", sympy.Le), (">", sympy.Gt), ("<", sympy.Lt)):
        if f" {op} " in text:
            lhs, rhs = text.split(f" {op} ", 1)
            return rel(sympy.sympify(lhs.replace("^", "**"), locals=names), sympy.sympify(rhs.replace("^", "**"), locals=names))
    raise Error(f"to_sympy: no relation in '{ascii_text}'")


def _short(text: str, width: int = 80) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"


_NAME = _re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_BIG_INTEGER = _re.compile(r"(?<![A-Za-z0-9_.])(\d{16,})(?![0-9.])")


def _python_expression(ascii_text: str) -> str:
    """GiNaC's ASCII syntax as a Python expression over floats or NumPy arrays: ^ is **, a relation
    "P > Q" is P − Q, and integers past 2⁵³ are floats (NumPy cannot hold them as integers)."""
    for rel in _RELATIONS:
        if rel in ascii_text:
            lhs, rhs = ascii_text.split(rel, 1)
            ascii_text = f"({lhs})-({rhs})"
            break
    return _BIG_INTEGER.sub(r"\1.0", ascii_text.replace("^", "**"))


@dataclass(frozen=True, repr=False)
class Condition:
    """A condition of an evolution case (paper §4), "P > 0" or "P ≥ 0".

    ``kind``: ``superball`` (U₁⁺ > a), ``evolution`` (an open contact opens,
    U_i⁺ > U_{i+1}⁺), ``contact`` (a closed contact does not interpenetrate,
    R ≤ 0) or ``psd`` (a principal minor of M ≥ 0).  ``about`` says which
    (``"U1 > a"``, ``"2-3"``).  ``text``/``latex``: the exact form (m_n = ∞)
    as a person writes it (−α₂ > 2m₁ + K₁₂ + K₁₃); ``exact``: the same in
    GiNaC's ASCII syntax (m1, K12, alpha2, c_12_14, a); ``asymptotic``,
    ``asymptotic_text``, ``asymptotic_latex``: the dominant balance in the
    regime (m₁ ~ ε, K₁ₙ ~ 1/ε by default).  A long condition (from about 6
    bodies) is written through its case's elimination (``eliminated``: the
    forms Σ ℓ_c V_c + β REL 0 over the names of ``Derivation.definitions``);
    then, unless derived with ``expanded=True``, its expanded forms are not
    kept (``exact``/``asymptotic`` are None; ``text``/``latex`` are the
    eliminated ones).  ``data``: every field of ``superball derive --format json``.
    """

    kind: str
    about: str
    text: str
    latex: str
    exact: Optional[str]
    asymptotic: Optional[str]
    asymptotic_text: str
    asymptotic_latex: str
    verdict: str
    order: str
    eliminated: Optional[Dict[str, Any]] = field(compare=False, default=None)
    data: Dict[str, Any] = field(compare=False, default_factory=dict)
    symbols: Tuple[Any, ...] = field(compare=False, default=())
    definitions: Tuple[Tuple[str, str], ...] = field(compare=False, default=())
    small: Tuple[str, ...] = field(compare=False, default=())

    def _repr_latex_(self) -> str:
        return f"${self.latex}$"

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<Condition {self.kind} {self.about}: {_short(self.text)} ({self.verdict})>"

    def _repr_html_(self) -> str:
        e = _html.escape
        return (f"<table><tr><th>{e(self.kind)} {e(self.about)}</th><td>{e(self.text)}</td><td>{e(self.verdict)}</td></tr>"
                f"<tr><th>asymptotic</th><td>{e(self.asymptotic_text)}</td><td>order ε^{e(self.order)}</td></tr></table>")

    def _form(self, asymptotic: bool) -> Tuple[str, Tuple[Tuple[str, str], ...], Tuple[str, ...]]:
        """The ASCII form evaluated: the expanded one when kept, else the eliminated one with the
        definitions (and the small parameters at 0 when that form takes them so)."""
        expanded = self.asymptotic if asymptotic else self.exact
        if expanded is not None:
            return expanded, (), ()
        form = (self.eliminated or {}).get("asymptotic" if asymptotic else "exact")
        if form is None:
            raise Error(f"Condition {self.about}: no {'asymptotic' if asymptotic else 'exact'} form")
        return form["ascii"], self.definitions, self.small if form.get("limit") else ()

    def _symbol_names(self) -> List[str]:
        return [s["name"] for s in self.symbols]

    def evaluate(self, values: Mapping[str, Any], asymptotic: bool = False) -> Fraction:
        """The exact value of the condition's expression P − Q ("P > Q") at ``values`` (symbol name →
        int, Fraction, str such as "1/3" or "0.001", or float taken exactly), computed by GiNaC in
        rationals.  A condition written through the elimination without its expanded form gives
        Σ ℓ_c V_c + β: the expanded P − Q divided by det(ZᵀAZ) > 0, so with the same sign.
        Raises InputError for a name that is not a symbol of the derivation or a symbol without value."""
        names = self._symbol_names()
        if not isinstance(values, Mapping):
            raise InputError(f"evaluate: values: expected a dict of symbol name to number, got {type(values).__name__}")
        exact: Dict[str, Tuple[str, str]] = {}
        for key, value in values.items():
            if key not in names:
                raise InputError(f"evaluate: '{key}' is not a symbol of this derivation (symbols: {', '.join(names)})")
            if isinstance(value, bool):
                raise InputError(f"evaluate: {key}: expected a number, got {value!r}")
            try:
                # text by the library's number reader (its exponent bound: Fraction("1e999999999") would not end)
                f = Fraction(_superball.Values.from_text([value]).as_text()[0]) if isinstance(value, str) else Fraction(value)
                exact[key] = (str(f.numerator), str(f.denominator))
            except (TypeError, ValueError, OverflowError) as e:  # InputError is a ValueError
                try:
                    shown = repr(value)
                except ValueError:  # an int past Python's limit of int to text
                    shown = f"an int of more than {_sys.get_int_max_str_digits()} digits"
                raise InputError(f"evaluate: {key}: {shown} is not a number ({e})") from None
        form, definitions, zero = self._form(asymptotic)
        return _superball.evaluate(form, list(definitions), exact, list(zero))

    def lambdify(self, asymptotic: bool = False) -> Callable[..., Any]:
        """A function of the symbols the condition uses (keywords or positionally, in the order of its
        ``parameters`` attribute) giving P − Q over floats or NumPy arrays (vectorised, float64;
        no SymPy): positive where a strict condition holds.  Through the elimination it computes the
        definitions in order, as :meth:`evaluate` does."""
        form, definitions, zero = self._form(asymptotic)
        defined = {name for name, _ in definitions} | set(zero)
        used = set(_NAME.findall(form)) | {n for _, v in definitions for n in _NAME.findall(v)}
        parameters = [n for n in self._symbol_names() if n in used and n not in defined]
        lines = [f"def condition({', '.join(parameters)}):"]
        lines += [f"    {name} = 0" for name in zero]
        lines += [f"    {name} = {_python_expression(value)}" for name, value in definitions]
        lines.append(f"    return {_python_expression(form)}")
        namespace: Dict[str, Any] = {}
        exec(compile("\n".join(lines), f"<superball condition {self.about}>", "exec"), namespace)  # our own ASCII, names checked above
        f = namespace["condition"]
        f.parameters = tuple(parameters)
        f.__doc__ = f"{self.kind} {self.about}: {_short(form, 200)} as P − Q of ({', '.join(parameters)})"
        return f

    def to_sympy(self, asymptotic: bool = False) -> Any:
        """The condition as a SymPy relational (masses, K's and a positive
        symbols, couplings real); SymPy is imported only when this is called.
        Needs the expanded form (derive with ``expanded=True`` for a long case)."""
        form = self.asymptotic if asymptotic else self.exact
        if form is None:
            raise Error(f"to_sympy: {self.about} is written through the elimination only; derive with expanded=True")
        return _sympy_relation(form, self.symbols)


@dataclass(frozen=True, repr=False)
class Derivation:
    """One evolution case solved symbolically (``superball derive``).

    ``velocities``: U₁⁺ … U_n⁺ as GiNaC ASCII text (``velocities_text``,
    ``velocities_latex`` as a person writes them); ``reactions``: R on each
    contact (0 where open); ``conditions``: superball, evolution, contact,
    then psd; ``actual``: whether the case can be the actual evolution
    (``depends``, ``always``, ``never``); ``definitions``: the case's
    elimination (name, value) in order, empty when it has none (a long value
    is then written over those names, ``V1``); ``data``: the whole JSON.
    """

    case: str
    closed_contacts: Tuple[str, ...]
    velocities: List[str]
    velocities_text: List[str]
    velocities_latex: List[str]
    reactions: List[str]
    reactions_text: List[str]
    reactions_latex: List[str]
    conditions: List[Condition]
    actual: str
    report: str = field(repr=False)
    report_latex: str = field(repr=False)
    data: Dict[str, Any] = field(repr=False, compare=False)
    definitions: Tuple[Tuple[str, str], ...] = field(compare=False, default=())

    def condition(self, about: str) -> Condition:
        """The condition about ``about`` ("U1 > a", "2-3", …); InputError names the ones there are."""
        for c in self.conditions:
            if c.about == about:
                return c
        raise InputError(f"condition: no condition about '{about}' in case {self.case} (there are: "
                         f"{', '.join(repr(c.about) for c in self.conditions)})")

    def velocity_sympy(self, body: int) -> Any:
        """U_body⁺ as a SymPy expression."""
        import sympy

        names = {s["name"]: sympy.Symbol(s["name"], positive=s["positive"]) if s["positive"] else sympy.Symbol(s["name"], real=True)
                 for s in self.data["symbols"]}
        return sympy.sympify(self.velocities[body - 1].replace("^", "**"), locals=names)

    def __str__(self) -> str:
        return self.report

    def __repr__(self) -> str:
        closed = "{" + ",".join(self.closed_contacts) + "}"
        return (f"<Derivation case {self.case} {closed}: {len(self.velocities)} bodies, {len(self.conditions)} conditions, "
                f"actual {self.actual}>")

    def _repr_latex_(self) -> str:
        rows = [f"U_{{{i + 1}}}^{{+}} &= {v}" for i, v in enumerate(self.velocities_latex)]
        rows += [f"&{c.latex} && \\text{{{c.kind} {c.about}}}" for c in self.conditions]
        return "$$\\begin{aligned}" + " \\\\ ".join(rows) + "\\end{aligned}$$"

    def _repr_html_(self) -> str:
        e = _html.escape
        rows = [f"<tr><th>U{i + 1}⁺</th><td colspan='2'>{e(_short(v, 300))}</td></tr>" for i, v in enumerate(self.velocities_text)]
        rows += [f"<tr><th>{e(c.kind)} {e(c.about)}</th><td>{e(_short(c.text, 300))}</td><td>{e(c.verdict)}</td></tr>"
                 for c in self.conditions]
        closed = "{" + ",".join(self.closed_contacts) + "}"
        return f"<table><caption>case {e(self.case)} {e(closed)}, actual {e(self.actual)}</caption>{''.join(rows)}</table>"


def _derivation(d: Dict[str, Any]) -> Derivation:
    data = d["data"]
    symbols = tuple(data["symbols"])
    elimination = data.get("elimination") or {}
    definitions = tuple((x["name"], x["value"]) for x in elimination.get("definitions", ()))
    small = tuple(elimination.get("small", ()))
    conditions = []
    for c in data["conditions"]:
        eliminated = c.get("eliminated")
        exact_text = c.get("text", (eliminated or {}).get("exact", {}).get("text", ""))
        exact_latex = c.get("latex", (eliminated or {}).get("exact", {}).get("latex", ""))
        asymptotic_text = c.get("asymptotic_text", (eliminated or {}).get("asymptotic", {}).get("text", ""))
        asymptotic_latex = c.get("asymptotic_latex", (eliminated or {}).get("asymptotic", {}).get("latex", ""))
        conditions.append(Condition(c["kind"], c["about"], exact_text, exact_latex, c.get("exact"), c.get("asymptotic"), asymptotic_text,
                                    asymptotic_latex, c["verdict"], c["order"], eliminated, c, symbols, definitions, small))
    n = len(d["velocities_text"])
    reactions = [data["reactions"].get(f"{k + 1}-{k + 2}", "0") for k in range(n - 1)]
    return Derivation(data["case"], tuple(data["closed_contacts"]), [data["velocities_after"][f"U{i + 1}"] for i in range(n)],
                      list(d["velocities_text"]), list(d["velocities_latex"]), reactions, list(d["reactions_text"]),
                      list(d["reactions_latex"]), conditions, data["actual"], d["report"], d["report_latex"], data, definitions)


class _TerminalProgress:
    """The estimate and "NAME: k of N cases" on standard error when it is a terminal, redrawn in place, erased at the end."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.shown = False

    def notice(self, text: str, seconds: float) -> None:
        self.shown = seconds >= 2 and _sys.stderr.isatty()
        if self.shown:
            _sys.stderr.write(f"{self.name}: {text}; Ctrl-C (KeyboardInterrupt) stops it\n")

    def __call__(self, done: int, total: int) -> None:
        if self.shown:
            _sys.stderr.write(f"\r{self.name}: {done} of {total} cases" + ("\r\033[K" if done == total else ""))
            _sys.stderr.flush()


def _run(name: str, options: Dict[str, Any], expanded: bool, jobs: Optional[int], progress: Union[None, bool, Progress],
         checkpoint: str = "") -> List[Derivation]:
    if progress is None:
        bar = _TerminalProgress(name)
        notice, step = bar.notice, bar
    else:
        notice, step = None, (progress if callable(progress) else None)
        if progress is not False and not callable(progress):
            raise InputError(f"{name}: progress must be None, False or a callable (done, total), got {progress!r}")
    out = [_derivation(d) for d in _superball.derive(options, bool(expanded), 0 if jobs is None else _int_option(jobs, "jobs"), step, notice,
                                                  checkpoint)]
    # Compact JSON of several cases has the conditions on M in the first case only: every Derivation shows them.
    psd = [c for c in out[0].conditions if c.kind == "psd"] if out else []
    return [d if any(c.kind == "psd" for c in d.conditions) else _with_conditions(d, d.conditions + psd) for d in out]


def _with_conditions(d: Derivation, conditions: List[Condition]) -> Derivation:
    return _replace(d, conditions=conditions)


def derive(case: Optional[str] = None, alphas: Any = None, bodies: Optional[int] = None, pairs: Any = None, coupling: Any = None,
           obstacle: str = "infinite", scaling: Any = None, order: int = 0, closed: Any = None, scene: Any = None,
           expanded: bool = False, progress: Union[None, bool, Progress] = None) -> Derivation:
    """Solve one evolution case symbolically and give its conditions (paper §4).

    The case: ``case`` (the paper's name for 4 bodies: "1", "2.1", …) or
    ``closed`` (the closed contacts, ``"2-3,3-4"`` or a list, ``"none"``);
    every case: :func:`derive_all`.  The pattern of M: ``alphas`` (the
    paper's α_k in play, 4 bodies: ``2`` or ``[1, 6]``), ``bodies`` (None:
    4), ``pairs`` (``"all"``, the default, ``"near"``, ``"near2"`` or a list
    of pairs with a diagonal K), ``coupling`` (``"1-2/1-4,…"``, a list, or
    ``"near2"``), or ``scene`` (a scene file's declared entries: not with
    bodies, alphas, coupling or pairs).  ``obstacle``: ``"infinite"``
    (m_n = ∞) or ``"finite"``; ``scaling``: orders in ε (``"m1=1,K14=-1"`` or
    a dict; default m₁ ~ ε, K₁ₙ ~ 1/ε); ``order``: correction orders kept.
    ``expanded``: keep every expanded form of a long case too (as
    ``derive --expanded``; by default a form written through the
    elimination is kept only that way, as the command's JSON does).

    With Z the cluster incidence of the case, the velocities solve
    (ZᵀAZ)V = Zᵀ(diag(m)u − Ku) by fraction-free determinants, the
    reactions are running sums, and everything is substituted back into the
    equations (a check).  The conditions: U₁⁺ > a, each open contact
    opening, each closed contact's R ≤ 0, M ⪰ 0.  The case is derived in a
    worker process: Ctrl-C (KeyboardInterrupt) stops it at once.  Any
    number of bodies (2 to 21) is taken; only one that cannot fit in
    memory is refused (InputError), and on a terminal a long one says its
    estimate first (``progress=False``: never; a callable: called with
    (0, 1) and (1, 1)).
    """
    if case is None and closed is None:
        raise InputError("derive: give a case (case= or closed=); every case: derive_all()")
    options = _selection(case, alphas, bodies, pairs, coupling, obstacle, scaling, order, closed, False, scene)
    return _run("derive", options, expanded, 1, progress)[0]


def derive_all(alphas: Any = None, bodies: Optional[int] = None, pairs: Any = None, coupling: Any = None, obstacle: str = "infinite",
               scaling: Any = None, order: int = 0, scene: Any = None, expanded: bool = False, jobs: Optional[int] = None,
               progress: Union[None, bool, Progress] = None, checkpoint: Any = None) -> List[Derivation]:
    """Every evolution case of a pattern (2ⁿ⁻¹ of them, in mask order: the
    contact (c, c+1) closed for bit c − 1), as :func:`derive` gives one.

    The cases are derived in parallel in ``jobs`` worker processes (None or
    0: one per core, at most 1024; fewer when their memory would not fit), the ones
    ``superball derive --all`` uses (GiNaC is not thread-safe, so processes);
    the result does not depend on their number.  ``progress``: None shows
    the estimate and "derive_all: k of N cases" on standard error when it is
    a terminal and the run is estimated over 2 s; False shows nothing; a
    callable is called with (cases done, cases in all) after each case.
    Ctrl-C (KeyboardInterrupt) stops the workers at once.  The GIL is
    released while the workers compute.
    ``checkpoint``: a folder (``superball derive --all --checkpoint``) where
    each case is written by its worker as soon as it is derived; the same
    call made again derives only the cases not there, and the result is the
    same.  A callable ``progress`` is then told the cases found there first.
    """
    options = _selection(None, alphas, bodies, pairs, coupling, obstacle, scaling, order, None, True, scene)
    return _run("derive_all", options, expanded, jobs, progress, _checkpoint_option(checkpoint, "derive_all"))
