"""The control ranges and defaults live in the model (model/controls.py); the URL parser
reads them, and the defaults are the model's own (Params, SolverOptions, REGIMES)."""
import math

from model import REGIMES, Params, SolverOptions
from model.controls import CONTROLS, DEFAULT_REGIME, LOAD_RANGE, STIFFNESS_RANGE
from model.contact.options import RTOL_CHOICES
from model.contact.params import RANGES


def test_defaults_are_the_models():
    p, o = Params(1.0, 1.0), SolverOptions()
    assert CONTROLS["k_r"].default == REGIMES[DEFAULT_REGIME].k_r
    assert CONTROLS["k_theta"].default == REGIMES[DEFAULT_REGIME].k_theta
    assert CONTROLS["F_N"].default == p.F_N
    assert CONTROLS["theta0_deg"].default == math.degrees(p.theta0)
    assert CONTROLS["beta"].default == p.beta
    assert CONTROLS["rtol"].default == o.rtol and o.rtol in RTOL_CHOICES


def test_control_ranges_lie_inside_what_the_model_accepts():
    for name in ("k_r", "k_theta", "F_N"):
        lo, hi = CONTROLS[name].bounds
        Params(1.0, 1.0).replace(**{name: lo})  # raises if the model refused the slider's end
        Params(1.0, 1.0).replace(**{name: hi})
        assert lo in RANGES[name][0] and hi in RANGES[name][0]
    for rtol in RTOL_CHOICES:
        SolverOptions(rtol=rtol)


def test_the_url_parser_reads_the_models_table():
    from app import urlstate

    assert urlstate.K_BOUNDS == STIFFNESS_RANGE.bounds == (0.01, 3.0)
    assert urlstate.F_N_BOUNDS == LOAD_RANGE.bounds == (0.1, 10.0)
    assert urlstate.RTOLS == RTOL_CHOICES
    assert urlstate.DEFAULTS["k_r"] == CONTROLS["k_r"].default
    assert urlstate.DEFAULTS["theta0"] == 90.0
    values, notices = urlstate.parse("?k_r=5&F_N=0.05&rtol=1e-3")
    assert values == {}
    assert notices[0].startswith("URL parameter k_r='5' is not usable (a number in [0.01, 3]")
    assert "(a number in [0.1, 10] expected)" in notices[1]
    assert "(one of 0.0001, 1e-05, 1e-06, 1e-07, 1e-08 expected)" in notices[2]


def test_model_imports_no_gui():
    """The controls table is plain data: importing it pulls in no dashboard library."""
    import subprocess
    import sys

    code = ("import sys, model.controls, model.arrays.quantities, model.validation, model.csvfile; "
            "bad = [m for m in ('panel', 'param', 'bokeh', 'holoviews', 'app') if m in sys.modules]; "
            "sys.exit(bool(bad))")
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0
