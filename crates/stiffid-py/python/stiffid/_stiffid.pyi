"""Types of the native module of stiffid (see the docstrings for shapes, units and sources)."""

import os
from typing import Any, Literal, Optional, Sequence, Union, final, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._documents import (
    CalibrateCellDocument,
    CalibrateDocument,
    ForceDocument,
    KinematicsDocument,
    PlaceDocument,
    PlanDocument,
    PredictDocument,
    RegisterDocument,
    RegisterPosturesDocument,
)

__version__: str
__all__: list[str]

_Coordinates = Literal["axis", "kinematic"]
_CriterionName = Literal[
    "classical", "zhang2021", "scaled-cond", "d-optimal", "relative-a", "test-pose",
    "scaled_cond", "d_optimal", "relative_a", "test_pose_mm",
]
_PathLike = Union[str, "os.PathLike[str]"]
_Array = NDArray[np.float64]
_Ints = NDArray[np.int64]

class _Placed(PlaceDocument):
    """`place`'s document and the setup with the chosen ``[workpiece]``."""

    setup_text: str

@final
class Error(ValueError):
    """The library's error, with its message (a ``ValueError``)."""

class InputError(Error):
    """Bad input: a file, line, field or argument and what was expected."""

class InfeasibleError(Error):
    """A search that finds no feasible group, or a pose out of reach."""

class UnidentifiableError(Error):
    """Data that cannot identify every parameter."""

class GateError(Error):
    """A result beyond a bound the caller set (``compensate``'s ``max_error_mm``)."""

class Robot:
    """A 6-axis serial robot (immutable); postures in deg, (6,) or (n, 6)."""

    @staticmethod
    def preset(name: str) -> "Robot": ...
    @staticmethod
    def presets() -> list[str]: ...
    @staticmethod
    def from_file(
        path: _PathLike, tip: Optional[str] = None, *, package_paths: Sequence[_PathLike] = ()
    ) -> "Robot": ...
    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def lower_limit_deg(self) -> _Array: ...
    @property
    def upper_limit_deg(self) -> _Array: ...
    def flange_pose(self, q_deg: ArrayLike) -> _Array:
        """(4, 4) or (n, 4, 4) homogeneous transform, translation in mm."""
    def jacobian(
        self, q_deg: ArrayLike, point_mm: Optional[ArrayLike] = None, coordinates: _Coordinates = "axis"
    ) -> _Array:
        """(6, 6) or (n, 6, 6), rows [v; omega] in m/rad and rad/rad, base frame."""
    def read_postures(self, path: _PathLike) -> _Array:
        """(n, 6) deg from a postures CSV (posture,q1_deg,...,q6_deg)."""
    def inverse_kinematics(
        self,
        pose_mm: ArrayLike,
        q0_deg: ArrayLike,
        *,
        point_mm: Optional[ArrayLike] = None,
        position_tolerance_mm: Optional[float] = None,
        rotation_tolerance_deg: Optional[float] = None,
        max_iterations: Optional[int] = None,
        restarts: Optional[int] = None,
        seed: int = 1,
    ) -> dict[str, Any]:
        """pose_mm (4, 4) or (n, 4, 4), base frame, translation mm: q_deg (6,) or (n, 6), iterations, position_error_mm, rotation_error_deg."""
    def characteristic_length_mm(self, point_mm: Optional[ArrayLike] = None) -> float:
        """The robot's own characteristic length, mm: minimises the point's median dexterity."""
    def kinematics(
        self,
        q_deg: ArrayLike,
        point_mm: Optional[ArrayLike] = None,
        characteristic_length_mm: Optional[float] = None,
        coordinates: _Coordinates = "axis",
        stiffness_nm_per_rad: Optional[ArrayLike] = None,
        external: Optional[ArrayLike] = None,
    ) -> KinematicsDocument:
        """The kinematics document (docs/schemas/kinematics.schema.json), equal to `stiffid kinematics --json`; `external` (mm/deg, the cell's order) for a robot with external axes."""
    @property
    def external_axes(self) -> list[dict[str, Any]]:
        """The cell's external axes in the cell's order (name, column, role, direction, point_mm, limits, offset in mm or deg)."""
    def with_external_axes(self, axes: Optional[Sequence[dict[str, Any]]]) -> "Robot":
        """The robot with these external axes: dicts with the keys of [[external_axis]] tables."""
    @overload
    def dexterity(
        self,
        q_deg: Sequence[float],
        point_mm: Optional[ArrayLike] = None,
        characteristic_length_mm: Optional[float] = None,
        coordinates: _Coordinates = "axis",
    ) -> float: ...
    @overload
    def dexterity(
        self,
        q_deg: ArrayLike,
        point_mm: Optional[ArrayLike] = None,
        characteristic_length_mm: Optional[float] = None,
        coordinates: _Coordinates = "axis",
    ) -> Union[float, _Array]: ...

