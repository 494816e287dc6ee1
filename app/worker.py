"""What the dashboard computes, as plain data: the functions its worker processes run.

* ``compute_support``: one support at theta0 -- the trajectory of one contact (Eqs. 5-6,
  9) with ``SAMPLES`` points for the scene and Fig. 7, and the fixed-orientation array at
  theta0 (Figs. 9-11). The trajectory is integrated with the array's load factor beta, so
  it is the motion behind the readouts.
* ``compute_polar``: fixed arrays over ``POLAR_THETA0`` (Fig. 11).
* ``compute_uniform``: the uniform array (Figs. 5, 6, 8) as one row of plain numbers.
* ``compute_load``: uniform arrays along ``LOAD_F_N`` for one pair of springs (Fig. 6).

Each function runs inside a budget derived from its inputs (``budget_steps``), so the
most expensive URL costs a bounded amount of one worker. The module imports the model
only (no Panel, no Bokeh): it is what the worker processes load, by its ordinary name
``app.worker``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from model import (REGIMES, FixedArrayResult, Params, SupportResult, fixed_orientation,
                   simulate_support)
from model.runs import shipped_map
from model.contact.regimes import map_axis
from model.runs.shipped_map import load_regime_map
from model.runs.sweeps import orientation_table, regime_map

SAMPLES = 400
POLAR_N = 72
#: Midpoints of POLAR_N equal cells of [0, pi]: off the on-axis starts 0 and pi.
POLAR_THETA0 = (np.arange(POLAR_N) + 0.5) * math.pi / POLAR_N
#: The loads of the Fig. 6 curves (log-spaced on [0.1, 10]).
LOAD_F_N = tuple(float(f) for f in np.logspace(-1, 1, 7))
UNIFORM_TOL = 1e-3
#: Step budget of one contact in the dashboard (the library's default is 1e6): the
#: hardest contact of the controls' ranges (theta0 on the axis, rtol 1e-8) needs ~3e4.
MAX_STEPS = 200_000


def warm() -> None:
    """Load the compiled kernel (the first call of a process)."""
    simulate_support(REGIMES["stiff"], samples=10)


def ping() -> int:
    """Nothing: a call that makes a worker process start (and warm up)."""
    return 0


@dataclass(frozen=True)
class SupportData:
    """One support at theta0 and its fixed-orientation array; ``error`` says what failed.

    ``result`` is None only when the model raised; a run that did not reach the end of
    its contact still has its (partial) ``result`` and an ``error``.
    """

    params: Params
    result: SupportResult | None
    fixed: FixedArrayResult | None
    error: str = ""
    seconds: float = 0.0

    @property
    def series(self):
        return None if self.result is None else self.result.series

    def energy_fractions(self) -> dict:
        """D_x, D_y, U_el, K as fractions of the slab work W (Eq. 12), and the residual."""
        r = self.result
        if r is None or not np.isfinite(r.W) or r.W == 0:
            return {k: math.nan for k in ("D_x", "D_y", "U_el", "K", "residual")}
        return {"D_x": r.D_x / r.W, "D_y": r.D_y / r.W, "U_el": r.U_el / r.W, "K": r.K / r.W,
                "residual": r.energy_residual / r.W}


def compute_support(params: Params, beta="self", rtol: float = 1e-6,
                    samples: int = SAMPLES) -> SupportData:
    """The fixed-orientation array at ``params.theta0`` (beta self-consistent or fixed) and
    the trajectory of its support, integrated with the array's beta. Never raises: a
    failure is described in ``error``."""
    start = time.perf_counter()
    try:
        fixed = fixed_orientation(params, beta=beta, rtol=rtol)
        used = params.replace(beta=fixed.beta)
        result = simulate_support(used, rtol=rtol, samples=samples, max_steps=MAX_STEPS)
    except Exception as exc:  # shown on the page; the controls stay usable
        return SupportData(params, None, None,
                           f"The model raised {type(exc).__name__}: {exc}",
                           time.perf_counter() - start)
    problems = []
    if not result.success:
        problems.append(f"The contact did not reach its end (status {result.status}): "
                        f"{result.message}.")
    elif not result.accurate:
        problems.append(f"Inaccurate run: {result.message}.")
    if not fixed.success:
        problems.append(f"Fixed array at theta0: {fixed.message}.")
    if result.series is None:
        problems.append("No time series could be sampled for this run.")
    return SupportData(used, result, fixed, " ".join(problems), time.perf_counter() - start)


def compute_polar(params: Params, beta="self", rtol: float = 1e-6):
    """``orientation_table`` (Fig. 11) of the support ``params`` (no theta0 of its own:
    ``ExplorerState.support``) over ``POLAR_THETA0``: a ``SweepResult``."""
    return orientation_table(params, theta0=POLAR_THETA0, beta=beta, rtol=rtol)


def sweep_row(sweep, i: int = 0) -> dict:
    """Row ``i`` of a ``SweepResult`` as plain Python numbers."""
    return {k: np.asarray(v)[i].item() for k, v in sweep.columns.items()}


def compute_uniform(k_r: float, k_theta: float, F_N: float, beta="self") -> dict:
    """The uniform array at (k_r, k_theta, F_N) as a row of plain numbers: F_T,x/(mu0 F_N)
    (paper, Eq. 10, and duration-weighted), D_y/D_x, N_c/N_c0, beta, the quadrature error,
    failed and pivot-passing members, success (through the model's on-disk sweep cache)."""
    return sweep_row(regime_map(k_r=[k_r], k_theta=[k_theta], F_N=F_N, beta=beta,
                                tol=UNIFORM_TOL))


def compute_load(k_r: float, k_theta: float, beta="self", loads=LOAD_F_N) -> dict:
    """Fig. 6 for one pair of springs: {F_N: uniform-array row} along ``loads``."""
    return {F_N: compute_uniform(k_r, k_theta, F_N, beta) for F_N in loads}


#: The paper's four regimes, drawn on Fig. 6 beside the current springs.
LOAD_REGIMES = tuple(REGIMES)


def compute_load_regimes(beta="self") -> dict:
    """The Fig. 6 curves of the paper's four regimes: {regime: {F_N: row}}."""
    return {name: compute_load(REGIMES[name].k_r, REGIMES[name].k_theta, beta)
            for name in LOAD_REGIMES}


#: Grid sizes of a regime map computed for the page: a first picture, then the finer one.
MAP_COARSE_N, MAP_FINE_N = 6, 12


def shipped_load(F_N: float) -> float | None:
    """The load of a shipped regime map equal to ``F_N`` (to 1e-9), or None."""
    loads = getattr(shipped_map, "SHIPPED_LOADS", (1.0,))
    return next((f for f in loads if math.isclose(f, F_N, rel_tol=1e-9)), None)


def compute_map(F_N: float, beta="self", n: int = MAP_FINE_N):
    """The regime map (Fig. 5) at ``F_N``: the shipped one when there is one (self-consistent
    beta), else uniform arrays on an ``n`` x ``n`` log grid (through the disk cache)."""
    from model.runs.shipped_map import RegimeMap
    load = shipped_load(F_N)
    if load is not None and beta == "self":
        try:
            return load_regime_map() if load == 1.0 else load_regime_map(F_N=load)
        except (OSError, ValueError):  # not shipped after all: compute it
            pass
    k = map_axis(n)  # the axes of Fig. 5
    sweep = regime_map(k_r=k, k_theta=k, F_N=F_N, beta=beta, tol=UNIFORM_TOL)
    cols = sweep.columns

    def square(name):
        return np.asarray(cols[name]).reshape(k.size, k.size)
    return RegimeMap(
        k_r=k, k_theta=k, FTx_over_mu0FN=square("FTx_over_mu0FN"),
        FTx_over_mu0FN_duration=square("FTx_over_mu0FN_duration"),
        Dy_over_Dx=square("Dy_over_Dx"), Nc_over_Nc0=square("Nc_over_Nc0"),
        beta=square("beta"), quadrature_error=square("quadrature_error_FTx"),
        success=square("success").astype(bool),
        metadata={"F_N": float(F_N), "beta": beta, "tol": UNIFORM_TOL,
                  "grid": {"n": int(n)}, "seconds": round(float(sweep.seconds), 2),
                  "max_quadrature_error": float(np.nanmax(square("quadrature_error_FTx"))),
                  "computed": "on this server"})


#: Frames of the animation of the array under the slab.
ARRAY_FRAMES = 600


def array_params(state) -> Params:
    """The ``Params`` of the Array tab's ``compute_array_motion`` for an ``ExplorerState``:
    the support alone for a uniform array (its orientations cover the circle), at the
    slider's theta0 otherwise; beta is solved inside."""
    return state.support if state.orientation == "uniform" else state.params


def compute_array_motion(params: Params, orientation: str = "uniform"):
    """The array under the slab (Figs. 2a, 4): ~100 supports' trajectories on
    ``ARRAY_FRAMES`` frames (``model.arrays.array_motion``), computed once per parameter set."""
    from model.arrays.array_motion import array_motion
    return array_motion(params, orientation=orientation, n_frames=ARRAY_FRAMES)


#: Animations for slides made in the page: frames and size (small enough for a worker).
EXPORT_FRAMES, EXPORT_SIZE = 90, (640, 360)


def compute_animation(what: str, fmt: str, params: Params, orientation: str = "uniform"):
    """An animation file for slides (``app.animation_export``): {bytes, mime, message}."""
    from .animation_export import animation_bytes
    data, mime, result = animation_bytes(what, fmt, params, frames=EXPORT_FRAMES,
                                         size=EXPORT_SIZE, orientation=orientation)
    if not result.success:
        raise RuntimeError(result.message)
    return {"bytes": data, "mime": mime, "message": result.message, "what": what,
            "format": fmt}


# ---------------------------------------------------------------------- Design tab
def design_of(inputs: dict):
    """The ``model.designs.units.PillarDesign`` of the Design tab's texts; ``ValueError`` naming
    the input that is not a usable quantity."""
    from model.designs.units import PillarDesign
    return PillarDesign(**inputs)


def design_model_params(design) -> Params:
    """The ``Params`` the model computes for ``design`` (its point, scaled into the model
    range when it lies beyond it: ``model.designs.design_point.model_params``); ``ValueError`` if it cannot."""
    from model.designs.design_point import model_params
    return model_params(design)


def compute_design_point(design) -> dict:
    """Where ``design`` sits: its dimensionless point (k~_r, k~_theta, F~_N, zeta, L0), the
    point the model computes, the status (``model.designs.design_point.POINT_STATUS``) and its message,
    the regime, the speeds and heights of each regime, and the speed line (plain data).
    A design the model cannot compute keeps its point, with ``error`` saying why."""
    from model.designs.design_point import model_point, regime_intervals, speed_line
    d = design.dimensionless()
    try:
        computed, status, message = model_point(design)
        error = ""
    except ValueError as exc:
        computed, status, message, error = None, "unusable", str(exc), str(exc)
    line = {k: np.asarray(v).tolist() for k, v in speed_line(design).items()}
    return {"point": d, "computed": computed, "status": status, "message": message,
            "error": error, "regime": design.regime(), "intervals": regime_intervals(design),
            "speed_line": line, "design": design.to_dict(), "V0_m_per_s": design.V0}


#: Quadrature tolerance of the Design tab's arrays, and the seconds the model may refine.
DESIGN_TOL, DESIGN_REFINE_S = 1e-3, 20.0


def compute_design_array(design, distribution: dict, psi_deg: float = 0.0,
                         beta="self") -> dict:
    """The array of ``design`` with orientations ``distribution`` (a ``to_dict`` form) seen
    at ``psi_deg``: ``model.designs.design_point.evaluate`` as plain data (dimensionless and physical)."""
    from model.designs.distributions import from_dict
    from model.designs.design_point import evaluate
    result = evaluate(design, from_dict(distribution), psi=math.radians(psi_deg), beta=beta,
                      tol=DESIGN_TOL, budget=DESIGN_REFINE_S)
    return result.to_dict()


#: Seconds of one speed of the Design tab's friction-velocity curve (``model.lab.speed_curve``):
#: its quadrature stops refining there and the point says the budget ran out.
SPEED_POINT_S = 10.0


def compute_speed_point(design, V0: float, distribution: dict, psi_deg: float = 0.0,
                        beta="self"):
    """``design`` at the sliding speed ``V0`` (m/s) with orientations ``distribution`` (a
    ``to_dict`` form): ``model.lab.speed_curve.speed_point`` (a ``SpeedPoint``)."""
    from model.designs.distributions import from_dict
    from model.lab.speed_curve import speed_point
    return speed_point(design, V0, from_dict(distribution), psi=math.radians(psi_deg),
                       beta=beta, tol=DESIGN_TOL, budget=SPEED_POINT_S)


#: The optimiser's model evaluations in the dashboard (its default is 200).
OPTIMUM_EVALUATIONS = 60


def compute_design_optimum(params: Params, family: str, beta="self", objective="min-FTx",
                           bound=None) -> dict:
    """``model.designs.design.optimise`` of ``objective`` under ``bound`` over ``family`` for the
    springs and load of ``params``: the optimum's ``to_dict`` (distribution, value, gain
    over uniform)."""
    from model.designs.design import optimise
    return optimise(params, family=family, objective=objective, bound=bound, beta=beta,
                    tol=DESIGN_TOL, max_evaluations=OPTIMUM_EVALUATIONS).to_dict()
