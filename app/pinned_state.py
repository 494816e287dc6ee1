"""The pinned state "A" of a comparison: what it keeps.

A pinned state keeps every input of the results it is compared on: the support's
(``PINNED_KEYS``: springs, load, theta0, tolerance, load factor; Eqs. 1-10 of
docs/model.md) and the Design tab's (``PINNED_DESIGN_KEYS``: the pillars' physical
inputs, which make the dimensionless point of Eq. 5, and the orientation distribution:
family, angle, concentration, sliding direction psi, and a mixture's second component).

The URL holds it as one parameter (``app.urlstate.pinned_text`` writes it,
``parse_pinned`` reads it), its values written as ``app.urlstate`` writes the
controls' (same URL keys, same readers) and joined as ``key:value`` by commas: the
support's always, ``rtol`` and ``beta`` only when not the default, and the Design tab's
only where they differ from the defaults, so a comparison that never touched the Design
tab writes nothing of it: ``A=k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:60,d_D:10 um,dist:pair``.
A "," or "%" in a design input's text is written ``%2C`` or ``%25``. The text is at most
``MAX_PINNED_CHARS`` long (every input at its longest fits); a longer one is refused
unread, and any unusable part refuses the whole of A: comparing with a state other than
the one written is worse than comparing with none.
"""
from __future__ import annotations

from collections.abc import Mapping

from .defaults import DEFAULTS, DESIGN_INPUTS

__all__ = ["PINNED_KEYS", "PINNED_DIST_KEYS", "PINNED_DESIGN_KEYS", "PINNED_ALL",
           "PINNED_URL_KEYS", "complete"]

#: What a pinned state keeps of the support: every input of the support, the orientation
#: sweep, the uniform array and the load curve.
PINNED_KEYS = ("k_r", "k_theta", "F_N", "theta0", "rtol", "beta_mode", "beta")
#: The Design tab's orientation distribution (``ExplorerState.distribution``).
PINNED_DIST_KEYS = ("dist_family", "dist_deg", "dist_kappa", "dist_psi", "mix_weight",
                    "dist2_family", "dist2_deg", "dist2_kappa", "dist_hist")
#: What a pinned state keeps of the Design tab: its physical inputs and its distribution.
PINNED_DESIGN_KEYS = (*DESIGN_INPUTS, *PINNED_DIST_KEYS)
#: Every state parameter of a pinned state.
PINNED_ALL = (*PINNED_KEYS, *PINNED_DESIGN_KEYS)
#: The URL keys ``A=key:value,...`` may hold: the support's, then the Design tab's.
PINNED_URL_KEYS = ("k_r", "k_theta", "F_N", "theta0_deg", "rtol", "beta",
                   *(v[0] for v in DESIGN_INPUTS.values()),
                   "dist", "dist_deg", "kappa", "psi_deg", "mix", "dist2", "dist2_deg", "kappa2",
                   "hist")


def complete(pinned: Mapping) -> dict:
    """Every parameter of a pinned state (``PINNED_ALL``): those ``pinned`` omits (a
    state pinned before the Design tab's were kept) at their defaults."""
    return {name: pinned.get(name, DEFAULTS[name]) for name in PINNED_ALL}
