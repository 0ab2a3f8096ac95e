"""map(): the evolution cases and the superball over a grid of two parameters
(``superball map``), with the boundaries between regions located exactly."""

from __future__ import annotations

import html as _html
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from . import _progress, _superball
from ._options import _checkpoint_option

# Distinct colours for the cases (Tableau 10, as the command's figure), grey where M is not PSD.
_COLOURS = ("#4E79A7", "#F28E2B", "#59A14F", "#E15759", "#B07AA1", "#76B7B2", "#EDC948", "#9C755F", "#FF9DA7", "#3B3B98")
_NOT_PSD = "#C8C8C8"
_PALE = 0.6  # how far toward white the part of a case without the superball is drawn


@dataclass(frozen=True)
class MapAxis:
    """One axis of a map: ``steps`` exact values of ``key`` from ``start`` to ``stop`` (Fractions), ends included;
    ``values`` rounded to float64."""

    key: str
    start: Fraction
    stop: Fraction
    steps: int
    values: np.ndarray = field(repr=False, compare=False)

    def fractions(self) -> List[Fraction]:
        """The values, exact."""
        return [self.start + (self.stop - self.start) * k / (self.steps - 1) for k in range(self.steps)]


@dataclass(frozen=True)
class BoundaryPoint:
    """A change of region between two neighbouring grid points, bracketed exactly.

    Along ``along`` (the key of the axis that varies: between (x_i, y_j) and
    (x_{i+1}, y_j) when ``along_x``, else (x_i, y_j) and (x_i, y_{j+1})), the
    change lies in [``low``, ``high``] (Fractions, low < high); ``x``, ``y``: the
    point in float (the bracket's middle on that axis); ``below``/``above``: the
    region at low and at high (``{"psd": True, "case": "3.3", "closed": [...],
    "superball": True}`` or ``{"psd": False}`` where M is not PSD)."""

    along: str
    along_x: bool
    i: int
    j: int
    x: float
    y: float
    low: Fraction
    high: Fraction
    width: float
    below: Dict[str, Any]
    above: Dict[str, Any]


@dataclass(frozen=True)
class MapCurve:
    """Boundary points chained through the grid's cells: ``kind`` ``"case change"`` (between ``cases``),
    ``"superball edge"`` or ``"psd edge"``; ``boundaries``: indices into ``MapResult.boundary_points``;
    ``points``: float64 (k, 2), x and y of each; ``closed``: the last point joins the first;
    ``brackets``: the exact (low, high) of each point on its varying axis."""

    kind: str
    cases: Tuple[str, ...]
    closed: bool
    boundaries: List[int]
    points: np.ndarray = field(repr=False, compare=False)
    brackets: List[Tuple[Fraction, Fraction]] = field(repr=False, compare=False)


@dataclass(frozen=True)
class DerivedZero:
    """A zero of one derived condition of ``case`` on a grid segment (as a
    :class:`BoundaryPoint`'s: along ``along``), bracketed by [``low``,
    ``high``] (Fractions); ``x``, ``y``: the bracket's middle in float;
    ``condition``: what it is (``"superball U1 > a"``, ``"contact 2-3 ..."``);
    ``holds_low``: the condition holds at ``low``'s end; ``next_to_case``: one
    end of the segment is a grid point of ``case`` (elsewhere the case is not
    actual and its conditions say nothing)."""

    case: str
    condition: str
    along: str
    x: float
    y: float
    low: Fraction
    high: Fraction
    holds_low: bool
    next_to_case: bool


@dataclass(frozen=True)
class OverlayMatch:
    """How boundary point ``boundary`` (an index into ``MapResult.boundary_points``)
    compares with the derived zeros: ``found`` one on its segment, ``zero`` the
    nearest (an index into ``Overlay.zeros``), ``distance`` between the
    brackets' middles and ``allowed`` (the two brackets' widths); ``agrees``
    when found within the allowed distance."""

    boundary: int
    found: bool
    zero: Optional[int]
    distance: Optional[float]
    allowed: Optional[float]
    agrees: bool


