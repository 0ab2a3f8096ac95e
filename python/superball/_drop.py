"""drop(): the whole drop of a scene with a ``[drop]`` table (``superball drop``):
every collision in time order, the bodies that come to rest, each body's apex."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Tuple

import numpy as np

from . import _superball
from ._report import _Report


@dataclass(frozen=True)
class DropEvent:
    """One collision: at ``time`` (s) the ``contacts`` closing then (``"2-3"``)
    made the bodies ``bodies`` (first, last; 1 the top) collide by the law of
    that cluster; ``case``: the contacts it left closed (``closed``);
    ``heights`` and the velocities of every body before and after (m, m/s);
    the kinetic energy and the momentum of the cluster before and after (the
    fixed obstacle's left out)."""

    time: float
    contacts: Tuple[str, ...]
    bodies: Tuple[int, int]
    case: str
    closed: Tuple[str, ...]
    heights: np.ndarray
    velocities_before: np.ndarray
    velocities_after: np.ndarray
    kinetic_energy_before: float
    kinetic_energy_after: float
    momentum_before: float
    momentum_after: float


@dataclass(frozen=True)
class DropApex:
    """Body ``body``'s apex after its last collision: ``height`` (m) at ``time`` (s)."""

    body: int
    height: float
    time: float


@dataclass(frozen=True)
class DropRest:
    """Body ``body`` comes to rest on the fixed obstacle (or on bodies at rest
    there) at ``time`` (s): left at rest by a collision, or, when
    ``accumulation``, at the sum of its bounces' geometric series of ratio ``ratio`` (0 otherwise)."""

    body: int
    time: float
    accumulation: bool
    ratio: float


class DropResult(_Report):
    """A whole drop (``superball drop``).

    ``events``: the collisions in time order (:class:`DropEvent`); as arrays,
    ``times`` (k,), ``velocities_after`` (k, n) and ``kinetic_energy_after``
    (k,); ``apexes`` (:class:`DropApex`), ``rest`` (:class:`DropRest`);
    ``end``: what ended the run (``"apex"``, ``"until"``, ``"rest"``,
    ``"no-more-events"``, ``"max-events"``, ``"numerical-issue"``,
    ``"inexact"``) at
    ``end_time``; ``top_apex_ratio``: the top body's apex over its release
    height; ``near_ties``: events that came closer than the doubt margin
    without being tied (docs/DROP.md).  ``str()`` is the command's text,
    ``to_dict()`` its ``--json``, ``plot()`` the figure of ``--plot``."""

    def __init__(self, d: Dict[str, Any]) -> None:
        super().__init__({k: v for k, v in d.items() if k != "trace"})
        self._trace: Dict[str, Any] = d["trace"]
        self.scene: str = d["scene"]
        self.title: str = d["title"]
        self.precision: str = d["precision"]
        self.g: float = d["g"]
        self.fixed_obstacle: bool = d["fixed_obstacle"]
        self.masses: np.ndarray = np.array([float(m) for m in d["masses"]])
        self.release_heights: np.ndarray = np.array(d["release_heights"], dtype=float)
        self.release_velocities: np.ndarray = np.array(d["release_velocities"], dtype=float)
        self.events: List[DropEvent] = [
            DropEvent(e["time"], tuple(e["contacts"]), (e["bodies"][0], e["bodies"][1]), e["case"], tuple(e["closed"]),
                      np.array(e["heights"], dtype=float), np.array(e["velocities_before"], dtype=float),
                      np.array(e["velocities_after"], dtype=float), e["kinetic_energy_before"], e["kinetic_energy_after"],
                      e["momentum_before"], e["momentum_after"]) for e in d["events"]]
        n = len(self.masses)
        self.times: np.ndarray = np.array([e.time for e in self.events], dtype=float)
        self.velocities_after: np.ndarray = (np.vstack([e.velocities_after for e in self.events]) if self.events
                                             else np.zeros((0, n)))
        self.kinetic_energy_after: np.ndarray = np.array([e.kinetic_energy_after for e in self.events], dtype=float)
        self.apexes: List[DropApex] = [DropApex(a["body"], a["height"], a["time"]) for a in d["apexes"]]
        self.rest: List[DropRest] = [DropRest(r["body"], r["time"], r["accumulation"], r.get("ratio", 0.0)) for r in d["rest"]]
        self.end: str = d["end"]
        self.end_time: float = d["end_time"]
        self.top_apex_ratio: float = d["top_apex_ratio"]
        self.near_ties: int = d["near_ties"]

    def trajectories(self) -> List[Tuple[np.ndarray, np.ndarray]]:
        """Each body's ``(time, height)`` samples, top to bottom (the fixed
        obstacle's too), from the release to ``end_time``: the curves that
        ``superball drop --plot`` and :meth:`plot` draw (parabolas between
        events; a bounce sequence that accumulates drawn at rest from its
        rest time)."""
        return [(np.array(t, dtype=float), np.array(z, dtype=float)) for t, z in zip(self._trace["time"], self._trace["height"])]

    def plot(self, ax: Any = None, legend: bool = True) -> Any:
        """Draw every body's height against time on ``ax`` (a new figure's
        when None) with matplotlib, the collisions (each closing contact)
        and the rests marked, as ``superball drop --plot``.  Returns ``ax``."""
        try:  # optional: imported only here
            import matplotlib.pyplot as plt
        except ImportError as e:
            raise ImportError(f"DropResult.plot() needs matplotlib (python3-matplotlib, or pip install matplotlib): {e}") from e

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 5))
        n = len(self.masses)
        for i, (t, z) in enumerate(self.trajectories()):
            obstacle = self.fixed_obstacle and i == n - 1
            ax.plot(t, z, linewidth=1 if obstacle else 1.5, color="dimgrey" if obstacle else None,
                    label="obstacle" if obstacle else f"body {i + 1}")
        for key, label, marker in (("collisions", "collisions", "."), ("rest", "at rest", "o")):
            t, z = self._trace[key]
            if len(t):
                ax.plot(t, z, linestyle="none", marker=marker, markersize=4, color="black", label=label)
        ax.set_xlabel("time since the release (s)")
        ax.set_ylabel("height above the obstacle's release height (m)")
        ax.set_title(self.title or self.scene, fontsize=10)
        if legend:
            ax.legend(fontsize=8, loc="best")
        return ax

    def __repr__(self) -> str:
        return (f"<superball.DropResult {self.scene!r} ({self.precision}): {len(self.events)} collisions, {len(self.rest)} at rest, "
                f"ended by {self.end} at t = {self.end_time:.6g} s; top apex {self.top_apex_ratio:.6g} x its release height>")


def drop(scene: Any, precision: str = "double") -> DropResult:
    """Release ``scene`` (a :class:`Scene` with a ``[drop]`` table: ``drop=``
    or a file's ``[drop]``; each body's ``gap`` and the ``drop_height``) and
    follow it collision by collision (``superball drop``): flights in closed
    form, each collision solved by the law of the touching cluster, bounce
    sequences on the fixed obstacle summed to their rest time, until the top
    body's apex (``until = "apex"``, the default) or a time.
    ``precision``: ``"double"``, ``"long-double"``, ``"digits:N"``,
    ``"exact"`` (as far as every event's time is rational; the run ends
    ``"inexact"`` at the first that is not) or ``"auto"`` (double, then long
    double, then exact, while an order of events is not certified); an
    unknown arithmetic and a scene without ``[drop]`` are :class:`InputError`
    with the command's message.  See docs/DROP.md.
    """
    from . import InputError, Scene

    if not isinstance(scene, Scene):
        raise InputError(f"drop: expected a superball.Scene, got {type(scene).__name__}")
    if not isinstance(precision, str):
        raise InputError(f"drop: precision: expected a string such as 'double' or 'exact', got {precision!r}")
    return DropResult(_superball.drop(scene._scene, precision))
