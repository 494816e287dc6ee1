"""This view as code: the Python (public ``model`` API) that reproduces the numbers the
dashboard shows for an ``ExplorerState``.

The snippet makes the calls the server's workers make (``app.worker``): the
fixed-orientation array at theta0 and the contact of its support, integrated with the
array's load factor (Support tab, Fig. 7), and the uniform-orientation array behind the
readouts (Figs. 5, 6, 8). Settings the page fixes (samples, step budget, quadrature
tolerance) are taken from ``app.worker``, so the snippet follows them.
"""
from __future__ import annotations

import math

from model import __version__
from model.cli.snippet import params_source, source

from . import worker

__all__ = ["view_as_python"]

#: Which uniform-array attribute each average of the page shows (``ExplorerState.average``).
AVERAGE_ATTRIBUTES = {"paper": ("FTx_over_mu0FN", "paper average over supports, Eq. 10"),
                      "duration": ("FTx_over_mu0FN_duration",
                                   "duration-weighted average over supports")}


def view_as_python(state) -> str:
    """The snippet for ``state`` (an ``app.state.ExplorerState``): runs on its own in a
    fresh interpreter and prints the readouts' numbers."""
    p = state.params
    beta = state.array_beta
    attribute, meaning = AVERAGE_ATTRIBUTES[state.average]
    # Degrees as on the slider; math.radians is how ExplorerState converts them.
    params = params_source(p, theta0=f"math.radians({source(float(state.theta0))})")
    # A uniform array covers every theta0 and takes its load factor as an argument.
    springs = params_source(p.replace(theta0=math.pi / 2, beta=1.0))
    return f'''\
# The dashboard's current view as Python (micropillar-friction {__version__})
import math

from model import Params, fixed_orientation, simulate_support, uniform_array

params = {params}

# Support tab: the fixed-orientation array at theta0 (Figs. 9-11) and the contact of its
# support, integrated with the array's load factor beta (Eqs. 5-9, Fig. 7)
fixed = fixed_orientation(params, beta={source(beta)}, rtol={source(state.rtol)})
support = simulate_support(params.replace(beta=fixed.beta), rtol={source(state.rtol)},
                           samples={worker.SAMPLES}, max_steps={worker.MAX_STEPS})
print(f"fixed array: F_T,x/(mu0 F_N) = {{fixed.FTx_over_mu0FN!r}}, "
      f"D_y/D_x = {{fixed.Dy_over_Dx!r}}, beta = {{fixed.beta!r}}")
print(f"support: t_out = {{support.t_out!r}}, W = {{support.W!r}}, "
      f"D_x = {{support.D_x!r}}, D_y = {{support.D_y!r}}")

# Readouts: the uniform-orientation array, theta0 uniform on [0, 2 pi) (Figs. 5, 6, 8)
springs = {springs}
uniform = uniform_array(springs, beta={source(beta)}, tol={source(worker.UNIFORM_TOL)})
print(f"uniform array: F_T,x/(mu0 F_N) = {{float(uniform.{attribute})!r}}"
      f" ({meaning})")
print(f"uniform array: D_y/D_x = {{float(uniform.Dy_over_Dx)!r}}, "
      f"N_c/N_c0 = {{float(uniform.Nc_over_Nc0)!r}}")
'''
