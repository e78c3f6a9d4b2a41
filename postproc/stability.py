"""Stability functions R(z) of the fixed-step integrators on y' = lambda y (z = h lambda):
RK4's Taylor polynomial and RODAS3's rational function, for the stability and damping
studies and their charts."""
import numpy as np

# RODAS3 as in src/solve/rosenbrock.f90 (KPP form): stage coefficients a_ij, c_ij, weights
# m_i and the diagonal gamma.
RODAS3_A = np.array([[0, 0, 0, 0], [0, 0, 0, 0], [2, 0, 0, 0], [2, 0, 1, 0]], float)
RODAS3_C = np.array([[0, 0, 0, 0], [4, 0, 0, 0], [1, -1, 0, 0], [1, -1, -8 / 3, 0]], float)
RODAS3_M = np.array([2, 0, 1, 1], float)
RODAS3_GAMMA = 0.5


def stability_function(method, z):
    """R(z) of one step on y' = lambda y, z = h lambda (complex)."""
    if method == "rk4":
        return 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24
    if method == "rosenbrock":
        # (1/gamma - z) K_i = z (1 + sum_j a_ij K_j) + sum_j c_ij K_j,  R = 1 + sum m_i K_i
        z = np.asarray(z, complex)
        k = []
        for i in range(4):
            rhs = z * (1 + sum(RODAS3_A[i, j] * k[j] for j in range(i))) + \
                sum(RODAS3_C[i, j] * k[j] for j in range(i))
            k.append(rhs / (1 / RODAS3_GAMMA - z))
        return 1 + sum(RODAS3_M[i] * k[i] for i in range(4))
    raise ValueError(f"no stability function for '{method}'")
