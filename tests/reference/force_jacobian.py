"""Central differences of the force stage: the reference for the damping matrices of implicit friction
(mbd_core.kernels.friction_damping), which are −∂(F, τ)/∂(v, ω) of a body's contact forces in world
coordinates (ω world) where the friction law is linear."""

import numpy as np

from mbd_core.multibody import evaluate_forces

from .multibody import matrix


def force_velocity_jacobian(model, state, body, eps):
    """−∂(F, τ)/∂(v, ω_world) (6, 6) of body ``body``'s force and moment about its centre (world) by central
    differences of step ``eps`` (m/s, rad/s) at a fixed pose; ω is stored in the body frame."""
    R = matrix(state.q[body, 3:])
    jac = np.zeros((6, 6))
    for k in range(6):
        out = []
        for sign in (1.0, -1.0):
            st = state.copy()
            du = np.zeros(6)
            du[k] = sign * eps
            st.v[body, :3] += du[:3]
            st.v[body, 3:] += R.T @ du[3:]
            w = evaluate_forces(model, st)
            out.append(np.concatenate([w.body_f[body], w.body_t[body]]))
        jac[:, k] = -(out[0] - out[1]) / (2 * eps)
    return jac
