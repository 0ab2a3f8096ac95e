"""Type stubs of superball (collisions of aligned balls in Frémond's theory)."""

import os
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

Number = Union[int, float, Fraction, str]
Values = Union["ExactRange", npt.ArrayLike, range, Sequence[Number]]

class Error(Exception):
    """A failure of superball that is not bad input."""

class InputError(Error, ValueError):
    """Bad input: the command line's one-line message."""

__version__: str
DEFAULT_RTOL: float
STATUSES: Tuple[str, ...]

class Scene:
    def __init__(
        self,
        bodies: Optional[Sequence[Union[Number, Mapping[str, Number]]]] = ...,
        *,
        title: Optional[str] = ...,
        fall_speed: Optional[Number] = ...,
        drop_height: Optional[Number] = ...,
        g: Optional[Number] = ...,
        K: Optional[Mapping[str, Number]] = ...,
        alpha: Optional[Mapping[Union[int, str], Number]] = ...,
        coupling: Optional[Sequence[Any]] = ...,
        flight: Union[bool, Mapping[str, Number], None] = ..., drop: Union[bool, Mapping[str, Any], None] = ...,
    ) -> None: ...
    @classmethod
    def load(cls, path: Any) -> Scene: ...
    @classmethod
    def from_toml(cls, text: str, origin: str = ...) -> Scene: ...
    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> Scene: ...
    def with_value(self, key: str, value: Number) -> Scene: ...
    def to_toml(self, comment: str = ...) -> str: ...
    @property
    def title(self) -> str: ...
    @property
    def origin(self) -> str: ...
    @property
    def bodies(self) -> int: ...
    @property
    def masses(self) -> List[Union[Fraction, float]]: ...
    @property
    def velocities(self) -> List[Optional[Fraction]]: ...
    @property
    def fall_speed(self) -> Optional[Fraction]: ...
    @property
    def drop_height(self) -> Optional[Fraction]: ...
    @property
    def g(self) -> Fraction: ...
    @property
    def K(self) -> Dict[str, Fraction]: ...
    @property
    def alpha(self) -> Dict[int, Fraction]: ...
    @property
    def couplings(self) -> Dict[str, Fraction]: ...
    @property
    def keys(self) -> List[str]: ...
    @property
    def flight(self) -> bool: ...
    @property
    def drop(self) -> bool: ...
    def _repr_html_(self) -> str: ...

class Result:
    origin: str
    title: str
    precision: str
    precision_requested: str
    error_bound: Optional[float]
    escalation: List[str]
    warnings: List[str]
    status: str
    case: str
    closed_contacts: Tuple[str, ...]
    superball: bool
    bodies: int
    pivots: int
    exact: bool
    kinetic_energy_before: float
    kinetic_energy_after: float
    dissipation: float
    momentum_before: float
    momentum_after: float
    residual_motion: float
    residual_complementarity: float
    contacts: Tuple[str, ...]
    @property
    def masses(self) -> npt.NDArray[np.float64]: ...
    @property
    def velocities_before(self) -> npt.NDArray[np.float64]: ...
    @property
    def velocities_after(self) -> npt.NDArray[np.float64]: ...
    @property
    def velocities_after_text(self) -> List[str]: ...
    @property
    def velocities_after_exact(self) -> Optional[List[Optional[Fraction]]]: ...
    @property
    def velocities_before_exact(self) -> List[Optional[Fraction]]: ...
    @property
    def ratio(self) -> Union[Fraction, float, None]: ...
    @property
    def reactions(self) -> npt.NDArray[np.float64]: ...
    @property
    def reactions_exact(self) -> Optional[List[Optional[Fraction]]]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def to_text(self) -> str: ...
    def _repr_html_(self) -> str: ...

def solve(scene: Scene, precision: str = ..., rtol: Optional[float] = ...) -> Result: ...

