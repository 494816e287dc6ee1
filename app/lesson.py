"""A 45-minute lesson on the four regimes (docs/teaching.md), checked against the model.

* ``STEPS``: the lesson's predict-observe-explain questions, each with the explorer state
  it opens (URL keys of ``app.urlstate``; ``tab=array`` is the array tab);
* ``lesson_url(step)``: the link of a step, and ``offline_url(step)`` its equivalent in the
  offline explorer (``micropillar pack``: the same keys in the file's fragment). A lesson is taught from one screen, so its
  links keep the presentation: projector mode (``projector=1``) unless asked for a
  screen, and never autoplay (``play=1``): the animation waits at its first frame until
  the class has predicted and the teacher presses Play (Space);
* ``facts(regime, theta0_deg, F_N)``: what the model does in that state -- the motion of
  the support on the Support tab (integrated, like the page, with the fixed array's
  self-consistent beta) and the fixed and uniform arrays' readouts;
* ``fact_line(step)``: the one-line summary quoted in docs/teaching.md under each question;
  ``python -m app.lesson`` prints them all, and the tests check the document quotes them;
* ``REGIME_TEXTS``: regime descriptions that say what the model does on screen at the
  default theta0 = 90 deg (proposed for the page's regime panel).
"""
from __future__ import annotations

import argparse
import math
from dataclasses import dataclass
from functools import lru_cache
from urllib.parse import urlencode

import numpy as np

from model import REGIMES, fixed_orientation, simulate_support, uniform_array

from .texts import MECHANISMS

__all__ = ["STEPS", "Step", "facts", "fact_line", "lesson_url", "offline_url", "REGIME_TEXTS",
           "BASE_URL"]

BASE_URL = "http://localhost:5006/app"
#: |v_R| below this counts as "sticking" (the friction law peaks at |v_R| = 0.1 V0 = V_s).
STICK_SPEED = 0.1


@dataclass(frozen=True)
class Step:
    key: str
    minutes: int
    regime: str
    theta0_deg: float
    F_N: float
    tab: str

    def query(self, projector: bool = True) -> dict:
        """The URL keys of this step's state; ``projector``: in projector mode. Never
        ``play``: the class predicts before the motion starts."""
        q = {"regime": self.regime, "theta0_deg": f"{self.theta0_deg:g}", "F_N": f"{self.F_N:g}",
             "tab": self.tab}
        if projector:
            q["projector"] = "1"
        return q


STEPS = (
    Step("stiff", 5, "stiff", 90, 1, "support"),
    Step("pendulum", 7, "pendulum", 90, 1, "support"),
    Step("slider", 7, "slider", 90, 1, "support"),
    Step("slider-150", 3, "slider", 150, 1, "support"),
    Step("soft", 6, "soft", 90, 1, "support"),
    Step("array", 7, "slider", 90, 1, "array"),
    Step("load", 5, "soft", 90, 10, "load"),
)


def lesson_url(step: Step, projector: bool = True, base_url: str = BASE_URL) -> str:
    """The link of ``step`` (projector mode unless ``projector`` is False; paused)."""
    return f"{base_url}?{urlencode(step.query(projector))}"


def offline_url(step: Step, projector: bool = True, file: str = "explorer.html") -> str:
    """The link of ``step`` in the offline explorer: the dashboard link's keys in the file's
    fragment (a tab the file does not have opens its closest, with a notice)."""
    return f"{file}#{urlencode(step.query(projector))}"


@lru_cache(maxsize=64)
def facts(regime: str, theta0_deg: float, F_N: float) -> dict:
    """The model's numbers for one state (rounded only when printed)."""
    p = REGIMES[regime].replace(theta0=math.radians(theta0_deg), F_N=F_N)
    fixed = fixed_orientation(p)
    res = simulate_support(p.replace(beta=fixed.beta), samples=4000)
    s = res.series
    v_r = np.hypot(s.v_x - 1.0, s.v_y)
    theta = np.degrees(s.theta)
    uni = uniform_array(p.replace(theta0=math.pi / 2))  # it covers every theta0
    return {
        "beta": fixed.beta, "tau_out": res.t_out,
        "r_min": float(s.r.min()), "r_max": float(s.r.max()), "r_end": float(s.r[-1]),
        "theta_min": float(theta.min()), "theta_max": float(theta.max()),
        "theta_end": float(theta[-1]), "stick_fraction": float(np.mean(v_r < STICK_SPEED)),
        "fixed_FTx": fixed.FTx_over_mu0FN, "fixed_FTy": fixed.FTy_over_mu0FN,
        "fixed_Dy_Dx": fixed.Dy_over_Dx, "fixed_Nc": fixed.Nc_over_Nc0,
        "fixed_U_el": fixed.work_split["U_el"],
        "uniform_FTx": uni.FTx_over_mu0FN, "uniform_FTx_duration": uni.FTx_over_mu0FN_duration,
        "uniform_Dy_Dx": uni.Dy_over_Dx, "uniform_Nc": uni.Nc_over_Nc0,
        "uniform_U_el": uni.work_split["U_el"]}


def fact_line(step: Step) -> str:
    """The model check quoted under a question of docs/teaching.md."""
    f = facts(step.regime, step.theta0_deg, step.F_N)
    return (f"r {1.0:.2f} → {f['r_min']:.2f}…{f['r_max']:.2f} r₀, θ {step.theta0_deg:g}° → "
            f"{f['theta_min']:.0f}…{f['theta_max']:.0f}° (ends at {f['theta_end']:.0f}°), "
            f"τ_out = {f['tau_out']:.1f}, sticking {100 * f['stick_fraction']:.0f} % of the "
            f"contact; fixed array F_T,x/(μ₀F_N) = {f['fixed_FTx']:.3f}, D_y/D_x = "
            f"{f['fixed_Dy_Dx']:.3f}, N_c/N_c0 = {f['fixed_Nc']:.2f}; uniform array "
            f"F_T,x/(μ₀F_N) = {f['uniform_FTx']:.3f} (duration-weighted "
            f"{f['uniform_FTx_duration']:.3f}), N_c/N_c0 = {f['uniform_Nc']:.2f}, "
            f"U_el/W = {f['uniform_U_el']:.2f}")


#: The regime texts of the page (what the model does at theta0 = 90 deg, F_N = 1).
REGIME_TEXTS = MECHANISMS


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m app.lesson", description="The lesson's links (docs/teaching.md) and "
        "the model's numbers each question quotes.")
    parser.add_argument("--screen", action="store_true",
                        help="links for a screen (no projector mode)")
    parser.add_argument("--base-url", default=BASE_URL,
                        help=f"address of the served explorer (default {BASE_URL})")
    parser.add_argument("--offline", action="store_true",
                        help="the links' equivalents in the offline explorer (micropillar pack)")
    args = parser.parse_args(argv)
    if args.offline:
        for i, step in enumerate(STEPS, 1):
            print(f"Q{i}  {offline_url(step, not args.screen)}")
        return 0
    for step in STEPS:
        print(f"[{step.key}] {lesson_url(step, not args.screen, args.base_url)}\n"
              f"  {fact_line(step)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
