"""The BEM database's davit variables: names, shapes, units, descriptions, and a reader.

The database (input/ship_bem.nc) is a netCDF4 (= HDF5) file: Capytaine's own dataset
(cpt.assemble_dataset + separate_complex_values, Capytaine's frame and conventions) plus the
root variables below, all double precision (davit_ss_order int32), in davit's frame and
conventions. Shapes are numpy's (C order); HDF5 Fortran sees the dimensions reversed.

davit's frame: ship body axes x forward, y starboard, z down, about the CG; DOFs surge,
sway, heave, roll, pitch, yaw. Capytaine's: x forward, y port, z up, so the DOF sign flip
S = diag(1, -1, -1, 1, -1, -1) takes vectors and matrices across (A_davit = S A_cpt S).
Wave elevation eta = a cos(w t + eps - k (x cos g + y sin g)), positive up, g the direction
the waves travel to, from x towards y (starboard); relative heading beta = g - ship heading
(0 following seas, 90 waves travelling to starboard, 180 head seas).
"""
import h5py
import numpy as np

OMEGA = "davit_omega"
HEADING = "davit_heading"
WAVENUMBER = "davit_wavenumber"
ADDED_MASS = "davit_added_mass"
DAMPING = "davit_radiation_damping"
ADDED_MASS_INF = "davit_added_mass_inf"
ADDED_MASS_ZERO = "davit_added_mass_zero"
EXCITATION_RE = "davit_excitation_re"
EXCITATION_IM = "davit_excitation_im"
FROUDE_KRYLOV_RE = "davit_froude_krylov_re"
FROUDE_KRYLOV_IM = "davit_froude_krylov_im"
STIFFNESS = "davit_hydrostatic_stiffness"
MASS = "davit_mass_matrix"
VOLUME = "davit_displaced_volume"
WATERPLANE_AREA = "davit_waterplane_area"
BUOYANCY_CENTRE = "davit_centre_of_buoyancy"
CG = "davit_cg"
SS_ORDER = "davit_ss_order"
SS_A = "davit_ss_a"
SS_B = "davit_ss_b"
SS_C = "davit_ss_c"
SS_FIT_ERROR = "davit_ss_fit_error"
SS_FIT_ERROR_ADDED_MASS = "davit_ss_fit_error_added_mass"
SS_FIT_ERROR_DAMPING = "davit_ss_fit_error_damping"
SS_FIT_ERROR_RETARDATION = "davit_ss_fit_error_retardation"
RETARDATION_TIME = "davit_retardation_time"
RETARDATION = "davit_retardation"
DRIFT = "davit_drift"
# the infinite-frequency added mass of the fitted model (Cummins' mass M + A_inf): the BEM's
# davit_added_mass_inf but where an impedance fit shifted it (postproc.bem_fit.fit_impedance);
# davit reads it when present (databases without it: davit_added_mass_inf)
SS_ADDED_MASS_INF = "davit_ss_added_mass_inf"
# the frame and conventions above, as a root attribute of every database built
ATTR_CONVENTIONS = "davit_conventions"
DRIFT_ENERGY_DEFECT = "davit_drift_energy_defect"

# root attributes of the database read back (the full list: postproc.bem_build.build)
ATTR_HULL_KIND = "hull_kind"
ATTR_LENGTH = "length"
ATTR_BEAM = "beam"
ATTR_DRAUGHT = "draught"
ATTR_PANELS = "panels"
ATTR_LID_PANELS = "lid_panels"
ATTR_COMMAND_LINE = "command_line"
ATTR_SOLVE_TIME = "solve_time_s"
ATTR_DRIFT_ROLL_DAMPING = "drift_roll_damping_ratio"
# the fitted damping matrix's smallest scaled eigenvalue after and before the matrix
# passivity enforcement, and whether it was enforced (postproc.bem_passive)
ATTR_FIT_MIN_EIGEN = "fit_min_eigen_damping"
ATTR_FIT_MIN_EIGEN_UNENFORCED = "fit_min_eigen_damping_unenforced"
ATTR_FIT_PASSIVE_MATRIX = "fit_passive_matrix"
# the fit's data tail and the retardation grid (postproc.bem_build), read by the re-fit
ATTR_FIT_TAIL = "fit_tail"
ATTR_RETARDATION_GRID = "retardation_dt_end_window"

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
DOF_SIGN = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
VECTOR_SIGN = np.array([1.0, -1.0, -1.0])

