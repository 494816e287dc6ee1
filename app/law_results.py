"""The Design tab's friction law fitted to a measured curve: ``ExplorerState.friction_curve``
(an uploaded file) -> ``LawResults.friction_fit`` (``model.fit_friction``: Eq. (4)'s
mu_s, A, B, V_s with 95 % intervals, the band and warnings) -> the views.

A fit that converged sets the design's four law inputs (``ExplorerState.set_friction_law``),
so the design's predictions, the URL, the CSV and "this view as code" carry the fitted law;
one that did not is shown with its message and changes nothing (as the command line writes
nothing then). The fit takes ~20 ms for the example's 40 points and is bounded by the
upload's size (``app.views.design_law.MAX_POINTS``), so it runs in the session itself.
"""
from __future__ import annotations

import math

import param

from model.lab.friction_fit import fit_friction
from model.lab.friction_law import COEFFICIENTS

#: Relative difference below which the law in use counts as the fit (the inputs keep 6
#: significant digits).
SAME_LAW = 1e-5


class LawResults(param.Parameterized):
    """The fit of the uploaded curve (see the module docstring); a base of
    ``app.results.SessionResults``."""

    friction_fit = param.Parameter(None, doc=(
        "Design tab: the fit of Eq. (4) to the uploaded curve (model.FrictionFit), or None"))

    def _init_law(self) -> None:
        self.state.param.watch(self._fit_curve, ["friction_curve"])
        self._fit_curve()

    def _fit_curve(self, *_events) -> None:
        curve = self.state.friction_curve
        fit = None if curve is None else fit_friction(curve)
        self.friction_fit = fit
        if fit is not None and fit.success:
            self.state.set_friction_law(fit.law)

    @property
    def fit_in_use(self) -> bool:
        """Whether the design's friction law is the fit's (to the inputs' 6 digits)."""
        fit = self.friction_fit
        if fit is None or not fit.success:
            return False
        try:
            law = self.state.friction_law
        except ValueError:
            return False
        if law.V_s is None:
            return False
        return all(math.isclose(getattr(law, name), fit.values[name], rel_tol=SAME_LAW)
                   for name in COEFFICIENTS)
