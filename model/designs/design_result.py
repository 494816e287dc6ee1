"""What ``model.designs.design.optimise`` returns: the best distribution of a family, its array,
the uniform array for comparison and the search's statistics."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..contact.params import Params

class OptimisationCancelled(Exception):
    """The ``cancel`` event was set; ``evaluations`` model evaluations had finished."""

    def __init__(self, evaluations: int):
        super().__init__(f"optimisation cancelled after {evaluations} model evaluations")
        self.evaluations = evaluations


@dataclass(frozen=True)
class DesignResult:
    """The best distribution found, its array, and the uniform array for comparison."""

    params: Params
    family: str
    objective: str
    bound: float | None
    distribution: object
    array: object  # DistributionArrayResult of the optimum
    FTx_over_mu0FN: float
    FTy_over_mu0FN: float
    error_estimate: float  # on the objective's value: quadrature + integration
    uniform_FTx_over_mu0FN: float
    gain: float  # 1 - F_T,x(optimum) / F_T,x(uniform)
    feasible: bool
    scan_best: float  # the objective's value at the best scan point (the surrogate)
    evaluations: int
    success: bool
    message: str
    seconds: float
    scan: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        d = {"family": self.family, "objective": self.objective,
             "FTx_over_mu0FN": self.FTx_over_mu0FN, "FTy_over_mu0FN": self.FTy_over_mu0FN}
        d.update(family_keys(self.family, self.distribution))
        d.update({
            "distribution": self.distribution.to_dict(),
            "uniform_FTx_over_mu0FN": self.uniform_FTx_over_mu0FN, "gain": self.gain,
            "max_abs_FTy" if self.objective == "min-FTx" else "max_FTx": self.bound,
            "error_estimate": self.error_estimate,
            "quadrature_error": dict(self.array.quadrature_error),
            "integration_error": self.array.integration_error,
            "Dy_over_Dx": self.array.Dy_over_Dx, "Nc_over_Nc0": self.array.Nc_over_Nc0,
            "beta": self.array.beta, "feasible": self.feasible, "scan_best": self.scan_best,
            "evaluations": self.evaluations, "success": self.success, "message": self.message,
            "seconds": self.seconds, "params": self.params.as_dict()})
        return d


def family_keys(family, dist) -> dict:
    d = dist.to_dict()
    if family in ("fixed", "pair"):
        return {"theta0_deg": d["theta0_deg"]}
    if family == "vonmises":
        return {"mean_deg": d["mean_deg"], "kappa": d["kappa"]}
    (a, b), (w, _) = dist.components, dist.weights
    return {"theta1_deg": math.degrees(a.theta0), "theta2_deg": math.degrees(b.theta0),
            "weight1": w}