class Overlay:
    """The derived conditions of the cases of a map located on its grid lines
    and compared with its exact boundaries (``superball map --overlay``):
    ``cases`` whose conditions were derived, ``conditions`` (how many, PSD
    left out), ``zeros`` (:class:`DerivedZero`), ``matches``
    (:class:`OverlayMatch`, one per boundary point between solved points),
    ``agrees`` (every boundary point has a derived zero within its allowed
    distance), ``largest_distance_in_steps`` and ``largest_allowed_in_steps``
    (in grid steps of the axis).  ``str()`` is the command's overlay text."""

    def __init__(self, d: Dict[str, Any]) -> None:
        self.cases: Tuple[str, ...] = tuple(d["cases"])
        self.conditions: int = d["conditions"]
        self.agrees: bool = d["agrees"]
        self.largest_distance_in_steps: float = d["largest_distance_in_steps"]
        self.largest_allowed_in_steps: float = d["largest_allowed_in_steps"]
        self.zeros: List[DerivedZero] = [
            DerivedZero(z["case"], z["condition"], z["along"], z["x"], z["y"], z["low"], z["high"], z["holds_low"], z["next_to_case"])
            for z in d["zeros"]]
        self.matches: List[OverlayMatch] = [
            OverlayMatch(m["boundary"], m["found"], m.get("zero"), m.get("distance"), m.get("allowed"), m["agrees"]) for m in d["matches"]]
        self._text: str = d["text"]

    def __str__(self) -> str:
        return self._text

    def __repr__(self) -> str:
        return (f"<superball.Overlay cases {', '.join(self.cases) or 'none'}: {self.conditions} conditions, {len(self.zeros)} zeros, "
                f"{len(self.matches)} boundary points compared: {'agree' if self.agrees else 'DISAGREE'}>")

    def _repr_html_(self) -> str:
        return f"<pre>{_html.escape(self._text)}</pre>"


