"""The lab's measurements: a friction law in physical units, measured friction curves, the fit of Eq. (4), friction against sliding speed and its comparison with a measured structured surface."""
