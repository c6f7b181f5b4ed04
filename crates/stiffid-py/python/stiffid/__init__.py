"""stiffid: joint stiffness identification of industrial robots and the design of its experiment.

A thin Python layer over the stiffid Rust library (the same code as the ``stiffid`` command):
robots and their kinematics (``Robot``), experimental setups and posture selection (``Setup``),
identification and validation from measurements (``identify``, ``validate``), the deflection
under a wrench (``deflection``), the compensation of a machining path (``compensate``), the Monte Carlo
simulation (``simulate``) and the paper's study (``reproduce``).

Units: postures in degrees (controller axis angles), points in mm, forces in N, moments in Nm,
stiffness in Nm/rad; Jacobians in SI (m/rad, rad/rad). Method: Zhang, Guo, Sun and Sun, "Method of
Postures Selection for Industrial Robot Joint Stiffness Identification", IEEE Access 9 (2021),
doi:10.1109/ACCESS.2021.3073671 (equation numbers in the docstrings are that paper's).

Bad input raises ``ValueError`` with the library's message; a search that finds no feasible group
raises ``RuntimeError``.
"""

from ._stiffid import (
    Identification,
    Robot,
    Setup,
    Study,
    __version__,
    compensate,
    deflection,
    identify,
    reproduce,
    simulate,
    validate,
)

__all__ = [
    "Identification",
    "Robot",
    "Setup",
    "Study",
    "__version__",
    "compensate",
    "deflection",
    "identify",
    "reproduce",
    "simulate",
    "validate",
]
