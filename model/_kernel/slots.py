"""Names of the kernel's state slots, stats slots and status codes (defined once).

The state vector (N_STATE = 12) is the motion (x, y, v_x, v_y, theta) of Eqs. (5)-(6),
six quadratures integrated alongside it (docs/model.md, "What one contact yields") and
the time tau (the kernel integrates in the Sundman variable s, see ``rhs``):

    W    = int F_f,x dtau             slab work; the slab moves at speed 1 (Eq. 12)
    I_Y  = int F_f,y dtau
    D_X  = -int F_f,x v_R,x dtau      Eq. (13)
    D_Y  = -int F_f,y v_R,y dtau
    S_TH = int (theta - theta0)^2 dtau (for Delta theta_rms, Fig. 10f)
    S_R  = int (r - 1)^2 dtau          (for Delta r_rms)

Only the motion and tau enter the step-size control (``ERROR_SLOTS``): the quadratures
never feed back into the motion, so their error follows the motion's; the energy
residual W - (D_x + D_y + U_el + K) of every result measures it (as CVODES does with
quadrature error control switched off).

Status codes are plain ints for numba; ``model.contact.results.Status`` gives each its
message and remedy.
"""
X, Y, VX, VY, THETA, W, I_Y, D_X, D_Y, S_TH, S_R, TAU = range(12)
N_STATE = 12
N_MOTION = 5
ERROR_SLOTS = (X, Y, VX, VY, THETA, TAU)
N_ERROR = len(ERROR_SLOTS)

# Status codes of one contact.
OK = 0                # the contact ended: the slab slid L0 over the support (Eq. 9)
STEP_BUDGET = 1       # max_steps ran out
TIME_BUDGET = 2       # tau_max reached
STEP_UNDERFLOW = 3    # the step size fell below the resolution of s
NONFINITE = 4         # the state became non-finite

# Stats slots.
ST_ACC, ST_REJ, ST_RHS, ST_JAC, ST_LU, ST_SWITCH, ST_ACC_EXPL, ST_ACC_IMPL = range(8)
N_STATS = 8
STAT_NAMES = ("n_steps", "n_rejected", "n_rhs", "n_jac", "n_lu", "n_switches",
              "n_steps_explicit", "n_steps_implicit")