class MapResult:
    """A map over two parameters (``superball map``).

    Arrays are (ny, nx): row j at ``y.values[j]``, column i at ``x.values[i]``.
    ``cases``: the evolution case per point (str, ``""`` where M is not PSD);
    ``case_codes`` (int32, −1 where not PSD) into ``case_list``/``closed_list``;
    ``ratio``: U₁⁺/a (U₁⁺/|U₁⁻|) in the map's precision, NaN where not solved;
    ``superball``: U₁⁺ > a (bool); ``psd``: M positive semi-definite, the point
    solved (bool); ``status_codes`` (int8, −1 where not solved, see
    :data:`STATUSES`); ``boundary_points``: :class:`BoundaryPoint` (exact
    brackets); ``curves``: :class:`MapCurve`; ``overlay``: the :class:`Overlay`
    of the derived conditions when ``map(..., overlay=True)``, else None.
    ``str()`` is the command's summary (and overlay).
    """

    def __init__(self, d: Dict[str, Any]) -> None:
        self.scene: str = d["scene"]
        self.title: str = d["title"]
        self.precision: str = d["precision"]
        self.x = MapAxis(d["x"]["key"], d["x"]["from"], d["x"]["to"], d["x"]["steps"], d["x"]["values"])
        self.y = MapAxis(d["y"]["key"], d["y"]["from"], d["y"]["to"], d["y"]["steps"], d["y"]["values"])
        self.case_codes: np.ndarray = d["case_codes"]
        self.case_list: Tuple[str, ...] = d["case_list"]
        self.closed_list: Tuple[Tuple[str, ...], ...] = d["closed_list"]
        self.cases: np.ndarray = np.array(list(self.case_list) + [""], dtype=str)[self.case_codes]
        self.ratio: np.ndarray = d["ratio"]
        self.superball: np.ndarray = d["superball"]
        self.psd: np.ndarray = d["psd"]
        self.status_codes: np.ndarray = d["status_codes"]
        self.boundary_points: List[BoundaryPoint] = [
            BoundaryPoint(b["along"], b["along_x"], b["i"], b["j"], b["x"], b["y"], b["low"], b["high"], b["bracket_width"], b["below"],
                          b["above"]) for b in d["boundary_points"]]
        self.curves: List[MapCurve] = [
            MapCurve(c["kind"], tuple(c.get("cases", ())), c["closed"], list(c["boundaries"]), c["points"],
                     [(self.boundary_points[k].low, self.boundary_points[k].high) for k in c["boundaries"]]) for c in d["curves"]]
        self.overlay: Optional[Overlay] = Overlay(d["overlay"]) if "overlay" in d else None
        self._summary: str = d["summary"]

    @property
    def shape(self) -> Tuple[int, int]:
        """(ny, nx)."""
        return self.case_codes.shape

    def __str__(self) -> str:
        return self._summary + (str(self.overlay) if self.overlay else "")

    def _shares(self) -> List[Tuple[str, float, float]]:
        """(case, share of the solved points, share of it superball) per case present."""
        solved = int(self.psd.sum())
        out = []
        for k, name in enumerate(self.case_list):
            here = self.case_codes == k
            n = int(here.sum())
            out.append((name, n / solved if solved else 0.0, float(self.superball[here].sum()) / n if n else 0.0))
        return out

    def __repr__(self) -> str:
        solved = int(self.psd.sum())
        share = float(self.superball.sum()) / solved if solved else 0.0
        return (f"<superball.MapResult {self.scene!r} {self.x.key} x {self.y.key} ({self.x.steps} x {self.y.steps}, {self.precision}): "
                f"cases {', '.join(self.case_list) or 'none'}; superball {share:.1%} of {solved} solved points; "
                f"{len(self.boundary_points)} boundary points, {len(self.curves)} curves"
                f"{'; overlay ' + ('agrees' if self.overlay.agrees else 'DISAGREES') if self.overlay else ''}>")

    def _repr_html_(self) -> str:
        e = _html.escape
        solved = int(self.psd.sum())
        rows = "".join(f"<tr><td>{e(c)}</td><td>{s:.1%}</td><td>{b:.1%}</td></tr>" for c, s, b in self._shares())
        return (f"<div><b>{e(self.scene)}</b>{': ' + e(self.title) if self.title else ''}<br>"
                f"{e(self.x.key)} from {self.x.start} to {self.x.stop} ({self.x.steps} values) by "
                f"{e(self.y.key)} from {self.y.start} to {self.y.stop} ({self.y.steps} values), in {e(self.precision)}<br>"
                f"{solved} of {self.psd.size} points solved (M positive semi-definite); superball at "
                f"{float(self.superball.sum()) / solved if solved else 0:.1%}<table><tr><th>case</th><th>share</th>"
                f"<th>of it superball</th></tr>{rows}</table>{len(self.boundary_points)} boundary points, "
                f"{len(self.curves)} curves{self.overlay._repr_html_() if self.overlay else ''}</div>")

    def plot(self, ax: Any = None, curves: bool = True, legend: bool = True) -> Any:
        """Draw the map on ``ax`` (a new figure's when None) with matplotlib:
        the case regions in distinct colours (the superball part in full
        colour, the rest pale; M not PSD in grey) and, with ``curves``, the
        exact boundary curves (superball edge thick black, case changes
        thin white, PSD edge dashed) and, with an overlay, the derived
        zeros next to their case as small black dots (as the command's
        ``--plot`` with ``--overlay``).  Returns ``ax``."""
        try:  # optional: imported only here
            import matplotlib.colors as mcolors
            import matplotlib.patches as mpatches
            import matplotlib.pyplot as plt
        except ImportError as e:
            raise ImportError(f"MapResult.plot() needs matplotlib (python3-matplotlib, or pip install matplotlib): {e}") from e

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 5))
        colours = np.array([mcolors.to_rgb(_COLOURS[k % len(_COLOURS)]) for k in range(len(self.case_list))] + [mcolors.to_rgb(_NOT_PSD)])
        rgb = colours[self.case_codes]
        pale = self.psd & ~self.superball
        rgb[pale] = rgb[pale] + (1 - rgb[pale]) * _PALE
        xv, yv = self.x.values, self.y.values
        dx = (xv[-1] - xv[0]) / (len(xv) - 1) / 2
        dy = (yv[-1] - yv[0]) / (len(yv) - 1) / 2
        ax.imshow(rgb, origin="lower", extent=(xv[0] - dx, xv[-1] + dx, yv[0] - dy, yv[-1] + dy), aspect="auto", interpolation="nearest")
        if curves:
            for c in self.curves:
                p = np.vstack([c.points, c.points[:1]]) if c.closed and len(c.points) else c.points
                if c.kind == "superball edge":
                    ax.plot(p[:, 0], p[:, 1], color="black", linewidth=2)
                elif c.kind == "psd edge":
                    ax.plot(p[:, 0], p[:, 1], color="dimgrey", linewidth=1, linestyle="--")
                else:
                    ax.plot(p[:, 0], p[:, 1], color="white", linewidth=1)
            if self.overlay:
                near = [(z.x, z.y) for z in self.overlay.zeros if z.next_to_case]
                if near:
                    ax.plot([p[0] for p in near], [p[1] for p in near], linestyle="none", marker=".", markersize=3, color="black")
        if legend:
            handles = [mpatches.Patch(color=colours[k], label=f"case {name}") for k, name in enumerate(self.case_list)]
            if not self.psd.all():
                handles.append(mpatches.Patch(color=_NOT_PSD, label="M not PSD"))
            handles.append(mpatches.Patch(facecolor="white", edgecolor="grey", label="pale: no superball"))
            ax.legend(handles=handles, fontsize=8, loc="best")
        ax.set_xlabel(self.x.key)
        ax.set_ylabel(self.y.key)
        ax.set_title(self.title or self.scene, fontsize=10)
        return ax


