"""Orientation distributions of an array's supports (theta0 measured from the sliding direction).

An array's rest orientations follow a probability distribution on the circle: point
masses (``atoms``) plus a continuous density. The array quantities of Eq. (10) are then
averages weighted by this distribution (``model.designs.distribution_array``).

* ``Fixed(theta0)``: every support at theta0 (Figs. 9-11);
* ``Uniform()``: theta0 uniform on [0, 2 pi) (Figs. 5, 6, 8);
* ``Pair(theta0)``: half at +theta0, half at -theta0 (orthotropic: F_T,y = 0 by mirror symmetry);
* ``VonMises(mean, kappa)``: density exp(kappa cos(theta0 - mean)) / (2 pi I0(kappa));
* ``Mixture(components, weights)``: a weighted sum of the above;
* ``Histogram(edges, weights)``: piecewise-constant density, e.g. ``Histogram.from_csv``.

A slab sliding at angle psi to the array sees the same distribution rotated by -psi
(``rotated(dist, psi)``). Angles are radians; ``to_dict`` reports degrees.
All distributions are frozen and hashable, so they serve as cache keys.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import i0e

from .histogram_csv import parse_histogram

__all__ = ["Distribution", "Fixed", "Uniform", "Pair", "VonMises", "Mixture", "Histogram",
           "Rotated", "rotated", "from_dict", "FAMILIES", "KAPPA_MAX"]

TWO_PI = 2 * math.pi
#: Concentrations above this are numerically a point mass at the mean (width < 1e-4 rad).
KAPPA_MAX = 1e8


def _angle(name: str, value) -> float:
    try:
        if isinstance(value, (bool, np.bool_, str, bytes)):
            raise TypeError
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name}={value!r} is not a number; give an angle in radians") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}={value!r} must be a finite angle in radians")
    return x


def wrap(theta):
    """Angles into (-pi, pi]."""
    t = np.mod(np.asarray(theta, dtype=float) + math.pi, TWO_PI) - math.pi
    return np.where(t == -math.pi, math.pi, t)


class Distribution:
    """Base class: point masses ``atoms()`` plus a continuous part with ``density``.

    The total mass (atoms plus the integral of the density over the circle) is 1.
    """

    def atoms(self) -> tuple:
        """((theta, weight), ...) point masses."""
        return ()

    @property
    def continuous_mass(self) -> float:
        return 1.0 - sum(w for _, w in self.atoms())

    def density(self, theta) -> np.ndarray:
        """Density of the continuous part at ``theta`` (per radian)."""
        return np.zeros_like(np.asarray(theta, dtype=float))

    def points(self) -> np.ndarray:
        """Angles where the continuous part has its mass or its jumps (for the partition)."""
        return np.array([])

    def breaks(self) -> np.ndarray:
        """Angles where the density jumps (quadrature intervals must end there)."""
        return np.array([])

    def partition_hint(self) -> np.ndarray:
        """Suggested interval ends around concentrated mass (first quadrature partition)."""
        return np.array([])

    def to_dict(self) -> dict:
        raise NotImplementedError


@dataclass(frozen=True)
class Fixed(Distribution):
    """Every support at ``theta0`` (radians)."""

    theta0: float

    def __post_init__(self):
        object.__setattr__(self, "theta0", _angle("theta0", self.theta0))

    def atoms(self):
        return ((self.theta0, 1.0),)

    def to_dict(self):
        return {"family": "fixed", "theta0_deg": math.degrees(self.theta0)}


@dataclass(frozen=True)
class Pair(Distribution):
    """Half the supports at +theta0, half at -theta0: F_T,y = 0 by mirror symmetry."""

    theta0: float

    def __post_init__(self):
        object.__setattr__(self, "theta0", _angle("theta0", self.theta0))

    def atoms(self):
        return ((self.theta0, 0.5), (-self.theta0, 0.5))

    def to_dict(self):
        return {"family": "pair", "theta0_deg": math.degrees(self.theta0)}


@dataclass(frozen=True)
class Uniform(Distribution):
    """theta0 uniform on [0, 2 pi): the paper's random arrays (Figs. 5, 6, 8)."""

    def density(self, theta):
        return np.full(np.shape(theta), 1.0 / TWO_PI)

    def to_dict(self):
        return {"family": "uniform"}


