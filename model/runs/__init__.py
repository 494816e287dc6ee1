"""Many points at once: the sweeps behind the paper's figures, the shipped regime maps, the on-disk cache and serial, process-pool or dask runs."""
