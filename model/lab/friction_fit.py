"""Fit the friction law of Eq. (4) to a measured friction curve (``model.lab.friction_curve``).

    mu(v) = mu_s sin(A atan(x - B (x - atan x))),   x = v / V_s

A bounded nonlinear least-squares fit (``scipy.optimize.least_squares``, trust-region
reflective, analytic Jacobian) of mu_s, A, B and ln V_s, started from a few guesses read
off the curve (its peak, its plateau). The bounds of mu_s, A and B are the model's
(``model.contact.params.RANGES``); V_s lies within a factor ``V_S_SPAN`` of the measured speeds.

Uncertainty: the covariance of the linearised fit, (J^T J)^-1 scaled by the residual
variance (or, with ``mu_err``, taking the errors as the points' standard errors), gives
95 % intervals (Student's t with n - 4 degrees of freedom; normal with ``mu_err``) and
the correlations; V_s's interval is that of ln V_s, so it stays positive. A coefficient
whose interval is wider than its value (V_s: spanning more than a factor 100), that sits
at a bound, or that lies along a direction the data do not constrain is named in a
plain warning; data consistent with a constant mu (the plateau far above V_s) get the
warning that they fix mu_s sin(A pi/2) alone.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from ..contact.friction import law
from ..contact.params import DEFAULTS, RANGES
from .friction_curve import N_COEFFICIENTS, FrictionCurve
from .friction_law import COEFFICIENTS, FrictionLaw

__all__ = ["FrictionFit", "fit_friction", "V_S_SPAN", "CONFIDENCE"]

#: V_s is sought within [min v / V_S_SPAN, max v * V_S_SPAN] (positive speeds).
V_S_SPAN = 1e3
#: Confidence level of the reported intervals.
CONFIDENCE = 0.95
#: Where the paper's law peaks, in v/V_s (mu'(x) = 0 at B = -20, A = 1.44): the first
#: guess puts V_s at the measured peak's speed over this.
_PEAK_X = 0.55


def _bounds(v_pos: np.ndarray):
    """Lower and upper bounds of (mu_s, A, B, ln V_s); open ends moved just inside."""
    lo, hi = [], []
    for name in ("mu_s", "A", "B"):
        interval = RANGES[name][0]
        lo.append(np.nextafter(interval.lo, math.inf) if interval.lo_open else interval.lo)
        hi.append(np.nextafter(interval.hi, -math.inf) if interval.hi_open else interval.hi)
    lo.append(math.log(v_pos.min() / V_S_SPAN))
    hi.append(math.log(v_pos.max() * V_S_SPAN))
    return np.array(lo), np.array(hi)


def _model(p, v):
    return law(v * math.exp(-p[3]), p[0], p[1], p[2])


def _jacobian(p, v):
    """d mu / d (mu_s, A, B, ln V_s) of Eq. (4)."""
    mu_s, A, B = p[:3]
    x = v * math.exp(-p[3])
    t = np.arctan(x)
    w = x - B * (x - t)
    g = np.arctan(w)
    c = mu_s * np.cos(A * g)
    dg = A * c / (1 + w * w)  # d mu / d w
    return np.column_stack([np.sin(A * g), c * g, -dg * (x - t),
                            -dg * (1 - B * x * x / (1 + x * x)) * x])


def _starts(v, mu, v_pos, lo, hi):
    """First guesses of (mu_s, A, B, ln V_s) from the curve's peak and plateau."""
    peak = int(np.argmax(mu))
    mu_max = max(float(mu[peak]), 1e-12)
    fast = v >= np.quantile(v, 0.9)
    ratio = float(np.clip(np.mean(mu[fast]) / mu_max, 0.0, 1.0))
    # sin(A pi/2) = plateau / peak: A > 1 when the curve falls after its peak.
    A0 = 2 - 2 / math.pi * math.asin(ratio) if ratio < 0.98 else 1.0
    v_peak = float(v[peak]) if v[peak] > 0 else float(np.median(v_pos))
    middle = math.exp(np.mean(np.log(v_pos)))
    guesses = []
    for V_s in {v_peak / _PEAK_X, v_peak, middle, float(v_pos.min())}:
        for B in (DEFAULTS["B"], -1.0, 0.0):
            p = np.array([mu_max, A0, B, math.log(V_s)])
            guesses.append(np.clip(p, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo)))
    return guesses


