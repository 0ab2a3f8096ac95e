"""gaps_to_zero(): a drop as its gaps go to 0 against the simultaneous
collision (``superball drop --gaps-to-zero``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _superball
from ._options import _int_option
from ._report import _Report


@dataclass(frozen=True)
class GapLimitStep:
    """One drop of the series: the scene's gaps times ``scale`` (0: every gap
    closed, the simultaneous collision).  Its first cascade (the collisions
    until every body moves up at least as fast as the one below it) has
    ``events`` collisions, ``collisions`` (``"2-4 {3-4}"``: bodies and case),
    ends with ``velocities`` (m/s) after ``duration`` (s), ``complete`` when
    the bodies did separate; ``deviation``: the largest difference of those
    velocities from the simultaneous collision's, over the landing speed (None
    when one of the two drops had no collision); ``top_apex_ratio``, ``end``
    and the number of collisions ``drop_collisions`` of the whole drop."""

    scale: float
    events: int
    complete: bool
    collisions: Tuple[str, ...]
    velocities: np.ndarray
    duration: float
    deviation: Optional[float]
    drop_collisions: int
    end: str
    top_apex_ratio: Optional[float]


def _step(d: Dict[str, Any]) -> GapLimitStep:
    c = d["cascade"]
    return GapLimitStep(d["scale"], c["events"], c["complete"], tuple(c["collisions"]), np.array(c["velocities"], dtype=float),
                        c["duration"], d["deviation"], d["collisions"], d["end"], d["top_apex_ratio"])


class GapLimit(_Report):
    """A drop as its gaps go to 0 (``superball drop --gaps-to-zero``).

    ``steps``: the gapped drops (:class:`GapLimitStep`, scale 1, 0.1, ...);
    ``simultaneous``: the drop with every gap 0; as arrays, ``scales`` (k,),
    ``velocities`` (k, n) after each cascade and ``deviations`` (k,);
    ``landing_speed`` a (m/s); ``verdict``: ``"converges"`` when the smallest
    gaps' cascade ends within ``tolerance`` a of the simultaneous collision,
    ``"differs"`` when farther, ``"undecided"`` when a drop ended (the scene's
    ``until`` or ``max_events``) before its first cascade did; ``converges``:
    whether the verdict is ``"converges"``.
    ``str()`` is the command's text, ``to_dict()`` its ``--json``."""

    def __init__(self, d: Dict[str, Any]) -> None:
        super().__init__(d)
        self.scene: str = d["scene"]
        self.title: str = d["title"]
        self.precision: str = d["precision"]
        self.landing_speed: float = d["landing_speed"]
        self.tolerance: float = d["tolerance"]
        self.verdict: str = d["verdict"]
        self.simultaneous: GapLimitStep = _step(d["simultaneous"])
        self.steps: List[GapLimitStep] = [_step(s) for s in d["steps"]]
        self.scales: np.ndarray = np.array([s.scale for s in self.steps], dtype=float)
        self.velocities: np.ndarray = np.vstack([s.velocities for s in self.steps])
        self.deviations: np.ndarray = np.array([np.inf if s.deviation is None else s.deviation for s in self.steps], dtype=float)

    @property
    def converges(self) -> bool:
        """Whether the verdict is ``"converges"``: the gapped drops tend to the simultaneous collision."""
        return self.verdict == "converges"

    def __repr__(self) -> str:
        return (f"<superball.GapLimit {self.scene!r} ({self.precision}): {len(self.steps)} gapped drops, "
                f"verdict {self.verdict} against the simultaneous collision "
                f"(deviation {self.deviations[-1]:.3g} a at gaps x {self.scales[-1]:.0e})>")


def gaps_to_zero(scene: Any, decades: int = 8, precision: str = "double") -> GapLimit:
    """Drop ``scene`` (a :class:`Scene` with a ``[drop]`` table and a gap > 0)
    with its gaps times 1, 1e-1, ... 1e-``decades`` (1 to 12) and with every
    gap 0 (the simultaneous collision of the stack), and compare the first
    cascades (``superball drop --gaps-to-zero``; docs/DROP.md).
    ``precision``: ``"double"`` or ``"long-double"``.  Bad input is an
    :class:`InputError` with the command's message."""
    from . import InputError, Scene

    if not isinstance(scene, Scene):
        raise InputError(f"gaps_to_zero: expected a superball.Scene, got {type(scene).__name__}")
    if not isinstance(precision, str):
        raise InputError(f"gaps_to_zero: precision: expected 'double' or 'long-double', got {precision!r}")
    return GapLimit(_superball.gaps_to_zero(scene._scene, precision, _int_option(decades, "decades")))
