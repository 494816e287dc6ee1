"""The structured surface's predicted friction against sliding speed
(``model.lab.speed_curve``) compared with a measured one (a CSV file read by
``model.lab.friction_curve.read_curve``, as the fit reads the flat curve).

At each measured speed v the prediction is taken from the predicted curve, linearly in
log V0 between the two computed speeds around v (exact at a computed speed: compute the
curve at the measured speeds themselves, ``friction_velocity(design, measured.v)``, as
``micropillar pillar --compare`` does, and nothing is interpolated). Log V0 because the
curves are sampled evenly in log V0 (``speed_range``) and Eq. (4) varies with log v; an
interpolated point's model error is the larger of its two neighbours' (the interpolation's
own error is not estimated). A measured speed outside the computed ones is refused: no
extrapolation.

The difference is measured - predicted; its RMS is over the speeds compared. A speed
*disagrees* when ``abs(difference)`` exceeds the combined error: the model's error there (the
quadrature error of F_T,x/F_N, ``SpeedPoint.quadrature_error``) plus ``n_sigma`` times
the measurement's standard error (``mu_err`` of the file, else ``DEFAULT_MU_ERR``).
``n_sigma = 2`` (about 95 % for Gaussian errors) keeps a measurement that agrees with the
model from naming a third of its speeds, as one standard error would.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .friction_curve import CurveFileError, FrictionCurve, curve_from_text

__all__ = ["FrictionComparison", "compare_friction", "read_measured", "measured_from_text",
           "DEFAULT_MU_ERR", "N_SIGMA"]

#: The measurement's standard error of mu assumed when the file has no mu_err column
#: (an assumption, not a property of any instrument: give mu_err when it is known).
DEFAULT_MU_ERR = 0.01
#: Standard errors of the measurement within which the model and the measurement agree.
N_SIGMA = 2.0
#: Relative distance in log V0 within which a measured speed is a computed one.
_SAME_SPEED = 1e-9


@dataclass(frozen=True)
class FrictionComparison:
    """The predicted and measured friction of the structured surface at the measured
    speeds ``v`` (m/s): ``difference`` = measured - predicted, its ``rms``, the combined
    ``tolerance`` and the ``disagree`` speeds (m/s) where ``abs(difference)`` exceeds it (module
    doc). A speed the model could not compute has NaN there and is not compared."""

    success: bool
    message: str
    v: np.ndarray
    measured: np.ndarray
    predicted: np.ndarray
    difference: np.ndarray
    model_error: np.ndarray
    measured_error: np.ndarray
    tolerance: np.ndarray
    rms: float
    disagree: tuple
    n_sigma: float
    mu_err_given: bool
    source: str = ""

    @property
    def n_compared(self) -> int:
        return int(np.sum(np.isfinite(self.difference)))

    def to_dict(self) -> dict:
        """JSON-ready: the columns (speeds in m/s), the RMS, the disagreeing speeds."""
        return {"success": self.success, "message": self.message,
                "v_m_per_s": self.v.tolist(), "measured": self.measured.tolist(),
                "predicted": self.predicted.tolist(), "difference": self.difference.tolist(),
                "model_error": self.model_error.tolist(),
                "measured_error": self.measured_error.tolist(),
                "tolerance": self.tolerance.tolist(), "rms": self.rms,
                "disagree_m_per_s": list(self.disagree), "n_compared": self.n_compared,
                "n_sigma": self.n_sigma, "mu_err_given": self.mu_err_given,
                "source": self.source}


def _at(x, xp, fp, ep):
    """Value and error of the curve (xp, fp, ep) at x, linear in x (here log V0)."""
    j = int(np.searchsorted(xp, x))
    for k in (j - 1, j):
        if 0 <= k < len(xp) and abs(x - xp[k]) <= _SAME_SPEED:
            return fp[k], ep[k]
    lo, hi = j - 1, j
    w = (x - xp[lo]) / (xp[hi] - xp[lo])
    return (1 - w) * fp[lo] + w * fp[hi], max(ep[lo], ep[hi])


def compare_friction(prediction, measured: FrictionCurve, mu_err: float | None = None,
                     n_sigma: float = N_SIGMA) -> FrictionComparison:
    """Compare a predicted friction-velocity curve with a measured one (module doc).

    Parameters
    ----------
    prediction : SpeedCurve
        The structured surface's F_T,x/F_N against V0 (``friction_velocity``), computed at
        speeds that cover the measured ones.
    measured : FrictionCurve
        The structured sample's measured mu against v (m/s), e.g. from ``read_curve``.
    mu_err : float, optional
        The measurement's standard error of mu where ``measured`` has no ``mu_err``
        (default ``DEFAULT_MU_ERR`` = 0.01).
    n_sigma : float, default 2
        Standard errors of the measurement added to the model's error.

    Returns
    -------
    FrictionComparison
        Differences (measured - predicted), their RMS, and the disagreeing speeds (m/s).

    Examples
    --------
    >>> import numpy as np
    >>> from model import FrictionCurve, compare_friction
    >>> from model.lab.speed_curve import SpeedCurve, SpeedPoint
    >>> pts = tuple(SpeedPoint(v, 1.0, 0.9, 0.001, 1e-6, True, "in_map", "ok")
    ...             for v in (0.1, 1.0, 10.0))                       # V0 in m/s
    >>> predicted = SpeedCurve(law={}, points=pts, seconds=0.0)
    >>> measured = FrictionCurve([0.1, 0.3, 1.0, 10.0], [0.9, 0.91, 0.95, 0.9], [0.005] * 4)
    >>> c = compare_friction(predicted, measured)
    >>> c.difference.round(3).tolist(), round(c.rms, 4), c.disagree
    ([0.0, 0.01, 0.05, 0.0], 0.0255, (1.0,))
    """
    if not (isinstance(n_sigma, (int, float)) and math.isfinite(n_sigma) and n_sigma >= 0):
        raise ValueError(f"n_sigma={n_sigma!r} must be a finite number >= 0")
    given = measured.mu_err is not None
    if not given:
        mu_err = DEFAULT_MU_ERR if mu_err is None else mu_err
        if not (isinstance(mu_err, (int, float)) and math.isfinite(mu_err) and mu_err >= 0):
            raise ValueError(f"mu_err={mu_err!r} must be a finite standard error >= 0")
    sigma = measured.mu_err if given else np.full(measured.n_points, float(mu_err))
    V0 = prediction.column("V0")
    if V0.size == 0:
        raise ValueError("the prediction has no speeds; compute it with friction_velocity")
    xp, v = np.log(V0), measured.v
    lo, hi = xp[0] - _SAME_SPEED, xp[-1] + _SAME_SPEED
    for i, speed in enumerate(v):
        if not (speed > 0 and lo <= math.log(speed) <= hi):
            raise ValueError(
                f"measured point {i}: v = {speed:.4g} m/s lies outside the predicted speeds "
                f"{V0[0]:.4g}..{V0[-1]:.4g} m/s; predict over speeds that cover the "
                f"measurement (nothing is extrapolated)")
    fp, ep = prediction.column("mu_apparent"), prediction.column("quadrature_error")
    pairs = [_at(math.log(speed), xp, fp, ep) for speed in v]
    predicted = np.array([p[0] for p in pairs], dtype=float)
    model_error = np.array([p[1] for p in pairs], dtype=float)
    difference = measured.mu - predicted
    tolerance = model_error + n_sigma * sigma
    ok = np.isfinite(difference)
    rms = float(np.sqrt(np.mean(difference[ok] ** 2))) if ok.any() else math.nan
    disagree = tuple(float(s) for s in v[ok & (np.abs(np.where(ok, difference, 0.0))
                                                > tolerance)])
    missing = int(np.sum(~ok))
    where = "mu_err" if given else f"an assumed mu_err of {mu_err:g}"
    message = (f"{int(ok.sum())} speeds compared, rms difference {rms:.3g}; {len(disagree)} "
               f"disagree beyond the model's error + {n_sigma:g} x {where}")
    if missing:
        message += (f"; {missing} measured speeds not compared: the model could not compute "
                    f"the prediction there (see the prediction's points)")
    return FrictionComparison(
        success=missing == 0, message=message, v=v.copy(), measured=measured.mu.copy(),
        predicted=predicted, difference=difference, model_error=model_error,
        measured_error=np.asarray(sigma, dtype=float), tolerance=tolerance, rms=rms,
        disagree=disagree, n_sigma=float(n_sigma), mu_err_given=given,
        source=measured.source)


def read_measured(path, v_unit: str | None = None) -> FrictionCurve:
    """The structured sample's measured curve in ``path`` (``read_curve``'s form and
    errors), refusing a zero speed (the model needs sliding) with the line that holds it:
    ``CurveFileError``."""
    from ..files import read_user_text

    try:
        text = read_user_text(path, "CSV")
    except ValueError as error:
        raise CurveFileError(str(error)) from None
    return measured_from_text(text, Path(path).name, v_unit, source=str(path))


def measured_from_text(text: str, name: str, v_unit: str | None = None,
                       source: str = "") -> FrictionCurve:
    """The structured sample's measured curve in the CSV ``text`` of the file ``name`` (as
    ``read_measured`` reads a file, e.g. an upload's content); ``CurveFileError``."""
    from ..designs.histogram_csv import data_rows

    curve = curve_from_text(text, name, v_unit, source=source)
    zero = np.flatnonzero(curve.v <= 0)
    if zero.size:
        line = data_rows(text)[1 + int(zero[0])][0]
        raise CurveFileError(f"{name} line {line}: v = 0; the structured surface "
                             f"is predicted at sliding speeds above zero: drop this row")
    return curve