@dataclass(frozen=True)
class FrictionFit:
    """A fit of Eq. (4) to a measured curve: the coefficients (V_s in m/s), their 95 %
    intervals, correlations (of mu_s, A, B, ln V_s), the residual and the warnings."""

    success: bool
    message: str
    values: dict
    ci95: dict
    correlation: np.ndarray
    rms_residual: float
    n_points: int
    weighted: bool
    chi2_reduced: float | None
    warnings: tuple = field(default_factory=tuple)
    nfev: int = 0
    #: Covariance of (mu_s, A, B, ln V_s) behind the intervals, and the quantile that
    #: makes their half-widths (None: not kept).
    covariance: np.ndarray | None = field(default=None, repr=False)
    quantile: float = math.nan

    @property
    def law(self) -> FrictionLaw:
        """The fitted law (``FrictionLaw``), to carry into a design."""
        return FrictionLaw(**self.values)

    def predict(self, v):
        """The fitted mu at speeds ``v`` (m/s)."""
        return self.law.mu(v)

    def band(self, v):
        """The 95 % confidence band of the fitted curve at speeds ``v`` (m/s): ``(lo, hi)``,
        mu(v) -+ q sqrt(g^T C g), with g = d mu / d (mu_s, A, B, ln V_s) at ``v`` and C the
        fit's covariance (the delta method, as the coefficients' intervals); infinite
        where a coefficient is not determined, NaN without a covariance."""
        v = np.asarray(v, dtype=float)
        mu = self.predict(v)
        if self.covariance is None:
            return np.full_like(mu, math.nan), np.full_like(mu, math.nan)
        p = [self.values["mu_s"], self.values["A"], self.values["B"],
             math.log(self.values["V_s"])]
        g = _jacobian(p, v.ravel())
        with np.errstate(invalid="ignore"):
            var = np.einsum("ij,jk,ik->i", g, self.covariance, g)
        half = self.quantile * np.sqrt(np.where(np.isnan(var), math.inf, var))
        half = half.reshape(v.shape)
        return mu - half, mu + half

    def to_dict(self) -> dict:
        """``{"mu_s": {"value", "ci95"}, "A", "B", "V_s" (m/s), "rms_residual",
        "n_points", "warnings", "correlation", "success", "message"}``."""
        out = {name: {"value": self.values[name], "ci95": list(self.ci95[name])}
               for name in COEFFICIENTS}
        out.update(rms_residual=self.rms_residual, n_points=self.n_points,
                   warnings=list(self.warnings),
                   correlation={"order": ["mu_s", "A", "B", "ln V_s"],
                                "matrix": self.correlation.tolist()},
                   success=self.success, message=self.message)
        return out


def _covariance(jac: np.ndarray):
    """(J^T J)^-1 through the SVD; directions the data do not constrain (singular values
    below the rounding level) give infinite variance to the coefficients along them."""
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    threshold = np.finfo(float).eps * max(jac.shape) * s[0]
    kept = s > threshold
    cov = (vt[kept].T / s[kept] ** 2) @ vt[kept]
    loose = np.any(np.abs(vt[~kept]) > 1e-3, axis=0) if np.any(~kept) else np.zeros(len(s), bool)
    cov[loose, :] = math.inf
    cov[:, loose] = math.inf
    return cov


def fit_friction(curve: FrictionCurve) -> FrictionFit:
    """Fit mu_s, A, B and V_s of Eq. (4) to ``curve`` (speeds in m/s); see the module doc.

    Parameters
    ----------
    curve : FrictionCurve
        Measured mu against sliding speed (``read_curve``), optionally with ``mu_err``.

    Returns
    -------
    FrictionFit
        The coefficients with 95 % intervals, correlations, residual and warnings.

    Examples
    --------
    >>> import numpy as np
    >>> from model import FrictionCurve, FrictionLaw, fit_friction
    >>> v = np.geomspace(1e-5, 1e-1, 60)                      # m/s
    >>> truth = FrictionLaw(mu_s=1.3, A=1.44, B=-20, V_s=1e-3)
    >>> fit = fit_friction(FrictionCurve(v, truth.mu(v)))
    >>> fit.success, round(fit.values["mu_s"], 3), round(fit.values["V_s"] * 1e3, 3)
    (True, 1.3, 1.0)
    """
    v, mu = curve.v, curve.mu
    sigma = np.ones_like(mu) if curve.mu_err is None else curve.mu_err
    v_pos = v[v > 0]
    lo, hi = _bounds(v_pos)

    def residual(p):
        return (_model(p, v) - mu) / sigma

    def jacobian(p):
        return _jacobian(p, v) / sigma[:, None]

    starts = sorted(_starts(v, mu, v_pos, lo, hi), key=lambda p: float(np.sum(residual(p) ** 2)))
    best, nfev = None, 0
    for p0 in starts[:3]:
        res = optimize.least_squares(residual, p0, jac=jacobian, bounds=(lo, hi),
                                     x_scale="jac", method="trf")
        nfev += res.nfev
        if best is None or res.cost < best.cost:
            best = res
    return _result(best, curve, lo, hi, nfev)


