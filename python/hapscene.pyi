# Type hints for the hapscene module (python/module.cpp). Values documented as
# `Quantity` take a number in SI or a string with a unit ("10 mm", "2 kHz").
import os
from typing import Any, Iterable, Mapping, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

Quantity = Union[float, int, str]
Point = Union[Tuple[Quantity, Quantity], Sequence[Quantity], str]
PathLike = Union[str, os.PathLike]
ArrayLike = npt.ArrayLike

class InputError(ValueError):
    """Invalid input; the message names the place, as the command line prints it."""

class ScriptFaultWarning(RuntimeWarning):
    """A script fault (or a note on a script's state or time) met while probing."""

class Scene:
    """An environment as the engine loaded it (hapscene.load)."""
    @property
    def path(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def rate(self) -> float: ...
    @property
    def axes(self) -> int: ...
    @property
    def device(self) -> str: ...
    @property
    def effects(self) -> list[dict[str, Any]]: ...
    @property
    def parameters(self) -> Mapping[str, float]:
        """Read-only: a Scene is immutable (edit the dict and hapscene.loads() it)."""
        ...
    @property
    def load_warnings(self) -> list[str]: ...
    def probe(
        self,
        x: ArrayLike,
        y: Optional[ArrayLike] = None,
        *,
        v: Optional[Quantity] = None,
        vx: Optional[Quantity] = None,
        vy: Optional[Quantity] = None,
        t: Quantity = 0.0,
    ) -> dict[str, npt.NDArray[np.float64]]:
        """The open-loop force at each point, as `hapscene probe` computes it.

        1-DOF: columns x_m, v_m_per_s, force_N, output_N. 2-DOF (x and y): x_m, y_m,
        vx_m_per_s, vy_m_per_s, force_x_N, force_y_N, output_x_N, output_y_N. Raises
        RuntimeError when the scripts are too slow for the loop's checks.
        """
        ...

def effect_types() -> list[dict[str, Any]]:
    """Every built-in effect type of every number of axes as the engine declares it:
    "type", "axes", "description" and "keys" (name, form, quantity, unit, required, min,
    min_excluded, max, min_items and max_items of points, default or default_from,
    choices, slidable, field, description)."""
    ...

def load(path: PathLike) -> Scene:
    """Loads an environment file; raises InputError with the CLI's located message."""
    ...

def loads(source: Union[str, dict[str, Any]], *, base_dir: PathLike = ".", name: str = "<string>") -> Scene:
    """Loads an environment from JSON text or a dict (scripts and profiles from base_dir)."""
    ...

class RunSummary(TypedDict, total=False):
    scene: str
    source: str
    device: str
    rate_hz: float
    pacing: str
    hand: str
    ticks: int
    device_time_s: float
    achieved_rate_hz: float
    max_abs_requested_N: float
    max_abs_output_N: float
    force_limit_N: float
    clamped_ticks: int
    slew_limited_ticks: int
    soft_start_ticks: int
    outside_workspace_ticks: int
    position_hold_ticks: int
    pose_hold_ticks: int
    motor_saturated_ticks: int
    nonfinite_faults: int
    script_errors: int
    script_budget_overruns: int
    scripts: list[dict[str, Any]]
    tick_compute_us: dict[str, float]
    device_report: str
    faulted: bool
    exit_code: int
    plant_linkage_faults: int

def simulate(
    scene: Union[PathLike, Scene],
    *,
    duration: Optional[Quantity] = None,
    hand: Optional[str] = None,
    hold: Optional[Union[Quantity, Point]] = None,
    start: Optional[Union[Quantity, Point]] = None,
    hand_stiffness: Optional[Quantity] = None,
    hand_damping: Optional[Quantity] = None,
    release: Optional[Quantity] = None,
    noise: Optional[Quantity] = None,
    seed: Optional[Union[int, str]] = None,
    device: str = "sim",
) -> dict[str, Any]:
    """`hapscene run --sim-time --log` in memory: the log's columns as numpy arrays,
    the simulator's true state (x_true_m, v_true_m_per_s, motor_force_N, hand_force_N,
    per axis in 2-D) and "summary" (RunSummary)."""
    ...

def validate(
    scene: Union[PathLike, Scene],
    *,
    scenarios: Optional[Union[str, Iterable[str]]] = None,
    hand_stiffness: Optional[Quantity] = None,
    hand_damping: Optional[Quantity] = None,
    hand_mass: Optional[Quantity] = None,
    noise: Optional[Quantity] = None,
    seed: Optional[Union[int, str]] = None,
    start: Optional[Union[Quantity, Point]] = None,
) -> dict[str, Any]:
    """The JSON report of `hapscene validate --report`, as a dict."""
    ...

def test(paths: Optional[Union[PathLike, Iterable[PathLike]]] = None) -> list[dict[str, Any]]:
    """Runs test specs as `hapscene test`; one dict per spec (spec, environment, pass,
    error, outcomes)."""
    ...
