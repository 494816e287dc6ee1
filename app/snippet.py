"""This view as code: the Python (public ``model`` API) that reproduces the numbers the
dashboard shows for an ``ExplorerState``.

The snippet makes the calls the server's workers make (``app.worker``): the
fixed-orientation array at theta0 and the contact of its support, integrated with the
array's load factor (Support tab, Fig. 7), and the uniform-orientation array behind the
readouts (Figs. 5, 6, 8); on the Design tab also the design's array for its orientation
distribution, in physical units (``model.designs.design_point.evaluate``). Settings the page fixes
(samples, step budget, quadrature tolerances) are taken from ``app.worker``, so the snippet
follows them. With a pinned state A of a comparison (``app.compare``) the snippet computes
A's numbers as well (its variables end in ``_A``) and prints B − A.
"""
from __future__ import annotations

import textwrap

from model import __version__
from model.cli.snippet import params_source, source
from model.lab.friction_law import COEFFICIENTS
from model.designs.units import to_si

from . import worker
from .pinned_state import complete
from .snippet_tabs import BLOCKS, IMPORTS
from .state import ExplorerState
from .texts import FELT_AVERAGE

__all__ = ["view_as_python"]

#: Which uniform-array attribute each average of the page shows (``ExplorerState.average``).
AVERAGE_ATTRIBUTES = {"paper": ("FTx_over_mu0FN", "paper average over supports, Eq. 10"),
                      "duration": ("FTx_over_mu0FN_duration",
                                   "duration-weighted average over supports")}