def _result(res, curve: FrictionCurve, lo, hi, nfev: int) -> FrictionFit:
    from scipy import stats  # here: importing the package stays quick

    n, p = curve.n_points, res.x
    dof = n - N_COEFFICIENTS
    weighted = curve.mu_err is not None
    chi2 = 2 * res.cost
    cov = _covariance(res.jac)
    warnings = []
    if weighted:
        q = stats.norm.ppf(0.5 + CONFIDENCE / 2)
        chi2_reduced = chi2 / dof if dof > 0 else None
        if dof > 0 and stats.chi2.sf(chi2, dof) < 1e-3:
            warnings.append(f"the scatter about the fit exceeds mu_err (reduced chi-square "
                            f"{chi2_reduced:.3g}): the intervals, taken from mu_err, are too "
                            f"narrow; check mu_err")
    elif dof > 0:
        q = stats.t.ppf(0.5 + CONFIDENCE / 2, dof)
        cov = cov * (chi2 / dof)
        chi2_reduced = None
    else:
        q, chi2_reduced = math.inf, None
        warnings.append(f"{n} points for {N_COEFFICIENTS} coefficients leave nothing to "
                        f"estimate the scatter: no intervals (add points or a mu_err column)")
    with np.errstate(invalid="ignore"):
        se = np.sqrt(np.diag(cov))
        correlation = cov / np.outer(se, se)
    correlation[~np.isfinite(correlation)] = math.nan
    values = {"mu_s": float(p[0]), "A": float(p[1]), "B": float(p[2]), "V_s": math.exp(p[3])}
    half = q * se
    ci95 = {name: (float(p[k] - half[k]), float(p[k] + half[k]))
            for k, name in enumerate(("mu_s", "A", "B"))}
    ci95["V_s"] = (math.exp(p[3] - half[3]), math.exp(p[3] + half[3])) if math.isfinite(half[3]) \
        else (0.0, math.inf)
    warnings += _undetermined(values, ci95, half, res.active_mask, curve, chi2, lo, hi)
    rms = float(np.sqrt(np.mean((_model(p, curve.v) - curve.mu) ** 2)))
    success = bool(res.success)
    message = "converged: " + res.message if success else "did not converge: " + res.message
    return FrictionFit(success=success, message=message, values=values, ci95=ci95,
                       correlation=correlation, rms_residual=rms, n_points=n,
                       weighted=weighted, chi2_reduced=chi2_reduced,
                       warnings=tuple(warnings), nfev=nfev, covariance=cov, quantile=float(q))


def _undetermined(values, ci95, half, active, curve, rss, lo, hi) -> list:
    """Plain warnings for coefficients the data do not determine (module doc)."""
    out = []
    if _flat(curve, rss):
        sigma = np.ones_like(curve.mu) if curve.mu_err is None else curve.mu_err
        level = float(np.average(curve.mu, weights=sigma ** -2.0))
        out.append(f"the data are consistent with a constant mu = {level:.4g}: like data only "
                   f"on the plateau far above V_s, they fix mu_s sin(A pi/2) = "
                   f"{values['mu_s'] * math.sin(values['A'] * math.pi / 2):.4g}, not mu_s and "
                   f"A apart, nor B and V_s; measure down to speeds below V_s")
    units = {"V_s": " m/s"}
    for k, name in enumerate(COEFFICIENTS):
        lo_ci, hi_ci = ci95[name]
        shown = f"[{lo_ci:.3g}, {hi_ci:.3g}]{units.get(name, '')}"
        if active[k] != 0:
            edge = lo[k] if active[k] < 0 else hi[k]
            edge = math.exp(edge) if name == "V_s" else edge
            out.append(f"{name} = {values[name]:.4g} sits at its bound {edge:.3g}: the data "
                       f"push it there, so its interval {shown} does not hold")
        elif not math.isfinite(half[k]):
            out.append(f"{name} is not determined by the data (no finite interval)")
        elif name == "V_s" and hi_ci / lo_ci > 100:
            out.append(f"V_s is not determined by the data: its 95 % interval {shown} spans "
                       f"more than a factor 100")
        elif name != "V_s" and half[k] > max(abs(values[name]), 1.0 if name == "B" else 0.0):
            out.append(f"{name} is not determined by the data: its 95 % interval {shown} is "
                       f"wider than its value")
    return out


def _flat(curve: FrictionCurve, rss: float) -> bool:
    """True when a constant mu is not rejected against the fit of Eq. (4) (residual sum
    of squares ``rss``) at the 5 % level: an F test, or with mu_err the chi-square
    difference."""
    from scipy import stats

    dof = curve.n_points - N_COEFFICIENTS
    if dof <= 0:
        return False
    sigma = np.ones_like(curve.mu) if curve.mu_err is None else curve.mu_err
    level = np.average(curve.mu, weights=sigma ** -2.0)
    extra = max(float(np.sum(((curve.mu - level) / sigma) ** 2)) - rss, 0.0)
    if curve.mu_err is not None:
        return bool(stats.chi2.sf(extra, N_COEFFICIENTS - 1) > 0.05)
    if rss <= 0:
        return extra <= 0
    f = extra / (N_COEFFICIENTS - 1) / (rss / dof)
    return bool(stats.f.sf(f, N_COEFFICIENTS - 1, dof) > 0.05)