@dataclass(frozen=True)
class VonMises(Distribution):
    """Density exp(kappa cos(theta0 - mean)) / (2 pi I0(kappa)); kappa = 0 is uniform.

    Evaluated as exp(kappa (cos - 1)) / (2 pi i0e(kappa)) so large kappa cannot overflow.
    """

    mean: float
    kappa: float

    def __post_init__(self):
        object.__setattr__(self, "mean", _angle("mean", self.mean))
        k = self.kappa
        try:
            if isinstance(k, (bool, np.bool_, str, bytes)):
                raise TypeError
            k = float(k)
        except (TypeError, ValueError, OverflowError):
            raise ValueError(f"kappa={self.kappa!r} is not a number; the concentration must be "
                             f"in [0, {KAPPA_MAX:g}]") from None
        if not (math.isfinite(k) and 0.0 <= k <= KAPPA_MAX):
            raise ValueError(f"kappa={self.kappa!r} is invalid: the concentration must be finite "
                             f"and in [0, {KAPPA_MAX:g}] (0 is uniform; larger is narrower)")
        object.__setattr__(self, "kappa", k)

    def density(self, theta):
        theta = np.asarray(theta, dtype=float)
        return np.exp(self.kappa * (np.cos(theta - self.mean) - 1.0)) / (TWO_PI * i0e(self.kappa))

    def points(self):
        if self.kappa <= 1.0:
            return np.array([self.mean])
        # Mass within ~10 standard deviations 1/sqrt(kappa) of the mean.
        return self.mean + np.linspace(-10, 10, 201) / math.sqrt(self.kappa)

    def partition_hint(self):
        if self.kappa <= 16.0:
            return np.array([])
        # Beyond 12 standard deviations the density is below 1e-31 of its peak: those
        # intervals hold no mass and cost no trajectory.
        return self.mean + np.array([-12, -6, -3, -1.5, 0, 1.5, 3, 6, 12]) / math.sqrt(self.kappa)

    def to_dict(self):
        return {"family": "vonmises", "mean_deg": math.degrees(self.mean), "kappa": self.kappa}


@dataclass(frozen=True)
class Mixture(Distribution):
    """sum_i weights[i] components[i] (weights normalised to sum 1)."""

    components: tuple
    weights: tuple

    def __post_init__(self):
        comps = tuple(self.components)
        try:
            w = np.asarray(self.weights, dtype=float).ravel()
        except (TypeError, ValueError):
            raise ValueError(f"weights={self.weights!r} must be non-negative numbers") from None
        if not comps or len(comps) != w.size:
            raise ValueError(f"weights={self.weights!r} must give one weight per component "
                             f"({len(comps)} components)")
        if not all(isinstance(c, Distribution) for c in comps):
            raise ValueError(f"components={comps!r} must be orientation distributions")
        if not (np.all(np.isfinite(w)) and np.all(w >= 0) and w.sum() > 0):
            raise ValueError(f"weights={self.weights!r} must be finite, non-negative and not all 0")
        object.__setattr__(self, "components", comps)
        object.__setattr__(self, "weights", tuple(float(x) for x in w / w.sum()))

    def atoms(self):
        return tuple((t, w * a) for c, w in zip(self.components, self.weights)
                     for t, a in c.atoms())

    def density(self, theta):
        theta = np.asarray(theta, dtype=float)
        return sum((w * c.density(theta) for c, w in zip(self.components, self.weights)),
                   np.zeros_like(theta))

    def points(self):
        return np.concatenate([c.points() for c in self.components] + [np.array([])])

    def breaks(self):
        return np.concatenate([c.breaks() for c in self.components] + [np.array([])])

    def partition_hint(self):
        return np.concatenate([c.partition_hint() for c in self.components] + [np.array([])])

    def to_dict(self):
        return {"family": "mixture", "weights": list(self.weights),
                "components": [c.to_dict() for c in self.components]}