class ExactRange:
    start: Number
    stop: Number
    steps: int
    def __init__(self, start: Number, stop: Number, steps: int) -> None: ...
    def __len__(self) -> int: ...
    def __array__(self, dtype: Any = ...) -> npt.NDArray[np.float64]: ...
    def fractions(self) -> List[Fraction]: ...

def linspace(start: Number, stop: Number, steps: int) -> ExactRange: ...

@dataclass(frozen=True)
class SweepResult:
    key: str
    precision: str
    values: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]
    cases: npt.NDArray[np.str_]
    case_codes: npt.NDArray[np.int32]
    case_list: Tuple[str, ...]
    closed_list: Tuple[Tuple[str, ...], ...]
    status_codes: npt.NDArray[np.int8]
    psd: Optional[npt.NDArray[np.bool_]]
    scene: Optional[Scene]
    exact_values: Any
    @property
    def ratio(self) -> npt.NDArray[np.float64]: ...
    def switch_points(self, bits: int = ..., threads: int = ...) -> List[SwitchPoint]: ...
    def _repr_html_(self) -> str: ...
    @property
    def status(self) -> npt.NDArray[np.str_]: ...
    @property
    def ok(self) -> bool: ...
    def closed(self, k: int) -> Tuple[str, ...]: ...
    def __len__(self) -> int: ...

@dataclass(frozen=True)
class DropSweepResult:
    key: str
    precision: str
    values: npt.NDArray[np.float64]
    ratio: npt.NDArray[np.float64]
    labels: npt.NDArray[np.str_]
    events: npt.NDArray[np.int32]
    end: Tuple[str, ...]
    @property
    def ok(self) -> bool: ...
    def __len__(self) -> int: ...

def sweep(scene: Scene, key: str, values: Values, precision: str = ..., threads: int = ..., progress: Any = ...,
          checkpoint: Union[str, os.PathLike[str], None] = ...) -> Union[SweepResult, DropSweepResult]: ...

@dataclass(frozen=True)
class SwitchPoint:
    key: str
    value: float
    low: Fraction
    high: Fraction
    width: float
    case_below: str
    case_above: str
    closed_below: Tuple[str, ...]
    closed_above: Tuple[str, ...]
    text: str

def switch_points(scene: Scene, key: str, values: Values, bits: int = ..., threads: int = ...) -> List[SwitchPoint]: ...

Progress = Callable[[int, int], Any]

@dataclass(frozen=True)
class Condition:
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
    eliminated: Optional[Dict[str, Any]]
    data: Dict[str, Any]
    symbols: Tuple[Any, ...]
    definitions: Tuple[Tuple[str, str], ...]
    small: Tuple[str, ...]
    def _repr_latex_(self) -> str: ...
    def _repr_html_(self) -> str: ...
    def evaluate(self, values: Mapping[str, Any], asymptotic: bool = ...) -> Fraction: ...
    def lambdify(self, asymptotic: bool = ...) -> Callable[..., Any]: ...
    def to_sympy(self, asymptotic: bool = ...) -> Any: ...

@dataclass(frozen=True)
class Derivation:
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
    report: str
    report_latex: str
    data: Dict[str, Any]
    definitions: Tuple[Tuple[str, str], ...]
    def condition(self, about: str) -> Condition: ...
    def velocity_sympy(self, body: int) -> Any: ...
    def _repr_latex_(self) -> str: ...
    def _repr_html_(self) -> str: ...

def derive(
    case: Optional[str] = ...,
    alphas: Any = ...,
    bodies: Optional[int] = ...,
    pairs: Any = ...,
    coupling: Any = ...,
    obstacle: str = ...,
    scaling: Any = ...,
    order: int = ...,
    closed: Any = ...,
    scene: Any = ...,
    expanded: bool = ...,
    progress: Union[None, bool, Progress] = ...,
) -> Derivation: ...

def derive_all(
    alphas: Any = ...,
    bodies: Optional[int] = ...,
    pairs: Any = ...,
    coupling: Any = ...,
    obstacle: str = ...,
    scaling: Any = ...,
    order: int = ...,
    scene: Any = ...,
    expanded: bool = ...,
    jobs: Optional[int] = ...,
    progress: Union[None, bool, Progress] = ...,
    checkpoint: Union[str, os.PathLike[str], None] = ...,
) -> List[Derivation]: ...

