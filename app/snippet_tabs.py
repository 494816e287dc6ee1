"""This view as code, for the tabs that draw more than one support: the Orientation tab's
sweep (Fig. 11), the Regime map (Fig. 5), the Load tab (Fig. 6) and the Array tab (the
slab over ~100 supports, Figs. 2a, 4). Each block makes the calls the server's workers make
for that tab (``app.worker``), with the page's settings taken from there, and prints or
holds what the tab draws. A variable near the top (``n``) sets the size of the grid or
sweep, so a smaller one can be tried first; with the page's value the numbers are the
tab's own.
"""
from __future__ import annotations


from model.cli.snippet import params_source, source
from model.contact.regimes import EXPLORED_MAP

from . import worker
from .figures.arrays import AVERAGE_COLUMNS, map_column, map_title
from .worker import array_params
from .texts import AVERAGE_NAMES, FELT_AVERAGE

#: tab -> (extra imports, the block's writer); other tabs show the support's snippet.
IMPORTS = {
    "polar": "import numpy as np\nfrom model import Params, orientation_table",
    "map": ("import numpy as np\nfrom model import regime_map\n"
            "from model.runs.shipped_map import load_regime_map"),
    "load": "import numpy as np\nfrom model import REGIMES, Params, uniform_array",
    "array": "from model import Params\nfrom model.arrays.array_motion import array_motion",
}


def _springs(state) -> str:
    return params_source(state.support)


def polar_block(state) -> str:
    """Fig. 11: fixed arrays at ``n`` orientations, the midpoints of n equal cells of
    [0, pi] (``worker.POLAR_THETA0``; the mirror image gives (pi, 2 pi))."""
    return f'''\
# Orientation tab (Fig. 11): a fixed-orientation array for each theta0, the midpoints of
# n equal cells of [0, pi] (the mirror image y -> -y gives the other half)
n = {worker.POLAR_N}
springs = {_springs(state)}
polar = orientation_table(springs, n=n, beta={source(state.array_beta)}, rtol={source(state.rtol)})
for name in ("FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0"):
    values = np.asarray(polar.columns[name], float)
    print(f"{{name}}: {{values.min():.6g}} ... {{values.max():.6g}} over {{len(values)}} theta0")
# polar.to_csv("polar_sweep.csv")  # the table, as the page's "Polar sweep CSV" gives it
'''


def map_block(state) -> str:
    """Fig. 5: the uniform arrays over (k_r, k_theta) at the current load: the shipped map
    where the page takes it, else an ``n`` x ``n`` log grid as ``worker.compute_map``."""
    F_N, beta = float(state.F_N), state.array_beta
    column = map_column(state.map_quantity, state.average)
    what = " ".join(map_title(state.map_quantity, None, state.average).split())  # one line
    shipped = worker.shipped_load(F_N) if beta == "self" else None
    if shipped is not None:
        load = "" if shipped == 1.0 else f"F_N={source(shipped)}"
        made = f'''\
# The map shipped with the package for this load (uniform arrays on a log grid)
the_map = load_regime_map({load})
k_r, k_theta = the_map.k_r, the_map.k_theta
shown = np.asarray(the_map.{column}, float)  # [k_r, k_theta]'''
    else:
        made = f'''\
# Uniform arrays on an n x n log grid of {list(EXPLORED_MAP)} (the page draws a
# {worker.MAP_COARSE_N} x {worker.MAP_COARSE_N} grid first, then this one)
n = {worker.MAP_FINE_N}
k_r = k_theta = np.geomspace({EXPLORED_MAP[0]!r}, {EXPLORED_MAP[1]!r}, n)
sweep = regime_map(k_r=k_r, k_theta=k_theta, F_N={source(F_N)}, beta={source(beta)},
                   tol={source(worker.UNIFORM_TOL)})
shown = np.asarray(sweep.columns["{column}"], float).reshape(n, n)  # [k_r, k_theta]
# sweep.to_csv("regime_map.csv")  # the table, as the tab's "Map CSV" gives it'''
    return f'''\
# Regime map tab (Fig. 5) at F_N = {F_N:g}: {what}
{made}
i, j = np.unravel_index(np.nanargmin(shown), shown.shape)
print(f"{{shown.shape[0]}} x {{shown.shape[1]}} cells: {column} from {{np.nanmin(shown):.6g}} "
      f"(k_r = {{k_r[i]:.3g}}, k_theta = {{k_theta[j]:.3g}}) to {{np.nanmax(shown):.6g}}")
'''


def load_block(state) -> str:
    """Fig. 6: uniform arrays at ``n`` loads log-spaced on [0.1, 10] (``worker.LOAD_F_N``)
    for the current springs and the paper's four regimes (``worker.compute_load``)."""
    column = AVERAGE_COLUMNS[state.average]
    return f'''\
# Load tab (Fig. 6): uniform arrays (theta0 uniform on [0, 2 pi)) against the normal load,
# for the current springs (black) and the paper's four regimes (coloured)
n = {len(worker.LOAD_F_N)}
loads = np.logspace(-1, 1, n)
curves = {{"current": ({source(float(state.k_r))}, {source(float(state.k_theta))})}}
for name in {source(worker.LOAD_REGIMES)}:
    curves[name] = (REGIMES[name].k_r, REGIMES[name].k_theta)
shown = {{}}  # curve -> {{F_N: F_T,x/(mu0 F_N)}}
for curve, (k_r, k_theta) in curves.items():
    shown[curve] = {{}}
    for F_N in loads:
        row = uniform_array(Params(k_r=k_r, k_theta=k_theta, F_N=float(F_N)),
                            beta={source(state.array_beta)}, tol={source(worker.UNIFORM_TOL)})
        shown[curve][float(F_N)] = float(row.{column})  # {AVERAGE_NAMES[state.average]}
    print(curve, ", ".join(f"F_N = {{f:.3g}}: {{v:.6g}}" for f, v in shown[curve].items()))
'''


def array_block(state) -> str:
    """The Array tab: ``array_motion`` as ``worker.compute_array_motion`` calls it."""
    p = array_params(state)
    theta0 = (None if state.orientation == "uniform"
              else f"math.radians({source(float(state.theta0))})")
    felt = AVERAGE_COLUMNS[FELT_AVERAGE]
    return f'''\
# Array tab (Figs. 2a, 4): the slab sliding over ~100 supports, frame by frame; theta0
# {"uniform over the supports" if theta0 is None else "the same for every support"}
n_frames = {worker.ARRAY_FRAMES}
params = {params_source(p, theta0=theta0)}
motion = array_motion(params, orientation={source(state.orientation)}, n_frames=n_frames)
print(f"{{motion.n_supports}} supports on a {{motion.n_rows}} x {{motion.n_cols}} grid")
print(f"array model: N_c/N_c0 = {{motion.model['Nc_over_Nc0']!r}}, the slab feels "
      f"F_T,x/(mu0 F_N) = {{motion.model['{felt}']!r}} ({AVERAGE_NAMES[FELT_AVERAGE].split(':')[0]})")
'''


BLOCKS = {"polar": polar_block, "map": map_block, "load": load_block, "array": array_block}