# dimension names of the davit variables (netCDF dimensions; davit_omega, davit_heading
# and davit_retardation_time are coordinate variables of their own dimension)
DIM_OMEGA, DIM_HEADING, DIM_TIME = OMEGA, HEADING, RETARDATION_TIME
DIM_I, DIM_J, DIM_XYZ = "davit_dof_i", "davit_dof_j", "davit_xyz"
DIM_N, DIM_M = "davit_ss_n", "davit_ss_m"
DIM_DRIFT = "davit_drift_dof"

_UNITS_6x6 = ("kg (i, j <= 3), kg m (one of i, j >= 4), kg m^2 (both >= 4); i force/moment, "
              "j motion")
# name -> (dims, units, description)
VARIABLES = {
    OMEGA: ((DIM_OMEGA,), "rad/s", "Wave (= encounter, zero speed) frequencies of the "
            "database, ascending; 0 and infinity are separate variables"),
    HEADING: ((DIM_HEADING,), "rad", "Relative wave headings beta = g - ship heading: 0 "
              "following seas, pi/2 waves travelling to starboard (coming from port), pi head "
              "seas; 0..2 pi inclusive (the last equals the first)"),
    WAVENUMBER: ((DIM_OMEGA,), "rad/m", "Deep-water wave number k = omega^2/g"),
    ADDED_MASS: ((DIM_OMEGA, DIM_I, DIM_J), _UNITS_6x6,
                 "Added mass A_ij(omega), davit body frame about the CG; i influenced "
                 "(force/moment) DOF, j radiating (motion) DOF"),
    DAMPING: ((DIM_OMEGA, DIM_I, DIM_J), "kg/s, kg m/s, kg m^2/s (as added mass, per second)",
              "Radiation damping B_ij(omega), davit body frame about the CG"),
    ADDED_MASS_INF: ((DIM_I, DIM_J), _UNITS_6x6, "Infinite-frequency added mass A_ij(inf)"),
    ADDED_MASS_ZERO: ((DIM_I, DIM_J), _UNITS_6x6, "Zero-frequency added mass A_ij(0)"),
    EXCITATION_RE: ((DIM_OMEGA, DIM_HEADING, DIM_I), "N/m (i <= 3), N m/m (i >= 4)",
                    "Real part of the first-order wave load X_i (Froude-Krylov + diffraction) "
                    "per unit wave amplitude, about the CG, davit body frame: "
                    "F_i(t) = Re[X_i a exp(i (omega t + eps - k (x_G cos g + y_G sin g)))]"),
    EXCITATION_IM: ((DIM_OMEGA, DIM_HEADING, DIM_I), "N/m (i <= 3), N m/m (i >= 4)",
                    "Imaginary part of X_i (see davit_excitation_re)"),
    FROUDE_KRYLOV_RE: ((DIM_OMEGA, DIM_HEADING, DIM_I), "N/m (i <= 3), N m/m (i >= 4)",
                       "Real part of the Froude-Krylov part of X_i (same convention)"),
    FROUDE_KRYLOV_IM: ((DIM_OMEGA, DIM_HEADING, DIM_I), "N/m (i <= 3), N m/m (i >= 4)",
                       "Imaginary part of the Froude-Krylov part of X_i"),
    STIFFNESS: ((DIM_I, DIM_J), "N/m, N, N m (by DOF pair)",
                "Hydrostatic (+ gravity) stiffness C_ij about the CG, davit body frame "
                "(Capytaine's, including the rho g V z_B - m g z_G terms, transformed)"),
    MASS: ((DIM_I, DIM_J), _UNITS_6x6, "Rigid-body mass matrix about the CG (davit frame)"),
    VOLUME: ((), "m^3", "Displaced volume"),
    WATERPLANE_AREA: ((), "m^2", "Waterplane area"),
    BUOYANCY_CENTRE: ((DIM_XYZ,), "m", "Centre of buoyancy relative to the CG, davit body "
                      "frame (x forward, y starboard, z down)"),
    CG: ((DIM_XYZ,), "m", "Centre of gravity = rotation centre in the mesh frame "
         "(Capytaine's: x forward, y port, z up, waterline z = 0), as given"),
    SS_ORDER: ((DIM_I, DIM_J), "-", "Order n_ij of the state-space model of the memory "
               "kernel K_ij (0: not fitted, negligible)"),
    SS_A: ((DIM_I, DIM_J, DIM_N, DIM_M), "1/s", "State matrix A_s of pair (i, j), "
           "zero-padded beyond n_ij: x' = A_s x + B_s u_j, mu_ij = C_s x"),
    SS_B: ((DIM_I, DIM_J, DIM_N), "-", "Input vector B_s of pair (i, j), zero-padded"),
    SS_C: ((DIM_I, DIM_J, DIM_N), "as davit_radiation_damping, per second",
           "Output vector C_s of pair (i, j), zero-padded; mu_i = sum_j C_s x_ij is the "
           "memory force in (M + A_inf) u' + mu + C eta = F"),
    SS_FIT_ERROR: ((DIM_I, DIM_J), "-", "Fit error max(added mass, damping error) of pair "
                   "(i, j) (0 where not fitted)"),
    SS_FIT_ERROR_ADDED_MASS: ((DIM_I, DIM_J), "-", "max_w |A_fit - A| / max_w |A - A_inf| "
                              "with A_fit = A_inf + Im K_fit(i w)/w"),
    SS_FIT_ERROR_DAMPING: ((DIM_I, DIM_J), "-", "max_w |B_fit - B| / max_w |B| with "
                           "B_fit = Re K_fit(i w)"),
    SS_FIT_ERROR_RETARDATION: ((DIM_I, DIM_J), "-", "||K_ss(t) - K(t)||_2 / ||K(t)||_2 over "
                               "0..30 s, K from the cosine transform"),
    RETARDATION_TIME: ((DIM_TIME,), "s", "Time grid of davit_retardation"),
    RETARDATION: ((DIM_TIME, DIM_I, DIM_J), "as davit_radiation_damping, per second",
                  "Retardation function K_ij(t) = (2/pi) int_0^inf B_ij(w) cos(w t) dw "
                  "(B piecewise linear on the grid, tail B_N (w_N/w)^2), for checking"),
}

