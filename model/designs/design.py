"""The orientation distribution that minimises friction (or steers it sideways).

``optimise`` searches a family of distributions (``model.designs.distributions``) for

* ``objective="min-FTx"``: the smallest F_T,x/(mu0 F_N) (Eq. 10) with |F_T,y|/(mu0 F_N)
  at most ``bound`` (no bound by default): the paper's closing design claim;
* ``objective="max-FTy"``: the largest |F_T,y|/(mu0 F_N) with F_T,x/(mu0 F_N) at most
  ``bound``: a directional interface.

Families: ``fixed`` (theta0), ``pair`` (+-theta0, F_T,y = 0 by mirror symmetry),
``vonmises`` (mean, kappa) and ``mixture`` (two orientations theta1, theta2 with weights
w, 1 - w: with beta fixed, the array is linear in the distribution, so a linear objective
under one linear bound is optimal at two point masses at most).

The polar curves of Fig. 11 have several minima, so the search is global: a scan first
(the fixed-orientation arrays on a theta0 grid in one batched call; for von Mises and
mixtures the grid's p-weighted sums stand in for the arrays), then the best few
candidates are refined with scipy.optimize on the full model (``distribution_array``:
self-consistent beta, adaptive quadrature). Results are cached; ``progress(done, total)``
is called after each model evaluation; setting the ``cancel`` event stops the search
with ``OptimisationCancelled``.
"""
from __future__ import annotations

import math
import threading
from collections import OrderedDict


from ..arrays.uniform import TOL
from ..contact.params import Params, check_array_params
from ..controls import OBJECTIVES
from ..validation import Interval, choice, instance, load_factor, number, whole
from .design_result import DesignResult, OptimisationCancelled
from .design_search import Search

__all__ = ["optimise", "DesignResult", "OptimisationCancelled", "FAMILIES", "OBJECTIVES"]

FAMILIES = ("fixed", "pair", "vonmises", "mixture")
_CACHE: OrderedDict = OrderedDict()
_CACHE_SIZE = 64
_LOCK = threading.Lock()


def optimise(params: Params, family: str = "pair", objective: str = "min-FTx",
             bound: float | None = None, beta="self", tol: float = 1e-3, n_scan: int = 90,
             candidates: int = 3, max_evaluations: int = 200, progress=None,
             cancel=None) -> DesignResult:
    """The distribution of ``family`` that best meets ``objective`` for the springs and
    load of ``params`` (theta0 ignored). See the module docstring.

    ``bound`` is the largest |F_T,y|/(mu0 F_N) (min-FTx) or F_T,x/(mu0 F_N) (max-FTy);
    ``tol`` the quadrature tolerance of each array; ``n_scan`` the theta0 grid on [0, pi];
    ``candidates`` the scan points refined; ``max_evaluations`` bounds model evaluations.
    """
    instance("params", params, Params)
    choice("family", family, FAMILIES)
    choice("objective", objective, OBJECTIVES)
    if family == "pair" and objective == "max-FTy":
        raise ValueError("family='pair' has F_T,y = 0 by mirror symmetry: choose fixed, "
                         "vonmises or mixture for objective='max-FTy'")
    if bound is not None:
        bound = number("bound", bound, Interval(0.0, math.inf),
                       "the bound (a finite number >= 0, or None)")
    n_scan = whole("n_scan", n_scan, 8)
    candidates = whole("candidates", candidates, 1)
    max_evaluations = whole("max_evaluations", max_evaluations, 1)
    beta = load_factor("beta", beta)
    check_array_params(params, "optimise", beta, uses_theta0=False)
    if not isinstance(beta, str):
        params = params.replace(beta=beta)
    tol = number("tol", tol, TOL, "quadrature tolerance tol")
    key = (params, family, objective, bound, beta if isinstance(beta, str) else "fixed",
           float(tol), int(n_scan), int(candidates), int(max_evaluations))
    with _LOCK:
        if key in _CACHE:
            _CACHE.move_to_end(key)
            return _CACHE[key]
    result = Search(params, family, objective, bound, beta, float(tol), int(n_scan),
                     int(candidates), int(max_evaluations), progress, cancel).run()
    with _LOCK:
        _CACHE[key] = result
        while len(_CACHE) > _CACHE_SIZE:
            _CACHE.popitem(last=False)
    return result