@dataclass(frozen=True)
class AuditResult:
    conditions: List[Dict[str, Any]]
    claims: List[Dict[str, Any]]
    data: Dict[str, Any]
    text: str
    def _repr_html_(self) -> str: ...

def audit(epsilon: Number = ..., samples: int = ..., seed: int = ...) -> AuditResult: ...

@dataclass(frozen=True)
class VerifyResult:
    case: str
    exact_agrees: bool
    epsilons: npt.NDArray[np.float64]
    points: npt.NDArray[np.int64]
    exact_agreement: npt.NDArray[np.float64]
    asymptotic_agreement: npt.NDArray[np.float64]
    data: Dict[str, Any]
    text: str
    def _repr_html_(self) -> str: ...

def verify(
    case: Optional[str] = ...,
    alphas: Any = ...,
    bodies: Optional[int] = ...,
    pairs: Any = ...,
    coupling: Any = ...,
    obstacle: str = ...,
    scaling: Any = ...,
    order: int = ...,
    closed: Any = ...,
    all: bool = ...,
    scene: Any = ...,
    epsilons: Optional[Sequence[Number]] = ...,
    samples: int = ...,
    boundary_pairs: int = ...,
    seed: int = ...,
    threads: int = ...,
    progress: Any = ...,
    checkpoint: Union[str, os.PathLike[str], None] = ...,
) -> Union[VerifyResult, List[VerifyResult]]: ...

@dataclass(frozen=True)
class ExploreResult:
    case: str
    reach: str
    ratio: Optional[Fraction]
    witness: Dict[str, Fraction]
    scene: Optional[Scene]
    data: Dict[str, Any]
    text: str
    def _repr_html_(self) -> str: ...

@dataclass(frozen=True)
class PatternTable:
    patterns: List[str]
    cases: List[str]
    reach: npt.NDArray[np.str_]
    data: Dict[str, Any]
    text: str
    def _repr_html_(self) -> str: ...

def explore(
    case: Optional[str] = ...,
    alphas: Any = ...,
    bodies: Optional[int] = ...,
    pairs: Any = ...,
    coupling: Any = ...,
    closed: Any = ...,
    all: bool = ...,
    scene: Any = ...,
    all_patterns: bool = ...,
    seed: int = ...,
    starts: int = ...,
    evaluations: int = ...,
    box: Tuple[float, float] = ...,
    progress: Any = ...,
    checkpoint: Union[str, os.PathLike[str], None] = ...,
) -> Union[ExploreResult, List[ExploreResult], PatternTable]: ...

# map(): python/superball/_map.py
@dataclass(frozen=True)
class MapAxis:
    key: str
    start: Fraction
    stop: Fraction
    steps: int
    values: npt.NDArray[np.float64]
    def fractions(self) -> List[Fraction]: ...

@dataclass(frozen=True)
class BoundaryPoint:
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
    kind: str
    cases: Tuple[str, ...]
    closed: bool
    boundaries: List[int]
    points: npt.NDArray[np.float64]
    brackets: List[Tuple[Fraction, Fraction]]

@dataclass(frozen=True)
class DerivedZero:
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
    boundary: int
    found: bool
    zero: Optional[int]
    distance: Optional[float]
    allowed: Optional[float]
    agrees: bool

class Overlay:
    cases: Tuple[str, ...]
    conditions: int
    agrees: bool
    largest_distance_in_steps: float
    largest_allowed_in_steps: float
    zeros: List[DerivedZero]
    matches: List[OverlayMatch]
    def _repr_html_(self) -> str: ...