# the mean drift coefficients (postproc.bem_drift): optional, so that databases written
# before them stay readable (davit then refuses `&ship drift` with a message naming the file)
DRIFT_VARIABLES = {
    DRIFT: ((DIM_OMEGA, DIM_HEADING, DIM_DRIFT), "N/m^2 (surge, sway), N m/m^2 (yaw)",
            "Mean wave drift load D_i(omega, beta) per unit wave amplitude squared on the "
            "freely floating body (i = surge, sway, yaw about the CG's vertical; davit body "
            "frame), far-field momentum flux (Maruo) from the Kochin functions; the mean load "
            "in a regular wave of amplitude a is D a^2"),
    DRIFT_ENERGY_DEFECT: ((DIM_OMEGA, DIM_HEADING), "-",
                          "(omega Im H(beta) + k^2 int |H|^2) / (k^2 int |H|^2) of the total "
                          "Kochin function H: zero for a body that absorbs no energy; a check "
                          "of the far-field discretisation"),
}


class Database:
    """The davit variables of a BEM database, read with h5py (plain HDF5, as the Fortran
    reader sees it): attribute access by the short names below."""

    def __init__(self, path):
        self.path = str(path)
        with h5py.File(path, "r") as f:
            missing = [n for n in VARIABLES if n not in f]
            if missing:
                raise ValueError(f"{path}: not a davit BEM database (missing {missing})")
            self.values = {n: f[n][()] for n in VARIABLES}
            self.values.update({n: f[n][()] for n in DRIFT_VARIABLES if n in f})
            self.attrs = {k: (v.decode() if isinstance(v, bytes) else v)
                          for k, v in f.attrs.items()}

    def __getitem__(self, name):
        return self.values[name]

    omega = property(lambda self: self.values[OMEGA])
    heading = property(lambda self: self.values[HEADING])
    added_mass = property(lambda self: self.values[ADDED_MASS])
    damping = property(lambda self: self.values[DAMPING])
    added_mass_inf = property(lambda self: self.values[ADDED_MASS_INF])
    stiffness = property(lambda self: self.values[STIFFNESS])
    mass = property(lambda self: self.values[MASS])

    @property
    def drift(self):
        """D (omega, beta, surge/sway/yaw), or None for a database written without it."""
        return self.values.get(DRIFT)

    @property
    def excitation(self):
        return self.values[EXCITATION_RE] + 1j * self.values[EXCITATION_IM]

    @property
    def froude_krylov(self):
        return self.values[FROUDE_KRYLOV_RE] + 1j * self.values[FROUDE_KRYLOV_IM]