class DropMapResult:
    """A map of the drops of a scene with a [drop] table (``superball map`` of a drop scene).

    Arrays are (ny, nx) as :class:`MapResult`'s: ``ratio`` the top body's
    apex ratio (float64), ``labels`` each drop's sequence of collisions (str,
    the command's ``label``), ``label_codes`` (int32) into ``label_list``
    (the distinct labels in the order met, L1, L2, …), ``events`` (int32)
    the number of collisions, ``end`` why each run ended (str).
    ``boundaries``: why none are bisected.  ``str()`` is the command's summary.
    """

    def __init__(self, d: Dict[str, Any]) -> None:
        self.scene: str = d["scene"]
        self.title: str = d["title"]
        self.precision: str = d["precision"]
        self.x = MapAxis(d["x"]["key"], d["x"]["from"], d["x"]["to"], d["x"]["steps"], d["x"]["values"])
        self.y = MapAxis(d["y"]["key"], d["y"]["from"], d["y"]["to"], d["y"]["steps"], d["y"]["values"])
        self.ratio: np.ndarray = d["ratio"]
        self.label_codes: np.ndarray = d["label_codes"]
        self.label_list: Tuple[str, ...] = d["label_list"]
        self.labels: np.ndarray = np.array(list(self.label_list), dtype=str)[self.label_codes]
        self.events: np.ndarray = d["events"]
        self.end: np.ndarray = np.array(d["end"], dtype=str).reshape(self.ratio.shape)
        self.boundaries: str = d["boundaries"]
        self._summary: str = d["summary"]

    @property
    def shape(self) -> Tuple[int, int]:
        """(ny, nx)."""
        return self.ratio.shape

    def __str__(self) -> str:
        return self._summary

    def __repr__(self) -> str:
        return (f"<superball.DropMapResult {self.scene!r} {self.x.key} x {self.y.key} ({self.x.steps} x {self.y.steps}, {self.precision}): "
                f"{len(self.label_list)} labels; top apex ratio {np.min(self.ratio):.6g} to {np.max(self.ratio):.6g}>")