@final
class Setup:
    """An experimental setup (read-only): mm, deg, N, Nm/rad."""

    @staticmethod
    def builtin(name: str) -> "Setup": ...
    @staticmethod
    def builtins() -> list[str]: ...
    @staticmethod
    def from_file(path: _PathLike, *, package_paths: Sequence[_PathLike] = ()) -> "Setup": ...
    @staticmethod
    def from_toml(
        text: str,
        source_name: str = "<string>",
        base_dir: Optional[_PathLike] = None,
        *,
        package_paths: Sequence[_PathLike] = (),
    ) -> "Setup": ...
    @property
    def parameters(self) -> list[dict[str, Any]]:
        """name, kind (drive, rotation, translation), unit (Nm/rad, N/mm), stiffness (nominal, or None)."""
    @property
    def model_toml(self) -> str: ...
    def with_model(self, toml: str, source_name: str = "<model>") -> "Setup": ...
    def feasibility(self, postures_deg: ArrayLike) -> list[dict[str, Any]]:
        """One dict per posture: posture (1-based), feasible, min_clearance_mm, violations."""
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def robot_ref(self) -> str: ...
    @property
    def robot(self) -> Robot: ...
    @property
    def springs(self) -> _Coordinates: ...
    @property
    def nominal_stiffness_nm_per_rad(self) -> Optional[_Array]: ...
    @property
    def characteristic_length_mm(self) -> Optional[float]: ...
    @property
    def loading_point_mm(self) -> _Array: ...
    @property
    def measuring_points_mm(self) -> _Array: ...
    @property
    def tcp_mm(self) -> _Array: ...
    @property
    def load_n(self) -> float: ...
    @property
    def load_steps_n(self) -> list[float]: ...
    @property
    def anchor_mm(self) -> _Array: ...
    @property
    def noise_variance_mm2(self) -> float: ...
    @property
    def level_multiples(self) -> _Array: ...
    @property
    def lower_deg(self) -> _Array: ...
    @property
    def upper_deg(self) -> _Array: ...
    @property
    def test_postures_deg(self) -> _Array: ...
    def evaluate(
        self,
        postures_deg: ArrayLike,
        *,
        candidates: Optional[Sequence[str]] = None,
        purpose: Literal["stiffness", "calibration", "both", "check"] = "stiffness",
        calibration_criterion: Optional[Literal["test-pose", "o1", "o3", "o4", "o5", "d-optimality"]] = None,
        geometry: Optional[Literal["none", "offsets", "full"]] = None,
        gravity: Optional[Literal["none", "arm", "masses", "lumped", "lumped-links"]] = None,
        weight: Optional[float] = None,
    ) -> dict[str, Any]:
        """The evaluate document: criteria (floats), relative_std (6,), predicted_deviation_pct (levels, 6), feasibility, parameters, unidentifiable, candidates, calibration (with purpose calibration or both); None where the setup lacks the field."""
    def select(
        self,
        criterion: Optional[_CriterionName] = None,
        method: Optional[Literal["global", "local", "pool"]] = None,
        start: Optional[ArrayLike] = None,
        n: Optional[int] = None,
        seed: int = 1,
        *,
        starts: Optional[int] = None,
        screen_steps: Optional[int] = None,
        polished: Optional[int] = None,
        max_evals: Optional[int] = None,
        gradient: Literal["exact", "fd"] = "exact",
        solver: Literal["auto", "slsqp", "active-set"] = "auto",
        pool: Optional[ArrayLike] = None,
        restarts: Optional[int] = None,
        target_pct: Optional[float] = None,
        margin_mm: Optional[float] = None,
        for_candidates: bool = False,
        candidates: Optional[Sequence[str]] = None,
        distinct: bool = False,
        distinct_deg: Optional[float] = None,
        distinct_mm: Optional[float] = None,
        purpose: Literal["stiffness", "calibration", "both", "check"] = "stiffness",
        calibration_criterion: Optional[Literal["test-pose", "o1", "o3", "o4", "o5", "d-optimality"]] = None,
        geometry: Optional[Literal["none", "offsets", "full"]] = None,
        gravity: Optional[Literal["none", "arm", "masses", "lumped", "lumped-links"]] = None,
        weight: Optional[float] = None,
        stations: Optional[Sequence[Sequence[float]]] = None,
    ) -> dict[str, Any]:
        """The select document: search, postures_deg (n, 6), value, start_value, evaluations, termination(s), criteria; pool, target, unconstrained, candidates where they apply."""
    def random_group(self, n: int = 6, seed: int = 1) -> _Array: ...

