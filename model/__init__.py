"""Dynamically induced friction reduction in micro-structured interfaces.

A model of elastic micropillar supports dragged by a sliding slab (Sci. Rep. 11,
8093, 2021): one support (Eqs. 1-6), its friction and energy per contact
(Eqs. 8-13), fixed-orientation arrays (Figs. 9-11) and uniform-orientation arrays with
the self-consistent contact count (Figs. 5, 6, 8). Conventions: docs/model.md.

    >>> from model import Params, REGIMES, simulate_support
    >>> res = simulate_support(REGIMES["pendulum"])
    >>> res.F_mean        # time-averaged friction / f_N (Eq. 8)
"""
from ._version import __version__
from .arrays.fixed import FixedArrayResult, OrientationSweep, fixed_orientation, orientation_sweep
from .arrays.uniform import UniformArrayResult, uniform_array
from .contact.friction import mu, mu0, mu_over_s
from .contact.options import METHODS, SolverOptions
from .contact.params import DEFAULTS, REGIMES, Params
from .contact.results import IntegrationError, SupportResult, TimeSeries
from .contact.support import simulate_support
from .lab.friction_compare import FrictionComparison, compare_friction
from .lab.friction_curve import FrictionCurve, read_curve
from .lab.friction_fit import FrictionFit, fit_friction
from .lab.friction_law import FrictionLaw
from .runs.sweeps import SweepCancelled, SweepResult, load_sweep, orientation_table, regime_map, stiffness_sweep

__all__ = ["Params", "REGIMES", "DEFAULTS", "SolverOptions", "METHODS", "simulate_support",
           "SupportResult", "TimeSeries", "IntegrationError", "mu", "mu0", "mu_over_s",
           "FrictionLaw", "FrictionCurve", "read_curve", "FrictionFit", "fit_friction",
           "compare_friction", "FrictionComparison",
           "fixed_orientation", "orientation_sweep", "uniform_array", "FixedArrayResult",
           "OrientationSweep", "UniformArrayResult", "regime_map", "load_sweep",
           "stiffness_sweep", "orientation_table", "SweepResult", "SweepCancelled"]