def _value_source(value) -> str:
    """Python source of a distribution's ``to_dict`` form (dicts, lists, numbers, text)."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k!r}: {_value_source(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):  # a mixture's components and weights
        return "[" + ", ".join(_value_source(v) for v in value) + "]"
    return source(value)


def _support_block(state, tag: str, who: str) -> str:
    """The support's and uniform array's lines of ``state``; variables end in ``tag``,
    printed lines start with ``who``."""
    p = state.params
    beta = state.array_beta
    (felt, felt_meaning), (other, other_meaning) = (
        AVERAGE_ATTRIBUTES[FELT_AVERAGE], *(v for k, v in AVERAGE_ATTRIBUTES.items()
                                            if k != FELT_AVERAGE))
    # Degrees as on the slider; math.radians is how ExplorerState converts them.
    params = params_source(p, theta0=f"math.radians({source(float(state.theta0))})")
    # A uniform array covers every theta0 and takes its load factor as an argument.
    springs = params_source(state.support)
    t, w = tag, who
    return f'''\
params{t} = {params}

# Support tab: the fixed-orientation array at theta0 (Figs. 9-11) and the contact of its
# support, integrated with the array's load factor beta (Eqs. 5-9, Fig. 7)
fixed{t} = fixed_orientation(params{t}, beta={source(beta)}, rtol={source(state.rtol)})
support{t} = simulate_support(params{t}.replace(beta=fixed{t}.beta), rtol={source(state.rtol)},
                           samples={worker.SAMPLES}, max_steps={worker.MAX_STEPS})
print(f"{w}fixed array: F_T,x/(mu0 F_N) = {{fixed{t}.FTx_over_mu0FN!r}}, "
      f"D_y/D_x = {{fixed{t}.Dy_over_Dx!r}}, beta = {{fixed{t}.beta!r}}")
print(f"{w}support: t_out = {{support{t}.t_out!r}}, W = {{support{t}.W!r}}, "
      f"D_x = {{support{t}.D_x!r}}, D_y = {{support{t}.D_y!r}}")

# Readouts: the uniform-orientation array, theta0 uniform on [0, 2 pi) (Figs. 5, 6, 8)
springs{t} = {springs}
uniform{t} = uniform_array(springs{t}, beta={source(beta)}, tol={source(worker.UNIFORM_TOL)})
print(f"{w}uniform array: F_T,x/(mu0 F_N) = {{float(uniform{t}.{felt})!r}}"
      f" ({felt_meaning}: the headline's), {{float(uniform{t}.{other})!r}} ({other_meaning})")
print(f"{w}uniform array: D_y/D_x = {{float(uniform{t}.Dy_over_Dx)!r}}, "
      f"N_c/N_c0 = {{float(uniform{t}.Nc_over_Nc0)!r}}")
'''


def _law_source(inputs: dict) -> str:
    """``FrictionLaw(...)`` of the Design tab's law inputs (numbers where they read as one,
    else the text, so the snippet raises as the page does; V_s with its unit)."""
    args = []
    for name in COEFFICIENTS:
        text = inputs[name].strip()
        if name == "V_s":
            args.append(f"V_s={source(text or None)}")
            continue
        try:
            args.append(f"{name}={source(to_si(name, text))}")
        except ValueError:
            args.append(f"{name}={text!r}")
    return f"FrictionLaw({', '.join(args)})"


def _design_block(state, tag: str, who: str) -> str:
    """The Design tab's array of ``state`` (as ``worker.compute_design_array``): the
    pillars, then their friction law (Eq. 4) as a ``FrictionLaw``."""
    given = state.design_inputs
    inputs = textwrap.fill(", ".join(f"{k}={v!r}" for k, v in given.items()
                                     if k not in COEFFICIENTS),
                           width=88, initial_indent="    ", subsequent_indent="    ",
                           break_long_words=False, break_on_hyphens=False)
    t, w = tag, who
    return f'''
# Design tab: the pillars in physical units with their friction law (Eq. 4), and their
# array for the orientation distribution seen at the sliding direction psi (Eq. 5 in
# physical units, Fig. 11a)
law{t} = {_law_source(given)}
design{t} = PillarDesign(
{inputs}).with_friction(law{t})
orientations{t} = from_dict({_value_source(state.distribution)})
array{t} = evaluate(design{t}, orientations{t},
    psi=math.radians({source(float(state.dist_psi))}), beta={source(state.array_beta)},
    tol={source(worker.DESIGN_TOL)}, budget={source(worker.DESIGN_REFINE_S)})
print(f"{w}design array: F_T,x/(mu0 F_N) = {{float(array{t}.array.FTx_over_mu0FN)!r}}, "
      f"F_T,y/(mu0 F_N) = {{float(array{t}.array.FTy_over_mu0FN)!r}}, "
      f"F_T,x = {{float(array{t}.FTx_N)!r}} N")
'''


def view_as_python(state) -> str:
    """The snippet for ``state`` (an ``app.state.ExplorerState``): runs on its own in a
    fresh interpreter and prints the readouts' numbers (and a pinned state's, and B − A);
    on the Orientation, Regime map, Load and Array tabs that tab's numbers instead
    (``app.snippet_tabs``)."""
    if state.tab in BLOCKS:  # a tab of many supports: its own calls
        return f'''\
# The dashboard's current view as Python (micropillar-friction {__version__})
import math

{IMPORTS[state.tab]}

{BLOCKS[state.tab](state)}'''
    design = state.tab == "design"
    pinned = state.pinned
    who = "B " if pinned is not None else ""
    imports = "from model import Params, fixed_orientation, simulate_support, uniform_array"
    if design:
        imports = imports.replace("from model import ", "from model import FrictionLaw, ")
        imports += ("\nfrom model.designs.design_point import evaluate\n"
                    "from model.designs.distributions import from_dict\n"
                    "from model.designs.units import PillarDesign")
    body = _support_block(state, "", who) + (_design_block(state, "", who) if design else "")
    if pinned is not None:
        a = ExplorerState(**complete(pinned), average=state.average)
        attribute = AVERAGE_ATTRIBUTES[FELT_AVERAGE][0]  # as the headline
        body += ("\n# The pinned state A of the comparison: the same calls with its values\n"
                 + _support_block(a, "_A", "A ") + (_design_block(a, "_A", "A ") if design
                                                    else ""))
        body += f'''
# B - A, as the compare readouts give it
print(f"B - A: fixed array F_T,x/(mu0 F_N) "
      f"{{fixed.FTx_over_mu0FN - fixed_A.FTx_over_mu0FN:+.6g}}, uniform array "
      f"{{float(uniform.{attribute}) - float(uniform_A.{attribute}):+.6g}}")
'''
        if design:
            body += ('print(f"B - A: design array F_T,x/(mu0 F_N) "\n'
                     '      f"{float(array.array.FTx_over_mu0FN - array_A.array.FTx_over_mu0FN)'
                     ':+.6g}")\n')
    return f'''\
# The dashboard's current view as Python (micropillar-friction {__version__})
import math

{imports}

{body}'''