@overload
def identify(
    setup: Setup,
    measurements: Optional[_PathLike] = None,
    *,
    q_deg: Optional[ArrayLike] = None,
    wrench: Optional[ArrayLike] = None,
    displacement_mm: Optional[ArrayLike] = None,
    point: Optional[Sequence[int]] = None,
    robust: Optional[Literal["huber", "tukey"]] = None,
    nonnegative: bool = False,
    cross_validate: bool = False,
    folds: Optional[int] = None,
    offsets: bool = False,
) -> dict[str, Any]:
    """The identify document (docs/schemas/identify.schema.json), equal to `stiffid identify --json`; the stiffness, compliance, their errors, intervals and covariance as NumPy arrays."""
@overload
def identify(
    setup: Setup,
    measurements: Optional[_PathLike] = None,
    *,
    q_deg: Optional[ArrayLike] = None,
    wrench: Optional[ArrayLike] = None,
    displacement_mm: Optional[ArrayLike] = None,
    point: Optional[Sequence[int]] = None,
    compare_models: Literal[True],
    candidates: Optional[Sequence[str]] = None,
    bootstrap: Optional[int] = None,
    seed: Optional[int] = None,
    stiffness_out: Optional[_PathLike] = None,
) -> dict[str, Any]: ...
def validate(
    setup: Setup,
    stiffness_nm_per_rad: Union[ArrayLike, _PathLike],
    measurements: Optional[_PathLike] = None,
    *,
    q_deg: Optional[ArrayLike] = None,
    wrench: Optional[ArrayLike] = None,
    displacement_mm: Optional[ArrayLike] = None,
    point: Optional[Sequence[int]] = None,
    level: Optional[float] = None,
) -> dict[str, Any]: ...
def simulate(setup: Setup, groups: Sequence[ArrayLike], runs: int = 200, seed: int = 1) -> list[dict[str, _Array]]: ...
def reproduce(
    setup: Optional[Setup] = None,
    runs: int = 200,
    seed: int = 1,
    starts: int = 16,
    trials: int = 20,
    solver: Literal["auto", "slsqp", "active-set"] = "auto",
    figures: bool = False,
) -> dict[str, Any]:
    """The document of `stiffid reproduce`'s summary.json; levels, test_deflection_mm and each group's postures and deviation rates as NumPy arrays; with figures=True, figures: the report's figures as SVG strings keyed by name."""