def _axis_text(axis: Any, name: str) -> str:
    """KEY=FROM:TO:STEPS as given, or from a tuple (key, start, stop, steps)."""
    if isinstance(axis, str):
        return axis
    from . import InputError, _number_text

    if isinstance(axis, (tuple, list)) and len(axis) == 4:
        key, start, stop, steps = axis
        return f"{key}={_number_text(start, name)}:{_number_text(stop, name)}:{steps}"
    raise InputError(f"{name}: expected KEY=FROM:TO:STEPS (e.g. 'K.3-4=0:20:201') or a tuple (key, from, to, steps), got {axis!r}")


def map(scene: Any, x: Any, y: Any, precision: str = "double", threads: Optional[int] = None, progress: Any = None,
        checkpoint: Any = None, overlay: bool = False) -> Union[MapResult, DropMapResult]:
    """Solve ``scene`` over a grid of two parameters and locate the boundaries
    between its regions exactly (``superball map``).

    ``x``, ``y``: ``"KEY=FROM:TO:STEPS"`` as the command's ``--x``/``--y``
    (``"K.3-4=0:20:201"``; keys as in :meth:`Scene.with_value`, 2 to 10000
    values per axis, exact ends) or a tuple ``(key, start, stop, steps)``.
    Each grid point is solved in ``precision``; where M is not positive
    semi-definite (decided exactly) the point is marked, not solved.  Between
    neighbours of different case or superball verdict the boundary is
    bisected on the exact solution (CLN rationals) to 2⁻⁶⁴ of the grid step,
    and so is the edge of M PSD; the points are chained into curves.
    ``threads``: None or 0 all cores; the result does not depend on it.
    ``progress``: a callable ``(phase, done, total)`` ("points", then
    "boundaries"), True/False, or None (a bar on standard error when it is a
    terminal).  The GIL is released while it computes; Ctrl-C stops it
    (KeyboardInterrupt) between two of its 64 tasks per phase.
    ``checkpoint``: a folder (``superball map --checkpoint``) where each task
    is written as soon as it is done; the same call made again computes only
    the tasks not there, and the result is the same.
    ``overlay``: also derive the conditions of every case present (superball,
    each contact's opening, each reaction's sign), locate their zeros on the
    grid lines exactly and compare them with the boundary points
    (``superball map --overlay``): ``MapResult.overlay``.  A disagreement is
    ``overlay.agrees`` false, not an exception.

    A scene with a [drop] table gives a :class:`DropMapResult` instead: each
    grid point's whole drop (:func:`drop`), its top apex ratio and its
    sequence of collisions, as ``superball map`` gives them (keys as above
    plus ``gap.i``; precision double or long-double; no boundaries, no
    checkpoint, no overlay; ``progress`` is not told).
    """
    from . import InputError, Scene
    from ._options import _int_option

    if not isinstance(scene, Scene):
        raise InputError(f"map: expected a superball.Scene, got {type(scene).__name__}")
    threads = 0 if threads is None else _int_option(threads, "threads")
    if not isinstance(precision, str):
        raise InputError(f"map: precision: expected a string ('double', 'long-double', 'digits:N', 'exact'), got {precision!r}")
    callback = _progress.resolve(progress, "map")
    if not isinstance(overlay, bool):
        raise InputError(f"map: overlay: expected True or False, got {overlay!r}")
    if scene.drop:
        return DropMapResult(_superball.drop_map(scene._scene, _axis_text(x, "x"), _axis_text(y, "y"), precision, threads,
                                                 _checkpoint_option(checkpoint, "map"), overlay))
    d = _superball.map(scene._scene, _axis_text(x, "x"), _axis_text(y, "y"), precision, threads, callback, _checkpoint_option(checkpoint, "map"),
                       overlay)
    return MapResult(d)