class MapResult:
    scene: str
    title: str
    precision: str
    x: MapAxis
    y: MapAxis
    cases: npt.NDArray[np.str_]
    case_codes: npt.NDArray[np.int32]
    case_list: Tuple[str, ...]
    closed_list: Tuple[Tuple[str, ...], ...]
    ratio: npt.NDArray[np.float64]
    superball: npt.NDArray[np.bool_]
    psd: npt.NDArray[np.bool_]
    status_codes: npt.NDArray[np.int8]
    boundary_points: List[BoundaryPoint]
    curves: List[MapCurve]
    overlay: Optional[Overlay]
    @property
    def shape(self) -> Tuple[int, int]: ...
    def plot(self, ax: Any = ..., curves: bool = ..., legend: bool = ...) -> Any: ...
    def _repr_html_(self) -> str: ...

@dataclass(frozen=True)
class DropEvent:
    time: float
    contacts: Tuple[str, ...]
    bodies: Tuple[int, int]
    case: str
    closed: Tuple[str, ...]
    heights: npt.NDArray[np.float64]
    velocities_before: npt.NDArray[np.float64]
    velocities_after: npt.NDArray[np.float64]
    kinetic_energy_before: float
    kinetic_energy_after: float
    momentum_before: float
    momentum_after: float

@dataclass(frozen=True)
class DropApex:
    body: int
    height: float
    time: float

@dataclass(frozen=True)
class DropRest:
    body: int
    time: float
    accumulation: bool
    ratio: float

class DropResult:
    scene: str
    title: str
    precision: str
    g: float
    fixed_obstacle: bool
    masses: npt.NDArray[np.float64]
    release_heights: npt.NDArray[np.float64]
    release_velocities: npt.NDArray[np.float64]
    events: List[DropEvent]
    times: npt.NDArray[np.float64]
    velocities_after: npt.NDArray[np.float64]
    kinetic_energy_after: npt.NDArray[np.float64]
    apexes: List[DropApex]
    rest: List[DropRest]
    end: str
    end_time: float
    top_apex_ratio: float
    near_ties: int
    def to_dict(self) -> Dict[str, Any]: ...
    def trajectories(self) -> List[Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]: ...
    def plot(self, ax: Any = ..., legend: bool = ...) -> Any: ...
    def _repr_html_(self) -> str: ...

def drop(scene: Scene, precision: str = ...) -> DropResult: ...

@dataclass(frozen=True)
class GapLimitStep:
    scale: float
    events: int
    complete: bool
    collisions: Tuple[str, ...]
    velocities: npt.NDArray[np.float64]
    duration: float
    deviation: Optional[float]
    drop_collisions: int
    end: str
    top_apex_ratio: Optional[float]

class GapLimit:
    scene: str
    title: str
    precision: str
    landing_speed: float
    tolerance: float
    verdict: str
    @property
    def converges(self) -> bool: ...
    simultaneous: GapLimitStep
    steps: List[GapLimitStep]
    scales: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]
    deviations: npt.NDArray[np.float64]
    def to_dict(self) -> Dict[str, Any]: ...
    def _repr_html_(self) -> str: ...

def gaps_to_zero(scene: Scene, decades: int = ..., precision: str = ...) -> GapLimit: ...

class DropMapResult:
    scene: str
    title: str
    precision: str
    x: MapAxis
    y: MapAxis
    ratio: npt.NDArray[np.float64]
    label_codes: npt.NDArray[np.int32]
    label_list: Tuple[str, ...]
    labels: npt.NDArray[np.str_]
    events: npt.NDArray[np.int32]
    end: npt.NDArray[np.str_]
    boundaries: str
    def __init__(self, d: Dict[str, Any]) -> None: ...
    @property
    def shape(self) -> Tuple[int, int]: ...

def map(scene: Scene, x: Union[str, Tuple[str, Number, Number, int]], y: Union[str, Tuple[str, Number, Number, int]],
        precision: str = ..., threads: Optional[int] = ..., progress: Any = ...,
        checkpoint: Union[str, os.PathLike[str], None] = ..., overlay: bool = ...) -> Union[MapResult, DropMapResult]: ...