def compensate(
    setup: Setup,
    path: Optional[Union[str, os.PathLike[str]]] = None,
    stiffness: Optional[Union[ArrayLike, str, os.PathLike[str]]] = None,
    *,
    program: Optional[Union[str, os.PathLike[str]]] = None,
    process: Optional[Union[str, os.PathLike[str]]] = None,
    output: Optional[Literal["gcode", "krl", "rapid", "ls", "inform"]] = None,
    chord_tolerance_mm: float = 0.01,
    backup: Optional[Union[str, os.PathLike[str], list[Union[str, os.PathLike[str]]]]] = None,
    leave_refused: bool = False,
    frame: Literal["base", "tool"] = "base",
    q0_deg: Optional[ArrayLike] = None,
    free: Optional[list[Union[str, dict[str, Any]]]] = None,
    minimise: Optional[Literal["bound", "deflection", "surge"]] = None,
    program_name: Optional[str] = None,
    targets: Optional[Literal["cartesian", "joint"]] = None,
    max_tcp_speed_mm_s: float = 2000.0,
    name_length: Optional[int] = None,
    moves_per_file: int = 10000,
    level: float = 0.95,
    max_error_mm: Optional[float] = None,
    force_tolerance_pct: float = 20.0,
    objective: Optional[Literal["sum", "max"]] = None,
    map: Union[bool, Literal["rotation", "track"], None] = None,
    margin_deg: Optional[float] = None,
    max_condition: Optional[float] = None,
    refine: Optional[int] = None,
    figures: bool = False,
) -> dict[str, Any]:
    """line (n,) int64, q_deg, q_compensated_deg (n, 6), deflection_mm, deflection_mrad, force_n (n, 3), residual_um, residual_urad (n,), iterations (n,) int64, tool_rotation_deg, lead_deg, tilt_deg (n,); surge_mm_s, surge_std_mm_s, effective_mass_kg, surge_before_mm_s (n,; the last with a free tool-rotation) at drilling exits and first_frequency_hz, tooth_passing_hz (n,) at milling points of a program (NaN elsewhere or without masses); bound_mm, bound_left_mm, bound_compensation_mm, bound_calibration_mm, bound_force_mm, bound_model_form_mm (n,; NaN where a part is absent); map (with map=True or "rotation": line, tool_rotation_deg, chosen_deg, bound_mm, deflection_mm, condition, limit_distance_deg (n, g); with map="track": station_offset_mm and chosen_mm for the first two; collision_distance_mm (n, g) with a cell floor or obstacles); deflection_std_mm with a covariance; document (the command's JSON); program (text), encoding ("utf-8", or "latin-1" for a program read as Latin-1: write its texts in it), subprograms (name: text, in call order), data (a KRL program's .dat) and subprogram_data (name: .dat text) with program=; figures (with figures=True: the report's figures as SVG strings keyed by name)."""

def process_force(
    process: Union[str, os.PathLike[str]],
    *,
    peak_resolution_deg: Optional[float] = None,
) -> ForceDocument:
    """The document of `stiffid force --json`: kind ("force"), process, peak_resolution_deg, operations (name, kind, mean_force_n, mean_moment_nm, peak_force_n)."""

def read_program(
    program: Union[str, os.PathLike[str]],
    *,
    chord_tolerance_mm: float = 0.01,
    setup: Optional[Setup] = None,
    process: Optional[Union[str, os.PathLike[str]]] = None,
) -> dict[str, Any]:
    """language, line (n,) int64; G-code: position_mm (n, 3), rapid (n,) bool, tool_number, operation; robot programs: q_deg (n, 6), NaN for a Cartesian target (its axis angles need the setup: compensate resolves them); both: external_axes (k names), external (n, k) mm or deg as written, NaN where a target gives none; feed_mm_s (n,) the TCP speed of each move (a G-code feed move's F, a robot program's linear motion's programmed speed; NaN elsewhere); robot programs: joint (n,) bool (a joint motion), time_s (n,) the move's time where given (NaN elsewhere), speed_not_read (list: why a linear motion's speed is not read, None where it is)."""