@dataclass(frozen=True)
class Histogram(Distribution):
    """Piecewise-constant density: ``weights[i]`` of the supports in [edges[i], edges[i+1]).

    Edges in radians, increasing, spanning at most 2 pi; weights are normalised.
    """

    edges: tuple
    weights: tuple

    def __post_init__(self):
        try:
            e = np.asarray(self.edges, dtype=float).ravel()
            w = np.asarray(self.weights, dtype=float).ravel()
        except (TypeError, ValueError):
            raise ValueError(f"histogram edges={self.edges!r} and weights={self.weights!r} must "
                             f"be numbers") from None
        if w.size == 0 or e.size != w.size + 1:
            raise ValueError(f"histogram weights={self.weights!r} must be non-empty with one more "
                             f"edge than weights ({e.size} edges, {w.size} weights)")
        span_ok = e[-1] - e[0] <= TWO_PI + 1e-9
        if not (np.all(np.isfinite(e)) and np.all(np.diff(e) > 0) and span_ok):
            raise ValueError(f"histogram edges={self.edges!r} must be finite, increasing and "
                             f"span at most 360 degrees")
        if not (np.all(np.isfinite(w)) and np.all(w >= 0) and w.sum() > 0):
            raise ValueError(f"histogram weights={self.weights!r} must be finite, non-negative "
                             f"and not all 0")
        object.__setattr__(self, "edges", tuple(float(x) for x in e))
        object.__setattr__(self, "weights", tuple(float(x) for x in w / w.sum()))

    def density(self, theta):
        e, w = np.asarray(self.edges), np.asarray(self.weights)
        t = e[0] + np.mod(np.asarray(theta, dtype=float) - e[0], TWO_PI)
        i = np.searchsorted(e, t, side="right") - 1
        inside = (i >= 0) & (i < w.size)
        return np.where(inside, (w / np.diff(e))[np.clip(i, 0, w.size - 1)], 0.0)

    def points(self):
        e = np.asarray(self.edges)
        return 0.5 * (e[1:] + e[:-1])

    def breaks(self):
        return np.asarray(self.edges)

    def to_dict(self):
        return {"family": "histogram", "edges_deg": [math.degrees(x) for x in self.edges],
                "weights": list(self.weights)}

    @classmethod
    def from_csv(cls, path) -> "Histogram":
        """Read a histogram from a CSV file (``model.designs.histogram_csv``): a header row, then
        ``lower_deg,upper_deg,weight`` (bin edges in degrees) or ``theta0_deg,weight``
        (equally spaced bin centres; each bin as wide as the spacing)."""
        try:
            with open(path, newline="", encoding="utf-8") as src:
                text = src.read()
        except (OSError, UnicodeDecodeError) as error:
            raise ValueError(f"histogram file {str(path)!r} cannot be read: {error}") from None
        return cls.from_text(text, f"histogram file {str(path)!r}")

    @classmethod
    def from_text(cls, text: str, source: str = "the histogram") -> "Histogram":
        """A histogram from the text of its CSV file (``from_csv``'s forms); ``ValueError``
        naming ``source``, the line and the fix."""
        edges, weights = parse_histogram(text, source)
        return cls(tuple(edges), tuple(weights))


@dataclass(frozen=True)
class Rotated(Distribution):
    """``base`` seen by a slab sliding at angle ``psi`` to the array: rotated by -psi."""

    base: Distribution
    psi: float

    def __post_init__(self):
        object.__setattr__(self, "psi", _angle("psi", self.psi))

    def atoms(self):
        return tuple((t - self.psi, w) for t, w in self.base.atoms())

    def density(self, theta):
        return self.base.density(np.asarray(theta, dtype=float) + self.psi)

    def points(self):
        return self.base.points() - self.psi

    def breaks(self):
        return self.base.breaks() - self.psi

    def partition_hint(self):
        return self.base.partition_hint() - self.psi

    def to_dict(self):
        return {**self.base.to_dict(), "psi_deg": math.degrees(self.psi)}


def rotated(dist: Distribution, psi: float) -> Distribution:
    """The distribution a slab sliding at ``psi`` (radians) to the array sees."""
    return dist if psi == 0 else Rotated(dist, psi)


#: Family name -> its parameters (angles in degrees in ``from_dict``).
FAMILIES = {"fixed": ("theta0_deg",), "uniform": (), "pair": ("theta0_deg",),
            "vonmises": ("mean_deg", "kappa"), "mixture": ("components", "weights"),
            "histogram": ("edges_deg", "weights")}


def from_dict(d: dict) -> Distribution:
    """A distribution from its ``to_dict`` form (the inverse of ``to_dict``)."""
    if not isinstance(d, dict) or d.get("family") not in FAMILIES:
        raise ValueError(f"family={d.get('family') if isinstance(d, dict) else d!r} is unknown; "
                         f"choose one of {', '.join(FAMILIES)}")
    fam = d["family"]
    missing = [k for k in FAMILIES[fam] if k not in d]
    if missing:
        raise ValueError(f"{missing[0]}: required for the {fam} family")
    if fam == "fixed":
        dist = Fixed(math.radians(_angle("theta0_deg", d["theta0_deg"])))
    elif fam == "pair":
        dist = Pair(math.radians(_angle("theta0_deg", d["theta0_deg"])))
    elif fam == "uniform":
        dist = Uniform()
    elif fam == "vonmises":
        dist = VonMises(math.radians(_angle("mean_deg", d["mean_deg"])), d["kappa"])
    elif fam == "mixture":
        dist = Mixture(tuple(from_dict(c) for c in d["components"]), tuple(d["weights"]))
    else:
        dist = Histogram(tuple(np.radians(np.asarray(d["edges_deg"], dtype=float))),
                         tuple(d["weights"]))
    return rotated(dist, math.radians(d["psi_deg"])) if d.get("psi_deg") else dist
