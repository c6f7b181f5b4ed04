"""Records Pinocchio's joint-space mass matrix (crba) and the operational-space inertia of the
frame tool0 of arm.urdf at fixed postures, for the test that compares stiffid's to them
(tests/it/dynamics.rs).

Run from this folder with Pinocchio installed (`pip install pin`):
    python3 record.py > reference.json
Lambda = (J M^-1 J^T)^-1 with J the frame Jacobian of tool0 in LOCAL_WORLD_ALIGNED (rows [v; w],
v of the frame's origin, base axes): stiffid's convention.
"""

import json

import numpy as np
import pinocchio as pin

POSTURES = [
    [0.3, -0.4, 0.8, 0.5, -0.9, 1.2],
    [-1.1, 0.2, -0.5, -2.0, 0.7, -0.3],
    [2.0, 0.9, -1.3, 1.4, 0.4, -2.5],
]


def main():
    model = pin.buildModelFromUrdf("arm.urdf")
    data = model.createData()
    frame = model.getFrameId("tool0")
    out = {"pinocchio": pin.__version__, "urdf": "arm.urdf", "frame": "tool0", "postures": []}
    for q in POSTURES:
        q = np.array(q)
        m = pin.crba(model, data, q)
        m = np.triu(m) + np.triu(m, 1).T
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        j = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        lam = np.linalg.inv(j @ np.linalg.solve(m, j.T))
        out["postures"].append(
            {"q_rad": q.tolist(), "mass_matrix": m.tolist(), "lambda": lam.tolist()}
        )
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