def place(
    setup: Union[str, os.PathLike[str]],
    stiffness: Union[ArrayLike, str, os.PathLike[str]],
    *,
    program: Optional[Union[str, os.PathLike[str]]] = None,
    process: Optional[Union[str, os.PathLike[str]]] = None,
    backup: Optional[Union[str, os.PathLike[str], list[Union[str, os.PathLike[str]]]]] = None,
    path: Optional[Union[str, os.PathLike[str]]] = None,
    frame: Literal["base", "tool"] = "base",
    region_mm: Sequence[float],
    rotation_deg: Sequence[float] = (-180.0, 180.0),
    free: Optional[Sequence[str]] = None,
    objective: Literal["max", "sum"] = "max",
    margin_deg: float = 5.0,
    max_condition: float = 1000.0,
    seed: int = 1,
    grid: int = 5,
    samples: int = 32,
    starts: int = 3,
    chord_tolerance_mm: float = 0.01,
    level: float = 0.95,
    force_tolerance_pct: float = 20.0,
    q0_deg: Optional[ArrayLike] = None,
) -> _Placed:
    """The document of `stiffid place --json` (placed, own, reach_only, gain_vs_own_pct, gain_vs_reach_only_pct, evaluations) and setup_text (the setup with the chosen [workpiece])."""

def cartesian_compliance(
    setup: Setup,
    q_deg: ArrayLike,
    *,
    point_mm: Optional[ArrayLike] = None,
    stiffness_nm_per_rad: Optional[Union[ArrayLike, _PathLike]] = None,
) -> _Array:
    """C_x (6, 6) or (n, 6, 6), SI, base frame: [dp; dphi] = C_x [f; m]."""

def cartesian_stiffness(
    setup: Setup,
    q_deg: ArrayLike,
    *,
    point_mm: Optional[ArrayLike] = None,
    stiffness_nm_per_rad: Optional[Union[ArrayLike, _PathLike]] = None,
) -> _Array:
    """K_x = C_x^-1 (6, 6) or (n, 6, 6), SI, base frame; NaN where singular."""

def predict(
    setup: Setup,
    q_deg: ArrayLike,
    wrench: ArrayLike,
    *,
    at_mm: Optional[ArrayLike] = None,
    frame: Literal["base", "tool"] = "base",
    stiffness_nm_per_rad: Optional[Union[ArrayLike, _PathLike]] = None,
    compliance_covariance_rad2_per_nm2: Optional[ArrayLike] = None,
    level: Optional[float] = None,
) -> PredictDocument:
    """The predict document (docs/schemas/predict.schema.json), equal to `stiffid predict --json`."""

def deflection(
    setup: Setup,
    q_deg: ArrayLike,
    wrench: ArrayLike,
    *,
    at_mm: Optional[ArrayLike] = None,
    frame: Literal["base", "tool"] = "base",
    stiffness_nm_per_rad: Optional[Union[ArrayLike, _PathLike]] = None,
    compliance_covariance_rad2_per_nm2: Optional[ArrayLike] = None,
    level: Optional[float] = None,
) -> list[dict[str, Any]]:
    """The predict document of each posture of q_deg ((6,) or (n, 6)) under wrench ((6,) or (n, 6)), each equal to `stiffid predict --json` (loaded_mm became at_mm; observed_mm was removed: every measuring point and the TCP are in each document)."""

def figures(document: Any, setup: Optional[Setup] = None) -> dict[str, str]:
    """The figures of a calibration (the dict calibrate() returns), an identification (the dict identify() returns, or a model comparison) or a plan (the dict plan() returns, with its setup) as SVG strings keyed by name, as `calibrate --report`, `identify --report` and `select --report` draw them."""

def register(
    setup: Setup,
    readings: Optional[Union[str, os.PathLike[str]]] = None,
    *,
    count: Optional[int] = None,
    seed: int = 1,
    candidates: Optional[int] = None,
    restarts: Optional[int] = None,
    force: bool = False,
    postures: None = None,
) -> Union[RegisterDocument, RegisterPosturesDocument]:
    """The document of `stiffid register --json`: setup, data, xyz_mm, rpy_deg, translation_std_mm, rotation_std_deg, residual_rms_mm, noise_std_mm, points, fragment. With count=N instead of readings, that of `stiffid register --count N --json` (`postures=` is refused: renamed count): setup, seed, postures (posture, q_deg), measuring_points, noise_std_mm, translation_std_mm, rotation_std_deg, rotation_std_total_deg, random_median_rotation_std_total_deg, candidates, feasible, checks, method, evaluations, readings_template."""

