"""stiffid: joint stiffness identification of industrial robots and the design of its experiment.

A thin Python layer over the stiffid Rust library (the same code as the ``stiffid`` command):
robots and their kinematics (``Robot``), experimental setups (``Setup``, a new one for your robot:
``setups_new``) and posture selection,
the measurement plan of a group (``plan``), identification and validation from measurements (``identify``, ``validate``), the deflection
under a wrench (``deflection``), the compensation of a machining path or program (``compensate``,
with ``process_force`` and ``read_program``), the part's placement (``place``), the tracker's registration, the cell's
calibration and the robot's geometric and elastostatic calibration from raw readings
(``register``, ``calibrate_cell``, ``calibrate``), the Monte Carlo
simulation (``simulate``) and the paper's study (``reproduce``).

Units: postures in degrees (controller axis angles), points in mm, forces in N, moments in Nm,
stiffness in Nm/rad; Jacobians in SI (m/rad, rad/rad). Method: Zhang, Guo, Sun and Sun, "Method of
Postures Selection for Industrial Robot Joint Stiffness Identification", IEEE Access 9 (2021),
doi:10.1109/ACCESS.2021.3073671 (equation numbers in the docstrings are that paper's).

Errors are ``stiffid.Error`` (a ``ValueError``) with the library's message, as one of its
subclasses: ``InputError`` (bad input), ``InfeasibleError`` (a search that finds no feasible group,
a pose out of reach), ``UnidentifiableError`` (data that cannot identify every parameter) or
``GateError`` (a result beyond a bound the caller set, such as ``compensate``'s ``max_error_mm``).
A missing file raises ``MissingFileError``, both an ``InputError`` naming the argument
(``setup: cell.toml: no such file``) and a ``FileNotFoundError``. Results to look at before trusting them (a stiffness
that is not physical, a likely unit mistake) raise ``UserWarning``, as the command prints
``warning: ...``.
"""

from ._stiffid import (
    Error,
    GateError,
    InfeasibleError,
    InputError,
    Robot,
    Scene,
    Setup,
    UnidentifiableError,
    __version__,
    calibrate,
    calibrate_cell,
    cartesian_compliance,
    cartesian_stiffness,
    compensate,
    deflection,
    figures,
    identify,
    place,
    plan,
    predict,
    process_force,
    read_program,
    register,
    reproduce,
    scene,
    setups_new,
    simulate,
    validate,
)

__all__ = [
    "Error",
    "GateError",
    "InfeasibleError",
    "InputError",
    "MissingFileError",
    "Robot",
    "Scene",
    "Setup",
    "UnidentifiableError",
    "__version__",
    "calibrate",
    "calibrate_cell",
    "cartesian_compliance",
    "cartesian_stiffness",
    "compensate",
    "deflection",
    "figures",
    "identify",
    "place",
    "plan",
    "predict",
    "process_force",
    "read_program",
    "register",
    "reproduce",
    "scene",
    "setups_new",
    "simulate",
    "validate",
]

# Every error in reading an argument names it (``_arguments``).
from . import _arguments  # noqa: E402
from ._arguments import MissingFileError  # noqa: E402

for _function in __all__:
    if type(globals()[_function]).__name__ == "builtin_function_or_method":
        globals()[_function] = _arguments.naming(globals()[_function])
for _class in (Robot, Scene, Setup):
    _arguments.name_arguments_of(_class)
del _function, _class

