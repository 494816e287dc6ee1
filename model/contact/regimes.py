"""Where a dimensionless point (k~_r, k~_theta) lies: the paper's explored map, the model's
range, and the regime (Figs. 5, 6). Pure numbers: ``model.designs.units`` adds physical units."""
from __future__ import annotations

import math

import numpy as np

from ..controls import STIFFNESS_RANGE
from .params import RANGES

__all__ = ["EXPLORED_MAP", "MODEL_RANGE", "REGIME_SPLIT", "regime_of", "map_status",
           "MAP_NOTE", "map_axis"]

#: The (k~_r, k~_theta) square the paper explored (Figs. 5, 8): the explorer's controls.
EXPLORED_MAP = STIFFNESS_RANGE.bounds
#: Where the model answers with tested, bounded-cost integration: up to the largest
#: stiffness ``Params`` accepts, down to 1e-3 (the softest corner the tests integrate).
MODEL_RANGE = (1e-3, RANGES["k_r"][0].hi)
#: The regimes are the quadrants of the paper's map, split at its logarithmic centre.
REGIME_SPLIT = math.sqrt(EXPLORED_MAP[0] * EXPLORED_MAP[1])
#: Said of a result whose springs lie outside the explored map.
MAP_NOTE = (f"(k_r, k_theta) outside the paper's explored map {list(EXPLORED_MAP)}^2: "
            f"computed by the same model, beyond the paper's figures")


def map_axis(n: int) -> np.ndarray:
    """``n`` stiffnesses spaced evenly in log over the explored map (an axis of Fig. 5).

    >>> map_axis(3)
    array([0.01      , 0.17320508, 3.        ])
    """
    return np.geomspace(*EXPLORED_MAP, int(n))


def regime_of(k_r: float, k_theta: float) -> str:
    """The quadrant of the map: stiff, pendulum (k_r high), slider (k_theta high) or soft."""
    high_r, high_t = k_r > REGIME_SPLIT, k_theta > REGIME_SPLIT
    return {(True, True): "stiff", (True, False): "pendulum", (False, True): "slider",
            (False, False): "soft"}[(high_r, high_t)]


def map_status(k_r: float, k_theta: float) -> str:
    """``in_map`` inside the explored map, else ``outside_map``."""
    lo, hi = EXPLORED_MAP
    return "in_map" if lo <= k_r <= hi and lo <= k_theta <= hi else "outside_map"