def calibrate_cell(setup: Setup, readings: Union[str, os.PathLike[str]], *, force: bool = False) -> CalibrateCellDocument:
    """The document of `stiffid calibrate-cell --json`: the transform as for register, points (setup_mm, fitted_mm, shift_mm, std_mm), absolute_error_rms_mm, noise_std_mm, readings, iterations, fragment."""
def calibrate(
    setup: Setup,
    readings: _PathLike,
    *,
    geometry: Literal["none", "offsets", "full"] = "full",
    gravity: Literal["auto", "none", "arm", "masses", "lumped", "lumped-links"] = "auto",
    gravity_bound_mrad: float = 3.0,
    validate: Optional[_PathLike] = None,
    reregister: bool = False,
    cross_validate: bool = False,
    tolerance_mm: Optional[float] = None,
    tolerance_deg: Optional[float] = None,
    maps: str = "auto",
    error_motions: str = "auto",
    level: Optional[float] = None,
    update: bool = False,
    update_parameters: Optional[str] = None,
    stiffness: Optional[_PathLike] = None,
    out: Optional[_PathLike] = None,
    urdf_out: Optional[_PathLike] = None,
    stiffness_out: Optional[_PathLike] = None,
    force: bool = False,
) -> CalibrateDocument:
    """The document of `stiffid calibrate --json` (update=True: a calibrated robot updated from check readings, check: whether it drifted beyond its intervals; update_parameters "offsets,base,tool,gravity,external" what it refits (external: a cell's external axes' zero offsets), stiffness the calibration's stiffness file whose gravity terms it keeps, held what it kept): parameters (name, kind, unit, nominal, value, sd, identified), merged, rank, condition, residual_rms_mm, noise_ratio, maps (auto, none or "J1,J3:16": the joint error maps chosen by cross-validation and their nested held-out gain), validation (with level: the held-out readings' jackknife+ prediction intervals, interval_mm per reading, and their coverage), cross_validation, robot_file (or robot_file_error), urdf (or urdf_error), fragment; out and urdf_out write the calibrated robot file and URDF (urdf_out refused, saying why, for an axis map that couples axes)."""
def plan(
    setup: Setup,
    postures_deg: ArrayLike,
    *,
    criterion: _CriterionName = "relative-a",
    target_pct: Optional[float] = None,
    external: Optional[Sequence[Sequence[float]]] = None,
) -> PlanDocument:
    """The measurement plan of a group, the plan.json of `stiffid select --report`: the setup's load and bodies, predicted_deviation_pct, parameters, and per posture the rope, the loading point's height, the expected displacements, the cell's checks and the leave-one-out rates; external (n, k) mm/deg, the cell's order: where each posture is read (its e1_mm.. in the document)."""
class Scene:
    """The 3D scene of a plan or an identification (`scene`): the robot at each posture in the cell, lines of sight, rope, compliance ellipsoids, displacements; shown inline by Jupyter."""

    def document(self) -> dict[str, Any]: ...
    def html(self, title: str = "stiffid scene") -> str: ...
    def glb(self) -> bytes: ...
    def _repr_html_(self) -> str: ...

def scene(setup: Setup, postures_deg: Optional[ArrayLike] = None, *, document: Optional[dict[str, Any]] = None) -> Scene:
    """The 3D scene of a group (1 to 500 postures, deg), of a plan (document=stiffid.plan(...)), of an identification (document=stiffid.identify(...), postures_deg its postures in order), of a calibration (document=stiffid.calibrate(...)) or of a compensation (document=stiffid.compensate(...)["document"]), the track and positioner at each posture's external values: what select, identify, calibrate and compensate --report show and write as .glb."""
def setups_new(
    robot: _PathLike,
    *,
    tip: Optional[str] = None,
    payload_kg: Optional[float] = None,
    out: Optional[_PathLike] = None,
    package_paths: Sequence[_PathLike] = (),
) -> str:
    """The commented setup TOML of `stiffid setups new` for a preset, robot TOML or URDF; with out, written to that new file."""
